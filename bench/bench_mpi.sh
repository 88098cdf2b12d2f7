#!/usr/bin/env bash
# Issue 18's bench: photons per second of `lucent mcml` on 2 MPI ranks x 1 thread against 1 rank x 2
# threads (the criterion: within 10%), and the samples a time-limited `lucent trace` gets on 1 and 2
# ranks (ranks share the pass schedule: N ranks, N times the samples). Prints the machine's load
# beside the figures: on a shared machine they move with it. Skipped without an MPI build.
# usage: bench/bench_mpi.sh [LUCENT]   (scripts/bench.sh passes build/lucent)
#   BENCH_MPI_PHOTONS (default 1000000), BENCH_MPI_TIME (trace seconds, default 8)
set -u
here=$(cd "$(dirname "$0")" && pwd)
lucent=${1:-$here/../build/lucent}
mpirun=$(command -v mpirun || command -v mpiexec || true)
if [ -z "$mpirun" ] || ! "$lucent" --help | grep -q "MPI build: yes"; then
  echo "bench_mpi: skipped (no mpirun, or $lucent built without MPI: cmake -DLUCENT_MPI=ON)"
  exit 0
fi
photons=${BENCH_MPI_PHOTONS:-1000000}
seconds=${BENCH_MPI_TIME:-8}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/lucent-bench-mpi-XXXXXX")
trap 'rm -rf "$tmp"' EXIT
sed "s/^20000 /$photons /" "$here/../tests/fixtures/mcml/three_layers.mci" >"$tmp/in.mci"
MPI=("$mpirun" --oversubscribe --allow-run-as-root --bind-to none)
load() { cut -d' ' -f1-3 /proc/loadavg; }

# mcml's own figure: photons / the seconds of the transport (reduction included, start-up not)
rate() { sed -n 's/.*; \([0-9.]*\) photons\/s).*/\1/p'; }
run_mcml() { # LABEL CMD...
  local label=$1 t0 t1 r
  shift
  t0=$(date +%s.%N)
  r=$("$@" 2>&1 | rate)
  t1=$(date +%s.%N)
  printf '  %-22s %10.0f photons/s (transport), %6.2f s wall (with start-up)   load %s\n' "$label" "${r:-0}" \
    "$(echo "$t1 - $t0" | bc)" "$(load)"
  echo "${r:-0}" >"$tmp/$label.rate"
}
echo "issue 18: photons/s, 2 ranks x 1 thread vs 1 rank x 2 threads (criterion: within 10%)"
echo "  $photons photons, three_layers.mci (MCML sample style), $(nproc) cores, load before: $(load)"
run_mcml 1rank-x-1thread "$lucent" mcml "$tmp/in.mci" --out-dir "$tmp" --threads 1
run_mcml 1rank-x-2threads "$lucent" mcml "$tmp/in.mci" --out-dir "$tmp" --threads 2
cp "$tmp/three_layers.mco" "$tmp/threads.mco"
run_mcml 2ranks-x-1thread "${MPI[@]}" -np 2 "$lucent" mcml "$tmp/in.mci" --out-dir "$tmp" --threads 1
cmp -s "$tmp/threads.mco" "$tmp/three_layers.mco" && same=identical || same=DIFFERENT
a=$(cat "$tmp/1rank-x-2threads.rate") b=$(cat "$tmp/2ranks-x-1thread.rate")
awk -v a="$a" -v b="$b" -v same="$same" 'BEGIN {
  r = a > 0 ? b / a : 0
  printf "  2 ranks / 2 threads: %.3f (%s the criterion of +-10%%); the two .mco files are %s\n",
    r, (r >= 0.9 && r <= 1.1) ? "within" : "OUTSIDE", same }'

scene="$here/skin1-sphere.json"
echo "issue 18: a time-limited trace (--time $seconds): samples on 1 and 2 ranks x 1 thread (ranks share the passes)"
for np in 1 2; do
  "${MPI[@]}" -np "$np" "$lucent" trace "$scene" --time "$seconds" --spp 100000 --set render.width=128 \
    --set render.height=128 --out "$tmp/t$np.png" --threads 1 --quiet
  s=$(sed -n 's/.*"samples":[[:space:]]*\([0-9]*\).*/\1/p' "$tmp/t$np.json" | head -1)
  printf '  %d rank(s): %12s samples in %s s   load %s\n' "$np" "${s:-?}" "$seconds" "$(load)"
  echo "${s:-0}" >"$tmp/t$np.samples"
done
awk -v a="$(cat "$tmp/t1.samples")" -v b="$(cat "$tmp/t2.samples")" \
  'BEGIN { printf "  2 ranks / 1 rank: %.2f times the samples (ideal 2 on 2 free cores)\n", (a > 0 ? b / a : 0) }'
