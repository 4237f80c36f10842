#!/usr/bin/env bash
# Whole files, side by side in one run: lrmesh's Edgebreaker container (connectivity and
# positions) against Draco 1.5.5, OpenCTM 1.0.3 and meshoptimizer 0.18, as Debian packages
# them (`apt-get install -y draco libdraco-dev openctm-tools libmeshoptimizer-dev`), on the
# meshes of ../shared/meshes with at least 1000 triangles (CGAL's data: nobody here wrote
# them). Not part of CI.
#
# Sizes, at 11, 14 and 16 bits per coordinate and lossless ("f32"):
# - lrmesh: `lrmesh encode --connectivity edgebreaker [--quantize-position N]` (default
#   level), split by `lrmesh info --json` into connectivity (EBRK, with COPY/COPC and KEPT/KEPC when the
#   mesh needs them), positions (GEOM) and the rest (header, section table, META, MESH); and
#   on a grid also at `-l 1` (positions in the anchored grid, GEOM encoding 6: fast decoding);
# - Draco: `draco_encoder -cl 10 -qp N` (-qp 0: no quantization) on the mesh as
#   `lrmesh convert` writes it to PLY, split into the bytes up to the end of the connectivity
#   and the attribute data (scripts/draco_bench/draco_bench.cc);
# - OpenCTM: `ctmconv --method MG2 --level 9 --vprec S/(2^N - 1)`, S the bounding box's
#   largest extent (the grid step of Draco and lrmesh: the same largest error), and MG1 for
#   lossless;
# - meshoptimizer: scripts/draco_bench/meshopt_bench.cc: positions on the same grid as 4 x u16,
#   vertex cache and fetch optimization, meshopt_encodeIndexBuffer + meshopt_encodeVertexBuffer
#   (its own codec, no general-purpose compression), and that output through gzip -9 and
#   zstd -19.
# Ratios are lrmesh / Draco (below 1: lrmesh smaller); "median" rows take each column's
# median over the meshes.
#
# Also: lossless positions of the Edgebreaker container (GEOM) against 12 bytes per vertex,
# and the LR container's positions at 16 bits (GEOM, default level) against 6 bytes per vertex.
#
# Timing (skipped with RUNS=0): full decode to arrays in memory and full encode, in M
# triangles/s, median of RUNS runs, the best of ROUNDS rounds (the programs alternate, mesh by
# mesh, which damps the noise of a shared machine):
# - lrmesh (benches/geometry.rs): `read::open` + `Container::to_mesh`; `write::encode` of the
#   mesh as read; at the default level and, on a grid, at level 1;
# - Draco (draco_bench.cc): `DecodeMeshFromBuffer` + faces and every attribute per point into
#   arrays; `Encoder::EncodeMeshToBuffer` with draco_encoder's settings for -cl 10 -qp N, on
#   the mesh as Draco's PLY reader loads it (checked: the same bytes as the tool's file).
#
# Usage: scripts/geometry-compare.sh [--markdown] [RUNS [ROUNDS]]   (defaults 11 and 2)
#   --markdown: the tables as Markdown, for the README.
#   GEOMETRY_COMPARE_MESHES="a.off b.off": other meshes than ../shared/meshes/*.
set -euo pipefail
cd "$(dirname "$0")/.."
markdown=0
if [ "${1:-}" = --markdown ]; then
  markdown=1
  shift
fi
runs=${1:-11}
rounds=${2:-2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

for tool in draco_encoder ctmconv jq gzip zstd g++; do
  command -v "$tool" >/dev/null || {
    echo "$tool not found (see the head of $0)" >&2
    exit 1
  }
done
g++ -O2 -std=c++17 scripts/draco_bench/draco_bench.cc -o "$work/draco_bench" -ldraco
g++ -O2 -std=c++17 scripts/draco_bench/meshopt_bench.cc -o "$work/meshopt_bench" -lmeshoptimizer
# Other engineers share the machine and the target directory: every cargo call takes the lock.
# Both builds come first, so that the CLI and the bench binary are of the same sources.
flock /tmp/cargo.lock cargo build --release --quiet --bin lrmesh
bench=$(flock /tmp/cargo.lock cargo bench --no-run --bench geometry 2>&1 |
  sed -n 's/.*Executable .*(\(.*\)).*/\1/p')
[ -x "$bench" ] || { echo "cannot find the geometry bench binary" >&2; exit 1; }
# Copies, so that a rebuild by someone else during the run changes nothing.
cp target/release/lrmesh "$work/lrmesh"
cp "$bench" "$work/geometry"
lrmesh=$work/lrmesh
bench=$work/geometry

say() { echo "$@" >&2; }
# key=value from a line of key=value pairs.
kv() { sed -nE "s/.*(^| )$2=([^ ]+).*/\2/p" <<<"$1"; }
calc() { awk "BEGIN { printf \"%.${2:-3}f\", $1 }"; }
# Median of the numeric arguments ("-" ignored).
median() {
  printf '%s\n' "$@" | { grep -v '^-$' || true; } | sort -g |
    awk '{ v[NR] = $1; whole = whole && $1 == int($1) } BEGIN { whole = 1 }
         END { if (NR == 0) { print "-"; exit }
               x = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
               printf (whole && x == int(x)) ? "%d" : "%.3f", x }'
}
# a / b with 3 decimals, "-" when either is missing.
ratio() {
  if [ "$1" = - ] || [ "$2" = - ]; then echo -; else calc "$1 / $2"; fi
}
bpt() { # bytes, triangles
  if [ "$1" = - ]; then echo -; else calc "$1 / $2"; fi
}

# The meshes: every mesh file with at least 1000 triangles, one per name (bunny_small comes
# as OBJ and PLY).
if [ -n "${GEOMETRY_COMPARE_MESHES:-}" ]; then
  read -r -a candidates <<<"$GEOMETRY_COMPARE_MESHES"
else
  candidates=(../shared/meshes/*.off ../shared/meshes/*.obj ../shared/meshes/*.ply)
fi
declare -A seen T V
meshes=()
for m in "${candidates[@]}"; do
  stem=$(basename "${m%.*}")
  [ -n "${seen[$stem]:-}" ] && continue
  "$lrmesh" info "$m" --json >"$work/info.json" 2>/dev/null || continue
  t=$(jq -r .triangles "$work/info.json")
  [ "$t" -ge 1000 ] || continue
  seen[$stem]=1
  meshes+=("$m")
  T[$(basename "$m")]=$t
  V[$(basename "$m")]=$(jq -r .vertices "$work/info.json")
done
[ ${#meshes[@]} -gt 0 ] || { echo "no meshes" >&2; exit 1; }

qps=(11 14 16 0) # 0: lossless
qname() { if [ "$1" = 0 ]; then echo f32; else echo "$1 bits"; fi; }
# Sizes, keyed name,qp: lt lg lc (lrmesh total, GEOM, connectivity: EBRK with the vertex
# copies COPY and the triangles kept aside KEPT that a mesh which is not an oriented manifold
# needs), dt dc (Draco total, bytes up to the connectivity's end), ct (OpenCTM), mt mi mv mg mz
# (meshopt total, index, vertex, gzip, zstd).
# Bytes per triangle and per vertex divide by the mesh's own counts (`lrmesh info`).
declare -A lt lg lc dt dc ct mt mi mv mg mz side lr16 lr16_0 lerr l1t
# Bytes of the sections of info.json $1 whose tags are among $2 (space separated).
section() {
  jq -r --arg t "$2" \
    '[.sections[] | select(.tag as $x | $t | split(" ") | index($x)) | .length] | add // 0' "$1"
}
for m in "${meshes[@]}"; do
  name=$(basename "$m")
  say "sizes: $name"
  ply=$work/$name.ply
  "$lrmesh" convert "$m" "$ply" >/dev/null 2>&1
  for q in "${qps[@]}"; do
    k=$name,$q
    # lrmesh
    opt=()
    [ "$q" = 0 ] || opt=(--quantize-position "$q")
    f=$work/$name.$q.lrm
    if "$lrmesh" encode "$m" -o "$f" --connectivity edgebreaker "${opt[@]}" \
      >/dev/null 2>"$work/err" &&
      "$lrmesh" info "$f" --json >"$work/info.json" 2>>"$work/err"; then
      lt[$k]=$(stat -c %s "$f")
      lg[$k]=$(section "$work/info.json" GEOM)
      lc[$k]=$(section "$work/info.json" "EBRK COPY COPC KEPT KEPC PERM")
    else
      lt[$k]=- lg[$k]=- lc[$k]=-
      say "  lrmesh at $(qname "$q") failed: $(head -c 200 "$work/err" | tr '\n' ' ')"
    fi
    # lrmesh at level 1 (on a grid)
    l1t[$k]=-
    if [ "$q" != 0 ] && "$lrmesh" encode "$m" -o "$f.l1" --connectivity edgebreaker \
      "${opt[@]}" -l 1 >/dev/null 2>"$work/err"; then
      l1t[$k]=$(stat -c %s "$f.l1")
    fi
    # Draco
    d=$work/$name.$q.drc
    draco_encoder -i "$ply" -o "$d" -cl 10 -qp "$q" >/dev/null
    line=$("$work/draco_bench" "$d" 1)
    dt[$k]=$(kv "$line" bytes)
    dc[$k]=$(kv "$line" conn_bytes)
    # meshoptimizer
    line=$("$work/meshopt_bench" "$ply" "$q" 1 "$work/mo.bin")
    mt[$k]=$(kv "$line" bytes)
    mi[$k]=$(kv "$line" index_bytes)
    mv[$k]=$(kv "$line" vertex_bytes)
    mg[$k]=$(gzip -9c "$work/mo.bin" | wc -c)
    mz[$k]=$(zstd -19 -q -c "$work/mo.bin" | wc -c)
    side[$name]=$(kv "$line" side)
    # OpenCTM (the comment would copy the PLY's; one space is the shortest it takes)
    c=$work/$name.$q.ctm
    if [ "$q" = 0 ]; then
      ctmconv "$ply" "$c" --method MG1 --level 9 --comment " " >/dev/null
    else
      vprec=$(awk -v s="${side[$name]}" -v n="$q" 'BEGIN { printf "%.9g", s / (2 ^ n - 1) }')
      ctmconv "$ply" "$c" --method MG2 --level 9 --vprec "$vprec" --comment " " >/dev/null
    fi
    ct[$k]=$(stat -c %s "$c")
  done
  # The LR container's positions at 16 bits: default level (coded), and level 0 (raw).
  for lvl in 6 0; do
    f=$work/$name.lr$lvl.lrm
    if "$lrmesh" encode "$m" -o "$f" --quantize-position 16 -l "$lvl" >/dev/null 2>"$work/err" &&
      "$lrmesh" info "$f" --json >"$work/info.json" 2>>"$work/err"; then
      g=$(section "$work/info.json" GEOM)
    else
      g=-
      say "  LR at 16 bits, level $lvl, failed: $(head -c 200 "$work/err" | tr '\n' ' ')"
    fi
    if [ "$lvl" = 6 ]; then lr16[$name]=$g; else lr16_0[$name]=$g; fi
  done
done

# Timing.
declare -A ld le dd de derr ld1 le1
max() {
  if [ "${1:--}" = - ]; then
    echo "$2"
  else
    awk -v a="$1" -v b="$2" 'BEGIN { print (a > b) ? a : b }'
  fi
}
if [ "$runs" -gt 0 ]; then
  # Each mesh's timing holds the cargo lock, so that no build (of anyone who takes it) runs
  # meanwhile: builds wait a few seconds, between meshes.
  exec 9>>/tmp/cargo.lock
  load_start=$(cut -d' ' -f1-3 /proc/loadavg)
  for round in $(seq "$rounds"); do
    for m in "${meshes[@]}"; do
      name=$(basename "$m")
      say "timing, round $round: $name"
      flock 9
      for q in "${qps[@]}"; do
        k=$name,$q
        line=$("$work/draco_bench" "$work/$name.$q.drc" "$runs" "$work/$name.ply" "$q")
        if [ "$(kv "$line" enc_bytes)" != "${dt[$k]}" ]; then
          say "  Draco's library encode gives $(kv "$line" enc_bytes) bytes, the tool ${dt[$k]}"
        fi
        dd[$k]=$(max "${dd[$k]:-}" "$(kv "$line" arrays_mtps)")
        de[$k]=$(max "${de[$k]:-}" "$(kv "$line" enc_mtps)")
        if [ "${lt[$k]}" = - ]; then
          ld[$k]=- le[$k]=-
          continue
        fi
        if line=$("$bench" "$m" "$q" "$runs" 2>"$work/err"); then
          ld[$k]=$(max "${ld[$k]:-}" "$(kv "$line" dec_mtps)")
          le[$k]=$(max "${le[$k]:-}" "$(kv "$line" enc_mtps)")
          lerr[$k]=$(kv "$line" max_err)
        else
          ld[$k]=- le[$k]=-
          say "  lrmesh bench at $(qname "$q") failed:" \
            "$(grep -m1 -i -E 'panicked|error' "$work/err" || true)"
        fi
        if [ "$q" != 0 ] && line=$("$bench" "$m" "$q" "$runs" 1 2>"$work/err"); then
          ld1[$k]=$(max "${ld1[$k]:-}" "$(kv "$line" dec_mtps)")
          le1[$k]=$(max "${le1[$k]:-}" "$(kv "$line" enc_mtps)")
        else
          ld1[$k]=${ld1[$k]:--} le1[$k]=${le1[$k]:--}
        fi
      done
      flock -u 9
    done
  done
  exec 9>&-
fi

# Tables: files of tab-separated rows, the first the header. `render FILE [COLUMNS]` prints
# them aligned, or as Markdown; COLUMNS (as cut -f takes them) keeps some columns only.
render() {
  local cols=${2:-1-}
  if [ "$markdown" = 1 ]; then
    cut -f "$cols" "$1" |
      awk -F'\t' '{ printf "|"; for (i = 1; i <= NF; i++) printf " %s |", $i; printf "\n" }
                  NR == 1 { printf "|"; for (i = 1; i <= NF; i++) printf (i == 1 ? " --- |" : " ---: |")
                            printf "\n" }'
  else
    cut -f "$cols" "$1" | column -t -s $'\t'
  fi
  echo
}
heading() {
  if [ "$markdown" = 1 ]; then echo "#### $*"; echo; else echo "== $*"; fi
}
row() { local IFS=$'\t'; echo "$*"; }
# The median row of a table: "median", "-", then each column's median from the third on.
median_row() {
  local file=$1 n j
  n=$(head -1 "$file" | awk -F'\t' '{ print NF }')
  local cells=(median -)
  for j in $(seq 3 "$n"); do
    # shellcheck disable=SC2046
    cells+=("$(median $(tail -n +2 "$file" | cut -f "$j"))")
  done
  row "${cells[@]}"
}

# Sizes, one table per precision. Columns: 1 mesh, 2 triangles, 3 lrmesh, 4 lrm conn,
# 5 lrm pos, 6 Draco, 7 Draco conn, 8 Draco pos, 9 lrm/Draco, 10 OpenCTM, 11 CTM/Draco,
# 12 meshopt, 13 mo idx, 14 mo vtx, 15 mo+gzip, 16 mo+zstd, 17 mo+zstd/Draco, 18 lrmesh -l 1,
# 19 -l 1/Draco.
for q in "${qps[@]}"; do
  f=$work/size.$q.tsv
  {
    row mesh triangles lrmesh "lrm conn" "lrm pos" Draco "Draco conn" "Draco pos" "lrm/Draco" \
      OpenCTM "CTM/Draco" meshopt "mo idx" "mo vtx" "mo+gzip" "mo+zstd" "mo+zstd/Draco" \
      "lrm -l 1" "-l 1/Draco"
    for m in "${meshes[@]}"; do
      name=$(basename "$m")
      k=$name,$q
      t=${T[$name]}
      total=$(bpt "${lt[$k]}" "$t") draco=$(bpt "${dt[$k]}" "$t") ctm=$(bpt "${ct[$k]}" "$t")
      zst=$(bpt "${mz[$k]}" "$t") l1=$(bpt "${l1t[$k]}" "$t")
      row "$name" "$t" "$total" "$(bpt "${lc[$k]}" "$t")" "$(bpt "${lg[$k]}" "$t")" \
        "$draco" "$(bpt "${dc[$k]}" "$t")" "$(bpt "$((dt[$k] - dc[$k]))" "$t")" \
        "$(ratio "$total" "$draco")" "$ctm" "$(ratio "$ctm" "$draco")" \
        "$(bpt "${mt[$k]}" "$t")" "$(bpt "${mi[$k]}" "$t")" "$(bpt "${mv[$k]}" "$t")" \
        "$(bpt "${mg[$k]}" "$t")" "$zst" "$(ratio "$zst" "$draco")" "$l1" \
        "$(ratio "$l1" "$draco")"
    done
  } >"$f"
  median_row "$f" >>"$f"
done

# Positions alone, per vertex.
f=$work/positions.tsv
{
  row mesh vertices "EB f32" "EB f32/12" "EB 11" "EB 14" "EB 16" "LR 16" "LR 16/6" "LR 16 -l 0" \
    "lrm other B"
  for m in "${meshes[@]}"; do
    name=$(basename "$m")
    v=${V[$name]}
    eb=$(bpt "${lg[$name,0]}" "$v") lr=$(bpt "${lr16[$name]}" "$v")
    other=-
    [ "${lt[$name,11]}" = - ] || other=$((lt[$name,11] - lg[$name,11] - lc[$name,11]))
    row "$name" "$v" "$eb" "$(ratio "$eb" 12)" "$(bpt "${lg[$name,11]}" "$v")" \
      "$(bpt "${lg[$name,14]}" "$v")" "$(bpt "${lg[$name,16]}" "$v")" "$lr" "$(ratio "$lr" 6)" \
      "$(bpt "${lr16_0[$name]}" "$v")" "$other"
  done
} >"$f"
median_row "$f" >>"$f"

# Timing: decode and encode tables, columns per precision: lrmesh, Draco, ratio.
if [ "$runs" -gt 0 ]; then
  for what in dec enc; do
    f=$work/$what.tsv
    {
      hdr=(mesh triangles)
      for q in "${qps[@]}"; do
        n=$(qname "$q" | tr -d ' ')
        hdr+=("lrm $n" "Draco $n" "ratio $n")
        [ "$q" = 0 ] || hdr+=("lrm -l1 $n" "ratio -l1 $n")
      done
      row "${hdr[@]}"
      for m in "${meshes[@]}"; do
        name=$(basename "$m")
        cells=("$name" "${T[$name]}")
        for q in "${qps[@]}"; do
          k=$name,$q
          if [ "$what" = dec ]; then a=${ld[$k]} b=${dd[$k]}; else a=${le[$k]} b=${de[$k]}; fi
          cells+=("$a" "$b" "$(ratio "$a" "$b")")
          if [ "$q" != 0 ]; then
            if [ "$what" = dec ]; then a=${ld1[$k]}; else a=${le1[$k]}; fi
            cells+=("$a" "$(ratio "$a" "$b")")
          fi
        done
        row "${cells[@]}"
      done
    } >"$f"
    median_row "$f" >>"$f"
  done
fi

load=$(cut -d' ' -f1-3 /proc/loadavg)
if [ "$markdown" = 1 ]; then
  # For the README: the medians, then per mesh the whole files and the ratio to Draco.
  f=$work/summary.tsv
  {
    row precision lrmesh Draco OpenCTM meshopt "meshopt+zstd" "lrmesh/Draco" "OpenCTM/Draco" \
      "meshopt+zstd/Draco" "lrmesh -l 1" "-l 1/Draco"
    for q in "${qps[@]}"; do
      IFS=$'\t' read -r -a c <<<"$(tail -1 "$work/size.$q.tsv")"
      row "$(qname "$q")" "${c[2]}" "${c[5]}" "${c[9]}" "${c[11]}" "${c[15]}" "${c[8]}" "${c[10]}" \
        "${c[16]}" "${c[17]}" "${c[18]}"
    done
  } >"$f"
  heading "Whole files, bytes per triangle, median over ${#meshes[@]} CGAL meshes" \
    "(ratios: median of the per-mesh ratios)"
  render "$f"
  for q in "${qps[@]}"; do
    if [ "$q" = 0 ]; then
      heading "Lossless positions, bytes per triangle" \
        "(Draco -cl 10 -qp 0, OpenCTM MG1, meshopt on the f32s)"
    else
      heading "$q bits per coordinate, bytes per triangle (Draco -cl 10 -qp $q)"
    fi
    render "$work/size.$q.tsv" 1-10,12,16,18,19
  done
  heading "Positions alone, bytes per vertex (raw: 12 for f32, 6 at 16 bits)"
  render "$work/positions.tsv"
  if [ "$runs" -gt 0 ]; then
    heading "Full decode to arrays, M triangles/s (median of $runs runs, best of $rounds" \
      "rounds; ratio lrmesh/Draco; load average $load_start before, $load after)"
    render "$work/dec.tsv"
    heading "Full encode, M triangles/s (ratio lrmesh/Draco)"
    render "$work/enc.tsv"
  fi
  exit 0
fi

for q in "${qps[@]}"; do
  if [ "$q" = 0 ]; then
    heading "Lossless positions (f32): bytes per triangle" \
      "(Draco -cl 10 -qp 0, OpenCTM MG1, meshopt on the f32s)"
  else
    heading "Positions at $q bits: bytes per triangle" \
      "(Draco -cl 10 -qp $q, OpenCTM MG2 of the same step, meshopt on 4 x u16)"
  fi
  render "$work/size.$q.tsv"
done
heading "Positions alone, bytes per vertex: Edgebreaker GEOM (f32 against 12 raw; 11, 14, 16" \
  "bits), LR GEOM at 16 bits (default level against 6 raw; level 0); lrm other: header," \
  "section table, META, MESH at 11 bits, in bytes"
render "$work/positions.tsv"
if [ "$runs" -gt 0 ]; then
  heading "Full decode to arrays, M triangles/s (median of $runs runs, best of $rounds rounds;" \
    "ratio lrmesh/Draco; load average $load_start before, $load after)"
  render "$work/dec.tsv"
  heading "Full encode, M triangles/s (ratio lrmesh/Draco)"
  render "$work/enc.tsv"
  heading "Largest position error of lrmesh after a round trip (units of the largest extent;" \
    "half a step: 11 bits 2.44e-4, 14 bits 3.05e-5, 16 bits 7.63e-6)"
  {
    row mesh "11 bits" "14 bits" "16 bits" f32
    for m in "${meshes[@]}"; do
      name=$(basename "$m")
      row "$name" "${lerr[$name,11]:--}" "${lerr[$name,14]:--}" "${lerr[$name,16]:--}" \
        "${lerr[$name,0]:--}"
    done
  } >"$work/err.tsv"
  render "$work/err.tsv"
fi
