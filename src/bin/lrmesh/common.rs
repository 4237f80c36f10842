//! What every command shares: output that survives a closed pipe, reading meshes with their
//! warnings, memory-mapping containers.

use std::path::{Path, PathBuf};

use lrmesh::io::{self, MeshFormat, ReadOptions};
use lrmesh::{Error, Mesh};

use crate::progress;

/// Prints a line to stdout; a closed pipe (`lrmesh info x | head`) is not an error.
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write;
        let _ = writeln!(std::io::stdout(), $($arg)*);
    }};
}
pub(crate) use say;

/// Prints text to stdout as it is, ignoring a closed pipe.
pub fn show(text: impl std::fmt::Display) {
    use std::io::Write;
    let _ = write!(std::io::stdout(), "{text}");
}

/// Prints a value as pretty JSON.
pub fn show_json(value: &impl serde::Serialize) {
    match serde_json::to_string_pretty(value) {
        Ok(text) => say!("{text}"),
        Err(e) => eprintln!("error: the report does not serialise: {e}"),
    }
}

/// A mesh to read: a file, or standard input (`-`), and how to read it. Every command that
/// reads a mesh takes these.
#[derive(clap::Args)]
pub struct MeshInput {
    /// The mesh (.obj, .off, .ply, .stl, .gltf, .glb; a container .lrm where the command
    /// reads one), or `-` for standard input
    #[arg(value_name = "INPUT")]
    pub path: PathBuf,
    /// The input's format, for standard input or a name without its extension (a container
    /// on standard input is recognised without it)
    #[arg(long, value_enum, value_name = "FORMAT")]
    pub format: Option<Format>,
    /// Merge vertices with identical positions into shared vertices (any input format:
    /// attributes that differ between them become per corner)
    #[arg(long)]
    pub weld: bool,
    /// With --weld, also merge vertices whose coordinates all differ by at most DISTANCE
    /// (each into the first one that close, taking its position)
    #[arg(long, value_name = "DISTANCE", requires = "weld")]
    pub weld_tolerance: Option<f32>,
}

/// Mesh formats named on the command line.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    Obj,
    Off,
    Ply,
    Stl,
    Gltf,
    Glb,
    /// The lrmesh container.
    Lrm,
}

impl From<Format> for MeshFormat {
    fn from(f: Format) -> MeshFormat {
        match f {
            Format::Obj => MeshFormat::Obj,
            Format::Off => MeshFormat::Off,
            Format::Ply => MeshFormat::Ply,
            Format::Stl => MeshFormat::Stl,
            Format::Gltf => MeshFormat::Gltf,
            Format::Glb => MeshFormat::Glb,
            Format::Lrm => MeshFormat::Lrm,
        }
    }
}

/// Whether `path` is `-`: standard input or output.
pub fn is_stdio(path: &Path) -> bool {
    path.as_os_str() == "-"
}

/// Standard input, whole.
fn stdin_bytes() -> lrmesh::Result<Vec<u8>> {
    use std::io::Read;
    let mut bytes = Vec::new();
    std::io::stdin()
        .lock()
        .read_to_end(&mut bytes)
        .map_err(|source| Error::Io {
            path: "-".into(),
            source,
        })?;
    Ok(bytes)
}

/// The format of `bytes` read from standard input: `format`, or without it a container
/// recognised by its first bytes (nothing else is).
fn stdin_format(bytes: &[u8], format: Option<Format>) -> lrmesh::Result<MeshFormat> {
    match format {
        Some(f) => Ok(f.into()),
        None if bytes.starts_with(&lrmesh::format::MAGIC) => Ok(MeshFormat::Lrm),
        None => Err(Error::InvalidArgument(
            "a mesh on standard input needs --format (obj, off, ply, stl, gltf or glb)".into(),
        )),
    }
}

/// The bytes of a container: a mapped file, or standard input read whole.
pub enum Bytes {
    Mapped(memmap2::Mmap),
    Read(Vec<u8>),
}

impl std::ops::Deref for Bytes {
    type Target = [u8];
    fn deref(&self) -> &[u8] {
        match self {
            Bytes::Mapped(m) => m,
            Bytes::Read(v) => v,
        }
    }
}

/// The bytes of the container `path` names (`-`: standard input).
pub fn read_container(path: &Path) -> lrmesh::Result<Bytes> {
    if is_stdio(path) {
        stdin_bytes().map(Bytes::Read)
    } else {
        map(path).map(Bytes::Mapped)
    }
}

impl MeshInput {
    /// Whether the input is a container: by `--format`, by its extension, or on standard
    /// input by its first bytes (which are then read and kept).
    pub fn container(&self) -> lrmesh::Result<Option<Bytes>> {
        let named = match self.format {
            Some(f) => f == Format::Lrm,
            None => is_container(&self.path),
        };
        if is_stdio(&self.path) && self.format.is_none() {
            let bytes = stdin_bytes()?;
            stdin_format(&bytes, None)?;
            return Ok(Some(Bytes::Read(bytes)));
        }
        if named {
            return read_container(&self.path).map(Some);
        }
        Ok(None)
    }

    /// Reads the mesh (a container is decoded, fully validated), printing the reader's
    /// warnings, welded as asked.
    pub fn load(&self) -> lrmesh::Result<Mesh> {
        let path = &self.path;
        let options = ReadOptions { weld: self.weld };
        let loaded = progress::step(&format!("reading {}", path.display()), || {
            let from_bytes = |bytes: &[u8], format: MeshFormat| {
                io::read_mesh_bytes(bytes, format, &options).map_err(|e| e.with_file(path))
            };
            match (is_stdio(path), self.format) {
                (true, format) => {
                    let bytes = stdin_bytes()?;
                    from_bytes(&bytes, stdin_format(&bytes, format)?)
                }
                (false, Some(f)) if MeshFormat::from_path(path).ok() != Some(f.into()) => {
                    let bytes = std::fs::read(path).map_err(|source| Error::Io {
                        path: path.clone(),
                        source,
                    })?;
                    from_bytes(&bytes, f.into())
                }
                _ => io::read_mesh(path, &options),
            }
        })?;
        for warning in &loaded.warnings {
            eprintln!("warning: {}: {warning}", path.display());
        }
        Ok(match self.weld_tolerance {
            Some(t) => loaded.mesh.weld_within(t),
            None => loaded.mesh,
        })
    }
}

/// Where a command's report goes: standard output, or standard error when the command's
/// data goes to standard output (`-o -`), so that a pipe carries the data alone.
pub struct Report {
    to_stderr: bool,
}

impl Report {
    pub fn new(data_on_stdout: bool) -> Report {
        Report {
            to_stderr: data_on_stdout,
        }
    }

    /// One line of text.
    pub fn line(&self, text: &str) {
        if self.to_stderr {
            eprintln!("{text}");
        } else {
            say!("{text}");
        }
    }

    /// A value as pretty JSON.
    pub fn json(&self, value: &impl serde::Serialize) {
        match serde_json::to_string_pretty(value) {
            Ok(text) => self.line(&text),
            Err(e) => eprintln!("error: the report does not serialise: {e}"),
        }
    }
}

/// Milliseconds of a duration.
pub fn ms(d: std::time::Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// Maps a container file read-only.
pub fn map(path: &Path) -> lrmesh::Result<memmap2::Mmap> {
    let io_error = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let file = std::fs::File::open(path).map_err(io_error)?;
    // SAFETY: the mapping is read-only and the library only reads it as a `&[u8]`, checking
    // every offset against its length. The remaining hazard is another process changing or
    // truncating the file while we run (changed bytes, or SIGBUS on truncation): the exposure
    // of any program that reads a file being rewritten under it, which a command-line tool
    // accepts. The library itself never maps files (a "safe" mapping API would be unsound).
    unsafe { memmap2::Mmap::map(&file) }.map_err(io_error)
}

/// Whether `path` names a container (`.lrm`).
pub fn is_container(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("lrm"))
}

/// Writes `bytes` to the file `path`, or to standard output (`-`).
pub fn write_out(path: &Path, bytes: &[u8]) -> lrmesh::Result<()> {
    use std::io::Write;
    let result = if is_stdio(path) {
        let mut out = std::io::stdout().lock();
        out.write_all(bytes).and_then(|()| out.flush())
    } else {
        std::fs::write(path, bytes)
    };
    result.map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// The format of an output: `format` when given, else the extension of `path` (standard
/// output, `-`, needs `format`).
pub fn output_format(path: &Path, format: Option<Format>) -> lrmesh::Result<MeshFormat> {
    match format {
        Some(f) => Ok(f.into()),
        None if is_stdio(path) => Err(Error::InvalidArgument(
            "writing a mesh to standard output needs --format (obj, off, ply, stl, gltf, glb)"
                .into(),
        )),
        None => MeshFormat::from_path(path),
    }
}

/// Writes a mesh as `format` (STL binary unless `ascii`) to the file `path` or standard
/// output (`-`), first warning on stderr about what the format cannot keep.
pub fn save(path: &Path, format: MeshFormat, mesh: &Mesh, ascii: bool) -> lrmesh::Result<()> {
    if ascii && format != MeshFormat::Stl {
        return Err(Error::InvalidArgument(format!(
            "--ascii applies to STL output only, not to {}",
            path.display()
        )));
    }
    for loss in losses(mesh, format) {
        eprintln!("warning: {}: {loss}", path.display());
    }
    progress::step("writing", || {
        if !ascii && !is_stdio(path) && MeshFormat::from_path(path).ok() == Some(format) {
            return io::write_mesh(path, mesh);
        }
        let mut bytes = Vec::new();
        if ascii {
            mesh.validate()?;
            io::stl::write_ascii(&mut bytes, mesh).map_err(|source| Error::Io {
                path: path.to_path_buf(),
                source,
            })?;
        } else {
            io::write_mesh_to(&mut bytes, mesh, format)?;
        }
        write_out(path, &bytes)
    })
}

/// What writing `mesh` as `format` loses, in words (nothing for the formats that keep all).
fn losses(mesh: &Mesh, format: MeshFormat) -> Vec<String> {
    let mut out = Vec::new();
    let libraries = mesh
        .parts
        .as_ref()
        .map_or(0, |p| p.material_libraries.len());
    match format {
        MeshFormat::Stl => {
            if !mesh.attributes.is_empty() {
                let names: Vec<String> = mesh
                    .attributes
                    .iter()
                    .map(|a| a.semantic.to_string())
                    .collect();
                out.push(format!(
                    "STL keeps positions only: the attributes {} are dropped",
                    names.join(", ")
                ));
            }
            if let Some(parts) = &mesh.parts {
                let n = parts.parts.len();
                out.push(format!(
                    "STL has no objects, groups or materials: the mesh's {n} part{} dropped",
                    if n == 1 { " is" } else { "s are" }
                ));
            }
        }
        MeshFormat::Gltf | MeshFormat::Glb if libraries > 0 => out.push(format!(
            "glTF has no material libraries: {libraries} mtllib references are dropped \
             (material names are kept)"
        )),
        _ => {}
    }
    out
}

/// How many threads a command's parallel phases use.
#[derive(clap::Args)]
pub struct Threads {
    /// Threads for the phases that run in parallel (ring tries, irregular triangles,
    /// position blocks); the default is every core. The output is the same for any count.
    #[arg(long, value_name = "N")]
    threads: Option<std::num::NonZeroU32>,
}

impl Threads {
    /// The count asked for, or the machine's available parallelism.
    pub fn get(&self) -> u32 {
        match self.threads {
            Some(n) => n.get(),
            None => std::thread::available_parallelism().map_or(1, |n| n.get() as u32),
        }
    }
}
