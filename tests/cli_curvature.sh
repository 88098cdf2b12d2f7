# Cases for `lucent curvature` (sourced by cli_test.sh: $LUCENT, $TMP, $FIXTURES, expect_ok,
# expect_fail, expect_true, expect_no_file).

# The tetrahedron fixture: CSV with a header and one row per vertex; PLY that reads back.
expect_ok -- "$LUCENT" curvature "$FIXTURES/mesh/tetra.ply" --out "$TMP/tetra.csv"
expect_true "curvature CSV has its header" -- \
  test "$(head -1 "$TMP/tetra.csv")" = "vertex,x,y,z,k1,k2,mean,gauss,flags"
expect_true "curvature CSV has one row per vertex" -- test "$(wc -l <"$TMP/tetra.csv")" -eq 5
expect_true "curvature CSV holds no NaN or Inf" -- sh -c "! grep -qi 'nan\|inf' '$TMP/tetra.csv'"
expect_true "curvature says what it wrote" -- grep -q "^wrote $TMP/tetra.csv$" <<<"$OUT"
for m in rusinkiewicz meyer garimella; do
  expect_ok -- "$LUCENT" curvature "$FIXTURES/mesh/tetra.ply" --method "$m" --smooth 1 --out "$TMP/tetra-$m.ply"
  expect_true "curvature --method $m writes a binary PLY with colours" -- \
    grep -aq "property uchar red" "$TMP/tetra-$m.ply"
done
expect_ok -- "$LUCENT" curvature "$TMP/tetra-meyer.ply" --out "$TMP/again.csv"
expect_ok -- "$LUCENT" curvature "$FIXTURES/mesh/tetra.ply" --fast --out "$TMP/fast.csv"
# A picture of the colour-mapped mesh (Kubo Fig. 10a), at the size asked for.
expect_ok -- "$LUCENT" curvature "$FIXTURES/mesh/tetra.ply" --size 64x48 --view 30,-10 --out "$TMP/tetra.png"
expect_ok -- "$LUCENT" image info "$TMP/tetra.png"
expect_true "curvature --out .png paints a 64x48 picture and its colour bar (64 more)" -- grep -q "128x48, 3 channels" <<<"$OUT"

# A sample mesh when present (make setup fetches them): the bunny, all finite.
BUNNY="$(dirname "$FIXTURES")/../data/meshes/bunny.ply"
if [ -f "$BUNNY" ]; then
  expect_ok -- "$LUCENT" curvature "$BUNNY" --mm-per-unit 10 --out "$TMP/bunny.csv"
  expect_true "bunny curvature has no NaN or Inf" -- sh -c "! grep -qi 'nan\|inf' '$TMP/bunny.csv'"
else
  echo "note: $BUNNY absent (make setup fetches it); bunny case skipped"
fi

# Bad input names the file; nothing is left behind.
for f in empty truncated garbage; do
  expect_fail 1 "$FIXTURES/mesh/$f.ply" -- "$LUCENT" curvature "$FIXTURES/mesh/$f.ply" --out "$TMP/$f.ply"
  expect_no_file "$TMP/$f.ply"
done
expect_fail 1 "$TMP/missing.ply: cannot open" -- "$LUCENT" curvature "$TMP/missing.ply"
expect_ok -- "$LUCENT" curvature "$FIXTURES/mesh/tetra.ply" --out "$TMP/newdir/curv/c.csv"
expect_true "curvature creates the folder of --out" -- test -s "$TMP/newdir/curv/c.csv"
expect_fail 2 "--method must be rusinkiewicz, meyer or garimella" -- \
  "$LUCENT" curvature "$FIXTURES/mesh/tetra.ply" --method taubin
expect_fail 2 "--smooth needs a whole number" -- "$LUCENT" curvature "$FIXTURES/mesh/tetra.ply" --smooth -1
expect_fail 2 "--out must end in .ply, .csv or .png" -- "$LUCENT" curvature "$FIXTURES/mesh/tetra.ply" --out x.jpg
expect_fail 2 "--size needs WIDTHxHEIGHT" -- "$LUCENT" curvature "$FIXTURES/mesh/tetra.ply" --size 64 --out "$TMP/s.png"
expect_fail 2 "--view needs AZIMUTH,ELEVATION" -- "$LUCENT" curvature "$FIXTURES/mesh/tetra.ply" --view 0,95 --out "$TMP/s.png"
expect_ok -- "$LUCENT" curvature "$FIXTURES/mesh/tetra.ply" --out "$TMP/newdir/curv/c.png"
expect_true "curvature creates the folder of a picture" -- test -s "$TMP/newdir/curv/c.png"
expect_no_file "$TMP/s.png"
expect_fail 2 "expected a mesh file" -- "$LUCENT" curvature --method meyer

# The picture carries a colour bar with its values in mm^-1 beside the mesh (64 pixels wider).
expect_ok -- "$LUCENT" curvature "$FIXTURES/mesh/tetra.ply" --size 200x160 --out "$TMP/bar.png"
expect_true "curvature picture: 200 + 64 x 160 with its colour bar" -- \
  bash -c "'$LUCENT' image info '$TMP/bar.png' | grep -q '264x160'"

