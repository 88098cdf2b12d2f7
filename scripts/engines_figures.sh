#!/usr/bin/env bash
# The figures of docs/engines.md: for Skin1, Marble and Ketchup on the spheres and bunny scenes, Lucent's
# burley method and Blender's Cycles (Christensen-Burley and Random Walk), each with `lucent fit`'s
# parameters and with the hand mapping (radius = 1/sigma_tr, colour = T), against the path-traced
# reference; the peers' own noise from a second seed; and `lucent fit` of the three materials and of a
# layered skin. Long: about an hour on 2 cores.
#
#   scripts/engines_figures.sh [build/lucent] [out/engines] [SPP] [TIME]
set -euo pipefail
LUCENT=${1:-build/lucent}
OUT=${2:-out/engines}
SPP=${3:-1024}  # reference samples per pixel
TIME=${4:-900}  # at most this many seconds per reference
PEER_SPP=${PEER_SPP:-256}
METHODS=lambert,ssss:preint,burley:fit,burley:hand
PEERS=blender-cycles-burley,blender-cycles-burley:hand,blender-cycles,blender-cycles:hand
mkdir -p "$OUT"

sets() { # SCENE MATERIAL: --set objects[i].material=MATERIAL for every object
  local n=$(grep -c '"name"' "data/scenes/$1.json")
  for ((i = 0; i < n - 1; i++)); do printf -- "--set objects[%d].material=%s " "$i" "$2"; done
}

for scene in spheres-skin bunny-skin; do
  for material in skin1 marble ketchup; do
    dir=$OUT/$scene-$material
    # the peers (Blender), and a cheap second run of them with another seed for their own noise
    if [ ! -s "$dir/results.json" ]; then
      # shellcheck disable=SC2046
      nice -n 5 "$LUCENT" compare "data/scenes/$scene.json" --scale 0.5 $(sets "$scene" "$material") \
        --spp "$SPP" --time "$TIME" --methods lambert --peers "$PEERS" --peer-spp "$PEER_SPP" --out "$dir" \
        >"$dir.log" 2>&1
      # shellcheck disable=SC2046
      nice -n 5 "$LUCENT" compare "data/scenes/$scene.json" --scale 0.5 $(sets "$scene" "$material") \
        --spp 4 --methods lambert --peers "$PEERS" --peer-spp "$PEER_SPP" --peer-seed 2 --out "$dir-seed2" \
        >"$dir-seed2.log" 2>&1
    fi
    # Lucent's methods
    if [ ! -s "$dir-methods/results.json" ]; then
      # shellcheck disable=SC2046
      nice -n 5 "$LUCENT" compare "data/scenes/$scene.json" --scale 0.5 $(sets "$scene" "$material") \
        --spp "$SPP" --time "$TIME" --methods "$METHODS" --out "$dir-methods" >"$dir-methods.log" 2>&1
    fi
  done
done

for material in skin1 marble ketchup; do
  nice -n 5 "$LUCENT" -q fit "$material" --transmittance --out "$OUT/fit-$material" >/dev/null
done
nice -n 5 "$LUCENT" -q fit --layers skin1:0.25,skin2:inf --out "$OUT/fit-skin-layers" >/dev/null
echo "engines_figures: done in $OUT"
