# Cases for `lucent kernel` (sourced by cli_test.sh: $LUCENT, $TMP, $FIXTURES, expect_ok,
# expect_fail, expect_true, expect_no_file).

# Jimenez's defaults reproduce the centre of the 17-tap table shipped in separable-sss.
expect_ok -- "$LUCENT" kernel --model jimenez --export json --out "$TMP/jimenez.json"
expect_true "kernel says what it wrote" -- grep -q "^wrote $TMP/jimenez.json$" <<<"$OUT"
expect_true "jimenez centre weights (0.536343, 0.624624, 0.748867)" -- \
  awk 'BEGIN{RS="\\]"} /"weights": \[\[/{sub(/.*"weights": \[\[/,""); split($0,w,", ");
       if ((w[1]-0.536343)^2 > 1e-10 || (w[2]-0.624624)^2 > 1e-10 || (w[3]-0.748867)^2 > 1e-10) exit 1; ok=1}
       END{exit !ok}' "$TMP/jimenez.json"
expect_true "jimenez offsets start 0, -2, -1.53125" -- grep -q '"offsets": \[0, -2, -1.53125,' "$TMP/jimenez.json"

# Every model and format runs; the exports are complete.
for model in svd preint guided sog; do
  expect_ok -- "$LUCENT" kernel marble --model "$model" --export json --out "$TMP/marble-$model.json"
  expect_true "kernel $model wrote a complete JSON file" -- grep -q '"passes"' "$TMP/marble-$model.json"
done
expect_ok -- "$LUCENT" kernel skin1 --model manual --export hlsl --out "$TMP/skin1-manual.hlsl"
expect_true "HLSL export declares the kernel" -- grep -q "static const float4 LUCENT_SSS_KERNEL\[17\]" "$TMP/skin1-manual.hlsl"
expect_ok -- "$LUCENT" kernel skin1 --model svd --rank 3 --taps 9 --export glsl
expect_true "rank 3 with 9 taps: 27 GLSL taps on stdout" -- grep -q "LUCENT_SSS_KERNEL\[27\]" <<<"$OUT"
expect_ok -- "$LUCENT" kernel apple --model guided --k 2 --b 50 --export c --out "$TMP/apple.h"
expect_true "C export defines the taps" -- grep -q "#define LUCENT_SSS_TAPS 17" "$TMP/apple.h"
expect_ok -- "$LUCENT" kernel potato --model manual --near 0.05,0.05,0.05 --far 1,1,1 --w 0.4 --export json
expect_true "manual with explicit parameters" -- grep -q '"rank": 1' <<<"$OUT"

# Bad input and usage.
expect_fail 1 "no Table A.1 parameters for 'Potato'" -- "$LUCENT" kernel potato --model manual --out "$TMP/potato.json"
expect_no_file "$TMP/potato.json"
expect_fail 1 "$FIXTURES/materials/negative.json: sigma_a[1]: must be >= 0" -- \
  "$LUCENT" kernel "$FIXTURES/materials/negative.json" --out "$TMP/neg.json"
expect_no_file "$TMP/neg.json"
expect_fail 1 "rank must be 1" -- "$LUCENT" kernel skin1 --model preint --rank 2
expect_fail 1 "taps: count must be odd" -- "$LUCENT" kernel skin1 --taps 16
expect_ok -- "$LUCENT" kernel skin1 --out "$TMP/newdir/kernel/k.json"
expect_true "kernel creates the folder of --out" -- test -s "$TMP/newdir/kernel/k.json"
expect_fail 2 "unknown model 'svd2'" -- "$LUCENT" kernel skin1 --model svd2
expect_fail 2 "unknown export format 'wgsl'" -- "$LUCENT" kernel skin1 --export wgsl
expect_fail 2 "expected a material" -- "$LUCENT" kernel --model svd
expect_fail 2 "--strength needs R,G,B" -- "$LUCENT" kernel --model jimenez --strength 0.5,0.5
expect_fail 2 "unknown option '--frobnicate'" -- "$LUCENT" kernel skin1 --frobnicate

# The Monte Carlo profile: the same seed gives the same kernel whatever the thread count.
expect_ok -- "$LUCENT" kernel marble --profile mc --photons 20000 --threads 1 --out "$TMP/kmc1.json"
expect_ok -- "$LUCENT" kernel marble --profile mc --photons 20000 --threads 2 --out "$TMP/kmc2.json"
expect_true "kernel --profile mc: 1 and 2 threads give identical taps" -- cmp "$TMP/kmc1.json" "$TMP/kmc2.json"
expect_fail 2 "--profile must be dipole, better-dipole, burley or mc" -- "$LUCENT" kernel skin1 --profile foo
