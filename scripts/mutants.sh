#!/usr/bin/env bash
# Mutation score of the reader, validation and decoders: cargo-mutants (crates.io) changes the
# code of src/read/, src/format/ and src/edgebreaker/decode.rs one mutant at a time and runs
# the tests that cover them; a mutant the tests do not catch "survives". Prints `killed K of N`
# last (N counts the mutants that built; timeouts count as killed). Takes long on 2 cores:
# `--shard k/n` (passed through) splits the work. Not part of CI.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! cargo mutants --version >/dev/null 2>&1; then
    cargo install cargo-mutants --locked
fi
out=$(mktemp -d)
cargo mutants --no-shuffle --output "$out" \
    -f 'src/read/*.rs' -f 'src/format/*.rs' -f src/edgebreaker/decode.rs \
    "$@" -- --release \
    --test forged_rules --test edgebreaker_malformed --test container \
    --test container_lr_compact --test every_kind --test vectors --test fuzz_replay \
    --test edgebreaker || true
dir="$out/mutants.out"
caught=$(wc -l <"$dir/caught.txt" 2>/dev/null || echo 0)
timeout=$(wc -l <"$dir/timeout.txt" 2>/dev/null || echo 0)
missed=$(wc -l <"$dir/missed.txt" 2>/dev/null || echo 0)
echo "survivors: $dir/missed.txt"
echo "killed $((caught + timeout)) of $((caught + timeout + missed))"
