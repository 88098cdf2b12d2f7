# Cases for `lucent pack` and the kernel's width on screen (sourced by cli_test.sh: $LUCENT, $TMP,
# $FIXTURES, $GLRUN, expect_ok, expect_fail, expect_true, expect_no_file).
export LUCENT_CACHE_DIR=$TMP/cache
few=(--sigma0-photons 2000 --transmit-photons 500 --fit-photons 5000 --fit-model-photons 1000)

# A GLSL pack in a folder that does not exist yet: every file (the shaders' compilation by glslang, the
# glTF's by Khronos' validator and Blender: tests/pack_peer_test.sh).
expect_ok -- "$LUCENT" pack marble --engine glsl --screen 1920x1080 --fov 45 --object-height 1.8m "${few[@]}" \
  --out "$TMP/packs/new/marble"
expect_true "pack prints the kernel width" -- grep -q "^kernel width: [0-9.]* px" <<<"$OUT"
for f in README.md taps.glsl blur.frag.glsl cdrf.glsl translucency.glsl cdrf-lut.exr cdrf-lut.png transmittance.csv \
  transmittance.png constants.json material.gltf; do
  expect_true "glsl pack has $f" -- test -s "$TMP/packs/new/marble/$f"
done
expect_true "the LUT is RGB 64 x 64" -- bash -c "'$LUCENT' image info '$TMP/packs/new/marble/cdrf-lut.exr' | grep -q '64x64, 3 channels'"
expect_true "the LUT's PNG is 16-bit (IHDR bit depth)" -- bash -c "[ \$(od -An -tu1 -j24 -N1 '$TMP/packs/new/marble/cdrf-lut.png') = 16 ]"
for ext in KHR_materials_transmission KHR_materials_volume KHR_materials_diffuse_transmission KHR_materials_volume_scatter \
  KHR_materials_ior KHR_lights_punctual; do
  expect_true "glTF uses $ext" -- grep -q "\"$ext\"" "$TMP/packs/new/marble/material.gltf"
done
expect_true "the README names the passes" -- grep -q "^## The passes, in order" "$TMP/packs/new/marble/README.md"
# The README carries the library's fit (lucent/engine.h): every engine, and the values `lucent fit` finds with
# the same photons (one library; the numbers themselves are tested in tests/test_engine.c).
expect_true "the README has every engine's fitted parameters" -- \
  test "$(grep -c '^### .* (`[a-z0-9-]*`)$' "$TMP/packs/new/marble/README.md")" = 9
expect_ok -- "$LUCENT" fit marble --no-hand --photons 5000 --model-photons 1000 --out "$TMP/packs/marble-fit"
for param in "Mean Free Path Distance" "Subsurface Radius" "KHR_materials_volume_scatter.multiscatterColor (draft)"; do
  expect_true "the README's $param is lucent fit's" -- \
    grep -qF "$(grep -m1 "^| $param |" "$TMP/packs/marble-fit.md")" "$TMP/packs/new/marble/README.md"
done
expect_ok -- "$LUCENT" pack marble --engine json "${few[@]}" --no-fit --out "$TMP/packs/marble-nofit"
expect_true "--no-fit: the README says how to get the fit" -- \
  grep -q "^Left out when this pack was made (\`--no-fit\`): \`lucent fit Marble\`" "$TMP/packs/marble-nofit/README.md"
expect_fail 2 "--fit-photons needs a whole number > 0" -- "$LUCENT" pack marble --engine json --fit-photons 0 \
  --out "$TMP/packs/none"
for e in gles vulkan; do
  expect_ok -- "$LUCENT" pack marble --engine $e "${few[@]}" --out "$TMP/packs/marble-$e"
  expect_true "$e pack has its blur pass" -- test -s "$TMP/packs/marble-$e/blur.frag.glsl"
done
expect_true "the gles blur is GLSL ES 3.00" -- grep -q "^#version 300 es" "$TMP/packs/marble-gles/blur.frag.glsl"
expect_true "the vulkan blur has push constants" -- grep -q "push_constant" "$TMP/packs/marble-vulkan/blur.frag.glsl"

# The pack's glTF is a scene Lucent reads: traced, and rendered (Lambert, a given albedo: no bake).
expect_ok -- "$LUCENT" trace "$TMP/packs/new/marble/material.gltf" --set render.width=12 --set render.height=8 \
  --set render.spp=1 --out "$TMP/packs/gltf-trace.png"
expect_true "the traced glTF scene records its meshes' source" -- grep -q '"gltf":[[:space:]]*"material.gltf"' "$TMP/packs/gltf-trace.json"
expect_ok -- "${GLRUN[@]}" render "$TMP/packs/new/marble/material.gltf" --method lambert --set render.width=12 \
  --set render.height=8 --set 'objects[0].albedo=[0.8, 0.8, 0.8]' --out "$TMP/packs/gltf-render.png" --no-cache
expect_fail 1 "$TMP/packs/new/marble/taps.gltf: cannot open" -- "$LUCENT" trace "$TMP/packs/new/marble/taps.gltf" \
  --out "$TMP/packs/none.png"

expect_ok -- "$LUCENT" pack marble --engine hlsl "${few[@]}" --out "$TMP/packs/marble-hlsl"
expect_true "hlsl pack has blur.hlsl" -- test -s "$TMP/packs/marble-hlsl/blur.hlsl"
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
# -q: the width is an informational line (both commands); a length needs its unit (a bare 30 was 30 m).
expect_ok -- "$LUCENT" -q pack skin1 --engine json --screen 96x32 --fov 25 --distance 125mm "${few[@]}" --out "$TMP/packs/skin1-q"
expect_true "-q pack prints no kernel width" -- test -z "$OUT"
expect_ok -- "$LUCENT" -q kernel skin1 --screen 96x32 --fov 25 --distance 125mm --out "$TMP/packs/kq.json"
expect_true "-q kernel prints no kernel width" -- test -z "$OUT"
expect_fail 2 "--object-height needs a length with its unit (m, cm or mm) from 0.001 mm to 1e12 mm, got '30'" -- \
  "$LUCENT" pack marble --engine glsl --object-height 30 --out "$TMP/packs/none"
expect_fail 2 "--distance needs a length with its unit (m, cm or mm)" -- \
  "$LUCENT" kernel skin1 --distance 0.125 --out "$TMP/packs/none.json"
expect_no_file "$TMP/packs/none.json"

# Bad usage and input: nothing written.
expect_fail 2 "--engine is required" -- "$LUCENT" pack marble --out "$TMP/packs/none"
expect_fail 2 "unknown engine 'wgsl' (glsl, gles, vulkan, hlsl, json)" -- "$LUCENT" pack marble --engine wgsl --out "$TMP/packs/none"
expect_fail 1 "$FIXTURES/mesh/garbage.ply" -- "$LUCENT" pack marble --engine glsl --mesh "$FIXTURES/mesh/garbage.ply" \
  --out "$TMP/packs/none"
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
