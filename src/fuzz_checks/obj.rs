//! The `import_obj` target: any bytes read as OBJ give an error or a mesh that validates,
//! and that mesh, written back to OBJ, reads again as the same mesh: the same vertices and
//! triangles in order, and at every corner the same texture coordinate, normal and color,
//! with the same parts.

use super::assert_same_in_order;
use crate::io::{obj, read_mesh_bytes, MeshFormat, ReadOptions};

/// Runs the `import_obj` checks on `data`.
pub fn import_obj(data: &[u8]) {
    let Ok(first) = read_mesh_bytes(data, MeshFormat::Obj, &ReadOptions::default()) else {
        return;
    };
    first
        .mesh
        .validate()
        .expect("a mesh the importer returns validates");
    let mut text = Vec::new();
    obj::write(&mut text, &first.mesh).expect("a mesh the reader returns can be written");
    let again = read_mesh_bytes(&text, MeshFormat::Obj, &ReadOptions::default())
        .unwrap_or_else(|e| panic!("what the writer wrote does not read back: {e}"));
    assert_same_in_order(&again.mesh, &first.mesh);
    assert!(
        again.warnings.is_empty(),
        "reading what the writer wrote warns: {:?}",
        again.warnings
    );
}
