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
echo "Demo outputs are in $out/:"
ls -1 "$out" | sed 's/^/  /'
