#!/usr/bin/env bash
# The library without the command line's weight: builds and runs lean-consumer/ (which depends
# on lrmesh with default-features = false and calls load, save and open), then checks that
# `cargo tree` lists none of clap, clap_complete, clap_mangen, indicatif, memmap2, png for it.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo run --quiet --locked --manifest-path lean-consumer/Cargo.toml
tree=$(cargo tree --locked --manifest-path lean-consumer/Cargo.toml -e normal --prefix none)
for crate in clap clap_complete clap_mangen indicatif memmap2 png; do
    if grep -q "^$crate v" <<<"$tree"; then
        echo "lean-check: $crate is compiled for a default-features = false user" >&2
        exit 1
    fi
done
echo "lean-check: none of clap, clap_complete, clap_mangen, indicatif, memmap2, png in the library's tree"
