#!/usr/bin/env bash
# Acceptance of issues 17 and 32: every hostile fixture (the reproducers of ../shared/repro and
# ../shared/repro-3, copied into tests/fixtures, and the fuzzers' findings) and every reproducer command of
# ../shared/repro-3/INDEX.txt that needs no file exits 1 (2 for usage) with a message naming the file and
# the field, in under 1 s of CPU time and 100 MB of peak memory. Run in the ASan build's unit tests (label
# unit), so the bounds hold under ASan + UBSan; by hand: tests/hostile_limits.sh build-asan/lucent.
#
# How it is measured: GNU time (/usr/bin/time -f '%e %U %S %M') around each command. %M is ru_maxrss of
# wait4: the peak resident set of the process and of the children it waited for (the assimp import's
# fork, a `bash -c ... exec`), which under ASan includes the shadow pages touched; RLIMIT_AS cannot bound
# an ASan process (its shadow reserves terabytes of address space), so the peak is measured and asserted
# instead. Time is user + system CPU (%U + %S), not wall time: on a shared, loaded machine the wall time
# says more about the other processes than about the command; it is printed beside.
# The viewer's reproducer (repro-3 item 14) runs in a GL context on llvmpipe, whose start alone costs
# seconds and over 100 MB under ASan; its bounds are asserted above a baseline run of the same viewer
# whose script only prints.
# Usage: hostile_limits.sh path/to/lucent [fixtures dir]
set -u
LUCENT=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
FIXTURES=${2:-$(cd "$(dirname "$0")" && pwd)/fixtures}
TESTS=$(cd "$(dirname "$0")" && pwd)
TMP=$(mktemp -d "${TMPDIR:-/tmp}/lucent-limits-XXXXXX")
[ -x /usr/bin/time ] || { echo "hostile_limits: /usr/bin/time missing (Debian package time, scripts/setup.sh)"; exit 1; }
failed=0
MAX_KB=102400    # 100 MB
MAX_CPU=1.0      # seconds of user + system CPU
measure() { # command...: sets rc, secs (wall), cpu, kb, msg (the first "lucent" line of stderr)
  /usr/bin/time -f "%e %U %S %M" -o "$TMP/time" "$@" >/dev/null 2>"$TMP/err"
  rc=$?
  local u s
  read -r secs u s kb < <(tail -1 "$TMP/time") 2>/dev/null || { secs=? u=9 s=9 kb=0; }
  cpu=$(awk -v u="$u" -v s="$s" 'BEGIN { printf "%.2f", u + s }')
  msg=$(grep "^lucent" "$TMP/err" | head -1)
}
# run NAME CODE EXPECT -- command...: exits CODE, its first "lucent" line naming NAME (the file; an info line
# of a bake, e.g. the viewer's "boundary tables of Skin1 ... in 0.7 s", may come before it) holds EXPECT
# (the field and the cause; empty where a fixture has no entry below), peak RSS < 100 MB, CPU < 1 s.
run() {
  local name=$1 code=$2 expect=$3; shift 4
  measure "$@"
  local named
  named=$(grep "^lucent" "$TMP/err" | grep -F -- "$name" | head -1)
  [ -z "$named" ] || msg=$named
  if [ "$rc" = "$code" ] && [[ "$msg" == *"$name"* ]] && [[ "$msg" == *"$expect"* ]] && [ "${kb:-0}" -lt $MAX_KB ] &&
    awk -v c="$cpu" -v m=$MAX_CPU 'BEGIN { exit !(c < m) }'; then
    printf 'ok   %-44s exit %s, cpu %4s s (wall %5s s), %6d KB: %s\n' "$name" "$rc" "$cpu" "$secs" "$kb" "${msg:0:110}"
  else
    printf 'FAIL %-44s exit %s (want %s), cpu %s s (wall %s s), %s KB: %s\n     want the words: %s\n' "$name" "$rc" \
      "$code" "$cpu" "$secs" "$kb" "$msg" "$expect"
    failed=$((failed + 1))
  fi
}
# The field and the cause each fixture's message must name (after its file's name).
declare -A EXPECT=(
  [bomb-ply-gz-mesh-30m-faces.ply.gz]="the header declares 30000000 face entries"
  [fuzz-abort-off-zero-bytes.off]="malformed off mesh: the importer (assimp) crashed on it"
  [fuzz-min-segv-ply-header.ply]='line 2: expected one "format'
  [fuzz-timeout-gltf-spin.gltf]="malformed gltf mesh: the importer (assimp) " # ran out of time; under ASan: needed more than 48 MB
  [fuzz-uaf-obj-point.obj]="no faces in the file (1 vertices)"
  [hand-gz-bad-crc.ply.gz]="corrupt gzip data after 269 inflated bytes: incorrect data check"
  [hand-gz-list-bomb.ply.gz]="gzip data inflating more than 100 times its size"
  [hand-gz-trailer-cut.ply.gz]="truncated gzip data"
  [hand-segv-ply-no-faces.ply]="no face element: this PLY holds points only"
  [bomb-points-scene.json]="objects[0].points: "
  [fuzz-null-mesh-name.json]="objects[0].mesh: not valid UTF-8 text"
  [fuzz-uninit-primitive-kind.json]="objects[0].mesh.subdiviseons: unknown field"
  [bomb-exr-tiled-379-bytes.exr]="corrupt OpenEXR chunk table (the chunk at tile 0, 0 claims 10 bytes"
  [hand-exr-short-zip-tile.exr]="truncated or corrupt OpenEXR data"
  [uninit-exr-short-scanline-chunk.exr]="truncated or corrupt OpenEXR data (the uncompressed chunk at line 0 holds 5 bytes"
  [uninit-exr-short-tile.exr]="truncated or corrupt OpenEXR data (the uncompressed chunk at tile 0, 0 holds 10 bytes"
  [bomb-ply-gz-points-20m.ply.gz]="the header declares 20000000 vertex entries"
  [hand-points-3dgs-scale-100.ply]="vertex 1: the scales (scale_0..2) give a radius of"
  [hand-points-double-1e300.ply]="vertex 2: x = 1e+300 does not fit a float"
  [hand-points-duplicate-property.ply]="line 10: element vertex declares the property x twice"
  [hand-points-extra-rows-binary.ply]="byte 217: data after the last element's rows"
  [hand-points-extra-rows.ply]="line 14: more rows than the header declares"
  [hand-points-radius-huge.ply]="vertex 2: radius must be > 0"
  [hand-points-radius-tiny.ply]="vertex 1: radius must be > 0"
  [hand-points-x-list.ply]="no vertex positions (property x is a list"
  [crash-ubsan-merge-int64-overflow.part-1-of-2]="header: a part file of format v1"
  [wrong-merge-negative-tallies.part-1-of-2]="header: a part file of format v1"
  [wrong-merge-tampered.part-1-of-2]="header: a part file of format v1"
)
fixture() { # NAME CODE -- command...: run with the fixture's entry of EXPECT
  local name=$1 code=$2; shift 3
  [ -n "${EXPECT[$name]+x}" ] || echo "note: $name has no entry in EXPECT (its field is not asserted)"
  run "$name" "$code" "${EXPECT[$name]:-}" -- "$@"
}

for f in "$FIXTURES"/bad-meshes/*; do
  fixture "$(basename "$f")" 1 -- "$LUCENT" curvature "$f" --out "$TMP/x.csv"
done
for f in "$FIXTURES"/bad-scenes/*; do
  fixture "$(basename "$f")" 1 -- "$LUCENT" trace "$f" --out "$TMP/x.png"
done
for f in "$FIXTURES"/bad-images/*; do
  [ -f "$f" ] && fixture "$(basename "$f")" 1 -- "$LUCENT" image info "$f"
done
# Point clouds (issue 32): each through a scene that holds it.
for f in "$FIXTURES"/bad-points/*; do
  printf '{"camera": {"position": [0, 0, 20], "target": [0, 0, 0]}, "lights": [{"type": "directional", "direction":
    [0, 0, -1], "intensity": 1}], "objects": [{"points": "%s", "material": "skin1"}]}\n' "$f" >"$TMP/cloud.json"
  fixture "$(basename "$f")" 1 -- "$LUCENT" trace "$TMP/cloud.json" --out "$TMP/x.png"
done
# Part files of ../shared/repro-3, written in format v1 (their tallies overflow, are negative or were changed).
for f in "$FIXTURES"/bad-parts/*-1-of-2; do
  fixture "$(basename "$f")" 1 -- "$LUCENT" merge "$f" "${f%-1-of-2}-2-of-2" -- --out-dir "$TMP/merged"
done
# The same damage in format v2 parts written now (tests/tamper_part.py; the CRC-32 recomputed except for
# keep-crc), so that the merge's own checks, not the version, refuse them: the overflow under UBSan too.
"$LUCENT" -q mcml "$FIXTURES/mcml/three_layers.mci" --out-dir "$TMP/parts" --seed 3 --part 1/2 &&
  "$LUCENT" -q mcml "$FIXTURES/mcml/three_layers.mci" --out-dir "$TMP/parts" --seed 3 --part 2/2 ||
  { echo "FAIL the parts to tamper with were not written"; failed=$((failed + 1)); }
for m in max negative keep-crc; do
  for k in 1 2; do
    python3 "$TESTS/tamper_part.py" $m "$TMP/parts/three_layers.mco.part-$k-of-2" "$TMP/parts/$m.part-$k-of-2"
  done
done
run "max.part-2-of-2" 1 "merge: tally 1 value 0 overflows when" -- \
  "$LUCENT" merge "$TMP/parts/max.part-1-of-2" "$TMP/parts/max.part-2-of-2" -- --out-dir "$TMP/merged"
run "negative.part-1-of-2" 1 "tally 1: value 0 is negative (-1): a damaged part file" -- \
  "$LUCENT" merge "$TMP/parts/negative.part-1-of-2" "$TMP/parts/negative.part-2-of-2" -- --out-dir "$TMP/merged"
run "keep-crc.part-1-of-2" 1 "the part's checksum does not match its contents" -- \
  "$LUCENT" merge "$TMP/parts/keep-crc.part-1-of-2" "$TMP/parts/keep-crc.part-2-of-2" -- --out-dir "$TMP/merged"
# ../shared/repro: hand-material-dense.json is, byte for byte, tests/fixtures/materials/dense-1e300.json.
run dense-1e300.json 1 "sigma_s[0]: sigma_t = sigma_a + sigma_s = 1e+300 mm^-1 is above" -- \
  "$LUCENT" profile "$FIXTURES/materials/dense-1e300.json" --model mc --out "$TMP/p"
cp "$FIXTURES/mcml/drtiny.mci" "$TMP/"
run drtiny.mci 1 "line 5 (the run of line 3): grid.dr" -- bash -c "cd '$TMP' && exec '$LUCENT' mcml drtiny.mci"

# The reproducers of ../shared/repro-3/INDEX.txt that need no file (INDEX item: command).
SM="$FIXTURES/scenes/trace-small.json"
run "--range" 2 "needs a number > 0 and at most 1e6" -- "$LUCENT" kernel skin1 --range 1e9 --export json --out "$TMP/k.json"
run "trace-small.json" 1 "no pass completed within the time limit of 0.001 s" -- \
  "$LUCENT" trace "$SM" --time 0.001 --out "$TMP/t.png" --exr "$TMP/t.exr" # INDEX 4
run "trace-small.json" 1 "render.background: must be in [0, 1e+30], got 1e+308" -- \
  "$LUCENT" trace "$SM" --spp 1 --set render.background=1e308 --out "$TMP/b.png" # INDEX 13
run "trace-small.json" 1 "objects[0].transform.scale: must be within" -- \
  "$LUCENT" trace "$SM" --spp 1 --set 'objects[0].transform={"scale":1e300}' --out "$TMP/b.png"
run "trace-small.json" 1 "objects[0].mesh.radius: must be > 0" -- \
  "$LUCENT" trace "$SM" --spp 1 --set 'objects[0].mesh={"primitive":"icosphere","radius":0}' --out "$TMP/b.png"
run "--radii" 2 "'1e-300' is not a radius" -- "$LUCENT" cdrf-fit skin1 --radii 1e-300 --photons 2000 --out "$TMP/cf"
run "--screen" 2 "'4294967297x1080'" -- "$LUCENT" pack skin1 --engine glsl --screen 4294967297x1080 --out "$TMP/pk" # 17
run "--object-height" 2 "from 0.001 mm to 1e12 mm" -- \
  "$LUCENT" pack skin1 --engine glsl --object-height 1e-300mm --out "$TMP/pk"
run "--size 16384x16384" 2 "the picture with its colour bar is 16512 x 16384 pixels" -- \
  "$LUCENT" curvature "$FIXTURES/mesh/tetra.ply" --out "$TMP/c.png" --size 16384x16384 # INDEX 16f
run "dense-1e300.json" 1 "sigma_s[0]: sigma_t = sigma_a + sigma_s = 1e+300 mm^-1 is above" -- \
  "$LUCENT" kernel "$FIXTURES/materials/dense-1e300.json" --profile mc --export json --out "$TMP/k.json" # INDEX 16a
run "objects[0].material: /proc/self/mem" 1 "read failed: Input/output error" -- \
  "$LUCENT" trace "$SM" --spp 1 --set 'objects[0].material=/proc/self/mem' --out "$TMP/t.png" # INDEX 16b
run "LUCENT_THREADS='abc'" 2 "needs a whole number from 1 to 256" -- env LUCENT_THREADS=abc "$LUCENT" materials

# repro-3 item 14 (wrong-view-orbit-nan-save.txt, tests/fixtures/view/orbit-nan-save.txt): exit 1 naming the
# script, the line and the cause, nothing saved; bounded above the viewer's start (a script that prints).
if [ -n "${LUCENT_GL_SKIP:-}" ]; then
  echo "skip the viewer's reproducer: $LUCENT_GL_SKIP"
else
  VIEW=("$LUCENT")
  [ -n "${LUCENT_GL_PRELOAD:-}" ] &&
    VIEW=(env "LD_PRELOAD=$LUCENT_GL_PRELOAD" "ASAN_OPTIONS=${ASAN_OPTIONS:-}:verify_asan_link_order=0" "$LUCENT")
  mkdir -p "$TMP/view/out" && printf 'print\n' >"$TMP/view/print.txt"
  ARGS=(view "$FIXTURES/scenes/sphere.json" --headless --no-cache --set render.method=lambert --script)
  measure bash -c 'cd "$1" && shift && exec "$@"' _ "$TMP/view" "${VIEW[@]}" "${ARGS[@]}" print.txt
  base_rc=$rc base_cpu=$cpu base_kb=$kb
  measure bash -c 'cd "$1" && shift && exec "$@"' _ "$TMP/view" "${VIEW[@]}" "${ARGS[@]}" "$FIXTURES/view/orbit-nan-save.txt"
  msg=$(grep "^lucent" "$TMP/err" | grep -F orbit-nan-save.txt | head -1) # the bakes' info lines come first
  extra_cpu=$(awk -v a="$cpu" -v b="$base_cpu" 'BEGIN { printf "%.2f", a - b }') extra_kb=$((kb - base_kb))
  if [ "$base_rc" = 0 ] && [ "$rc" = 1 ] && [[ "$msg" == *"orbit-nan-save.txt: line 1 (orbit): orbit: the camera would not be finite"* ]] &&
    [ ! -e "$TMP/view/out/view-nan.json" ] && [ "$extra_kb" -lt $MAX_KB ] &&
    awk -v c="$extra_cpu" -v m=$MAX_CPU 'BEGIN { exit !(c < m) }'; then
    printf 'ok   %-44s exit 1, cpu %s s above the start (%s s), %d KB above it (%d KB): %s\n' orbit-nan-save.txt \
      "$extra_cpu" "$base_cpu" "$extra_kb" "$base_kb" "${msg:0:110}"
  else
    printf 'FAIL %-44s exit %s (start: exit %s), cpu %s s above the start (%s s), %s KB above it: %s\n' \
      orbit-nan-save.txt "$rc" "$base_rc" "$extra_cpu" "$base_cpu" "$extra_kb" "$msg"
    failed=$((failed + 1))
  fi
fi
rm -rf "$TMP"
echo "$failed failed"
[ "$failed" -eq 0 ]
