//! Fuzz target `container_forged`: what it checks is `lrmesh::fuzz_checks`, shared with the tests that
//! replay `corpus/fuzz/container_forged/` and `corpus/fuzz/regressions/container_forged/`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| lrmesh::fuzz_checks::run("container_forged", data));
