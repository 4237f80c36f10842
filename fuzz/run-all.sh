#!/usr/bin/env bash
# Runs every fuzz target for N seconds (default 60), one after another, with the seeds of
# corpus/fuzz/<target>/ and a working corpus in fuzz/corpus/<target>/ (not committed).
# Needs a nightly toolchain and cargo-fuzz (`cargo install cargo-fuzz`); skips with a
# message when either is missing. A crash stops the run, leaves the input in
# fuzz/artifacts/<target>/ and exits non-zero: minimise it, fix the bug, and keep the input in
# corpus/fuzz/regressions/<target>/ so that `cargo test` replays it.
set -euo pipefail
seconds="${1:-60}"
cd "$(dirname "$0")"
if ! cargo +nightly --version >/dev/null 2>&1; then
    echo "fuzz: no nightly toolchain; skipped"
    exit 0
fi
if ! cargo +nightly fuzz --version >/dev/null 2>&1; then
    echo "fuzz: cargo-fuzz is not installed (cargo install cargo-fuzz); skipped"
    exit 0
fi
for target in $(cargo +nightly fuzz list); do
    mkdir -p "corpus/$target"
    seeds="../corpus/fuzz/$target"
    [ -d "$seeds" ] || seeds=""
    echo "fuzz: $target for ${seconds}s"
    cargo +nightly fuzz run "$target" "corpus/$target" $seeds -- \
        -max_total_time="$seconds" -rss_limit_mb=2048 -print_final_stats=1 2>&1 |
        grep -E "^(stat::number_of_executed_units|Done|==[0-9]+==|SUMMARY)" || true
    if [ -n "$(ls -A "artifacts/$target" 2>/dev/null)" ]; then
        echo "fuzz: $target found a failure: see fuzz/artifacts/$target/"
        exit 1
    fi
done
