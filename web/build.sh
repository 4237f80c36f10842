#!/usr/bin/env bash
# Builds lrmesh for web pages (web/API.md) from web/crate: web/pkg/ (decoder and encoder, what
# the viewer loads) and web/pkg-decoder/ (the decoder alone, optimised for size), and prints
# the gzipped size of each .wasm. Needs the wasm32-unknown-unknown target (`rustup target add
# wasm32-unknown-unknown`) and wasm-bindgen-cli at the exact version of the wasm-bindgen crate
# in web/crate/Cargo.lock, which it installs (`cargo install`) when missing.
set -euo pipefail
cd "$(dirname "$0")"
version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/version = |"/, ""); print }' crate/Cargo.lock)
if [ "$(wasm-bindgen --version 2>/dev/null | awk '{ print $2 }')" != "$version" ]; then
  echo "build: installing wasm-bindgen-cli $version"
  # Unoptimised: it builds in one minute instead of about four on two cores (CI installs it on
  # every fresh machine), and still runs in about a second on our modules.
  cargo install wasm-bindgen-cli --version "$version" --locked --debug
fi
rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown ||
  rustup target add wasm32-unknown-unknown
build() { # OUT_DIR [cargo options]
  local out=$1
  shift
  cargo build --quiet --locked --manifest-path crate/Cargo.toml --target wasm32-unknown-unknown \
    --release --target-dir "crate/target/$out" "$@"
  wasm-bindgen --target web --out-dir "$out" \
    "crate/target/$out/wasm32-unknown-unknown/release/lrmesh_wasm.wasm"
  echo "build: $out/lrmesh_wasm_bg.wasm $(wc -c <"$out/lrmesh_wasm_bg.wasm") bytes," \
    "$(gzip -9c "$out/lrmesh_wasm_bg.wasm" | wc -c) gzipped"
}
build pkg
# The decoder alone is optimised for size (the viewer loads pkg/, optimised for speed).
CARGO_PROFILE_RELEASE_OPT_LEVEL=z build pkg-decoder --no-default-features
