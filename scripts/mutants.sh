#!/usr/bin/env bash
# Mutation score of the reader, its validation and the Edgebreaker decoder: cargo-mutants
# (crates.io) changes src/read/ (all but the reports in summary.rs) and
# src/edgebreaker/decode.rs one mutant at a time and runs the tests that cover them; a
# mutant the tests do not catch "survives". Prints `killed K of N` last (N counts the mutants
# that built; timeouts count as killed). About 650 mutants, 10-20 s each on 2 cores: pass
# `--shard k/n` to split the work over runs. Not part of CI.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! cargo mutants --version >/dev/null 2>&1; then
    cargo install cargo-mutants --locked
fi
out="${MUTANTS_OUT:-$(mktemp -d)}"
cargo mutants --no-shuffle --output "$out" --profile mutants \
    -f 'src/read/*.rs' -e src/read/summary.rs -f src/edgebreaker/decode.rs \
    "$@" -- \
    --test forged_container --test forged_sections --test forged_lr --test forged_lrbe \
    --test forged_strips_ebrk --test edgebreaker_malformed --test container \
    --test container_lr_compact --test every_kind --test vectors --test fuzz_replay \
    --test edgebreaker --test limits_exact || true
dir="$out/mutants.out"
count() { if [ -f "$dir/$1" ]; then wc -l <"$dir/$1"; else echo 0; fi; }
caught=$(count caught.txt)
timeout=$(count timeout.txt)
missed=$(count missed.txt)
echo "survivors: $dir/missed.txt"
echo "killed $((caught + timeout)) of $((caught + timeout + missed))"
