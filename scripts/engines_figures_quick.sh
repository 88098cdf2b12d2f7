#!/usr/bin/env bash
# The reduced run behind docs/engines.md's rendered table (scripts/engines_figures.sh is the full one,
# about two hours): Skin1 on the spheres and bunny scenes at half size, Lucent's burley method and
# Blender's Cycles Christensen-Burley, each with `lucent fit`'s parameters and with the hand mapping,
# against a path-traced reference bounded in time; the peers again with a second seed, against the same
# reference (--reference), for their own noise. About 45 minutes on two shared cores.
#
#   scripts/engines_figures_quick.sh [build/lucent] [out/engines-quick] [TIME] [PEER_SPP]
# (LIBLUCENT: the liblucent.so the noise script loads; default beside LUCENT)
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
# The peers' own noise (scripts/engines_peer_noise.py), and the spheres' images top to bottom: the
# reference, burley:fit, burley:hand, Cycles' Christensen-Burley fitted and by hand (linear, 2-pixel
# white rules between them; docs/images/engines-spheres-skin1.png).
for scene in spheres-skin bunny-skin; do
  python3 scripts/engines_peer_noise.py "${LIBLUCENT:-$(dirname "$LUCENT")/liblucent.so}" "$OUT/$scene/$scene" \
    "$OUT/$scene-seed2/$scene" blender-cycles-burley blender-cycles-burley-hand | tee "$OUT/$scene-peer-noise.txt"
done
python3 - "$LUCENT" "$OUT/spheres-skin/spheres-skin" "$OUT/engines-spheres-skin1" <<'PY'
import os, struct, subprocess, sys
lucent, d, out = sys.argv[1:4]
rows, w = [], 0  # PFM runs bottom to top: the last image first
for stem in ["blender-cycles-burley-hand", "blender-cycles-burley", "burley-hand", "burley-fit", "reference"]:
    subprocess.run([lucent, "-q", "image", "convert", os.path.join(d, stem + ".exr"), out + ".tmp.pfm"], check=True)
    head = open(out + ".tmp.pfm", "rb").read().split(b"\n", 3)
    w, h = map(int, head[1].split())
    px = list(struct.unpack("<%df" % (3 * w * h), head[3][:12 * w * h]))
    if rows:
        rows.append([1.0] * (3 * w * 2))
    rows.append(px)
    os.unlink(out + ".tmp.pfm")
data = [v for r in rows for v in r]
with open(out + ".pfm", "wb") as f:
    f.write(b"PF\n%d %d\n-1.0\n" % (w, len(data) // (3 * w)))
    f.write(struct.pack("<%df" % len(data), *data))
subprocess.run([lucent, "-q", "image", "convert", out + ".pfm", out + ".png"], check=True)
os.unlink(out + ".pfm")
PY
echo "engines_figures_quick: done in $OUT"
