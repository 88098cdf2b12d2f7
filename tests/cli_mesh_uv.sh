# Cases for `lucent mesh-uv` (sourced by cli_test.sh).

# A mesh with its own coordinates keeps them (the quad fixture: half of the texture, no stretch).
expect_ok -- "$LUCENT" mesh-uv "$FIXTURES/mesh/quad-uv.obj" --out "$TMP/quad.obj"
expect_true "mesh-uv keeps a mesh's own coordinates" -- grep -q "its own coordinates, 1 charts" <<<"$OUT"
expect_true "mesh-uv: the quad's stretch is 1" -- grep -q "stretch L2 1.0000" <<<"$OUT"
expect_true "mesh-uv writes vt per corner" -- test "$(grep -c '^vt 1 0.5$' "$TMP/quad.obj")" -eq 2
expect_true "mesh-uv writes the chart picture beside OUT" -- test -f "$TMP/quad.png"
# --atlas makes Lucent's charts anyway; glTF output; the picture where --png says.
expect_ok -- "$LUCENT" mesh-uv "$FIXTURES/mesh/tetra.ply" --out "$TMP/tetra.gltf" --size 64 --png "$TMP/charts.png"
expect_true "mesh-uv: the tetrahedron in four charts, none overlapping" -- \
  grep -q "Lucent's atlas, 4 charts" <<<"$OUT"
expect_true "mesh-uv: no texel in two faces" -- grep -q " 0 texels of " <<<"$OUT"
expect_ok -- "$LUCENT" image info "$TMP/charts.png"
expect_true "mesh-uv --size 64 paints 64x64" -- grep -q "64x64, 3 channels" <<<"$OUT"
expect_ok -- "$LUCENT" mesh-uv "$TMP/tetra.gltf" --out "$TMP/tetra-again.obj"
expect_true "mesh-uv reads its glTF back with the coordinates" -- grep -q "its own coordinates, 4 charts" <<<"$OUT"
# Lucent 0.1's positional output still works, with a note pointing to --out (issue 35).
expect_ok -- "$LUCENT" mesh-uv "$FIXTURES/mesh/quad-uv.obj" "$TMP/quad-positional.obj"
expect_true "mesh-uv: the positional output is written" -- test -s "$TMP/quad-positional.obj"
expect_true "mesh-uv: the positional output gets a note naming --out" -- grep -q "write --out" "$TMP/.stderr"
expect_fail 2 "two outputs" -- "$LUCENT" mesh-uv "$FIXTURES/mesh/quad-uv.obj" "$TMP/a.obj" --out "$TMP/b.obj"

# Bad input: the file named, nothing written.
expect_fail 1 "$FIXTURES/mesh/garbage.ply" -- "$LUCENT" mesh-uv "$FIXTURES/mesh/garbage.ply" --out "$TMP/g.obj"
expect_no_file "$TMP/g.obj"
expect_no_file "$TMP/g.png"
# A missing folder is created (every command creates its output's folder); a plain file in its place fails.
expect_ok -- "$LUCENT" mesh-uv "$FIXTURES/mesh/quad-uv.obj" --out "$TMP/newdir/q.obj"
expect_true "mesh-uv creates the output's folder" -- test -s "$TMP/newdir/q.obj"
: > "$TMP/plainfile-uv"
expect_fail 1 "$TMP/plainfile-uv" -- "$LUCENT" mesh-uv "$FIXTURES/mesh/quad-uv.obj" --out "$TMP/plainfile-uv/q.obj"
expect_fail 2 "OUT must end in .obj or .gltf" -- "$LUCENT" mesh-uv "$FIXTURES/mesh/tetra.ply" --out "$TMP/t.ply"
expect_fail 2 "--angle needs degrees in (0, 90)" -- "$LUCENT" mesh-uv "$FIXTURES/mesh/tetra.ply" --out "$TMP/t.obj" --angle 90
expect_fail 2 "expected --out OUT.obj or OUT.gltf" -- "$LUCENT" mesh-uv "$FIXTURES/mesh/tetra.ply"
