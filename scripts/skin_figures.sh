#!/usr/bin/env bash
# The pictures and tables of docs/skin.md and the README's skin spheres: every skin preset path traced
# (data/scenes/skin-sphere.json) into docs/images/skin-<preset>.png, the spectral profile against the
# three-coefficient shortcut (docs/images/skin-light-shortcut.svg), and the table of colours (ITA by the
# Monte Carlo, the multipole's and the shortcut's distance from it in CIEDE2000), printed as Markdown.
# Usage: scripts/skin_figures.sh [build/lucent] [out/skin-figures] [SPP]. Needs python3.
set -euo pipefail
lucent=${1:-build/lucent}
work=${2:-out/skin-figures}
spp=${3:-512}
here=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$work" docs/images
export LUCENT_CACHE_DIR=$work/.cache
presets=(Skin-VeryLight Skin-Light Skin-Medium Skin-Tan Skin-Brown Skin-Dark Skin-Pale Skin-Flushed)
for p in "${presets[@]}"; do
  name=skin-$(tr '[:upper:]' '[:lower:]' <<<"${p#Skin-}")
  [ -s "$work/$name.png" ] || "$lucent" trace data/scenes/skin-sphere.json --set "objects[0].material=$p" \
    --set render.width=64 --set render.height=64 --spp "$spp" -q --out "$work/$name.png" --exr "$work/$name.exr"
  cp "$work/$name.png" "docs/images/$name.png"
done
"$lucent" profile skin-light --compare multipole,shortcut --out "$work/skin-light-shortcut" -q
cp "$work/skin-light-shortcut.svg" docs/images/skin-light-shortcut.svg
LUCENT_LIBRARY=${LUCENT_LIBRARY:-$(dirname "$lucent")/liblucent.so} PYTHONPATH=$here/python python3 - "${presets[@]}" <<'PY'
import sys
import lucent
print("| preset | ITA (Monte Carlo) | category | L* a* b* | multipole dE00 | shortcut dE00 |")
print("|---|---|---|---|---|---|")
for p in sys.argv[1:]:
    mc = lucent.skin_color(p, transport="mc", seed=1)
    mp, sc = lucent.skin_color(p), lucent.skin_color(p, transport="shortcut")
    print("| %s | %.1f | %s | %.1f %.1f %.1f | %.1f | %.1f |" % (
        p, mc["ita"], mc["category"], *mc["lab"], lucent.ciede2000(mp["lab"], mc["lab"]),
        lucent.ciede2000(sc["lab"], mp["lab"])))
PY
