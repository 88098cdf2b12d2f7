# Cases for `lucent fit` (sourced by cli_test.sh: $LUCENT, $TMP, $FIXTURES, expect_ok, expect_fail,
# expect_true, expect_no_file). Few photons: these check the command, the files and every engine's
# parameters in its own names; the models' numbers are tested in tests/test_engine.c.

FIT_FAST=(--photons 5000 --model-photons 1000 --cache "$TMP/fit-cache")
expect_ok -- "$LUCENT" fit skin1 "${FIT_FAST[@]}" --out "$TMP/fit/skin1"
expect_true "fit wrote skin1.json, skin1.md and skin1.svg" -- \
  test -s "$TMP/fit/skin1.json" -a -s "$TMP/fit/skin1.md" -a -s "$TMP/fit/skin1.svg"
expect_true "fit's chart is a complete SVG" -- grep -q "</svg>" "$TMP/fit/skin1.svg"
expect_true "fit says what it wrote" -- grep -q "^wrote $TMP/fit/skin1.md$" <<<"$OUT"
# every engine, each with a parameter in its own name
for pair in "unreal-burley:Mean Free Path Distance" "unreal-separable:Falloff Color" \
  "unity-hdrp:Scattering Color" "blender3-burley:Subsurface Radius" "blender3-rw:Subsurface Anisotropy" \
  "blender4-burley:Subsurface Scale" "openpbr:subsurface_radius_scale" "godot:subsurf_scatter_strength" \
  "gltf:KHR_materials_volume_scatter.multiscatterColor (draft)"; do
  engine=${pair%%:*} param=${pair#*:}
  expect_true "fit skin1: $engine in the JSON" -- grep -q "\"$engine\"" "$TMP/fit/skin1.json"
  expect_true "fit skin1: $engine's $param printed" -- grep -q "$param" <<<"$OUT"
done
expect_ok -- "$LUCENT" fit ketchup "${FIT_FAST[@]}" --engines unity-hdrp,godot --transmittance --out "$TMP/fit/ketchup"
expect_true "fit --transmittance fits HDRP's tint and Godot's depth" -- \
  grep -q "subsurf_scatter_transmittance_depth" "$TMP/fit/ketchup.md"
expect_true "fit prints the hand mapping beside the fit" -- grep -q "^  hand " <<<"$OUT"
expect_true "fit's Markdown has a table per engine" -- test "$(grep -c '^| parameter | value | unit |$' "$TMP/fit/skin1.md")" = 9

expect_ok -- "$LUCENT" fit marble "${FIT_FAST[@]}" --out "$TMP/fit/"
expect_true "fit marble: the default name in the folder" -- test -s "$TMP/fit/Marble-fit.json"
expect_true "fit marble: every engine" -- test "$(grep -c '^  fitted ' <<<"$OUT")" = 9

expect_ok -- "$LUCENT" fit --layers skin1:0.5,skin2:inf --engines unity-hdrp,blender3-rw "${FIT_FAST[@]}" \
  --out "$TMP/fit/layers"
expect_true "fit --layers says what it cannot express" -- grep -q "layers (2)" "$TMP/fit/layers.json"

# A spectral skin: its bands' truth, its equivalent medium for the models (as every command resolves it);
# in --layers it is refused (it is layered already).
expect_ok -- "$LUCENT" fit skin-light "${FIT_FAST[@]}" --engines unity-hdrp,gltf --out "$TMP/fit/skin-light"
expect_true "fit skin-light says its layers are fitted by one medium" -- \
  grep -q "layers (2, a spectral skin)" "$TMP/fit/skin-light.json"
expect_fail 1 "layers[0]: Skin-Light is a spectral skin, already layered" -- \
  "$LUCENT" fit --layers skin-light:0.25,skin2:inf "${FIT_FAST[@]}" --out "$TMP/fit/none"
expect_no_file "$TMP/fit/none.json"

# Bad input and usage.
expect_fail 2 "unknown engine \"unreal5\"" -- "$LUCENT" fit skin1 --engines unreal5
expect_fail 2 "expected a material" -- "$LUCENT" fit
expect_fail 2 "--transmittance goes with a homogeneous material" -- \
  "$LUCENT" fit --layers skin1:1,skin2:inf --transmittance
expect_fail 1 "--layers: only the last layer may be 'inf'" -- "$LUCENT" fit --layers skin1:inf,skin2:1
expect_fail 1 "$FIXTURES/materials/negative.json: sigma_a[1]: must be >= 0" -- \
  "$LUCENT" fit "$FIXTURES/materials/negative.json" "${FIT_FAST[@]}" --out "$TMP/fit/neg"
expect_no_file "$TMP/fit/neg.json" "$TMP/fit/neg.md"
: >"$TMP/fit/a-file"
expect_fail 1 "$TMP/fit/a-file/x.json" -- "$LUCENT" fit ketchup "${FIT_FAST[@]}" --engines unity-hdrp \
  --out "$TMP/fit/a-file/x"
expect_true "fit into a file's 'folder' leaves the file as it was" -- test -f "$TMP/fit/a-file" -a ! -s "$TMP/fit/a-file"
