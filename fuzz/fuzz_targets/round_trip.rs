//! Fuzz target `round_trip`: what it checks is `lrmesh::fuzz_checks`, shared with the tests that
//! replay `corpus/fuzz/round_trip/` and `corpus/fuzz/regressions/round_trip/`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| lrmesh::fuzz_checks::run("round_trip", data));
