# Cases for `lucent image` (sourced by cli_test.sh: $LUCENT, $TMP, expect_ok, expect_fail,
# expect_true, expect_no_file, as_nobody).
img=$TMP/image
mkdir -p "$img"
# A 2x2 little-endian RGB PFM written by hand: rows bottom-to-top, 1.0f = 00 00 80 3f, 0.5f = 00 00 00 3f.
{
  printf 'PF\n2 2\n-1.0\n'
  for _ in 1 2 3 4 5 6; do printf '\x00\x00\x80\x3f\x00\x00\x00\x3f'; done
} > "$img/a.pfm"

# ---- working cases ----
expect_ok -- "$LUCENT" image info "$img/a.pfm"
expect_true "image info shows the size" -- grep -q "2x2, 3 channels" <<<"$OUT"
expect_ok -- "$LUCENT" image convert "$img/a.pfm" "$img/a.png"
expect_ok -- "$LUCENT" image convert "$img/a.pfm" "$img/a16.png" --bits 16 --tonemap filmic --exposure -1
expect_ok -- "$LUCENT" image convert "$img/a.pfm" "$img/a.exr" --half
expect_ok -- "$LUCENT" image info "$img/a.exr" --json
expect_true "image info --json gives the channel means" -- grep -q '"name": "R", "min": 0.5, "max": 1, "mean": 0.75' <<<"$OUT"
expect_ok -- "$LUCENT" image diff "$img/a.exr" "$img/a.pfm" --json
expect_true "identical images: RMS 0" -- grep -q '"rms": 0, "rel_rms": 0}$' <<<"$OUT"
expect_ok -- "$LUCENT" image diff "$img/a.png" "$img/a.pfm" --out "$img/heat.png"
expect_true "diff --out writes the heat map" -- test -s "$img/heat.png"
expect_ok -- "$LUCENT" image diff "$img/a.png" "$img/a.pfm" --mask "$img/a.png" --out "$img/d.exr"
expect_ok -- "$LUCENT" image info "$img/heat.png"
expect_true "the heat map carries its colour bar below (at least 200 wide)" -- grep -qE '^[^:]*: (2[0-9][0-9]|[3-9][0-9][0-9])x' <<<"$OUT"
# a fixed scale (issue 35): the same error, the same colour in every map; the line says which scale
expect_ok -- "$LUCENT" image diff "$img/a.png" "$img/a.pfm" --out "$img/heat-fixed.png" --scale 0.5
expect_true "diff --scale says the map's scale" -- grep -q "white at |A - B| 0.5, --scale" <<<"$OUT"
expect_ok -- "$LUCENT" image diff "$img/a.png" "$img/a.pfm" --out "$img/heat-fixed.png" --scale 0.5 --json
expect_true "diff --json gives the heat map's scale" -- grep -q '"heat_scale": 0.5}' <<<"$OUT"
expect_fail 2 "--scale needs the error drawn white" -- "$LUCENT" image diff "$img/a.png" "$img/a.pfm" --scale 0

# ---- malformed input: exit 1, a message naming the file ----
echo "definitely not a picture" > "$img/text.png"
expect_fail 1 "text.png: not a PNG file (bad signature)" -- "$LUCENT" image info "$img/text.png"
head -c 60 "$img/a.png" > "$img/trunc.png"
expect_fail 1 "trunc.png: truncated or corrupt PNG data" -- "$LUCENT" image info "$img/trunc.png"
head -c 200 "$img/a.exr" > "$img/trunc.exr"
expect_fail 1 "trunc.exr: truncated or corrupt OpenEXR" -- "$LUCENT" image info "$img/trunc.exr"
cp "$img/text.png" "$img/text.exr"
expect_fail 1 "text.exr: not an OpenEXR file" -- "$LUCENT" image diff "$img/text.exr" "$img/a.exr"
printf 'PF\n2 2\n0\n' > "$img/scale.pfm"
expect_fail 1 "scale.pfm: PFM header: bad scale" -- "$LUCENT" image info "$img/scale.pfm"
printf 'PF\n200000 200000\n-1.0\n' > "$img/huge.pfm"
expect_fail 1 "huge.pfm: image too large" -- "$LUCENT" image convert "$img/huge.pfm" "$img/huge.png"
expect_no_file "$img/huge.png"
head -c 30 "$img/a.pfm" > "$img/short.pfm"
expect_fail 1 "short.pfm: truncated PFM data" -- "$LUCENT" image info "$img/short.pfm"
expect_fail 1 "absent.png: cannot open: No such file" -- "$LUCENT" image info "$img/absent.png"
printf 'Pf\n3 1\n-1.0\n\0\0\0\0\0\0\0\0\0\0\0\0' > "$img/small.pfm"
expect_fail 1 "images differ in size" -- "$LUCENT" image diff "$img/a.pfm" "$img/small.pfm"
expect_fail 1 "mask is 3x1" -- "$LUCENT" image diff "$img/a.pfm" "$img/a.png" --mask "$img/small.pfm"
expect_fail 1 "x.tga: unknown image format" -- "$LUCENT" image convert "$img/a.pfm" "$img/x.tga"

# ---- outputs: complete or absent ----
expect_ok -- "$LUCENT" image convert "$img/a.pfm" "$img/missing/x.png"
expect_true "image convert creates the output's folder" -- test -s "$img/missing/x.png"
: > "$img/plain"
expect_fail 1 "plain/x.png: cannot create: $img/plain is not a folder" -- "$LUCENT" image convert "$img/a.pfm" "$img/plain/x.png"
expect_no_file "$img/missing"
mkdir -p "$img/ro" && chmod 755 "$img" && chmod 555 "$img/ro"
expect_fail 1 "ro/x.exr: cannot create" -- as_nobody "$LUCENT" image convert "$img/a.pfm" "$img/ro/x.exr"
expect_no_file "$img/ro/x.exr"
expect_fail 1 "ro/d.png: cannot create" -- as_nobody "$LUCENT" image diff "$img/a.pfm" "$img/a.png" --out "$img/ro/d.png"
expect_no_file "$img/ro/d.png"
chmod 755 "$img/ro"

# ---- usage errors: exit 2 ----
expect_fail 2 "unknown subcommand 'shrink'" -- "$LUCENT" image shrink "$img/a.pfm"
expect_fail 2 "expected a subcommand" -- "$LUCENT" image
expect_fail 2 "expected an input and an output" -- "$LUCENT" image convert "$img/a.pfm"
expect_fail 2 "--tonemap must be" -- "$LUCENT" image convert "$img/a.pfm" "$img/b.png" --tonemap aces
expect_fail 2 "--bits must be 8 or 16" -- "$LUCENT" image convert "$img/a.pfm" "$img/b.png" --bits 12
expect_fail 2 "--exposure needs a number" -- "$LUCENT" image convert "$img/a.pfm" "$img/b.png" --exposure lots
expect_fail 2 "--half applies to OpenEXR" -- "$LUCENT" image convert "$img/a.pfm" "$img/b.png" --half
expect_fail 2 "unknown option '--frobnicate'" -- "$LUCENT" image diff "$img/a.pfm" "$img/a.pfm" --frobnicate
expect_fail 2 "expected two images" -- "$LUCENT" image diff "$img/a.pfm"
expect_fail 2 "--mask needs a file name" -- "$LUCENT" image diff "$img/a.pfm" "$img/a.pfm" --mask
expect_fail 2 "expected one image file" -- "$LUCENT" image info
expect_no_file "$img/b.png"
