#!/usr/bin/env bash
# Runs every benchmark in bench/ (built into build/bench). Benchmarks print their figures
# beside the anchor their issue names; they assert nothing.
set -euo pipefail
dir=${1:-build/bench}
status=0
for b in "$dir"/bench_*; do
  [ -x "$b" ] || continue
  echo "== $(basename "$b")"
  "$b" || status=1
done
exit $status
