#!/usr/bin/env bash
# The Blender peer of `lucent compare --peers` run for real (CTest label "peer": Debian's blender,
# installed by `make setup`; not under the sanitizers, since Blender is not ours).
# Usage: peer_blender_test.sh path/to/lucent
#
# A Skin1 sphere (6 mm, 48 x 36 pixels) lit from the side: the path-traced reference at 128 spp, and
# Cycles with `lucent fit`'s parameters at 64 spp, its Random Walk (blender-cycles, Blender's default)
# and its Christensen-Burley. Checked:
#   - each peer's relative RMS error against the reference is below its bound, measured on this scene:
#     the reference's own noise at 128 spp is 9.5% (reported by compare); Cycles' at 64 spp 15.5% for
#     Christensen-Burley and 12.5% for the Random Walk (two seeds differ by 21.9% and 17.7% relative RMS,
#     / sqrt 2); the model's own error 11.2% for Christensen-Burley (at 512 and 256 spp the error is 14.4%
#     with noises 4.7% and 7.8%: sqrt(14.4^2 - 4.7^2 - 7.8^2)), 26.4% for the Random Walk, whose diffuse
#     entry lets the light in at grazing angles where the material's boundary reflects it (docs/engines.md).
#     Together sqrt(9.5^2 + 15.5^2 + 11.2^2) = 21.3% (measured 21.8%, 21.5% with seeds 1 and 2) and
#     sqrt(9.5^2 + 12.5^2 + 26.4^2) = 30.7% (measured 32.1%, 29.4%); the bounds, 0.30 and 0.42, leave 35-40%
#     margin. A wrong light unit, a mirrored camera or sun, or meshes wound inward fail the checks below;
#   - Christensen-Burley's mean is within 10% of the reference's (the same light reaches the camera);
#   - the lit side is left in all three (the camera and the sun are not mirrored);
#   - a missing Blender fails with a message naming what to install; an unknown peer is refused.
set -u
LUCENT=$1
TMP=$(mktemp -d "${TMPDIR:-/tmp}/lucent-peer-XXXXXX")
failed=0
check() { # DESCRIPTION CONDITION...
  local what=$1; shift
  if "$@"; then echo "ok   $what"; else echo "FAIL $what"; failed=1; fi
}

cat >"$TMP/sphere.json" <<'EOF'
{
  "name": "peer-sphere",
  "camera": {"position": [0, 0, 40], "target": [0, 0, 0], "fov_y": 25},
  "lights": [{"type": "directional", "direction": [1, -0.15, -0.25], "intensity": 3.0},
             {"type": "environment", "intensity": 0.02}],
  "objects": [{"name": "s", "mesh": {"primitive": "icosphere", "radius": 6, "subdivisions": 4},
               "material": "skin1", "specular_f0": 0.028}],
  "render": {"width": 48, "height": 36, "method": "lambert"}
}
EOF

out=$("$LUCENT" compare "$TMP/sphere.json" --methods lambert --spp 128 \
  --peers blender-cycles,blender-cycles-burley --peer-spp 64 --out "$TMP/out" 2>&1)
rc=$?
check "compare --peers blender-cycles,blender-cycles-burley runs" test "$rc" = 0 || echo "$out"
results=$TMP/out/results.json
check "the peers' images are written beside the methods'" \
  test -s "$TMP/out/peer-sphere/blender-cycles.exr" -a -s "$TMP/out/peer-sphere/blender-cycles-burley.exr"
error_of() { # PEER: its relative RMS error in results.json
  python3 -c '
import json, sys
r = json.load(open(sys.argv[1]))
m = [m for s in r["scenes"] for m in s["methods"] if m.get("method", m.get("name")) == sys.argv[2]]
print(m[0]["rel_rms"] if m else "nan")' "$results" "$1" 2>/dev/null
}
for pair in blender-cycles:0.42 blender-cycles-burley:0.30; do
  peer=${pair%%:*} bound=${pair#*:}
  err=$(error_of "$peer")
  echo "     $peer: relative RMS error $err against the reference"
  check "$peer's error against the reference is below $bound" python3 -c "import sys; sys.exit(not float('$err') < $bound)"
done

means() { # FILE: "r g b" means
  "$LUCENT" image info "$1" | awk '$1 == "R" || $1 == "G" || $1 == "B" {printf "%s ", $4}'
}
ref=$(means "$TMP/out/peer-sphere/reference.exr") peer=$(means "$TMP/out/peer-sphere/blender-cycles-burley.exr")
echo "     means: reference $ref, peer $peer"
check "Christensen-Burley's mean is within 10% of the reference's" python3 -c "
r = [float(x) for x in '$ref'.split()]; p = [float(x) for x in '$peer'.split()]
import sys; sys.exit(not all(abs(a / b - 1) < 0.10 for a, b in zip(p, r)))"
halves() { # FILE: the mean of the left half over the right half, red channel
  "$LUCENT" image convert "$1" "$TMP/h.pfm" >/dev/null && python3 -c '
import struct, sys
d = open(sys.argv[1], "rb").read().split(b"\n", 3)
w, h = map(int, d[1].split()); px = struct.unpack("<%df" % (3 * w * h), d[3][:12 * w * h])
left = sum(px[3 * (y * w + x)] for y in range(h) for x in range(w // 2))
right = sum(px[3 * (y * w + x)] for y in range(h) for x in range(w // 2, w))
print(left / right)' "$TMP/h.pfm"
}
for f in reference blender-cycles blender-cycles-burley; do
  check "the sphere is lit from the left in $f" python3 -c "
import sys; sys.exit(not $(halves "$TMP/out/peer-sphere/$f.exr") > 1.5)"
done

# EEVEE headless (no display: Debian's Blender 3.4 renders EEVEE under -b here), against the same
# reference (--reference): its mean within 20% of the reference's per channel (measured at 16 spp:
# +3%, -9%, -5%; EEVEE's screen-space subsurface is not Cycles' and needs no bound of its own) and lit
# from the left.
out=$("$LUCENT" compare "$TMP/sphere.json" --methods lambert --reference "$TMP/out" --spp 128 \
  --peers blender-eevee --peer-spp 16 --out "$TMP/eevee" 2>&1)
rc=$?
check "compare --peers blender-eevee runs without a display" test "$rc" = 0 || echo "$out"
peer=$(means "$TMP/eevee/peer-sphere/blender-eevee.exr")
echo "     means: reference $ref, EEVEE $peer"
check "EEVEE's mean is within 20% of the reference's" python3 -c "
r = [float(x) for x in '$ref'.split()]; p = [float(x) for x in '$peer'.split()]
import sys; sys.exit(not all(abs(a / b - 1) < 0.20 for a, b in zip(p, r)))"
check "the sphere is lit from the left in EEVEE" python3 -c "
import sys; sys.exit(not $(halves "$TMP/eevee/peer-sphere/blender-eevee.exr") > 1.5)"

out=$(LUCENT_BLENDER=/nonexistent/blender "$LUCENT" compare "$TMP/sphere.json" --methods lambert --spp 1 \
  --peers blender-cycles --out "$TMP/none" 2>&1)
check "a missing Blender fails, saying what to install" grep -q "Blender not found.*install Debian's blender" <<<"$out"
out=$("$LUCENT" compare "$TMP/sphere.json" --methods lambert --spp 1 --peers unreal --out "$TMP/none" 2>&1)
check "an unknown peer is refused, naming the known ones" grep -q "unknown peer \"unreal\" (blender-cycles" <<<"$out"

[ "$failed" = 0 ] && rm -rf "$TMP"
exit "$failed"
