# Cases for `lucent render` (sourced by cli_test.sh: $LUCENT, $TMP, $FIXTURES, expect_ok, expect_fail,
# expect_true, expect_no_file). Small images on whatever GL the machine has (llvmpipe in CI).
SC=$FIXTURES/scenes
# The settings listing is the table; docs/scenes.md carries it verbatim between its markers.
expect_ok -- "$LUCENT" render --settings
expect_true "--settings lists the kernel setting with its names" -- grep -q "svd, preint, guided, manual, sog, jimenez" <<<"$OUT"
expect_ok -- "$LUCENT" render --settings=markdown
printf '%s\n' "$OUT" > "$TMP/settings.md"
sed -n '/<!-- settings:begin -->/,/<!-- settings:end -->/p' "$TESTS/../docs/scenes.md" | sed '1d;$d' > "$TMP/settings-doc.md"
expect_true "docs/scenes.md holds the table of lucent render --settings=markdown" -- diff -u "$TMP/settings-doc.md" "$TMP/settings.md"

if [ -n "${LUCENT_GL_SKIP:-}" ]; then
  echo "skip lucent render cases: $LUCENT_GL_SKIP"
  return 0
fi
RENDER=("${GLRUN[@]}") # GLRUN: see cli_test.sh

# A render writes the tonemapped PNG, the linear EXR, the mask and the sidecar.
expect_ok -- "${RENDER[@]}" render "$SC/sphere.json" --out "$TMP/r.png" --exr "$TMP/r.exr" --mask "$TMP/r-mask.png" --no-cache
for f in r.png r.exr r-mask.png r.json; do expect_true "render wrote $f" -- test -s "$TMP/$f"; done
expect_true "render says what it wrote" -- grep -q "^wrote $TMP/r.json$" <<<"$OUT"
expect_true "render prints per-pass GPU times" -- grep -q "GPU .* ms (shadow .*, geometry .*, blur h1 .*, blur v1 .*, compose" <<<"$OUT"
expect_ok -- "$LUCENT" image info "$TMP/r.exr"
expect_true "the EXR has the scene's size" -- grep -q "48x40, 3 channels" <<<"$OUT"
for key in '"timings"' '"passes"' '"gpu_ms"' '"renderer"' '"settings"' '"scene"' '"sigma0_mm"' '"kernels"' '"offsets_mm"'; do
  expect_true "the sidecar holds $key" -- grep -q "$key" "$TMP/r.json"
done
renderer=$(grep -m1 '"renderer"' "$TMP/r.json")

# --method and --set change what is rendered; the sidecar records the scene after overrides.
expect_ok -- "${RENDER[@]}" render "$SC/sphere.json" --method cdrf --set render.width=32 --set render.height=24 \
  --out "$TMP/c.exr" --json "$TMP/c-side.json" --frames 3 --no-cache
expect_ok -- "$LUCENT" image info "$TMP/c.exr"
expect_true "--set render.width resizes the image" -- grep -q "32x24, 3 channels" <<<"$OUT"
expect_true "the sidecar names the method" -- grep -q '"method":[[:space:]]*"cdrf"' "$TMP/c-side.json"
expect_true "the sidecar keeps the overrides" -- grep -q '"width":[[:space:]]*32' "$TMP/c-side.json"
expect_ok -- "${RENDER[@]}" render "$SC/sphere.json" --method ssss:svd2 --set render.depth_filter=gaussian --out "$TMP/s.png" --no-cache
expect_ok -- "${RENDER[@]}" render "$SC/sphere.json" --method cdrf+translucency --set render.cdrf_lut=false --out "$TMP/t.png" --no-cache
expect_ok -- "${RENDER[@]}" render "$SC/sphere.json" --method lambert --out "$TMP/l.png" --no-cache

# Failures: exit 1, a message naming the cause, and no output left behind.
expect_fail 1 "objects[0].mesh: cannot open" -- "${RENDER[@]}" render "$SC/missing-mesh.json" --out "$TMP/f1.png"
expect_fail 1 "render.width: must be in" -- "${RENDER[@]}" render "$SC/sphere.json" --set render.width=-5 --out "$TMP/f2.png"
expect_fail 1 "render.method: unknown method 'phong'" -- "${RENDER[@]}" render "$SC/sphere.json" --method phong --out "$TMP/f3.png"
expect_fail 1 "override 'render.width': expected key=value" -- "${RENDER[@]}" render "$SC/sphere.json" --set render.width --out "$TMP/f4.png"
expect_fail 1 "render.wdth" -- "${RENDER[@]}" render "$SC/sphere.json" --set render.wdth=3 --out "$TMP/f5.png"
expect_fail 1 "objects[0].material: unknown material" -- "${RENDER[@]}" render "$SC/sphere.json" --set 'objects[0].material=marbel' --out "$TMP/f6.png"
expect_fail 1 "EGL device 99 not found" -- env LUCENT_GL_PLATFORM=device LUCENT_GL_DEVICE=99 "${RENDER[@]}" render "$SC/sphere.json" --out "$TMP/f7.png"
expect_fail 1 "LUCENT_GL_PLATFORM: unknown GL platform 'teapot'" -- env LUCENT_GL_PLATFORM=teapot "${RENDER[@]}" render "$SC/sphere.json" --out "$TMP/f8.png"
if [[ "$renderer" == *llvmpipe* || "$renderer" == *Mesa* ]]; then # Mesa can be told to offer only GL 3.3
  expect_fail 1 "no OpenGL context: the driver offers no OpenGL 4.5 core context" -- \
    env MESA_GL_VERSION_OVERRIDE=3.3 LUCENT_GL_PLATFORM=surfaceless "${RENDER[@]}" render "$SC/sphere.json" --out "$TMP/f9.png"
fi
if [ -z "${DISPLAY:-}" ] && [ -z "${WAYLAND_DISPLAY:-}" ]; then
  expect_fail 1 "no OpenGL window" -- "${RENDER[@]}" render "$SC/sphere.json" --window --out "$TMP/f10.png"
fi
: > "$TMP/plainfile-render"
expect_fail 1 "$TMP/plainfile-render/x.png" -- "${RENDER[@]}" render "$SC/sphere.json" --out "$TMP/plainfile-render/x.png"
expect_no_file "$TMP"/f{1,2,3,4,5,6,7,8,9,10}.png "$TMP"/f{1,2,3,4,5,6,7,8,9,10}.json

# Bad usage: exit 2.
expect_fail 2 "expected a scene file" -- "${RENDER[@]}" render --out "$TMP/u.png"
expect_fail 2 "--out is required" -- "${RENDER[@]}" render "$SC/sphere.json"
expect_fail 2 "--out '$TMP/u.txt': use .png, .exr or .pfm" -- "${RENDER[@]}" render "$SC/sphere.json" --out "$TMP/u.txt"
expect_fail 2 "--exr '$TMP/u.png': use .exr or .pfm" -- "${RENDER[@]}" render "$SC/sphere.json" --out "$TMP/u.exr" --exr "$TMP/u.png"
expect_fail 2 "--frames needs a whole number" -- "${RENDER[@]}" render "$SC/sphere.json" --out "$TMP/u.png" --frames 0
expect_fail 2 "--gl-platform must be" -- "${RENDER[@]}" render "$SC/sphere.json" --out "$TMP/u.png" --gl-platform vulkan
expect_fail 2 "unknown option '--frob'" -- "${RENDER[@]}" render "$SC/sphere.json" --out "$TMP/u.png" --frob
expect_no_file "$TMP/u.png" "$TMP/u.exr" "$TMP/u.txt"


# Point clouds ("points": file.ply): a good one renders with points; a bad one (here a NaN) fails naming the
# file, the vertex and the property, and nothing is written.
printf 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\nend_header\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n1 1 0 0 0 1\n' > "$TMP/cloud.ply"
sed 's/^1 1 0 0 0 1$/1 1 nan 0 0 1/' "$TMP/cloud.ply" > "$TMP/cloud-nan.ply"
for c in cloud cloud-nan; do
  printf '{"camera": {"position": [0.5, 0.5, 5], "target": [0.5, 0.5, 0]}, "lights": [{"type": "directional", "direction": [0, 0, -1]}], "objects": [{"points": "%s.ply", "material": "skin1"}], "render": {"width": 24, "height": 24, "method": "points"}}\n' "$c" > "$TMP/scene-$c.json"
done
expect_ok -- "${RENDER[@]}" render "$TMP/scene-cloud.json" --out "$TMP/cloud.png" --no-cache
expect_true "a point cloud renders with points" -- test -s "$TMP/cloud.png"
expect_fail 1 "cloud-nan.ply: vertex 3: z is not finite" -- "${RENDER[@]}" render "$TMP/scene-cloud-nan.json" --out "$TMP/cloud-nan.png" --no-cache
expect_fail 1 "objects[0].points" -- "$LUCENT" trace "$TMP/scene-cloud-nan.json" --out "$TMP/cloud-nan-t.png"
expect_no_file "$TMP/cloud-nan.png" "$TMP/cloud-nan.json" "$TMP/cloud-nan-t.png"
