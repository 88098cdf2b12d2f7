# Cases for `lucent kernel-eval` (sourced by cli_test.sh: $LUCENT, $TMP, expect_ok, expect_fail,
# expect_true, as_nobody). Small signals at a coarse scale keep every preset quick.

# Every preset runs; results.json holds finite numbers only (cJSON writes NaN and inf as null).
for m in Apple Chicken1 Chicken2 Cream Ketchup Marble Potato Skimmilk Skin1 Skin2 Wholemilk; do
  expect_ok -- "$LUCENT" kernel-eval "$m" --size 48 --mm-per-pixel 0.4 --out "$TMP/eval-$m" -q
  expect_true "kernel-eval $m: results.json has finite numbers" -- \
    awk '/"kernel_rms"|"rms"/{n++} /null|nan|inf/{bad=1} END{exit bad || n < 2}' "$TMP/eval-$m/results.json"
done
expect_true "kernel-eval: manual skipped with a note where Table A.1 has no preset" -- \
  grep -q "Skipped manual" "$TMP/eval-Potato/tables.md"
expect_true "kernel-eval: manual built for a Table A.1 material" -- grep -q "^| manual |" "$TMP/eval-Skin1/tables.md"
expect_true "kernel-eval Skin1: the Table 6.5 comparison up to N = 6" -- grep -q "^| 6 |" "$TMP/eval-Skin1/tables.md"
expect_true "kernel-eval: slices, images, heat maps and tables written" -- \
  test -s "$TMP/eval-Skin1/kernel-axis.svg" -a -s "$TMP/eval-Skin1/kernel-diagonal.svg" \
    -a -s "$TMP/eval-Skin1/exact.exr" -a -s "$TMP/eval-Skin1/svd.png" -a -s "$TMP/eval-Skin1/sog-taps-diff.png"

# The shapes signal, a model list, Table 6.5 on request, no taps.
expect_ok -- "$LUCENT" kernel-eval marble --models preint,svd-r2 --signal shapes --size 40 --taps 0 \
  --table65 --mm-per-pixel 0.5 --out "$TMP/eval-shapes"
expect_true "kernel-eval says what it wrote" -- grep -q "^wrote $TMP/eval-shapes/results.json$" <<<"$OUT"
expect_true "kernel-eval --table65 on request" -- grep -q '"table65"' "$TMP/eval-shapes/results.json"
expect_true "kernel-eval --taps 0 writes no tap images" -- test ! -e "$TMP/eval-shapes/preint-taps.png"
# --out's missing parents are created, as every command does (issue 35).
expect_ok -- "$LUCENT" kernel-eval marble --models preint --size 32 --taps 0 --mm-per-pixel 0.5 \
  --out "$TMP/eval-deep/a/b/c"
expect_true "kernel-eval creates --out's parents" -- test -s "$TMP/eval-deep/a/b/c/results.json"

# A user image with its own scale.
expect_ok -- "$LUCENT" kernel-eval skin2 --models preint --signal "$TMP/eval-shapes/signal.png" \
  --mm-per-pixel 0.5 --out "$TMP/eval-image"
expect_true "kernel-eval reads a user image" -- test -s "$TMP/eval-image/preint.exr"

# Bad input and usage.
: > "$TMP/plainfile"
expect_fail 1 "$TMP/plainfile" -- "$LUCENT" kernel-eval skin1 --size 32 --out "$TMP/plainfile/out"
expect_fail 1 "potato" -- "$LUCENT" kernel-eval potato2 --out "$TMP/eval-bad"
expect_fail 2 "expected a material" -- "$LUCENT" kernel-eval
expect_fail 2 "unknown model 'svd3'" -- "$LUCENT" kernel-eval skin1 --models svd,svd3
expect_fail 2 "--size needs a whole number" -- "$LUCENT" kernel-eval skin1 --size -4
expect_fail 2 "--taps needs 0 or an odd number" -- "$LUCENT" kernel-eval skin1 --taps 16
expect_fail 2 "--profile needs dipole" -- "$LUCENT" kernel-eval skin1 --profile foo
expect_fail 2 "unknown option '--frobnicate'" -- "$LUCENT" kernel-eval skin1 --frobnicate

# A parent directory the user cannot write into.
mkdir -p "$TMP/ro" && chmod 555 "$TMP/ro"
expect_fail 1 "$TMP/ro/out" -- as_nobody "$LUCENT" kernel-eval skin1 --size 16 --models preint --out "$TMP/ro/out"
