#!/usr/bin/env bash
# Whole files with normals and texture coordinates, side by side in one run: lrmesh's
# Edgebreaker container against Draco 1.5.5 as Debian packages it (`apt-get install -y
# draco`), on OBJ meshes nobody here wrote. Sizes only; not part of CI.
#
# For each mesh and position bits N (11, 14, 16), normals 10 bits and texture coordinates
# 12 bits (QN, QT: ATTRIBUTE_COMPARE_QN, ATTRIBUTE_COMPARE_QT):
# - lrmesh: `lrmesh encode IN --connectivity edgebreaker --quantize-position N
#   --quantize-normal QN --quantize-texcoord QT` (default level), whole-file bytes, split by
#   `lrmesh info --json` into connectivity (EBRK, COPY or COPC, KEPT or KEPC), positions (GEOM),
#   attributes (ATTR), parts (PART) and the rest (header, section table, META, MESH); and the
#   same with `--weld` (vertices at equal positions merged, attributes per corner where they
#   differ: what Draco does to every input);
# - Draco: `draco_encoder -i IN -cl 10 -qp N -qn QN -qt QT`, whole-file bytes; and what it
#   kept, since Draco merges equal points and drops degenerate triangles silently: its file
#   decoded to OBJ by `draco_decoder`, `v` and `f` lines, next to lrmesh's vertices and
#   triangles (every input triangle, degenerate ones included).
# - OpenCTM: `ctmconv IN OUT.ctm --method MG2 --level 9 --vprec S/(2^N - 1) --nprec
#   2/(2^QN - 1) --tprec 1/(2^QT - 1)`, S the largest extent of the positions (Draco's grid
#   step); the normal and texture steps are those of QN bits over [-1, 1] and QT bits over
#   [0, 1], close to (not exactly) Draco's octahedral and bounding-box grids. OpenCTM keeps
#   one vertex per distinct position, normal and texture coordinate, and every triangle.
# Ratios are lrmesh / Draco and OpenCTM / Draco (below 1: smaller than Draco); the median
# rows take each column's median over the meshes.
#
# Usage: scripts/attribute-compare.sh [--markdown]   (needs draco, openctm-tools and jq)
#   ATTRIBUTE_COMPARE_MESHES="a.obj b.obj": other meshes than the corpus OBJ files with
#   attributes (and /tmp/am/WusonOBJ.obj, /tmp/am/engine.obj when present: assimp's test
#   models, `apt-get download assimp-testmodels`; engine is glTF2/2CylinderEngine converted
#   to OBJ by `lrmesh convert`).
set -euo pipefail
cd "$(dirname "$0")/.."
markdown=0
[ "${1:-}" = --markdown ] && markdown=1
qn=${ATTRIBUTE_COMPARE_QN:-10}
qt=${ATTRIBUTE_COMPARE_QT:-12}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for tool in draco_encoder draco_decoder ctmconv jq; do
  command -v "$tool" >/dev/null || {
    echo "$tool not found (see the head of $0)" >&2
    exit 1
  }
done
lrmesh=target/release/lrmesh
[ -x "$lrmesh" ] || flock /tmp/cargo.lock cargo build --release --quiet
if [ -n "${ATTRIBUTE_COMPARE_MESHES:-}" ]; then
  read -r -a meshes <<<"$ATTRIBUTE_COMPARE_MESHES"
else
  meshes=(corpus/assets/obj/spider/spider.obj corpus/assets/obj/regr01/regr01.obj
    corpus/assets/obj/tinyobjloader/map-bump.obj)
  for m in /tmp/am/WusonOBJ.obj /tmp/am/engine.obj; do [ -f "$m" ] && meshes+=("$m"); done
fi

calc() { awk "BEGIN { printf \"%.3f\", $1 }"; }
median() { tr ' ' '\n' | grep . | sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
row() {
  if [ $markdown = 1 ]; then
    local IFS='|'
    echo "| $* |"
  else
    printf '%-10s %4s %8s %7s %7s %7s %6s %6s %8s %8s %8s %7s %7s %7s %13s %13s\n' "$@"
  fi
}
# Section bytes of a container, by role: connectivity, positions, attributes, parts, rest.
split_sections() {
  "$lrmesh" info "$1" --json | jq -r '
    (.sections | map({(.tag): .length}) | add) as $s
    | [(($s.EBRK // 0) + ($s.COPY // 0) + ($s.COPC // 0) + ($s.KEPT // 0) + ($s.KEPC // 0)),
       ($s.GEOM // 0), ($s.ATTR // 0), ($s.PART // 0), .bytes, .vertices, .triangles]
    | @tsv'
}

row mesh bits lrmesh conn GEOM ATTR PART rest weld draco openctm ratio weld-rt ctm-rt \
  "lrm v/t" "draco v/t"
[ $markdown = 1 ] && row --- --: --: --: --: --: --: --: --: --: --: --: --: --: --: --:
declare -A ratios wratios cratios
for bits in 11 14 16; do
  for m in "${meshes[@]}"; do
    name=$(basename "$m" .obj)
    opts=(--connectivity edgebreaker --quantize-position "$bits" --quantize-normal "$qn"
      --quantize-texcoord "$qt")
    "$lrmesh" encode "$m" -o "$work/a.lrm" "${opts[@]}" >/dev/null 2>&1
    "$lrmesh" encode "$m" -o "$work/w.lrm" --weld "${opts[@]}" >/dev/null 2>&1
    read -r conn geom attr part total v t < <(split_sections "$work/a.lrm")
    weld=$("$lrmesh" info "$work/w.lrm" --json | jq .bytes)
    draco_encoder -i "$m" -o "$work/d.drc" -cl 10 -qp "$bits" -qn "$qn" -qt "$qt" >/dev/null
    draco=$(stat -c %s "$work/d.drc")
    draco_decoder -i "$work/d.drc" -o "$work/d.obj" >/dev/null
    dv=$(grep -c '^v ' "$work/d.obj" || true)
    df=$(grep -c '^f ' "$work/d.obj" || true)
    side=$(awk '$1 == "v" { for (i = 2; i <= 4; i++) {
        if (!(i in lo) || $i < lo[i]) lo[i] = $i; if (!(i in hi) || $i > hi[i]) hi[i] = $i } }
      END { m = 0; for (i = 2; i <= 4; i++) if (hi[i] - lo[i] > m) m = hi[i] - lo[i]
        printf "%.9g", m }' "$m")
    step() { awk -v s="$1" -v n="$2" 'BEGIN { printf "%.9g", s / (2 ^ n - 1) }'; }
    ctmconv "$m" "$work/c.ctm" --method MG2 --level 9 --vprec "$(step "$side" "$bits")" \
      --nprec "$(step 2 "$qn")" --tprec "$(step 1 "$qt")" --comment " " >/dev/null
    ctm=$(stat -c %s "$work/c.ctm")
    cratio=$(calc "$ctm / $draco")
    cratios[$bits]+="$cratio "
    ratio=$(calc "$total / $draco")
    wratio=$(calc "$weld / $draco")
    ratios[$bits]+="$ratio "
    wratios[$bits]+="$wratio "
    rest=$((total - conn - geom - attr - part))
    row "$name" "$bits" "$total" "$conn" "$geom" "$attr" "$part" "$rest" "$weld" "$draco" \
      "$ctm" "$ratio" "$wratio" "$cratio" "$v/$t" "$dv/$df"
  done
  row median "$bits" "" "" "" "" "" "" "" "" "" "$(echo "${ratios[$bits]}" | median)" \
    "$(echo "${wratios[$bits]}" | median)" "$(echo "${cratios[$bits]}" | median)" "" ""
done
