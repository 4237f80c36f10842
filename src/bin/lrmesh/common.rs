//! What every command shares: output that survives a closed pipe, reading meshes with their
//! warnings, memory-mapping containers.

use std::path::Path;

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

/// Reads a mesh file, printing the reader's warnings.
pub fn load(path: &Path, weld: bool) -> lrmesh::Result<Mesh> {
    let loaded = progress::step(&format!("reading {}", path.display()), || {
        io::read_mesh(path, &ReadOptions { weld })
    })?;
    for warning in &loaded.warnings {
        eprintln!("warning: {}: {warning}", path.display());
    }
    Ok(loaded.mesh)
}

/// Writes a mesh file in the format of its extension (STL binary unless `ascii`), first
/// warning on stderr about what the format cannot keep.
pub fn save(path: &Path, mesh: &Mesh, ascii: bool) -> lrmesh::Result<()> {
    let format = MeshFormat::from_path(path)?;
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
        if !ascii {
            return io::write_mesh(path, mesh);
        }
        mesh.validate()?;
        let io_error = |source| Error::Io {
            path: path.to_path_buf(),
            source,
        };
        let file = std::fs::File::create(path).map_err(io_error)?;
        io::stl::write_ascii(file, mesh).map_err(io_error)
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
