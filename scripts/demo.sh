#!/usr/bin/env bash
# The main job: every real-time method of Lucent against the path-traced reference on the default
# scenes, as one HTML report; then the building blocks (materials, profiles, kernels, the CDRF).
# Writes under OUT (default out/demo) and says where the report is.
set -euo pipefail
lucent=${1:-build/lucent}
out=${2:-out/demo}
mkdir -p "$out"
# The references get DEMO_TIME seconds each (default 60) at DEMO_SCALE times each scene's size
# (default 0.5): a few minutes on 2 cores. Raise them for cleaner references; the report prints
# each reference's own noise beside the errors.
scale=${DEMO_SCALE:-0.5}
seconds=${DEMO_TIME:-60}
cat <<EOF
Lucent demo: real-time subsurface scattering against the truth.

For each default scene (the Stanford dragon in marble, the bunny in skin, skin spheres of growing
radius) Lucent renders a physically based reference with its volumetric path tracer ($seconds s
each), then every real-time method with OpenGL, and reports each method's error against the
reference beside its frame time. This takes a few minutes on 2 cores.

EOF

methods=lambert,cdrf,cdrf+translucency,ssss:preint,ssss:svd1,ssss:svd3,ssss:guided,ssss:manual,ssss:jimenez,points
"$lucent" compare data/scenes/spheres-skin.json data/scenes/bunny-skin.json data/scenes/dragon-marble.json \
  --methods "$methods" --spp 1000000 --time "$seconds" --scale "$scale" --out "$out/compare"

echo
echo "== The building blocks"
"$lucent" materials --json --out "$out/materials.json" -q
"$lucent" materials --swatches "$out/materials.png" -q
for m in skin1 marble; do
  "$lucent" profile "$m" --compare mc,dipole,better-dipole,burley --photons 200000 --sog 4 \
    --out "$out/$m-profiles" -q
done
"$lucent" kernel skin1 --model svd --export glsl --out "$out/skin1-svd.glsl" -q
"$lucent" kernel marble --model preint --export json --out "$out/marble-preint.json" -q
"$lucent" kernel skin1 --model jimenez --export hlsl --out "$out/jimenez.hlsl" -q
"$lucent" cdrf-lut --out "$out/cdrf-lut.exr" -q
"$lucent" cdrf-fit skin1 --radii 2,5,10,20 --photons 200000 --out "$out/skin1-cdrf" -q
echo "materials, profiles (Skin1, Marble), kernel exports, the CDRF LUT and the Skin1 sigma0 fit: in $out/"

echo
echo "The report: $out/compare/report.html   (tables alone: $out/compare/report.md)"
