//! Pictures of an LR (`lrmesh render`): a small z-buffer rasterizer with flat Lambert
//! shading, colouring triangles by ring order (blue at a ring's start to red at its end, as in
//! the right column of the LR paper's Table 1) or by triangle class (T0, T2 and warts
//! highlighted on neutral T1 triangles, as in its Fig. 1), written out as PNG.
//!
//! The view is orthographic (or perspective) along a direction given by azimuth and
//! elevation around an up axis, fitted to the projected mesh. Work and memory are bounded by
//! the image size ([`MAX_SAMPLES`]) and the triangle count; positions that are not finite are
//! skipped, so any mesh the LR accepts renders.
//!
//! ```
//! use lrmesh::io::{read_mesh, ReadOptions};
//! use lrmesh::lr::{Lr, LrOptions};
//! use lrmesh::render::{render, ColorMode, RenderOptions};
//! use lrmesh::{CornerOps, CornerTable, Vertex};
//!
//! # fn main() -> Result<(), lrmesh::Error> {
//! let path = concat!(env!("CARGO_MANIFEST_DIR"), "/corpus/meshes/bunny_small.obj");
//! let mesh = read_mesh(path.as_ref(), &ReadOptions::default())?.mesh;
//! let lr = Lr::build(&CornerTable::from_mesh(&mesh)?, &LrOptions::default())?;
//! // Positions by LR vertex.
//! let positions: Vec<[f32; 3]> = (0..lr.vertex_id_bound())
//!     .map(|v| mesh.positions[lr.input_vertex(Vertex(v)) as usize])
//!     .collect();
//! let options = RenderOptions {
//!     width: 200,
//!     height: 150,
//!     mode: ColorMode::Classes,
//!     ..Default::default()
//! };
//! let image = render(lr.tables(), &positions, &options)?;
//! let mut png = Vec::new();
//! image.write_png(&mut png).expect("writing to memory");
//! assert_eq!(&png[1..4], b"PNG");
//! # Ok(())
//! # }
//! ```

mod camera;
mod colors;
mod legend;
mod raster;

use std::io::Write;

use self::camera::{add3, cross, dot, norm, normalize, scale3, sub3};
use self::colors::{blue_to_red, class_color, OFF_RING};
use self::raster::{depth_bias, Target};
use crate::error::{Error, Result};
use crate::lr::{LrInspect, LrLayout};
use crate::ops::CornerOps;

pub use self::camera::Camera;
pub use self::legend::{legend_height, with_legend};

/// Most samples (pixels times supersamples) an image may have: 2^26, about 470 MB of buffers.
pub const MAX_SAMPLES: u64 = 1 << 26;

/// What the colours say.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ColorMode {
    /// Each triangle coloured by its place along its ring, blue (start) to red (end).
    #[default]
    Ring,
    /// T0 green, T0^w red, T2 blue, T2^w violet, T1 cream (right) and light orange (left).
    Classes,
}

/// The world axis that points up in the picture.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Axis {
    /// x up.
    X,
    /// y up (most scanned meshes).
    #[default]
    Y,
    /// z up (most CAD meshes).
    Z,
}

/// How to draw the picture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderOptions {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Colouring.
    pub mode: ColorMode,
    /// Rotation of the viewpoint around the up axis, in degrees (0: looking along the third
    /// axis, e.g. from +z for y up).
    pub azimuth: f32,
    /// Height of the viewpoint above the horizontal plane, in degrees.
    pub elevation: f32,
    /// The up axis.
    pub up: Axis,
    /// Perspective projection (30 degree field of view) instead of orthographic.
    pub perspective: bool,
    /// Supersamples per pixel along each axis (1 to 4): 2 smooths the edges.
    pub samples: u32,
    /// Draw the ring edges as black lines (the ring of Fig. 1; busy on large meshes).
    pub ring_lines: bool,
    /// Colour of the pixels no triangle covers.
    pub background: [u8; 3],
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 800,
            height: 600,
            mode: ColorMode::Ring,
            azimuth: 30.0,
            elevation: 20.0,
            up: Axis::Y,
            perspective: false,
            samples: 2,
            ring_lines: false,
            background: BACKGROUND,
        }
    }
}

/// The default background: white, which no shaded triangle reaches.
pub const BACKGROUND: [u8; 3] = [255, 255, 255];

/// An RGB image, 8 bits a channel, rows top to bottom.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    width: u32,
    height: u32,
    rgb: Vec<u8>,
}

impl Image {
    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The pixel at column `x`, row `y` (0 at the top); `None` outside the image.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 3]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = 3 * (y as usize * self.width as usize + x as usize);
        Some([self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]])
    }

    /// The pixels, three bytes each, row by row.
    pub fn rgb(&self) -> &[u8] {
        &self.rgb
    }

    /// Writes the image as an 8-bit RGB PNG.
    ///
    /// # Errors
    /// The writer's I/O errors, and the PNG encoder's as [`std::io::ErrorKind::Other`].
    pub fn write_png<W: Write>(&self, out: W) -> std::io::Result<()> {
        let mut encoder = png::Encoder::new(out, self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(png_error)?;
        writer.write_image_data(&self.rgb).map_err(png_error)?;
        writer.finish().map_err(png_error)
    }
}

fn png_error(e: png::EncodingError) -> std::io::Error {
    match e {
        png::EncodingError::IoError(e) => e,
        other => std::io::Error::other(other),
    }
}

/// Renders the triangles of `lr` at `positions` (indexed by LR vertex).
///
/// # Errors
/// [`Error::InvalidArgument`] when `positions` has fewer entries than `lr` has vertices;
/// [`Error::LimitExceeded`] when the image would have more than [`MAX_SAMPLES`] samples.
pub fn render<L: LrLayout>(
    lr: &L,
    positions: &[[f32; 3]],
    options: &RenderOptions,
) -> Result<Image> {
    if positions.len() < lr.vertex_id_bound() as usize {
        return Err(Error::InvalidArgument(format!(
            "{} positions for an LR of {} vertices",
            positions.len(),
            lr.vertex_id_bound()
        )));
    }
    let s = options.samples.clamp(1, 4);
    let (width, height) = (options.width.max(1), options.height.max(1));
    let samples = width as u64 * height as u64 * (s * s) as u64;
    if samples > MAX_SAMPLES {
        return Err(Error::LimitExceeded {
            what: "image samples (width x height x samples^2)",
            value: samples,
            limit: MAX_SAMPLES,
        });
    }
    let camera = camera(lr, positions, options);
    let mut target = Target::new(width * s, height * s, options.background);
    let fine = Camera {
        scale: camera.scale * s as f32,
        width: camera.width * s as f32,
        height: camera.height * s as f32,
        ..camera
    };
    let light = normalize(add3(
        add3(camera.back, scale3(camera.up, 0.6)),
        scale3(camera.right, -0.35),
    ));
    let ring = lr.ring_places();
    for t in lr.triangles() {
        let vs = lr.triangle_vertices(t);
        let p = vs.map(|v| positions[v.idx()]);
        let Some(base) = (match options.mode {
            ColorMode::Ring => Some(
                lr.triangle_ring_place(&ring, t)
                    .map_or(OFF_RING, blue_to_red),
            ),
            ColorMode::Classes => lr.triangle_class(t).map(class_color),
        }) else {
            continue;
        };
        let n = cross(sub3(p[1], p[0]), sub3(p[2], p[0]));
        let len = norm(n);
        let lambert = if len > 0.0 && len.is_finite() {
            (dot(n, light) / len).abs()
        } else {
            0.0
        };
        let shade = 0.28 + 0.67 * lambert;
        let color = base.map(|c| (255.0 * c * shade).round().clamp(0.0, 254.0) as u8);
        let (Some(a), Some(b), Some(c)) =
            (fine.project(p[0]), fine.project(p[1]), fine.project(p[2]))
        else {
            continue;
        };
        target.triangle([a, b, c], color);
    }
    if options.ring_lines {
        let bias = depth_bias(&fine, positions, lr);
        for r in 0..lr.ring_count() {
            let Some(range) = lr.ring_range(r) else {
                continue;
            };
            for v in range {
                let w = lr.ring_next(v);
                if let (Some(a), Some(b)) = (
                    fine.project(positions[v as usize]),
                    fine.project(positions[w as usize]),
                ) {
                    target.line(a, b, s as f32, bias, [20, 20, 20]);
                }
            }
        }
    }
    Ok(target.downsample(s))
}

/// The camera of [`render`]: fitted to the vertices of triangles (an unreferenced vertex far
/// away must not shrink the picture). Positions past the end of `positions` are left out.
pub fn camera<L: LrLayout>(lr: &L, positions: &[[f32; 3]], options: &RenderOptions) -> Camera {
    let mut used = vec![false; positions.len()];
    for t in lr.triangles() {
        for v in lr.triangle_vertices(t) {
            if let Some(u) = used.get_mut(v.idx()) {
                *u = true;
            }
        }
    }
    let points: Vec<[f32; 3]> = positions
        .iter()
        .zip(&used)
        .filter(|(_, &u)| u)
        .map(|(&p, _)| p)
        .collect();
    Camera::fit(&points, options)
}
