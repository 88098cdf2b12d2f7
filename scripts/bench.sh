#!/usr/bin/env bash
# Runs every benchmark in bench/ (built into build/bench, and the scripts bench/bench_*.sh). Benchmarks print their figures
# beside the anchor their issue names; they assert nothing.
set -euo pipefail
dir=${1:-build/bench}
status=0
for b in "$dir"/bench_*; do
  [ -x "$b" ] || continue
  echo "== $(basename "$b")"
  "$b" || status=1
done
# Benchmarks that drive the command (bench/bench_*.sh, given build/lucent)
for s in "$(dirname "$0")"/../bench/bench_*.sh; do
  [ -f "$s" ] || continue
  echo "== $(basename "$s")"
  bash "$s" "$dir/../lucent" || status=1
done
exit $status
