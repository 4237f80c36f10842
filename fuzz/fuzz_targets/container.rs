//! Fuzz target `container`: what it checks is `lrmesh::fuzz_checks`, shared with the tests that
//! replay `corpus/fuzz/container/` and `corpus/fuzz/regressions/container/`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| lrmesh::fuzz_checks::run("container", data));
