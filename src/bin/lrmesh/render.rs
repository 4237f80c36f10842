//! `lrmesh render`: a PNG of the LR, coloured by ring order or by triangle class.

use std::path::PathBuf;

use clap::ValueEnum;
use lrmesh::lr::{Lr, LrOptions};
use lrmesh::read::{self, Limits};
use lrmesh::render::{self, Axis, ColorMode, RenderOptions};
use lrmesh::{CornerOps, CornerTable, Error, Vertex};

use crate::common::{write_out, MeshInput};
use crate::progress;

/// Draw the mesh as a PNG: coloured by ring order (blue to red, LR paper Table 1) or by
/// triangle class (T0, T2 and warts highlighted, LR paper Fig. 1).
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    input: MeshInput,
    /// The PNG to write, or `-` for standard output.
    #[arg(short, long)]
    output: PathBuf,
    /// `ring`: ring order, blue to red; `classes`: T0 green, T0^w red, T2 blue, T2^w
    /// violet, T1 cream.
    #[arg(long, value_enum, default_value_t = RenderMode::Ring)]
    mode: RenderMode,
    /// Image size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "800x600", value_parser = parse_size)]
    size: (u32, u32),
    /// Viewpoint, AZIMUTH,ELEVATION in degrees around the up axis.
    #[arg(long, default_value = "30,20", value_parser = parse_view, allow_hyphen_values = true)]
    view: (f32, f32),
    /// The axis that points up in the picture.
    #[arg(long, value_enum, default_value_t = UpAxis::Y)]
    up: UpAxis,
    /// Perspective projection instead of orthographic.
    #[arg(long)]
    perspective: bool,
    /// Draw the ring edges as black lines.
    #[arg(long)]
    ring_lines: bool,
    /// Leave out the legend (the colour ramp or the class swatches, in a band at the
    /// bottom of the picture's size).
    #[arg(long)]
    no_legend: bool,
    /// Supersamples per pixel along each axis (anti-aliasing).
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=4))]
    samples: u32,
    /// RING-EXPANDER runs per component (mesh input only).
    #[arg(long, default_value_t = LrOptions::default().tries)]
    tries: u32,
    /// Seed for the choice of seed corners (mesh input only).
    #[arg(long, default_value_t = LrOptions::default().seed)]
    seed: u64,
}

/// Colourings of `lrmesh render`.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum RenderMode {
    /// Ring order, blue to red.
    Ring,
    /// Triangle classes.
    Classes,
}

/// Up axes of `lrmesh render`.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum UpAxis {
    /// x up.
    X,
    /// y up.
    Y,
    /// z up.
    Z,
}

/// `WIDTHxHEIGHT`, each from 1 to 16384.
fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("`{s}` is not WIDTHxHEIGHT"))?;
    let side = |t: &str| match t.trim().parse::<u32>() {
        Ok(n) if (1..=16384).contains(&n) => Ok(n),
        _ => Err(format!("`{t}` is not a size from 1 to 16384")),
    };
    Ok((side(w)?, side(h)?))
}

/// `AZIMUTH,ELEVATION` in degrees.
fn parse_view(s: &str) -> Result<(f32, f32), String> {
    let (a, e) = s
        .split_once(',')
        .ok_or_else(|| format!("`{s}` is not AZIMUTH,ELEVATION"))?;
    let angle = |t: &str| match t.trim().parse::<f32>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("`{t}` is not an angle in degrees")),
    };
    Ok((angle(a)?, angle(e)?))
}

pub fn run(args: Args) -> lrmesh::Result<()> {
    // The legend takes a band at the bottom of the size asked for, when there is room.
    let band = render::legend_height(args.size.0);
    let legend = !args.no_legend && args.size.1 >= 2 * band;
    let options = RenderOptions {
        width: args.size.0,
        height: args.size.1 - if legend { band } else { 0 },
        mode: match args.mode {
            RenderMode::Ring => ColorMode::Ring,
            RenderMode::Classes => ColorMode::Classes,
        },
        azimuth: args.view.0,
        elevation: args.view.1,
        up: match args.up {
            UpAxis::X => Axis::X,
            UpAxis::Y => Axis::Y,
            UpAxis::Z => Axis::Z,
        },
        perspective: args.perspective,
        samples: args.samples,
        ring_lines: args.ring_lines,
        ..RenderOptions::default()
    };
    let mesh = &args.input.path;
    let image = if let Some(bytes) = args.input.container()? {
        let view =
            read::open_verified(&bytes, &Limits::default()).map_err(|e| e.with_file(mesh))?;
        let positions = view.positions();
        if let Some(lr) = view.lr() {
            progress::step("rendering", || render::render(lr, &positions, &options))?
        } else if let Some(lr) = view.lr_compact() {
            progress::step("rendering", || render::render(lr, &positions, &options))?
        } else {
            return Err(Error::Unsupported(format!(
                "{}: render needs LR connectivity (lr or lr-compact), the file holds {}",
                mesh.display(),
                view.kind().name()
            )));
        }
    } else {
        let input = args.input.load()?;
        let table = progress::step("building the corner table", || {
            CornerTable::from_mesh(&input)
        })?;
        let lr = progress::step("building the LR", || {
            Lr::build(
                &table,
                &LrOptions {
                    tries: args.tries,
                    seed: args.seed,
                    ..LrOptions::default()
                },
            )
        })?;
        let positions: Vec<[f32; 3]> = (0..lr.vertex_id_bound())
            .map(|v| input.positions[lr.input_vertex(Vertex(v)) as usize])
            .collect();
        progress::step("rendering", || {
            render::render(lr.tables(), &positions, &options)
        })?
    };
    let image = if legend {
        render::with_legend(&image, options.mode)
    } else {
        image
    };
    let output = &args.output;
    let mut png = Vec::new();
    image.write_png(&mut png).map_err(|source| Error::Io {
        path: output.clone(),
        source,
    })?;
    write_out(output, &png)?;
    eprintln!(
        "wrote {}: {}x{} pixels",
        output.display(),
        image.width(),
        image.height()
    );
    Ok(())
}
