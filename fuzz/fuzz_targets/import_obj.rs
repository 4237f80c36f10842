//! Any bytes given to the OBJ importer: an error or a mesh that validates, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lrmesh::io::{read_mesh_bytes, MeshFormat, ReadOptions};

fuzz_target!(|data: &[u8]| {
    if let Ok(loaded) = read_mesh_bytes(data, MeshFormat::Obj, &ReadOptions::default()) {
        loaded
            .mesh
            .validate()
            .expect("a mesh the importer returns validates");
    }
});
