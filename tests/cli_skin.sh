# Cases for the spectral skin (docs/skin.md) in every command (sourced by cli_test.sh: $LUCENT, $TMP,
# $FIXTURES, $GLRUN, expect_ok, expect_fail, expect_true, expect_no_file). The skins' Monte Carlo
# colours land in a cache of their own, so each is computed once here.
SKIN_CACHE=$TMP/skin-cache
SK=(env LUCENT_CACHE_DIR="$SKIN_CACHE")
MATS=$FIXTURES/materials

# materials: a file's skin, its layers and colour
expect_ok -- "${SK[@]}" "$LUCENT" materials "$MATS/skin3.json" --photons 1000
expect_true "materials shows a skin file's layers" -- grep -q "^skin3 .* 0.2500  0.0200  0.6000  1.5000" <<<"$OUT"
expect_true "materials shows its ITA category" -- grep -Eq "^skin3 +[0-9.]+ .* (very light|light|intermediate|tan|brown|dark) " <<<"$OUT"
expect_fail 1 "skin_bad.json: skin.epidermis.carotene: unknown chromophore" -- "$LUCENT" materials "$MATS/skin_bad.json"
expect_ok -- "$LUCENT" materials skin-dark --json
printf '%s\n' "$OUT" >"$TMP/skin-dark.json"
expect_true "materials --json writes the chromophores" -- grep -q '"skin"' "$TMP/skin-dark.json"
expect_ok -- "${SK[@]}" "$LUCENT" materials "$TMP/skin-dark.json" --photons 1000
expect_true "the JSON reads back as the same skin" -- grep -q "^Skin-Dark .* 0.2500  0.0800" <<<"$OUT"

# profile: band by band, multipole or mc
expect_ok -- "$LUCENT" profile skin-light --model multipole --bands 10 --out "$TMP/skin/mp"
expect_true "profile writes the skin's multipole profile" -- grep -q '"skin-multipole"' "$TMP/skin/mp.json"
expect_ok -- "$LUCENT" profile skin-light --model mc --photons 2000 --bands 5 --dr 0.05 --bins 100 --out "$TMP/skin/mc"
expect_true "profile writes the skin's Monte Carlo profile" -- grep -q '"skin-mc"' "$TMP/skin/mc.json"
expect_fail 1 "Skin-Light is a spectral skin" -- "$LUCENT" profile skin-light --model dipole --out "$TMP/skin/d"
expect_fail 1 "--layers takes RGB materials" -- "$LUCENT" profile skin-light --layers skin1:0.25,skin2:inf --out "$TMP/skin/l"
expect_fail 2 "--bands needs a count from 1 to 80" -- "$LUCENT" profile skin-light --bands 81

# kernel, pack: the taps of its profile, the engine parameters of its equivalent medium
expect_ok -- "$LUCENT" kernel skin-tan --out "$TMP/skin/k.json"
expect_true "kernel writes the skin's taps" -- test -s "$TMP/skin/k.json"
expect_ok -- "${SK[@]}" "$LUCENT" pack skin-tan --engine glsl --sigma0-photons 2000 --transmit-photons 500 \
  --fit-photons 5000 --fit-model-photons 1000 --out "$TMP/skin/pack"
expect_true "the pack's glTF volume is finite" -- \
  bash -c "grep -q KHR_materials_volume '$TMP/skin/pack/material.gltf' && ! grep -Eqi 'nan|inf' '$TMP/skin/pack/material.gltf'"

# trace: the equivalent medium in the path tracer
expect_ok -- "${SK[@]}" "$LUCENT" trace "$FIXTURES/scenes/trace-small.json" --set 'objects[0].material=skin-brown' \
  --spp 2 --out "$TMP/skin/t.png" --exr "$TMP/skin/t.exr"
expect_true "trace renders a skin" -- test -s "$TMP/skin/t.exr"

if [ -z "${LUCENT_GL_SKIP:-}" ]; then
  expect_ok -- "${SK[@]}" "${GLRUN[@]}" render "$FIXTURES/scenes/sphere.json" --set 'objects[0].material=skin-light' \
    --set render.transmittance=profile --out "$TMP/skin/r.png" --exr "$TMP/skin/r.exr"
  expect_true "render renders a skin" -- test -s "$TMP/skin/r.exr"
  expect_ok -- "${SK[@]}" "${GLRUN[@]}" compare "$FIXTURES/scenes/sphere.json" --set 'objects[0].material=skin-light' \
    --set render.transmittance=profile --methods lambert,ssss --spp 1 --frames 1 --out "$TMP/skin/cmp"
  expect_true "compare compares on a skin" -- test -s "$TMP/skin/cmp/results.json"
fi
expect_fail 2 "--photons needs a whole number > 0" -- "$LUCENT" materials skin-light --photons 0
