//! Fuzz target `import_stl`: what it checks is `lrmesh::fuzz_checks`, shared with the tests that
//! replay `corpus/fuzz/import_stl/` and `corpus/fuzz/regressions/import_stl/`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| lrmesh::fuzz_checks::run("import_stl", data));
