#!/usr/bin/env bash
# Runs every fuzz target for N seconds (default 60), one after another, with the seeds of
# corpus/fuzz/<target>/ and a working corpus in fuzz/corpus/<target>/ (not committed).
# Needs a nightly toolchain and cargo-fuzz (`cargo install cargo-fuzz`); skips with a
# message when either is missing. A build error or a failing input stops the run with a
# non-zero exit; the input is left in fuzz/artifacts/<target>/: minimise it, fix the bug, and
# keep it in corpus/fuzz/regressions/<target>/ so that `cargo test` replays it.
# FUZZ_SEED fixes libFuzzer's random seed, so that a run from the committed seeds explores the
# same inputs each time (CI uses it: its short runs repeat a prefix of longer local runs).
# The targets build with 16 codegen units instead of cargo-fuzz's 1: on two cores the build
# takes about 7.5 minutes instead of 11, for runs a little slower; `run` takes the same
# options, or it would build everything again.
set -euo pipefail
build_options=(--codegen-units 16)
seconds="${1:-60}"
seed_option=()
[ -n "${FUZZ_SEED:-}" ] && seed_option=(-seed="$FUZZ_SEED")
cd "$(dirname "$0")"
if ! cargo +nightly --version >/dev/null 2>&1; then
    echo "fuzz: no nightly toolchain; skipped"
    exit 0
fi
if ! cargo +nightly fuzz --version >/dev/null 2>&1; then
    echo "fuzz: cargo-fuzz is not installed (cargo install cargo-fuzz); skipped"
    exit 0
fi
cargo +nightly fuzz build "${build_options[@]}"
log=$(mktemp)
for target in $(cargo +nightly fuzz list); do
    mkdir -p "corpus/$target"
    seeds=()
    [ -d "../corpus/fuzz/$target" ] && seeds=("../corpus/fuzz/$target")
    status=0
    cargo +nightly fuzz run "${build_options[@]}" "$target" "corpus/$target" "${seeds[@]}" -- \
        -max_total_time="$seconds" -rss_limit_mb=2048 -print_final_stats=1 "${seed_option[@]}" \
        >"$log" 2>&1 || status=$?
    runs=$(grep -E "^stat::number_of_executed_units" "$log" | awk '{print $2}')
    echo "fuzz: $target: ${runs:-?} executions in ${seconds}s, exit $status"
    if [ "$status" -ne 0 ]; then
        tail -40 "$log"
        echo "fuzz: $target failed; the input is in fuzz/artifacts/$target/"
        exit 1
    fi
done
