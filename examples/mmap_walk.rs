//! Memory-maps an `.lrm` container, opens the zero-copy view of its LR, and walks the
//! neighbours of a vertex with the corner operators, straight from the mapped bytes.
//!
//! ```sh
//! cargo run --example mmap_walk [FILE.lrm] [VERTEX]
//! ```
//!
//! Without a file it first encodes the bunny shipped in `corpus/meshes/` into the system's
//! temporary folder (as `cargo run --example load_and_save` does); the vertex defaults to 0.

use std::path::PathBuf;

use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::ops::{self, CornerOps};
use lrmesh::read::{self, Limits};
use lrmesh::write::{self, EncodeOptions};
use lrmesh::{Error, Vertex};

fn main() -> Result<(), Error> {
    let mut args = std::env::args_os().skip(1);
    let path = match args.next() {
        Some(path) => PathBuf::from(path),
        None => encode_the_bunny()?,
    };
    let vertex: u32 = args
        .next()
        .and_then(|s| s.to_str()?.parse().ok())
        .unwrap_or(0);

    let io_error = |source| Error::Io {
        path: path.clone(),
        source,
    };
    let file = std::fs::File::open(&path).map_err(io_error)?;
    // SAFETY: the mapping is read-only and only read as a `&[u8]`, every offset checked by the
    // library. Another process truncating or rewriting the file while we run could still
    // change the bytes under us (or raise SIGBUS): the hazard of any program reading a file
    // that is being rewritten, accepted here.
    let bytes = unsafe { memmap2::Mmap::map(&file) }.map_err(io_error)?;

    // One linear validation pass; afterwards the operators read the mapped bytes in place.
    let view = read::open(&bytes, &Limits::default()).map_err(|e| e.with_file(&path))?;
    let lr = view
        .lr()
        .ok_or_else(|| Error::InvalidMesh(format!("{}: not an LR container", path.display())))?;
    println!(
        "{}: {} vertices, {} triangles",
        path.display(),
        lr.vertex_id_bound(),
        view.triangle_count()
    );
    if vertex >= lr.vertex_id_bound() {
        return Err(Error::InvalidMesh(format!(
            "vertex {vertex} is not below {}",
            lr.vertex_id_bound()
        )));
    }
    let v = Vertex(vertex);
    let p = view.position(v);
    println!(
        "vertex {vertex} at ({:.4}, {:.4}, {:.4}), valence {}",
        p[0],
        p[1],
        p[2],
        ops::valence(lr, v)
    );

    // The star of v: every corner c at v, one per incident triangle, found by swinging
    // (c.s = c.n.o.n). The neighbour across the edge facing c.p is c.n.v.
    for c in ops::star(lr, v) {
        let neighbour = lr.vertex(lr.next(c));
        let q = view.position(neighbour);
        let across = match lr.opposite(lr.prev(c)) {
            Some(o) => format!("triangle {} across", lr.triangle(o).0),
            None => "boundary".to_string(),
        };
        println!(
            "  corner {:>6} in triangle {:>6}: neighbour {:>5} at ({:.4}, {:.4}, {:.4}), {across}",
            c.0,
            lr.triangle(c).0,
            neighbour.0,
            q[0],
            q[1],
            q[2]
        );
    }
    Ok(())
}

/// Writes the shipped bunny as an LR container in the temporary folder.
fn encode_the_bunny() -> Result<PathBuf, Error> {
    let input = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("corpus/meshes/bunny_small.obj");
    let mesh = read_mesh(&input, &ReadOptions::default())?.mesh;
    let bytes = write::encode(&mesh, &EncodeOptions::default())?;
    let path = std::env::temp_dir().join("lrmesh-mmap-walk.lrm");
    std::fs::write(&path, bytes).map_err(|source| Error::Io {
        path: path.clone(),
        source,
    })?;
    Ok(path)
}
