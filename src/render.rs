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

use std::io::Write;

use crate::error::{Error, Result};
use crate::ids::{Triangle, Vertex};
use crate::lr::{LrInspect, LrLayout, TriangleClass};
use crate::ops::CornerOps;

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

/// The projection of [`render`]: world positions to pixel coordinates and depth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    right: [f32; 3],
    up: [f32; 3],
    back: [f32; 3],
    center: [f32; 3],
    /// Distance of the eye from `center` (perspective only).
    eye: Option<f32>,
    /// Projected point that lands in the middle of the image.
    mid: [f32; 2],
    /// Pixels per projected unit.
    scale: f32,
    width: f32,
    height: f32,
}

impl Camera {
    /// The camera of `options`, fitted so that the given points fill the image with a margin.
    /// Points that are not finite are ignored.
    pub fn fit(points: &[[f32; 3]], options: &RenderOptions) -> Self {
        let (lo, hi) = points
            .iter()
            .filter(|p| p.iter().all(|x| x.is_finite()))
            .fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), &p| {
                (
                    [0, 1, 2].map(|k| lo[k].min(p[k])),
                    [0, 1, 2].map(|k| hi[k].max(p[k])),
                )
            });
        let (center, radius) = if lo[0] <= hi[0] {
            let c = [0, 1, 2].map(|k| 0.5 * lo[k] + 0.5 * hi[k]);
            let r = 0.5 * norm([0, 1, 2].map(|k| hi[k] - lo[k]));
            (c, if r.is_finite() && r > 0.0 { r } else { 1.0 })
        } else {
            ([0.0; 3], 1.0)
        };
        let (h1, up_axis, h2) = match options.up {
            Axis::X => ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            Axis::Y => ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            Axis::Z => ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]),
        };
        let (az, el) = (
            finite_or(options.azimuth, 0.0).to_radians(),
            finite_or(options.elevation, 0.0).to_radians(),
        );
        let back = normalize(add3(
            add3(
                scale3(h2, az.cos() * el.cos()),
                scale3(h1, az.sin() * el.cos()),
            ),
            scale3(up_axis, el.sin()),
        ));
        let right = {
            let r = cross(up_axis, back);
            if norm(r) < 1e-4 {
                // Looking straight down or up: keep the first horizontal axis to the right.
                h1
            } else {
                normalize(r)
            }
        };
        let up = cross(back, right);
        let mut camera = Camera {
            right,
            up,
            back,
            center,
            // A 30 degree field of view around the bounding sphere.
            eye: options
                .perspective
                .then(|| radius / (15f32.to_radians()).sin()),
            mid: [0.0; 2],
            scale: 1.0,
            width: options.width.max(1) as f32,
            height: options.height.max(1) as f32,
        };
        let (plo, phi) = points.iter().filter_map(|&p| camera.view(p)).fold(
            ([f32::MAX; 2], [f32::MIN; 2]),
            |(lo, hi), q| {
                (
                    [lo[0].min(q[0]), lo[1].min(q[1])],
                    [hi[0].max(q[0]), hi[1].max(q[1])],
                )
            },
        );
        if plo[0] <= phi[0] {
            camera.mid = [0.5 * plo[0] + 0.5 * phi[0], 0.5 * plo[1] + 0.5 * phi[1]];
            let margin = 0.92;
            let sx = margin * camera.width / (phi[0] - plo[0]);
            let sy = margin * camera.height / (phi[1] - plo[1]);
            let s = sx.min(sy);
            camera.scale = if s.is_finite() && s > 0.0 {
                s
            } else {
                margin * camera.width.min(camera.height) / (2.0 * radius)
            };
        }
        camera
    }

    /// View coordinates `(x right, y up, depth towards the eye)` of a finite point, after the
    /// perspective division; `None` for a point that is not finite or behind the eye.
    fn view(&self, p: [f32; 3]) -> Option<[f32; 3]> {
        if !p.iter().all(|x| x.is_finite()) {
            return None;
        }
        let d = sub3(p, self.center);
        let (x, y, z) = (dot(d, self.right), dot(d, self.up), dot(d, self.back));
        let q = match self.eye {
            None => [x, y, z],
            Some(eye) => {
                let w = eye - z;
                if w <= 1e-6 * eye {
                    return None;
                }
                [x * eye / w, y * eye / w, z]
            }
        };
        q.iter().all(|x| x.is_finite()).then_some(q)
    }

    /// Pixel coordinates `(column, row, depth)` of `p` (column and row in pixel units from the
    /// top-left corner; a pixel's centre is at `+0.5`), larger depth nearer the eye. `None`
    /// for a point that is not finite or behind the eye.
    pub fn project(&self, p: [f32; 3]) -> Option<[f32; 3]> {
        let [x, y, z] = self.view(p)?;
        Some([
            0.5 * self.width + (x - self.mid[0]) * self.scale,
            0.5 * self.height - (y - self.mid[1]) * self.scale,
            z,
        ])
    }

    /// The unit vector from the scene towards the eye.
    pub fn towards_eye(&self) -> [f32; 3] {
        self.back
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
    let ring = ring_parameters(lr);
    for t in lr.triangles() {
        let vs = lr.triangle_vertices(t);
        let p = vs.map(|v| positions[v.idx()]);
        let Some(base) = (match options.mode {
            ColorMode::Ring => ring_color(lr, &ring, t, vs),
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

/// Ring position of each ring vertex in `0..=1` (start to end of its ring).
fn ring_parameters<L: LrLayout>(lr: &L) -> Vec<f32> {
    let mut param = vec![0.0; lr.ring_vertices() as usize];
    for r in 0..lr.ring_count() {
        let Some(range) = lr.ring_range(r) else {
            continue;
        };
        let span = (range.len().max(2) - 1) as f32;
        for v in range.clone() {
            if let Some(p) = param.get_mut(v as usize) {
                *p = (v - range.start) as f32 / span;
            }
        }
    }
    param
}

/// Ring-order colour of triangle `t`: a ring-edge triangle takes its ring edge's place, a T0
/// the mean place of its ring vertices; grey when none of its vertices is on a ring.
fn ring_color<L: LrLayout>(lr: &L, ring: &[f32], t: Triangle, vs: [Vertex; 3]) -> Option<[f32; 3]> {
    let slot = t.0 / 2;
    if t.0 < 2 * lr.ring_vertices() {
        return ring.get(slot as usize).map(|&x| blue_to_red(x));
    }
    let on_ring: Vec<f32> = vs
        .iter()
        .filter_map(|v| ring.get(v.idx()).copied())
        .collect();
    if on_ring.is_empty() {
        return Some([0.6, 0.6, 0.6]);
    }
    Some(blue_to_red(
        on_ring.iter().sum::<f32>() / on_ring.len() as f32,
    ))
}

/// Hue from blue (`x = 0`) through cyan, green and yellow to red (`x = 1`).
fn blue_to_red(x: f32) -> [f32; 3] {
    let h = 4.0 * (1.0 - x.clamp(0.0, 1.0)); // 4 = blue, 0 = red, in sixths of the hue circle
    let f = h - h.floor();
    let rgb = match h as u32 {
        0 => [1.0, f, 0.0],
        1 => [1.0 - f, 1.0, 0.0],
        2 => [0.0, 1.0, f],
        3 => [0.0, 1.0 - f, 1.0],
        _ => [0.0, 0.0, 1.0],
    };
    // Slightly desaturated so that the shading reads on every hue.
    rgb.map(|c| 0.12 + 0.88 * c)
}

/// The palette of Fig. 1: neutral T1, highlighted T0, T2 and warts.
fn class_color(class: TriangleClass) -> [f32; 3] {
    match class {
        TriangleClass::T1Left => [1.0, 0.82, 0.6],
        TriangleClass::T1Right => [0.98, 0.95, 0.84],
        TriangleClass::T2 => [0.2, 0.45, 1.0],
        TriangleClass::T2Wart => [0.55, 0.25, 0.95],
        TriangleClass::T0 => [0.15, 0.75, 0.25],
        TriangleClass::T0Wart => [0.95, 0.15, 0.15],
    }
}

/// How far in front of the surface a ring line may be and still be drawn: a small fraction
/// of the depth range of the mesh.
fn depth_bias<L: LrLayout>(camera: &Camera, positions: &[[f32; 3]], lr: &L) -> f32 {
    let (lo, hi) = lr
        .vertices()
        .filter_map(|v| camera.project(positions[v.idx()]))
        .fold((f32::MAX, f32::MIN), |(lo, hi), p| {
            (lo.min(p[2]), hi.max(p[2]))
        });
    if lo <= hi {
        0.01 * (hi - lo)
    } else {
        0.0
    }
}

/// The supersampled colour and depth buffers.
struct Target {
    width: u32,
    height: u32,
    rgb: Vec<[u8; 3]>,
    depth: Vec<f32>,
}

impl Target {
    fn new(width: u32, height: u32, background: [u8; 3]) -> Target {
        let n = width as usize * height as usize;
        Target {
            width,
            height,
            rgb: vec![background; n],
            depth: vec![f32::NEG_INFINITY; n],
        }
    }

    /// Fills the samples whose centres lie inside (or on an edge of) triangle `p`, nearer
    /// than what is there. Scanline spans come from the edge functions, so the work is the
    /// rows of the triangle's bounding box plus the samples it covers.
    fn triangle(&mut self, p: [[f32; 3]; 3], color: [u8; 3]) {
        let area =
            (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
        if area == 0.0 || !area.is_finite() {
            return;
        }
        // Edge i from p[i] to p[i+1]: E(x, y) = a x + b y + c, positive inside.
        let sign = area.signum();
        let edges = [0, 1, 2].map(|i| {
            let (u, w) = (p[i], p[(i + 1) % 3]);
            let a = sign * (u[1] - w[1]);
            let b = sign * (w[0] - u[0]);
            let c = -(a * u[0] + b * u[1]);
            (a, b, c)
        });
        // Depth plane z = z0 + dzdx (x - x0) + dzdy (y - y0).
        let dzdx = ((p[1][2] - p[0][2]) * (p[2][1] - p[0][1])
            - (p[2][2] - p[0][2]) * (p[1][1] - p[0][1]))
            / area;
        let dzdy = ((p[2][2] - p[0][2]) * (p[1][0] - p[0][0])
            - (p[1][2] - p[0][2]) * (p[2][0] - p[0][0]))
            / area;
        let ymin = p.iter().map(|q| q[1]).fold(f32::MAX, f32::min);
        let ymax = p.iter().map(|q| q[1]).fold(f32::MIN, f32::max);
        let row0 = (ymin - 0.5).ceil().max(0.0);
        let row1 = (ymax - 0.5).floor().min(self.height as f32 - 1.0);
        if row0 > row1 {
            return;
        }
        for row in row0 as u32..=row1 as u32 {
            let y = row as f32 + 0.5;
            let (mut lo, mut hi) = (0.0f32, self.width as f32);
            for &(a, b, c) in &edges {
                let rhs = -(b * y + c);
                if a > 0.0 {
                    lo = lo.max(rhs / a);
                } else if a < 0.0 {
                    hi = hi.min(rhs / a);
                } else if rhs > 0.0 {
                    lo = f32::MAX;
                }
            }
            let col0 = (lo - 0.5).ceil().max(0.0);
            let col1 = (hi - 0.5).floor().min(self.width as f32 - 1.0);
            if col0.is_nan() || col1.is_nan() || col0 > col1 {
                continue;
            }
            let base = row as usize * self.width as usize;
            for col in col0 as u32..=col1 as u32 {
                let x = col as f32 + 0.5;
                let z = p[0][2] + dzdx * (x - p[0][0]) + dzdy * (y - p[0][1]);
                let i = base + col as usize;
                if z > self.depth[i] {
                    self.depth[i] = z;
                    self.rgb[i] = color;
                }
            }
        }
    }

    /// A line `width` samples wide from `a` to `b`, drawn where it is no more than `bias`
    /// behind the surface.
    fn line(&mut self, a: [f32; 3], b: [f32; 3], width: f32, bias: f32, color: [u8; 3]) {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let steps = dx.abs().max(dy.abs()).ceil();
        // The fitted camera keeps every vertex in the image, so no line is longer than its
        // diagonal; anything longer (never drawn) is skipped to keep the steps bounded.
        let limit = 4.0 * (self.width + self.height) as f32;
        if !steps.is_finite() || steps > limit {
            return;
        }
        let steps = steps.max(1.0) as u32;
        let half = (width * 0.5).max(0.5);
        for k in 0..=steps {
            let f = k as f32 / steps as f32;
            let (x, y, z) = (a[0] + f * dx, a[1] + f * dy, a[2] + f * (b[2] - a[2]));
            let (x0, x1) = ((x - half).round() as i64, (x + half).round() as i64);
            let (y0, y1) = ((y - half).round() as i64, (y + half).round() as i64);
            for row in y0.max(0)..y1.min(self.height as i64) {
                for col in x0.max(0)..x1.min(self.width as i64) {
                    let i = row as usize * self.width as usize + col as usize;
                    if z + bias >= self.depth[i] {
                        self.rgb[i] = color;
                    }
                }
            }
        }
    }

    /// Averages `s` x `s` blocks of samples into pixels.
    fn downsample(self, s: u32) -> Image {
        let (width, height) = (self.width / s, self.height / s);
        let mut rgb = Vec::with_capacity(3 * width as usize * height as usize);
        for y in 0..height {
            for x in 0..width {
                let mut sum = [0u32; 3];
                for j in 0..s {
                    let row = (y * s + j) as usize * self.width as usize;
                    for i in 0..s {
                        let c = self.rgb[row + (x * s + i) as usize];
                        for k in 0..3 {
                            sum[k] += c[k] as u32;
                        }
                    }
                }
                let n = s * s;
                rgb.extend(sum.map(|v| ((v + n / 2) / n) as u8));
            }
        }
        Image { width, height, rgb }
    }
}

fn finite_or(x: f32, default: f32) -> f32 {
    if x.is_finite() {
        x
    } else {
        default
    }
}

fn add3(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub3(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn scale3(a: [f32; 3], s: f32) -> [f32; 3] {
    a.map(|x| x * s)
}

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: [f32; 3]) -> f32 {
    dot(a, a).sqrt()
}

fn normalize(a: [f32; 3]) -> [f32; 3] {
    let n = norm(a);
    if n > 0.0 && n.is_finite() {
        scale3(a, 1.0 / n)
    } else {
        a
    }
}
