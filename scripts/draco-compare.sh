#!/usr/bin/env bash
# Same-run comparison of lrmesh's Edgebreaker with Draco's valence Edgebreaker (Draco 1.5.5 as
# packaged by Debian: `apt-get install -y draco libdraco-dev`). Not part of CI.
#
# For each mesh: our bits per triangle and decode speed (benches/edgebreaker.rs), Draco's
# connectivity size and connectivity-only decode speed (scripts/draco_bench/draco_bench.cc,
# on a file from `draco_encoder -cl 10 -qp 8`: the valence coder; attributes are not decoded),
# and the ratio of the two speeds. Each figure is a median over RUNS decodes; the two programs
# alternate, mesh by mesh, for ROUNDS rounds and the best round of each is kept, which damps
# the noise of a shared machine.
#
# Usage: scripts/draco-compare.sh [RUNS [ROUNDS]]   (defaults 21 and 3)
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-21}
rounds=${2:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

meshes=(
  ../shared/meshes/armadillo.off
  ../shared/meshes/bunny00.off
  corpus/meshes/fandisk.off
  corpus/meshes/knot1.off
  corpus/meshes/elephant-with-holes.off
  corpus/meshes/blobby_3cc.off
  corpus/meshes/mech-holes-shark.off
  corpus/meshes/cheese.off
  corpus/meshes/b9_mesh.off
  corpus/meshes/polygon_mesh.off
)

command -v draco_encoder >/dev/null || {
  echo "draco_encoder not found (apt-get install draco libdraco-dev)" >&2
  exit 1
}
g++ -O2 -std=c++17 scripts/draco_bench/draco_bench.cc -o "$work/draco_bench" -ldraco
cargo build --release --quiet --bin lrmesh
# The bench binary itself, so that timing never waits for cargo's lock on the target dir.
bench=$(cargo bench --no-run --bench edgebreaker 2>&1 | sed -n 's/.*Executable .*(\(.*\)).*/\1/p')
[ -x "$bench" ] || { echo "cannot find the edgebreaker bench binary" >&2; exit 1; }

declare -A dbpt dbest dtris obpt obest otris
for m in "${meshes[@]}"; do
  name=$(basename "$m")
  target/release/lrmesh convert "$m" "$work/$name.ply" >/dev/null 2>&1
  draco_encoder -i "$work/$name.ply" -o "$work/$name.drc" -cl 10 -qp 8 >/dev/null
  dbest[$name]=0
  obest[$name]=0
done

max() { awk -v a="$1" -v b="$2" 'BEGIN { print (a > b) ? a : b }'; }
for _ in $(seq "$rounds"); do
  for m in "${meshes[@]}"; do
    name=$(basename "$m")
    d=$("$work/draco_bench" "$work/$name.drc" "$runs")
    dbpt[$name]=$(sed -E 's/.*conn_bpt=([0-9.]+).*/\1/' <<<"$d")
    dtris[$name]=$(sed -E 's/.*faces=([0-9]+).*/\1/' <<<"$d")
    dbest[$name]=$(max "${dbest[$name]}" "$(sed -E 's/.*conn_mtps=([0-9.]+).*/\1/' <<<"$d")")
    # Our bench: decode only, this mesh only.
    line=$(LRMESH_BENCH_RUNS=$(((runs + 2) / 3)) LRMESH_BENCH_DECODE_ONLY=1 \
      LRMESH_BENCH_FILTER="$name" "$bench" 2>/dev/null | awk -v n="$name" '$1 == n')
    read -r _ tris bpt _ _ _ dec <<<"$line"
    otris[$name]=$tris
    obpt[$name]=$bpt
    obest[$name]=$(max "${obest[$name]}" "$dec")
  done
done

printf '%-24s %9s %9s %8s %8s %11s %11s %7s\n' mesh triangles "dr tris" "our bpt" "dr bpt" \
  "our Mtri/s" "dr Mtri/s" ratio
for m in "${meshes[@]}"; do
  name=$(basename "$m")
  printf '%-24s %9s %9s %8s %8s %11s %11s %7.2f\n' "$name" "${otris[$name]}" "${dtris[$name]}" "${obpt[$name]}" \
    "${dbpt[$name]}" "${obest[$name]}" "${dbest[$name]}" \
    "$(awk -v a="${obest[$name]}" -v b="${dbest[$name]}" 'BEGIN { print a / b }')"
done
