#!/usr/bin/env bash
# The reduced run behind docs/engines.md's rendered table (scripts/engines_figures.sh is the full one,
# about two hours): Skin1 on the spheres and bunny scenes at half size, Lucent's burley method and
# Blender's Cycles Christensen-Burley, each with `lucent fit`'s parameters and with the hand mapping,
# against a path-traced reference bounded in time; the peers again with a second seed, against the same
# reference (--reference), for their own noise. About 45 minutes on two shared cores.
#
#   scripts/engines_figures_quick.sh [build/lucent] [out/engines-quick] [TIME] [PEER_SPP]
set -euo pipefail
LUCENT=${1:-build/lucent}
OUT=${2:-out/engines-quick}
TIME=${3:-420}    # at most this many seconds per reference (two runs of half each)
PEER_SPP=${4:-64} # the peers' samples per pixel
SCALE=${SCALE:-0.5}
PEERS=blender-cycles-burley,blender-cycles-burley:hand
mkdir -p "$OUT"
for scene in spheres-skin bunny-skin; do
  dir=$OUT/$scene
  echo "$scene start $(date -u +%T) load $(cut -d' ' -f1-3 /proc/loadavg)"
  if [ ! -s "$dir/results.json" ]; then
    nice -n 5 "$LUCENT" compare "data/scenes/$scene.json" --scale "$SCALE" --spp 100000 --time "$TIME" \
      --methods burley:fit,burley:hand --peers "$PEERS" --peer-spp "$PEER_SPP" --out "$dir" >"$dir.log" 2>&1
  fi
  echo "$scene first run done $(date -u +%T) load $(cut -d' ' -f1-3 /proc/loadavg)"
  if [ ! -s "$dir-seed2/results.json" ]; then
    nice -n 5 "$LUCENT" compare "data/scenes/$scene.json" --scale "$SCALE" --spp 100000 --time "$TIME" \
      --reference "$dir" --methods burley:fit --peers "$PEERS" --peer-spp "$PEER_SPP" --peer-seed 2 \
      --out "$dir-seed2" >"$dir-seed2.log" 2>&1
  fi
  echo "$scene seed 2 done $(date -u +%T) load $(cut -d' ' -f1-3 /proc/loadavg)"
done
echo "engines_figures_quick: done in $OUT"
