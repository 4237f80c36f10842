//! Saves, loads and opens a mesh through lrmesh's front door, without its command line's
//! dependencies, and walks a vertex's star on the file's bytes.

use lrmesh::ops::{self, CornerOps};

fn main() -> Result<(), lrmesh::Error> {
    let source = concat!(env!("CARGO_MANIFEST_DIR"), "/../corpus/meshes/knot1.off");
    let mesh = lrmesh::load(source)?;
    let path = std::env::temp_dir().join(format!("lean-consumer-{}.lrm", std::process::id()));
    lrmesh::save(&path, &mesh)?;
    let bytes = std::fs::read(&path).map_err(|source| lrmesh::Error::Io {
        path: path.clone(),
        source,
    })?;
    let file = lrmesh::open(&bytes)?;
    let star = ops::star(file.connectivity(), lrmesh::Vertex(0)).count();
    let back = lrmesh::load(&path)?;
    std::fs::remove_file(&path).ok();
    assert_eq!(back.triangle_count(), mesh.triangle_count());
    println!(
        "lean consumer: {} triangles saved, loaded and opened; vertex 0 has {star} corners ({} kind)",
        back.triangle_count(),
        file.connectivity().name()
    );
    assert!(star > 0 && file.connectivity().vertex_id_bound() > 0);
    Ok(())
}
