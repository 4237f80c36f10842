//! Any bytes given to the STL importer, with and without welding: an error or a mesh that
//! validates, never a panic. Welding never changes the triangle count.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lrmesh::io::{read_mesh_bytes, MeshFormat, ReadOptions};

fuzz_target!(|data: &[u8]| {
    let plain = read_mesh_bytes(data, MeshFormat::Stl, &ReadOptions { weld: false });
    let welded = read_mesh_bytes(data, MeshFormat::Stl, &ReadOptions { weld: true });
    if let Ok(l) = &plain {
        l.mesh
            .validate()
            .expect("a mesh the importer returns validates");
    }
    if let Ok(l) = &welded {
        l.mesh.validate().expect("a welded mesh validates");
    }
    assert_eq!(plain.is_ok(), welded.is_ok());
    if let (Ok(a), Ok(b)) = (&plain, &welded) {
        assert_eq!(a.mesh.triangle_count(), b.mesh.triangle_count());
        assert!(b.mesh.vertex_count() <= a.mesh.vertex_count());
    }
});
