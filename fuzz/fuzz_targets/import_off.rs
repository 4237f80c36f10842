//! Fuzz target `import_off`: what it checks is `lrmesh::fuzz_checks`, shared with the tests that
//! replay `corpus/fuzz/import_off/` and `corpus/fuzz/regressions/import_off/`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| lrmesh::fuzz_checks::run("import_off", data));
