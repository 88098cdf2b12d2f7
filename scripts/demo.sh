#!/usr/bin/env bash
# The main job, as far as Lucent has grown: writes its results under OUT (default out/demo)
# and says what it wrote.
set -euo pipefail
lucent=${1:-build/lucent}
out=${2:-out/demo}
mkdir -p "$out"

echo "== Measured materials (Jensen et al. 2001) and their derived optical quantities"
"$lucent" materials
"$lucent" materials --json --out "$out/materials.json"
"$lucent" materials --swatches "$out/materials.png"

echo
echo "== Diffuse reflectance profiles R_d(r): Monte Carlo against the analytic models"
for m in skin1 marble; do
  "$lucent" profile "$m" --compare mc,dipole,better-dipole,burley --photons 200000 --sog 4 \
    --out "$out/$m-profiles"
done
"$lucent" profile skin1 --model mc --photons 200000 --out "$out/skin1-mc"

echo
echo "== Separable kernels (Freude 2014): shader-ready taps for Skin1 and Marble"
"$lucent" kernel skin1 --model svd --export glsl --out "$out/skin1-svd.glsl"
"$lucent" kernel marble --model preint --export json --out "$out/marble-preint.json"
"$lucent" kernel skin1 --model jimenez --export hlsl --out "$out/jimenez.hlsl"

echo
echo "== The curvature-dependent reflectance function (Kubo et al.)"
"$lucent" cdrf-lut --out "$out/cdrf-lut.exr"
"$lucent" cdrf-fit skin1 --radii 2,5,10,20 --photons 200000 --out "$out/skin1-cdrf"

echo
echo "Demo outputs are in $out/:"
ls -1 "$out" | sed 's/^/  /'
