//! The `import_gltf` target: any bytes read as glTF (GLB or JSON, welded or not) give an
//! error or a mesh that validates; a mesh read is written as `.glb` and as `.gltf` and read
//! back to the same vertices, in the same order, and the same triangles with the same values
//! at every corner and the same parts (up to the order of the triangles, which the writer
//! groups by part).

use super::assert_same_up_to_order;
use crate::io::{gltf, read_mesh_bytes, write_mesh_to, MeshFormat, ReadOptions};

/// Runs the check on `data`.
pub fn import_gltf(data: &[u8]) {
    for weld in [false, true] {
        let Ok(loaded) = gltf::read(data, &ReadOptions { weld }) else {
            continue;
        };
        let mesh = loaded.mesh;
        mesh.validate()
            .expect("a mesh the glTF reader returns validates");
        // glTF stores attributes per vertex: the writer splits a welded mesh's seams.
        let want = mesh.split_seams();
        for format in [MeshFormat::Glb, MeshFormat::Gltf] {
            let mut bytes = Vec::new();
            write_mesh_to(&mut bytes, &mesh, format).expect("a valid mesh is written");
            let back = read_mesh_bytes(&bytes, format, &ReadOptions::default())
                .expect("what the writer writes reads back")
                .mesh;
            assert_eq!(
                back.positions, want.positions,
                "{format}: vertices in order"
            );
            assert_same_up_to_order(&back, &want);
        }
    }
}
