//! Fuzz target `edgebreaker`: what it checks is `lrmesh::fuzz_checks`, shared with the tests that
//! replay `corpus/fuzz/edgebreaker/` and `corpus/fuzz/regressions/edgebreaker/`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| lrmesh::fuzz_checks::run("edgebreaker", data));
