# shellcheck shell=bash
# `lucent materials`: sourced by tests/cli_test.sh, which provides $LUCENT, $FIXTURES, $TMP,
# expect_ok, expect_fail, expect_true and expect_no_file.
MAT=$FIXTURES/materials

# ---- the presets ----
expect_ok -- "$LUCENT" materials --photons 500 # the skins' Monte Carlo colours: few photons here
for name in Apple Chicken1 Chicken2 Cream Ketchup Marble Potato Skimmilk Skin1 Skin2 Wholemilk; do
  expect_true "materials lists $name in each of its 3 tables" -- \
    test "$(grep -c "^$name " <<<"$OUT")" = 3
done
# The Rd columns (the last three of the albedo table) against Jensen et al. 2001's table,
# to +-0.001: Skin1 (0.436, 0.227, 0.131), Marble (0.830, 0.791, 0.753).
rd_row() { # NAME: the last three numbers of NAME's row in the "Albedos" table
  awk -v n="$1" '/^Albedos/{t=1} /^Lengths/{t=0} t && $1==n {print $(NF-2), $(NF-1), $NF}' <<<"$OUT"
}
near3() { # "a b c" "x y z" TOL
  awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN{split(a,p," "); split(b,q," ");
    for(i=1;i<=3;i++) if ((p[i]-q[i])>t || (q[i]-p[i])>t || p[i]=="") exit 1}'
}
expect_true "materials shows Skin1's dipole Rd (0.436, 0.227, 0.131) +-0.001" -- \
  near3 "$(rd_row Skin1)" "0.436 0.227 0.131" 0.001
expect_true "materials shows Marble's dipole Rd (0.830, 0.791, 0.753) +-0.001" -- \
  near3 "$(rd_row Marble)" "0.830 0.791 0.753" 0.001
not() { ! "$@"; }
expect_true "the Rd check itself rejects a value 0.01 off" -- not near3 "$(rd_row Skin1)" "0.446 0.227 0.131" 0.001
expect_true "materials fits in 100 columns" -- awk 'length($0) > 100 { exit 1 }' <<<"$OUT"

expect_ok -- "$LUCENT" materials SKIN1 marble
expect_true "preset names are case-insensitive" -- \
  test "$(grep -c "^Skin1 " <<<"$OUT")" = 3 -a "$(grep -c "^Marble " <<<"$OUT")" = 3

# ---- JSON ----
expect_ok -- "$LUCENT" materials --json
printf '%s\n' "$OUT" >"$TMP/materials.json"
if command -v python3 >/dev/null 2>&1; then
  expect_true "materials --json is valid JSON with 21 materials (11 RGB, 8 spectral skins, 2 g 0.9 skins)" -- python3 -c \
    'import json,sys; d=json.load(open(sys.argv[1])); assert len(d["materials"]) == 21' "$TMP/materials.json"
fi
expect_true "materials --json states its units" -- grep -q '"units":[[:space:]]*"mm^-1"' "$TMP/materials.json"
expect_ok -- "$LUCENT" materials "$TMP/materials.json"
expect_true "materials --json output reads back as a material file" -- \
  test "$(grep -c "^Wholemilk " <<<"$OUT")" = 3

expect_ok -- "$LUCENT" materials skin2 "$MAT/jade.json" "$MAT/two.json#soap" --out "$TMP/picked.json"
expect_true "materials --out says what it wrote" -- grep -q "^wrote $TMP/picked.json$" <<<"$OUT"
expect_true "materials --out wrote the 3 named materials" -- \
  test "$(grep -c '"name":' "$TMP/picked.json")" = 3
expect_ok -- "$LUCENT" materials --out "$TMP/newdir/mat/x.json"
expect_true "materials creates the folder of --out" -- test -s "$TMP/newdir/mat/x.json"
mkdir -p "$TMP/ro" && chmod 555 "$TMP/ro"
expect_fail 1 "$TMP/ro/x.json: cannot create: the folder $TMP/ro is not writable (Permission denied)" -- \
  as_nobody "$LUCENT" materials --out "$TMP/ro/x.json"
expect_no_file "$TMP/ro/x.json"

# ---- user files ----
expect_ok -- "$LUCENT" materials "$MAT/jade.json" "$MAT/two.json"
expect_true "materials reads a file's materials (jade, wax, soap)" -- \
  test "$(grep -cE "^(jade|wax|soap) " <<<"$OUT")" = 9

# ---- bad input: exit 1, the message names the file and the field, nothing printed or written ----
bad_material() { # FIXTURE MESSAGE
  expect_fail 1 "$MAT/$1: $2" -- "$LUCENT" materials "$MAT/$1"
  expect_true "no output for $1" -- test -z "$("$LUCENT" materials "$MAT/$1" 2>/dev/null)"
  expect_fail 1 "$1" -- "$LUCENT" materials skin1 "$MAT/$1" --out "$TMP/bad-$1"
  expect_no_file "$TMP/bad-$1"
}
bad_material missing_field.json "eta: missing field"
bad_material negative.json "sigma_a[1]: must be >= 0, got -0.02"
bad_material nan.json "line 4, column 21 (in field \"sigma_a\"): not a number JSON allows" # NaN is not JSON: located by line and field
bad_material huge.json "sigma_s_prime[1]: expected a finite number" # 1e999
bad_material wrong_type.json "eta: expected a number, got a string"
bad_material broken.json "line 5: invalid JSON: unexpected end of file"
bad_material unknown_key.json "anisotropy: unknown field"
bad_material no_units.json "units: missing field"
bad_material list_bad.json "materials[1].sigma_s_prime[2]: must be >= 0"
expect_fail 1 "$MAT/absent.json" -- "$LUCENT" materials "$MAT/absent.json"
expect_fail 1 'unknown material "jade"' -- "$LUCENT" materials jade
expect_fail 1 'no material named "tallow"' -- "$LUCENT" materials "$MAT/two.json#tallow"
expect_fail 1 "holds 2 materials" -- "$LUCENT" materials "$MAT/two.json#"

# ---- usage ----
expect_fail 2 "unknown option '--frobnicate'" -- "$LUCENT" materials --frobnicate
expect_fail 2 "--out needs a file name" -- "$LUCENT" materials --out

# ---- swatches ----
# One Skin1 swatch (96x96 at Rd) on a 112x126 backdrop of 0.18 (its name in the strip below): the
# pixel at (56, 56) holds Rd (Jensen 2001: 0.436, 0.227, 0.131, +-0.001), read from the PFM
# (little-endian floats, rows bottom-up, after its three header lines).
expect_ok -- "$LUCENT" materials skin1 --swatches "$TMP/skin1.pfm"
expect_true "materials --swatches says what it wrote" -- grep -q "^wrote $TMP/skin1.pfm" <<<"$OUT"
expect_ok -- "$LUCENT" image info "$TMP/skin1.pfm"
expect_true "the swatch image is 112x126 RGB" -- grep -q "112x126, 3 channels" <<<"$OUT"
hdr=$(head -n 3 "$TMP/skin1.pfm" | wc -c)
px=$(od -A n -t f4 -j $((hdr + ((126 - 1 - 56) * 112 + 56) * 12)) -N 12 "$TMP/skin1.pfm")
expect_true "the Skin1 swatch shows Rd (0.436, 0.227, 0.131)" -- near3 "$px" "0.436 0.227 0.131" 0.001
expect_ok -- "$LUCENT" materials --swatches "$TMP/all.png" --photons 500
expect_ok -- "$LUCENT" image info "$TMP/all.png"
expect_true "21 swatches (11 RGB presets, 8 skins, 2 g 0.9 skins) make a 2192x126 image" -- grep -q "2192x126" <<<"$OUT"
expect_ok -- "$LUCENT" materials --swatches "$TMP/newdir/mat/s.png" --photons 500
expect_true "materials creates the folder of --swatches" -- test -s "$TMP/newdir/mat/s.png"
expect_fail 2 "--swatches needs an image file name" -- "$LUCENT" materials --swatches
