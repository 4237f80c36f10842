//! One-run comparison of the connectivity representations (`lrmesh bench`, and the `lr`
//! bench): corner table, standard and compact (bit-efficient) LR (each owned, and as the
//! zero-copy view of the `.lrm` bytes), Edgebreaker and constrained strips. Size, build and open
//! times, and the loops of the LR paper's Fig. 10 (c.v and c.o over every corner, valence and
//! normal of every vertex, contour walks) as ratios to the corner table, all timed in the same
//! process with [`std::time::Instant`], each step the median of several runs. The loops of all
//! representations are timed in rounds ([`interleaved_loops`]), so that a drift in the
//! machine's speed does not move one representation's figures against another's.
//!
//! The loops live here once, for this report and for the bench binaries.

use std::hint::black_box;
use std::time::{Duration, Instant};

use crate::corner_table::CornerTable;
use crate::edgebreaker;
use crate::error::Result;
use crate::ids::Vertex;
use crate::lr::{CompactLr, CompactOptions, Lr, LrOptions, Zipper};
use crate::mesh::Mesh;
use crate::ops::CornerOps;
use crate::read;
use crate::strips::{Cts, StripOptions};
use crate::write::{self, EncodeOptions};

mod loops;
pub use loops::{contour_starts, fig10_loops, interleaved_loops, Fig10, LoopTimes, LOOP_NAMES};

/// The median wall-clock time of `runs` calls of `f` (at least one), its result kept alive
/// past the timer.
///
/// Within [`run`], each call is also recorded with its fastest and slowest run, under the
/// step [`run`] is at (the report's `timings`).
pub fn median_time<R>(runs: usize, mut f: impl FnMut() -> R) -> Duration {
    let times: Vec<Duration> = (0..runs.max(1))
        .map(|_| {
            let start = Instant::now();
            black_box(f());
            start.elapsed()
        })
        .collect();
    record(None, times)
}

/// The median of `times`, recorded (within [`run`]) with their fastest and slowest under
/// `step`, or the step [`run`] is at.
fn record(step: Option<String>, mut times: Vec<Duration>) -> Duration {
    times.sort();
    let median = times[times.len() / 2];
    RECORD.with_borrow_mut(|record| {
        if let Some((at, timings)) = record {
            timings.push(Timing {
                step: step.unwrap_or_else(|| at.clone()),
                min_ms: ms(times[0]),
                median_ms: ms(median),
                max_ms: ms(times[times.len() - 1]),
            });
        }
    });
    median
}

thread_local! {
    /// While [`run`] runs on this thread: the step it is at, and the timings so far.
    static RECORD: std::cell::RefCell<Option<(String, Vec<Timing>)>> =
        const { std::cell::RefCell::new(None) };
}

/// One timed measurement of [`run`]: its fastest, median and slowest run.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Timing {
    /// The step of the report it belongs to (`corner table`, `LR (owned)`, …).
    pub step: String,
    /// The fastest run, in milliseconds.
    pub min_ms: f64,
    /// The median run.
    pub median_ms: f64,
    /// The slowest run.
    pub max_ms: f64,
}

impl Timing {
    /// How far apart the runs were: `(max - min) / median`.
    pub fn spread(&self) -> f64 {
        (self.max_ms - self.min_ms) / self.median_ms.max(1e-9)
    }
}

/// Measurements shorter than this are not judged by their spread (timer noise).
const JUDGED_MS: f64 = 1.0;
/// A spread above this says the machine was busy while the runs ran.
const BUSY_SPREAD: f64 = 0.5;

/// The median time of copying `bytes` into a buffer of their size (allocated once): the
/// baseline that an open of the same bytes is measured against.
fn memcpy_time(runs: usize, bytes: &[u8]) -> Duration {
    let mut copy = vec![0u8; bytes.len()];
    // Once untimed: the first copy faults the buffer's pages in (8 ms of a 25 MB file, which
    // made every large run's spread look like a busy machine's).
    copy.copy_from_slice(black_box(bytes));
    median_time(runs, || {
        copy.copy_from_slice(black_box(bytes));
        black_box(copy.as_ptr());
    })
}

/// Options of [`run`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BenchOptions {
    /// Timed runs of every step; medians are reported.
    pub runs: usize,
    /// LR construction options (owned LR and the container).
    pub lr: LrOptions,
    /// Stripping options of the CTS.
    pub strips: StripOptions,
}

impl Default for BenchOptions {
    fn default() -> Self {
        BenchOptions {
            runs: 5,
            lr: LrOptions::default(),
            strips: StripOptions::default(),
        }
    }
}

/// One representation's row of the report. JSON keys are the field names; times in
/// milliseconds, loops as ratios of time per item to the corner table's (`null` where the
/// representation has no such step or no random access).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BenchRow {
    /// The representation.
    pub name: &'static str,
    /// Bytes of connectivity.
    pub bytes: u64,
    /// Connectivity bits per triangle.
    pub bits_per_triangle: f64,
    /// Construction time (see [`BenchReport`] for what each row's build covers).
    pub build_ms: Option<f64>,
    /// Time to open the stored form: [`read::open`] (well formed) for a view, decoding for
    /// Edgebreaker.
    pub open_ms: Option<f64>,
    /// Time of [`read::open_verified`] (every rule, the semantic ones included) for a view.
    pub verify_ms: Option<f64>,
    /// Time to copy the bytes that `open_ms` opens (the whole `.lrm` of a view, the stream
    /// for Edgebreaker), in the same run: open as a ratio to memory speed.
    pub memcpy_ms: Option<f64>,
    /// The Fig. 10 loops' time per item as ratios to the corner table's; `None` without
    /// random access.
    pub loops: Option<LoopFigures>,
}

/// One figure per Fig. 10 loop.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct LoopFigures {
    /// c.v over every corner.
    pub c_v: f64,
    /// c.o over every corner.
    pub c_o: f64,
    /// Valence of every vertex.
    pub valence: f64,
    /// Normal of every vertex.
    pub normals: f64,
    /// Contour walks (per triangle walked).
    pub contour: f64,
}

impl LoopFigures {
    fn new(f: [f64; 5]) -> LoopFigures {
        LoopFigures {
            c_v: f[0],
            c_o: f[1],
            valence: f[2],
            normals: f[3],
            contour: f[4],
        }
    }

    /// The figures in the order of [`LOOP_NAMES`].
    pub fn to_array(&self) -> [f64; 5] {
        [self.c_v, self.c_o, self.valence, self.normals, self.contour]
    }
}

/// The comparison of [`run`]: one row per representation, the corner table first.
///
/// Build times: the corner table from the mesh; owned LR, owned compact LR (every period of
/// [`CompactOptions`], the smallest kept), Edgebreaker and strips from the corner table; the
/// views' is the whole container's encoding from the mesh ([`write::encode`]). Open times:
/// [`read::open`] (validation) for the views, decoding for Edgebreaker.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BenchReport {
    /// Vertices of the mesh as read.
    pub vertices: usize,
    /// Triangles of the mesh as read.
    pub triangles: usize,
    /// Timed runs per step.
    pub runs: usize,
    /// The corner table's nanoseconds per item of each loop (the ratios' baseline).
    pub baseline_ns: LoopFigures,
    /// The rows.
    pub rows: Vec<BenchRow>,
    /// The largest `(max - min) / median` of the timed measurements of at least 1 ms.
    pub spread: f64,
    /// Set when that spread is above 0.5: the machine was busy.
    pub warning: Option<String>,
    /// Every timed measurement, with its fastest, median and slowest run.
    pub timings: Vec<Timing>,
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// A row with sizes and times (its loops are filled in once every row's are timed).
fn row(
    name: &'static str,
    bytes: u64,
    triangles: usize,
    build: Option<Duration>,
    open: Option<(Duration, Duration)>,
) -> BenchRow {
    BenchRow {
        name,
        bytes,
        bits_per_triangle: 8.0 * bytes as f64 / triangles.max(1) as f64,
        build_ms: build.map(ms),
        open_ms: open.map(|(open, _)| ms(open)),
        verify_ms: None,
        memcpy_ms: open.map(|(_, copy)| ms(copy)),
        loops: None,
    }
}

/// The input position of each vertex of `ops` (`input_vertex` maps it back; the origin for
/// an id with no input vertex).
fn input_positions(
    mesh: &Mesh,
    ops: &impl CornerOps,
    input_vertex: impl Fn(Vertex) -> u32,
) -> Vec<[f32; 3]> {
    (0..ops.vertex_id_bound())
        .map(|v| {
            let input = input_vertex(Vertex(v)) as usize;
            mesh.positions.get(input).copied().unwrap_or([0.0; 3])
        })
        .collect()
}

/// The row of a view of a container's bytes, for a mesh of `n` triangles: `timed` holds the
/// bytes, the time that encoded them and the runs per step. Times opening, verifying and a
/// memcpy of the same bytes; returns the row and the view's positions (for its loops).
fn view_row(
    name: &'static str,
    timed: (&[u8], Duration, usize),
    view: &read::Container,
    n: usize,
) -> (BenchRow, Vec<[f32; 3]>) {
    let (bytes, encode_time, runs) = timed;
    let limits = read::Limits::default();
    let open_time = median_time(runs, || {
        read::open(bytes, &limits).map(|v| v.triangle_count())
    });
    let positions = view.positions();
    let verify_time = median_time(runs, || {
        read::open_verified(bytes, &limits).map(|v| v.triangle_count())
    });
    let mut r = row(
        name,
        view.summary().connectivity_bytes,
        n,
        Some(encode_time),
        Some((open_time, memcpy_time(runs, bytes))),
    );
    r.verify_ms = Some(ms(verify_time));
    (r, positions)
}

/// Builds every representation of `mesh` and times it, reporting each step's name to
/// `progress` before it starts. A mesh that the encoders put in a cache-friendly order
/// ([`write::encoding_order`]) is put in it first, so that every row, the corner table's
/// too, works on the mesh that `encode` builds from. The loops of every representation are
/// timed last, together ([`interleaved_loops`]).
///
/// # Errors
/// Those of the constructions ([`CornerTable::from_mesh`], [`Lr::build`], [`write::encode`],
/// [`edgebreaker::encode`], [`Cts::build`]) on this mesh.
pub fn run(
    mesh: &Mesh,
    options: &BenchOptions,
    progress: &mut dyn FnMut(&str),
) -> Result<BenchReport> {
    let order = write::encoding_order(mesh, &EncodeOptions::default())?;
    let ordered = order.map(|o| o.apply_valid(mesh));
    let mesh = ordered.as_ref().unwrap_or(mesh);
    let runs = options.runs.max(1);
    let n = mesh.triangles.len();
    let mut rows = Vec::new();
    RECORD.set(Some((String::new(), Vec::new())));
    let progress = &mut |step: &str| {
        RECORD.with_borrow_mut(|r| {
            if let Some((at, _)) = r {
                *at = step.to_string();
            }
        });
        progress(step)
    };

    progress("corner table");
    let table = CornerTable::from_mesh(mesh)?;
    let ct_build = median_time(runs, || CornerTable::from_mesh(mesh));
    let ct_positions = table.extend_to_copies(&mesh.positions);
    let ct_refs = table.v_table().len() + table.o_table().len() + table.c_table().len();
    rows.push(row(
        "corner table",
        4 * ct_refs as u64,
        n,
        Some(ct_build),
        None,
    ));

    progress("LR (owned)");
    let lr = Lr::build(&table, &options.lr)?;
    let lr_build = median_time(runs, || Lr::build(&table, &options.lr));
    let lr_positions = input_positions(mesh, &lr, |v| lr.input_vertex(v));
    let lr_bytes = 4 * lr.tables().references();
    rows.push(row("LR (owned)", lr_bytes, n, Some(lr_build), None));

    let limits = read::Limits::default();
    let encoded = |connectivity| {
        let encode_options = EncodeOptions {
            connectivity,
            lr: options.lr,
            ..EncodeOptions::default()
        };
        let bytes = write::encode(mesh, &encode_options)?;
        let encode_time = median_time(runs, || write::encode(mesh, &encode_options));
        Ok::<_, crate::Error>((bytes, encode_time))
    };

    progress("LR (view of the .lrm bytes)");
    let (lr_file, encode_time) = encoded(write::Connectivity::Lr)?;
    let lr_view = read::open(&lr_file, &limits)?;
    let (lr_view_row, lr_view_positions) =
        view_row("LR (view)", (&lr_file, encode_time, runs), &lr_view, n);
    rows.push(lr_view_row);

    progress("compact LR (owned)");
    let compact_options = CompactOptions {
        lr: options.lr,
        ..CompactOptions::default()
    };
    let compact = CompactLr::build(&table, &compact_options)?;
    let compact_build = median_time(runs, || CompactLr::build(&table, &compact_options));
    let compact_positions = input_positions(mesh, compact.tables(), |v| compact.input_vertex(v));
    let compact_bytes = compact.stored_bytes();
    rows.push(row(
        "compact LR (owned)",
        compact_bytes,
        n,
        Some(compact_build),
        None,
    ));

    progress("compact LR (view of the .lrm bytes)");
    let (compact_file, encode_time) = encoded(write::Connectivity::LrCompact)?;
    let compact_view = read::open(&compact_file, &limits)?;
    let timed = (&compact_file[..], encode_time, runs);
    let (compact_view_row, compact_view_positions) =
        view_row("compact LR (view)", timed, &compact_view, n);
    rows.push(compact_view_row);

    progress("Zipper (owned)");
    let zipper = Zipper::build(&table, &options.lr)?;
    let zipper_build = median_time(runs, || Zipper::build(&table, &options.lr));
    let zipper_positions = input_positions(mesh, zipper.tables(), |v| zipper.input_vertex(v));
    let zipper_bytes = zipper.tables().stored_bytes();
    rows.push(row(
        "Zipper (owned)",
        zipper_bytes,
        n,
        Some(zipper_build),
        None,
    ));

    progress("Zipper (view of the .lrm bytes)");
    let (zipper_file, encode_time) = encoded(write::Connectivity::Zipper)?;
    let zipper_view = read::open(&zipper_file, &limits)?;
    let timed = (&zipper_file[..], encode_time, runs);
    let (zipper_view_row, zipper_view_positions) =
        view_row("Zipper (view)", timed, &zipper_view, n);
    // The same view read through a cursor (`ZipperTables::cursor`): its build is making the
    // cursor (its empty cache), then its loops.
    let cursor_build = zipper_view
        .zipper()
        .map(|tables| median_time(runs, || tables.cursor()));
    let cursor_row = row(
        "Zipper (cursor)",
        zipper_view_row.bytes,
        n,
        cursor_build,
        None,
    );
    rows.push(zipper_view_row);
    rows.push(cursor_row);

    progress("Edgebreaker");
    let eb = edgebreaker::encode(&table)?;
    let eb_build = median_time(runs, || edgebreaker::encode(&table));
    let eb_limits = edgebreaker::Limits::default();
    let eb_decode = median_time(runs, || edgebreaker::decode(&eb.bytes, &eb_limits));
    let eb_open = (eb_decode, memcpy_time(runs, &eb.bytes));
    rows.push(row(
        "Edgebreaker",
        eb.bytes.len() as u64,
        n,
        Some(eb_build),
        Some(eb_open),
    ));

    progress("strips (CTS)");
    let cts = Cts::build(&table, &options.strips)?;
    let cts_build = median_time(runs, || Cts::build(&table, &options.strips));
    let cts_bytes = (cts.bits_per_triangle() * cts.triangle_count() as f64 / 8.0).round() as u64;
    rows.push(row("strips (CTS)", cts_bytes, n, Some(cts_build), None));

    progress("Fig. 10 loops (every representation, interleaved)");
    // The loops run on each view's own tables, not through `read::Connectivity`'s dispatch.
    let zipper_cursor = zipper_view.zipper().map(|tables| tables.cursor());
    let mut subjects = vec![
        ("corner table", Fig10::new(&table, &ct_positions)),
        ("LR (owned)", Fig10::new(&lr, &lr_positions)),
    ];
    if let Some(tables) = lr_view.lr() {
        subjects.push(("LR (view)", Fig10::new(tables, &lr_view_positions)));
    }
    subjects.push((
        "compact LR (owned)",
        Fig10::new(compact.tables(), &compact_positions),
    ));
    if let Some(tables) = compact_view.lr_compact() {
        subjects.push((
            "compact LR (view)",
            Fig10::new(tables, &compact_view_positions),
        ));
    }
    subjects.push((
        "Zipper (owned)",
        Fig10::new(zipper.tables(), &zipper_positions),
    ));
    if let (Some(tables), Some(cursor)) = (zipper_view.zipper(), &zipper_cursor) {
        subjects.push(("Zipper (view)", Fig10::new(tables, &zipper_view_positions)));
        // Each run from an empty cache: on a mesh of a few hundred blocks, the blocks a run
        // leaves decoded would answer much of the next run.
        subjects.push((
            "Zipper (cursor)",
            Fig10::with_reset(cursor, &zipper_view_positions, || cursor.clear()),
        ));
    }
    subjects.push(("strips (CTS)", Fig10::new(&cts, &ct_positions)));
    let timed = interleaved_loops(&subjects, runs);
    for ((name, _), (_, ratios)) in subjects.iter().zip(&timed) {
        if let Some(r) = rows.iter_mut().find(|r| r.name == *name) {
            r.loops = Some(LoopFigures::new(*ratios));
        }
    }
    let ct_loops = &timed[0].0;

    let timings = RECORD.take().map(|(_, t)| t).unwrap_or_default();
    let judged = timings.iter().filter(|t| t.median_ms >= JUDGED_MS);
    let worst = judged.max_by(|a, b| a.spread().total_cmp(&b.spread()));
    let spread = worst.map_or(0.0, Timing::spread);
    let warning = worst
        .filter(|t| runs > 1 && t.spread() > BUSY_SPREAD)
        .map(|t| {
            format!(
                "the runs of a step differ by {:.0}% of its median ({}: {:.2} to {:.2} ms): the \
             machine was busy and the figures are unreliable; rerun on a quiet machine or with \
             more --runs",
                100.0 * t.spread(),
                t.step,
                t.min_ms,
                t.max_ms
            )
        });
    Ok(BenchReport {
        vertices: mesh.positions.len(),
        triangles: n,
        runs,
        baseline_ns: LoopFigures::new([0, 1, 2, 3, 4].map(|i| ct_loops.ns_per_item(i))),
        rows,
        spread,
        warning,
        timings,
    })
}

impl std::fmt::Display for BenchReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(
            f,
            "mesh: {} vertices, {} triangles; median of {} runs per step",
            self.vertices, self.triangles, self.runs
        )?;
        writeln!(
            f,
            "{:<20} {:>11} {:>9} {:>10} {:>10} {:>9} {:>10} {:>7} {:>7} {:>8} {:>8} {:>8}",
            "representation",
            "bytes",
            "bits/tri",
            "build ms",
            "open ms",
            "/memcpy",
            "verify ms",
            "c.v",
            "c.o",
            "valence",
            "normals",
            "contour"
        )?;
        let opt = |x: Option<f64>, width: usize, digits: usize| match x {
            Some(x) => format!("{x:>width$.digits$}"),
            None => format!("{:>width$}", "-"),
        };
        for r in &self.rows {
            let l = r.loops.map(|l| l.to_array());
            writeln!(
                f,
                "{:<20} {:>11} {:>9.2} {} {} {} {} {} {} {} {} {}",
                r.name,
                r.bytes,
                r.bits_per_triangle,
                opt(r.build_ms, 10, 2),
                opt(r.open_ms, 10, 2),
                opt(
                    r.open_ms.zip(r.memcpy_ms).map(|(o, c)| o / c.max(1e-9)),
                    9,
                    0
                ),
                opt(r.verify_ms, 10, 2),
                opt(l.map(|l| l[0]), 7, 2),
                opt(l.map(|l| l[1]), 7, 2),
                opt(l.map(|l| l[2]), 8, 2),
                opt(l.map(|l| l[3]), 8, 2),
                opt(l.map(|l| l[4]), 8, 2),
            )?;
        }
        write!(f, "loops: time per item as a ratio to the corner table's (")?;
        for (i, (name, ns)) in LOOP_NAMES
            .iter()
            .zip(self.baseline_ns.to_array())
            .enumerate()
        {
            let sep = if i == 0 { "" } else { ", " };
            write!(f, "{sep}{name} {ns:.2} ns")?;
        }
        writeln!(f, ")")?;
        writeln!(
            f,
            "build: corner table from the mesh; owned LRs, Edgebreaker, CTS from the corner \
             table; views: the whole .lrm encoded from the mesh. open: the well-formed check of \
             the .lrm (views), decoding (Edgebreaker); /memcpy: open as a ratio to copying the \
             same bytes; verify: every rule, the semantic ones included (views)"
        )?;
        writeln!(
            f,
            "spread: the runs of a step (1 ms or more) differ by at most {:.0}% of its median",
            100.0 * self.spread
        )?;
        if let Some(w) = &self.warning {
            writeln!(f, "warning: {w}")?;
        }
        Ok(())
    }
}
