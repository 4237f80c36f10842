#!/usr/bin/env bash
# The browser test of the web viewer (README, "In the browser"): builds the WebAssembly package
# (web/build.sh) and the lrmesh command, serves web/ on a local port, and drives headless
# Chromium (Debian's `chromium`; CHROMIUM names another executable) with playwright-core
# (web/test/run.mjs): every shipped mesh below is loaded through the file input and its counts
# checked against `lrmesh info --json`, a triangle is clicked and the highlighted stars checked
# against a corner table, the mesh is saved as .lrm in other connectivities and the saved
# files verified natively here, screenshots go to web/out/, and a 1M-triangle mesh is decoded
# in the page and natively, the WebAssembly speed reported as a ratio
# (a "# bench" line: the target is at least 0.5, measured, not asserted).
# The last line is `N passed, M failed`; the exit status is 1 when M > 0.
set -euo pipefail
web=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$web")
out=$web/out
mkdir -p "$out/bench" "$out/expected"
chromium=${CHROMIUM:-/usr/bin/chromium}
if [ ! -x "$chromium" ]; then
  echo "web test: no Chromium at $chromium (apt-get install chromium, or set CHROMIUM)"
  echo "0 passed, 1 failed"
  exit 1
fi

"$web/build.sh"
(cd "$root" && cargo build --release --locked --quiet --bin lrmesh)
lrmesh=$root/target/release/lrmesh
(cd "$web" && { [ -d node_modules/playwright-core ] || npm ci --silent --no-audit --no-fund; })

# Native checks, counted with the browser's.
passed=0
failed=0
check() { # DESCRIPTION COMMAND...
  local what=$1
  shift
  if "$@" >/dev/null 2>"$out/check.err"; then
    echo "ok - $what"
    passed=$((passed + 1))
  else
    echo "not ok - $what: $(head -c 300 "$out/check.err" | tr '\n' ' ')"
    failed=$((failed + 1))
  fi
}
# A key of a JSON file (node: no jq needed).
key() { node -e 'const o = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8")); console.log(o[process.argv[2]])' "$1" "$2"; }

# The shipped meshes: a container of each kind and mesh files the page encodes itself
# (with the CLI's defaults, so `lrmesh encode` gives the container the page shows).
meshes=(
  "$root/spec/vectors/torus_with_t0.lrm"
  "$root/spec/vectors/defective_torus.lr-compact.lrm"
  "$root/spec/vectors/defective_torus.zipper.lrm"
  "$root/spec/vectors/torus_with_t0.q12.l1.edgebreaker.lrm"
  "$root/spec/vectors/seamed_cube.obj"
  "$root/corpus/meshes/fandisk.off"
  "$root/corpus/meshes/bunny_small.ply"
)
entries=()
for m in "${meshes[@]}"; do
  name=$(basename "$m")
  name=${name%.*}
  if [ "${m##*.}" = lrm ]; then
    container=$m
  else
    container=$out/expected/$name.lrm
    "$lrmesh" encode "$m" -o "$container" >/dev/null
  fi
  "$lrmesh" info "$container" --json >"$out/expected/$name.json"
  entries+=("{\"path\": \"$m\", \"name\": \"$name\", \"info\": $(cat "$out/expected/$name.json"), \"screenshots\": true}")
done

# The decode bench: a 1M-triangle mesh as LR and as Edgebreaker (level 1, 16 bits); native
# time: `lrmesh decode`'s open (every rule) and decode, median of 5 runs.
"$lrmesh" generate "$out/bench/torus.ply" --triangles 1000000 --irregular --seed 1 >/dev/null
"$lrmesh" encode "$out/bench/torus.ply" -o "$out/bench/torus.lr.lrm" >/dev/null
"$lrmesh" encode "$out/bench/torus.ply" -o "$out/bench/torus.eb.lrm" --connectivity edgebreaker \
  --quantize-position 16 -l 1 >/dev/null
native_ms() {
  local times=()
  for _ in 1 2 3 4 5; do
    "$lrmesh" decode "$1" -o - --output-format ply --json 2>"$out/decode.json" >/dev/null
    times+=("$(node -e 'const o = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8")); console.log(o.open_ms + o.decode_ms)' "$out/decode.json")")
  done
  printf '%s\n' "${times[@]}" | sort -g | sed -n 3p
}
triangles=$("$lrmesh" info "$out/bench/torus.lr.lrm" --json >"$out/bench/info.json" && key "$out/bench/info.json" triangles)
bench=()
for kind in lr eb; do
  label=$([ $kind = lr ] && echo "lr" || echo "edgebreaker, 16 bits, -l 1")
  bench+=("{\"url\": \"out/bench/torus.$kind.lrm\", \"name\": \"$triangles-triangle torus, $label\", \"nativeMs\": $(native_ms "$out/bench/torus.$kind.lrm"), \"triangles\": $triangles}")
done

join() { local IFS=,; echo "$*"; }
cat >"$out/expect.json" <<EOF
{ "meshes": [$(join "${entries[@]}")],
  "saveKinds": ["edgebreaker", "lr-compact", "zipper"],
  "bench": [$(join "${bench[@]}")] }
EOF

# Serve web/ on a free port for the browser.
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
python3 -m http.server "$port" --bind 127.0.0.1 --directory "$web" >"$out/server.log" 2>&1 &
server=$!
trap 'kill $server 2>/dev/null || true' EXIT
for _ in $(seq 50); do
  python3 -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:$port/')" 2>/dev/null && break
  sleep 0.1
done

browser_status=0
CHROMIUM=$chromium node "$web/test/run.mjs" --url "http://127.0.0.1:$port/" \
  --expect "$out/expect.json" --out "$out" | grep -v -E '^[0-9]+ passed, [0-9]+ failed$' ||
  browser_status=$?

# The files the page saved open natively, every rule checked, with the same counts.
for m in "${meshes[@]}"; do
  name=$(basename "$m")
  name=${name%.*}
  for kind in edgebreaker lr-compact zipper; do
    saved=$out/$name.$kind.lrm
    check "$name saved as $kind: lrmesh verify" "$lrmesh" verify "$saved"
    same_counts() {
      "$lrmesh" info "$saved" --json >"$out/saved.json" &&
        [ "$(key "$out/saved.json" triangles)" = "$(key "$out/expected/$name.json" triangles)" ] &&
        [ "$(key "$out/saved.json" vertices)" = "$(key "$out/expected/$name.json" vertices)" ] &&
        [ "$(key "$out/saved.json" connectivity)" = "$kind" ]
    }
    check "$name saved as $kind: the triangle and vertex counts of the original" same_counts
  done
done

for build in pkg pkg-decoder; do
  echo "# $build/lrmesh_wasm_bg.wasm: $(gzip -9c "$web/$build/lrmesh_wasm_bg.wasm" | wc -c) bytes gzipped"
done
results=$out/browser-results.json
if [ -f "$results" ]; then
  passed=$((passed + $(key "$results" passed)))
  failed=$((failed + $(key "$results" failed)))
else
  echo "not ok - the browser test wrote no results (exit $browser_status)"
  failed=$((failed + 1))
fi
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
