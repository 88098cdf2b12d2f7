#!/usr/bin/env bash
# Runs the README's examples as a user would on a fresh clone (issue 16 item 4): every line of a
# ```sh block that starts with `lucent ` (continuation lines joined), and `for ...; do lucent ...;
# done` loops (run as written), in the order of the README,
# and `mpirun ...` lines (run as written: as root they need the flags the README gives), from a
# scratch copy of the repository's data/, docs/ and tests/, with the build's lucent first on PATH.
# An example may use files an earlier example wrote. Every example writes under out/ (issue 35):
# afterwards the scratch copy must hold no file that was not there before, out/ aside.
#
# Sizes: unless LUCENT_README_FULL=1, small-size options are appended per subcommand (the table
# below: later options win; tsd's texture is 256 texels a side: at 2048, one tsd frame takes 18 s on
# llvmpipe), so that the whole README runs in a minute or two. A line that cannot
# run here says `readme-test: skip (why)` in its comment; one that needs the fetched meshes is skipped when
# data/meshes lacks them. Usage: readme_test.sh LUCENT SOURCE_DIR [CACHE_DIR]
set -u
lucent=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/lucent-readme-XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/bin"
ln -s "$lucent" "$work/bin/lucent"
mkdir -p "$work/data"
cp -R "$src/docs" "$src/tests" "$work/"
for f in "$src"/data/*; do
  case $f in */meshes) ln -s "$f" "$work/data/meshes" ;; *) cp -R "$f" "$work/data/" ;; esac
done
listing() { (cd "$work" && find . -path ./bin -prune -o -path ./cache -prune -o -path ./out -prune -o -print | sort); }
before=$(listing)
export PATH=$work/bin:$PATH LUCENT_CACHE_DIR=${3:-$work/cache}

small_options() { # SUBCOMMAND: what makes its example small
  case $1 in
    render) echo "--set render.width=32 --set render.height=24 --set render.shadow_map_size=256 --set render.tsd_size=256" ;;
    trace) echo "--set render.width=32 --set render.height=24 --spp 2 --time 5" ;;
    compare) echo "--set render.width=32 --set render.height=24 --set render.shadow_map_size=256 --set render.tsd_size=256 --spp 2 --time 5 --frames 1" ;;
    profile) echo "--photons 5000" ;;
    kernel) echo "--photons 5000" ;;
    kernel-eval) echo "--size 32" ;;
    cdrf-fit) echo "--photons 2000 --bins 6" ;;
    cdrf-lut) echo "--width 16 --height 8" ;;
    pack) echo "--sigma0-photons 2000 --transmit-photons 500 --fit-photons 5000 --fit-model-photons 1000" ;;
    fit) echo "--photons 5000 --model-photons 1000" ;;
    *) echo "" ;;
  esac
}

# The examples, one per line (backslash continuations joined).
examples=$(awk '/^```sh[[:space:]]*$/ {inblock = 1; next} /^```/ {inblock = 0; next}
  inblock { line = (cont ? cont " " : "") $0; cont = "";
            if (line ~ /\\$/) { sub(/\\$/, "", line); cont = line; next }
            sub(/^[[:space:]]+/, "", line); if (line ~ /^lucent / || line ~ /^mpirun .* lucent / || line ~ /^for .*; do lucent .*; done/) print line }' "$src/README.md")
passed=0 failed=0 skipped=0
while IFS= read -r line; do
  [ -n "$line" ] || continue
  if [[ "$line" == *"readme-test: skip"* ]]; then skipped=$((skipped + 1)); echo "skip $line"; continue; fi
  cmd=${line%%#*}                     # the shell comment goes
  sub=$(awk '{print $2}' <<<"$cmd")
  if [[ "$cmd" == *data/meshes/* ]]; then
    missing=0
    for f in $(grep -o 'data/meshes/[^ ]*' <<<"$cmd"); do [ -e "$src/$f" ] || missing=1; done
    if [ "$missing" = 1 ]; then skipped=$((skipped + 1)); echo "skip (no meshes: make setup) $line"; continue; fi
  fi
  extra=""
  [ "${LUCENT_README_FULL:-0}" = 1 ] || [[ "$cmd" != lucent* ]] || extra=$(small_options "$sub")
  t0=$(date +%s.%N)
  out=$(cd "$work" && bash -c "$cmd $extra" 2>&1 </dev/null); rc=$?
  secs=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
  if [ "$rc" = 0 ]; then
    passed=$((passed + 1)); echo "ok   ${secs} s  $line"
  else
    failed=$((failed + 1)); echo "FAIL $line (exit $rc)"; { grep '^lucent' <<<"$out" | tail -5; printf '%s\n' "$out" | tail -5; } | sed 's/^/     /'
  fi
done <<<"$examples"
echo "$passed passed, $failed failed, $skipped skipped"
stray=$(comm -13 <(printf '%s\n' "$before") <(listing))
if [ -n "$stray" ]; then
  echo "FAIL: the examples wrote outside out/:"; printf '%s\n' "$stray" | sed 's/^/     /'; failed=$((failed + 1))
fi
[ "$passed" -gt 0 ] && [ "$failed" = 0 ]
