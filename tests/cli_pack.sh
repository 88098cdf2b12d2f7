# Cases for `lucent pack` and the kernel's width on screen (sourced by cli_test.sh: $LUCENT, $TMP,
# $FIXTURES, $GLRUN, expect_ok, expect_fail, expect_true, expect_no_file).
export LUCENT_CACHE_DIR=$TMP/cache
few=(--sigma0-photons 2000 --transmit-photons 500)

# A GLSL pack in a folder that does not exist yet: every file, and the shaders compile.
expect_ok -- "$LUCENT" pack marble --engine glsl --screen 1920x1080 --fov 45 --object-height 1.8m "${few[@]}" \
  --out "$TMP/packs/new/marble"
expect_true "pack prints the kernel width" -- grep -q "^kernel width: [0-9.]* px" <<<"$OUT"
for f in taps.glsl blur.frag.glsl cdrf.glsl translucency.glsl cdrf-lut.exr transmittance.csv constants.json material.gltf; do
  expect_true "glsl pack has $f" -- test -s "$TMP/packs/new/marble/$f"
done
if command -v glslangValidator >/dev/null 2>&1; then
  expect_true "the pack's blur pass compiles (glslangValidator)" -- glslangValidator -S frag "$TMP/packs/new/marble/blur.frag.glsl"
  { echo "#version 450 core"; cat "$TMP/packs/new/marble/cdrf.glsl" "$TMP/packs/new/marble/translucency.glsl"
    echo "layout(binding = 3) uniform sampler2D u_lut; out vec4 o; void main() { o = vec4(lucent_cdrf(u_lut, 0.5, 0.1) * lucent_transmittance(2.0), 1.0); }"
  } > "$TMP/packs/snippets.frag"
  expect_true "the pack's CDRF and translucency snippets compile" -- glslangValidator "$TMP/packs/snippets.frag"
fi
expect_true "the LUT is RGB 64 x 64" -- bash -c "'$LUCENT' image info '$TMP/packs/new/marble/cdrf-lut.exr' | grep -q '64x64, 3 channels'"
expect_true "glTF carries KHR_materials_volume" -- grep -q '"KHR_materials_volume": {"thicknessFactor"' "$TMP/packs/new/marble/material.gltf"
# Marble's sigma_t = sigma_a + sigma_s = (2.1921, 2.6241, 3.0071) /mm (Jensen 2001, Figure 5): the
# attenuation distance is 1 / 2.1921 mm in metres and the red attenuation colour e^-1.
expect_true "glTF attenuation from sigma_t" -- \
  grep -q '"attenuationDistance": 0.000456183568, "attenuationColor": \[0.367879441' "$TMP/packs/new/marble/material.gltf"

expect_ok -- "$LUCENT" pack marble --engine hlsl "${few[@]}" --out "$TMP/packs/marble-hlsl"
if command -v glslangValidator >/dev/null 2>&1; then
  expect_true "the HLSL blur pass compiles (glslangValidator -D)" -- \
    glslangValidator -D -V -e main -S frag "$TMP/packs/marble-hlsl/blur.hlsl" -o "$TMP/packs/b.spv"
fi
expect_ok -- "$LUCENT" pack marble --engine json "${few[@]}" --out "$TMP/packs/marble-json"
expect_true "json pack: data only" -- bash -c "test -s '$TMP/packs/marble-json/taps.json' && ! ls '$TMP/packs/marble-json'/*.glsl"

# The printed width is the renderer's: render the skin spheres (camera 125 mm from the spheres'
# centres, fov_y 25, 32 rows) with the blur, take the kernel from the sidecar, and compute the width
# from the projection, 2 R H / (2 tan(fov_y / 2) z) (blur.frag.glsl's pixels per mm).
expect_ok -- "${GLRUN[@]}" render "$TESTS/../data/scenes/spheres-skin.json" --method ssss --set render.width=96 \
  --set render.height=32 --out "$TMP/packs/r/s.png" --json "$TMP/packs/r/s.json" --no-cache
want=$(awk '/"offsets_mm"/ {gsub(/.*\[|\].*/, ""); n = split($0, o, ","); for (i = 1; i <= n; i++) { v = o[i] < 0 ? -o[i] : o[i]; if (v > r) r = v } }
            /"fov_y"/ {gsub(/[^0-9.]/, ""); f = $0}
            END {printf "%.2f", 2 * r * 32 / (2 * sin(f * 3.14159265358979 / 360) / cos(f * 3.14159265358979 / 360) * 125)}' "$TMP/packs/r/s.json")
expect_ok -- "$LUCENT" pack skin1 --engine json --screen 96x32 --fov 25 --distance 125mm "${few[@]}" --out "$TMP/packs/skin1"
expect_true "pack's width = the renderer's ($want px)" -- grep -q "^kernel width: $want px" <<<"$OUT"
expect_ok -- "$LUCENT" kernel skin1 --screen 96x32 --fov 25 --distance 125mm --out "$TMP/packs/k.json"
expect_true "kernel's width = the renderer's ($want px)" -- grep -q "^kernel width: $want px" <<<"$OUT"

# Bad usage and input: nothing written.
expect_fail 2 "--engine is required" -- "$LUCENT" pack marble --out "$TMP/packs/none"
expect_fail 2 "unknown engine 'wgsl'" -- "$LUCENT" pack marble --engine wgsl --out "$TMP/packs/none"
expect_fail 2 "--screen needs WxH" -- "$LUCENT" pack marble --engine glsl --screen 1920 --out "$TMP/packs/none"
expect_fail 2 "--object-height needs a length" -- "$LUCENT" pack marble --engine glsl --object-height 2ft --out "$TMP/packs/none"
expect_fail 1 "no render setting 'frob'" -- "$LUCENT" pack marble --engine glsl --set frob=1 --out "$TMP/packs/none"
expect_fail 1 "$FIXTURES/materials/negative.json: sigma_a[1]: must be >= 0" -- \
  "$LUCENT" pack "$FIXTURES/materials/negative.json" --engine glsl --out "$TMP/packs/none"
expect_no_file "$TMP/packs/none"
unset LUCENT_CACHE_DIR

# `lucent --version`: the version, the git revision, and what it links (Embree 3, OpenEXR 3, the GL
# renderer or why there is none).
expect_ok -- "${GLRUN[@]}" --version
expect_true "--version names the revision" -- grep -q "^revision  [0-9a-f]\{7,\}\|^revision  unknown" <<<"$OUT"
expect_true "--version names Embree 3" -- grep -q "^embree    3\.[0-9]*\.[0-9]*$" <<<"$OUT"
expect_true "--version names OpenEXR 3" -- grep -q "^openexr   3\.[0-9]*\.[0-9]*" <<<"$OUT"
expect_true "--version names the GL renderer" -- grep -q "^gl        " <<<"$OUT"

# --out as a folder for the commands that write several files with a prefix: a trailing '/' puts the
# default names inside (the folder is made).
expect_ok -- "$LUCENT" profile skin1 --model dipole --out "$TMP/outdir/profiles/"
expect_true "profile --out DIR/ writes Skin1-dipole.* inside" -- test -s "$TMP/outdir/profiles/Skin1-dipole.json"
expect_ok -- "$LUCENT" cdrf-fit marble --radii 3 --photons 200 --bins 4 --out "$TMP/outdir/profiles/"
expect_true "cdrf-fit --out DIR/ writes Marble-cdrf.* inside" -- test -s "$TMP/outdir/profiles/Marble-cdrf.csv"
