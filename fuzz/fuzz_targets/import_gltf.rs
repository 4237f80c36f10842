//! Fuzz target `import_gltf`: what it checks is `lrmesh::fuzz_checks`, shared with the tests that
//! replay `corpus/fuzz/import_gltf/` and `corpus/fuzz/regressions/import_gltf/`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| lrmesh::fuzz_checks::run("import_gltf", data));
