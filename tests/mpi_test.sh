#!/usr/bin/env bash
# MPI runs of the commands that share Monte Carlo work (docs/scale.md): for the same seed,
# `mpirun -np 1`, 2 and 3 (oversubscribed: this checks correctness, not speed) give the plain run's
# files byte for byte, since the ranks run the same chunks with the same RNG streams and their
# tallies are summed exactly. A failing rank ends the job with a message and no output.
# usage: mpi_test.sh LUCENT FIXTURES MPIEXEC   (registered by tests/CMakeLists.txt when LUCENT_MPI)
set -u
TESTS=$(cd "$(dirname "$0")" && pwd)
# The harness is cli_test.sh up to its first check, which a marker line starts; without the marker the
# whole CLI suite would run here first (it did for a while: 300-500 s instead of about 60).
MARK='^# ---- the command itself ----'
grep -q "$MARK" "$TESTS/cli_test.sh" || { echo "mpi_test: no line '$MARK' in cli_test.sh to cut its harness at" >&2; exit 1; }
awk -v mark="$MARK" '$0 ~ mark {exit} {print}' "$TESTS/cli_test.sh" >"${TMPDIR:-/tmp}/lucent-mpi-harness.$$"
# shellcheck disable=SC1090
. "${TMPDIR:-/tmp}/lucent-mpi-harness.$$" # $LUCENT, $FIXTURES, $TMP, expect_*, _report
rm -f "${TMPDIR:-/tmp}/lucent-mpi-harness.$$"
MPIRUN=("$3" --oversubscribe --allow-run-as-root)
M="$TMP/mpi"
mkdir -p "$M/plain" "$M/bad"
MCI3="$FIXTURES/mcml/three_layers.mci"
SC="$FIXTURES/scenes/trace-small.json"

# ---- the plain runs ----
expect_ok -- "$LUCENT" mcml "$MCI3" --out-dir "$M/plain" --quiet
expect_ok -- "$LUCENT" profile skin1 --model mc --photons 8000 --bins 40 --out "$M/plain/p" --quiet
expect_ok -- "$LUCENT" trace "$SC" --spp 3 --out "$M/plain/t.png" --exr "$M/plain/t.exr" --quiet
expect_ok -- "$LUCENT" trace "$SC" --spp 6 --adaptive --out "$M/plain/a.png" --exr "$M/plain/a.exr" --quiet

for np in 1 2 3; do
  O="$M/np$np"
  mkdir -p "$O"
  expect_ok -- "${MPIRUN[@]}" -np "$np" "$LUCENT" mcml "$MCI3" --out-dir "$O" --threads 1 --quiet
  expect_true "mcml: mpirun -np $np gives the plain run's .mco byte for byte" -- \
    cmp "$M/plain/three_layers.mco" "$O/three_layers.mco"
  expect_ok -- "${MPIRUN[@]}" -np "$np" "$LUCENT" profile skin1 --model mc --photons 8000 --bins 40 --out "$O/p" \
    --threads 1 --quiet
  expect_true "profile --model mc: mpirun -np $np gives the plain run's CSV byte for byte" -- \
    cmp "$M/plain/p.csv" "$O/p.csv"
  expect_ok -- "${MPIRUN[@]}" -np "$np" "$LUCENT" trace "$SC" --spp 3 --out "$O/t.png" --exr "$O/t.exr" \
    --threads 1 --quiet
  expect_true "trace: mpirun -np $np gives the plain run's EXR byte for byte" -- cmp "$M/plain/t.exr" "$O/t.exr"
done
# every SIMD path this CPU has (--isa; docs/mcml.md, "SIMD paths"): 1 and 2 ranks give that path's plain
# run byte for byte (the lanes of a chunk draw from the chunk's stream, whichever rank runs it)
for isa in scalar avx2 avx512; do
  if ! "$LUCENT" --isa "$isa" mcml --help >/dev/null 2>&1; then
    echo "note: this CPU has no $isa path: its rank checks are left out"
    continue
  fi
  I="$M/isa-$isa"
  mkdir -p "$I/plain" "$I/np1" "$I/np2"
  expect_ok -- "$LUCENT" --isa "$isa" mcml "$MCI3" --out-dir "$I/plain" --quiet
  expect_ok -- "$LUCENT" --isa "$isa" profile skin1 --model mc --photons 8000 --bins 40 --out "$I/plain/p" --quiet
  for np in 1 2; do
    expect_ok -- "${MPIRUN[@]}" -np "$np" "$LUCENT" --isa "$isa" mcml "$MCI3" --out-dir "$I/np$np" --threads 1 --quiet
    expect_true "mcml, $isa: mpirun -np $np gives the plain run's .mco byte for byte" -- \
      cmp "$I/plain/three_layers.mco" "$I/np$np/three_layers.mco"
    expect_ok -- "${MPIRUN[@]}" -np "$np" "$LUCENT" --isa "$isa" profile skin1 --model mc --photons 8000 --bins 40 \
      --out "$I/np$np/p" --threads 1 --quiet
    expect_true "profile --model mc, $isa: mpirun -np $np gives the plain run's CSV byte for byte" -- \
      cmp "$I/plain/p.csv" "$I/np$np/p.csv"
  done
done
expect_ok -- "${MPIRUN[@]}" -np 2 "$LUCENT" trace "$SC" --spp 6 --adaptive --out "$M/np2/a.png" \
  --exr "$M/np2/a.exr" --threads 1 --quiet
expect_true "trace --adaptive: 2 ranks (sharing the pilot after every pass) give the plain run's EXR" -- \
  cmp "$M/plain/a.exr" "$M/np2/a.exr"

# --target-error: every rank measures the whole image's error (exactly), so the stop comes after the
# same pass as in one process
expect_ok -- "$LUCENT" trace "$SC" --spp 40 --target-error 0.2 --out "$M/plain/e.png" --exr "$M/plain/e.exr" --quiet
expect_ok -- "${MPIRUN[@]}" -np 3 "$LUCENT" trace "$SC" --spp 40 --target-error 0.2 --out "$M/np3/e.png" \
  --exr "$M/np3/e.exr" --threads 1 --quiet
expect_true "trace --target-error: 3 ranks stop after the plain run's pass, same EXR" -- \
  cmp "$M/plain/e.exr" "$M/np3/e.exr"
expect_true "... which is before --spp 40 (the target was met)" -- \
  awk '/"spp":/ { gsub(/[^0-9]/, "", $2); exit !($2 >= 16 && $2 < 40) }' "$M/np3/e.json"

# cdrf-fit: the spheres' batches; mcml with two runs (two .mco files, the tallies of each in turn)
expect_ok -- "$LUCENT" cdrf-fit skin1 --radii 2,5 --photons 2000 --bins 12 --out "$M/plain/c" --quiet
expect_ok -- "${MPIRUN[@]}" -np 2 "$LUCENT" cdrf-fit skin1 --radii 2,5 --photons 2000 --bins 12 --out "$M/np2/c" \
  --threads 1 --quiet
expect_true "cdrf-fit: 2 ranks give the plain run's CSV and JSON (the fit)" -- \
  sh -c "cmp '$M/plain/c.csv' '$M/np2/c.csv' && cmp '$M/plain/c.json' '$M/np2/c.json'"
expect_ok -- "$LUCENT" mcml "$FIXTURES/mcml/two_runs.mci" --out-dir "$M/plain" --quiet
expect_ok -- "${MPIRUN[@]}" -np 3 "$LUCENT" mcml "$FIXTURES/mcml/two_runs.mci" --out-dir "$M/np3" --threads 1 --quiet
expect_true "mcml, two runs: 3 ranks give both of the plain run's .mco files" -- \
  sh -c "cmp '$M/plain/glass.mco' '$M/np3/glass.mco' && cmp '$M/plain/half.mco' '$M/np3/half.mco'"

# ranks inside parts: parts 1/2 and 2/2 on 2 ranks each, merged, give the plain run
for k in 1 2; do
  expect_ok -- "${MPIRUN[@]}" -np 2 "$LUCENT" mcml "$MCI3" --out-dir "$M/np2" --part "$k/2" --threads 1 --quiet
done
mkdir -p "$M/merged"
expect_ok -- "$LUCENT" merge "$M"/np2/three_layers.mco.part-*-of-2 -- --out-dir "$M/merged"
expect_true "2 parts of 2 ranks each, merged, give the plain run's .mco" -- \
  cmp "$M/plain/three_layers.mco" "$M/merged/three_layers.mco"

# ---- a rank that fails ----
# rank 1 sees a bad input file (its copy differs): every rank ends, exit 1, rank 1's message
BADMCI="$FIXTURES/mcml/bad_g.mci"
on_rank1() { # FILE-ON-RANK-1 FILE-ELSEWHERE OUT-DIR
  "${MPIRUN[@]}" -np 2 sh -c 'if [ "${OMPI_COMM_WORLD_RANK:-0}" = 1 ]; then f=$1; else f=$2; fi
    exec "$0" mcml "$f" --out-dir "$3" --threads 1' "$LUCENT" "$@"
}
expect_fail 1 "rank 1 of 2 failed: $BADMCI: line 15: layer 1: g must be in [-1, 1], got 1.5" -- \
  on_rank1 "$BADMCI" "$MCI3" "$M/bad"
expect_no_file "$M/bad/three_layers.mco"
# rank 1 is killed mid-run: mpirun ends the other ranks; nothing is written. (mpirun's exit status
# is then the killed rank's, 137, and the message is mpirun's.)
sed 's/^20000 /100000000 /' "$MCI3" >"$M/bad/long.mci"
killed_rank1() {
  "${MPIRUN[@]}" -np 2 sh -c 'if [ "${OMPI_COMM_WORLD_RANK:-0}" = 1 ]; then
      "$0" mcml "$1" --out-dir "$2" --threads 1 & p=$!; sleep 1; kill -9 $p; wait $p; exit $?
    else exec "$0" mcml "$1" --out-dir "$2" --threads 1; fi' "$LUCENT" "$@"
}
expect_fail 137 "exited with non-zero status" -- killed_rank1 "$M/bad/long.mci" "$M/bad"
expect_no_file "$M/bad/three_layers.mco"

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ] && rm -rf "$TMP"
[ "$failed" -eq 0 ]
