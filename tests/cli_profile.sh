# Cases for `lucent profile` (sourced by cli_test.sh: $LUCENT, $TMP, $FIXTURES, expect_ok,
# expect_fail, expect_true, expect_no_file).

# The classical dipole's profile integrates to Jensen 2001's total diffuse reflectance:
# Skin1 (0.436, 0.227, 0.131) +-0.001 (the default grid reaches 32 reduced mean free paths).
expect_ok -- "$LUCENT" profile skin1 --model dipole --out "$TMP/skin1-dipole"
for ext in json csv svg; do
  expect_true "profile wrote skin1-dipole.$ext" -- test -s "$TMP/skin1-dipole.$ext"
done
expect_true "profile says what it wrote" -- grep -q "^wrote $TMP/skin1-dipole.svg$" <<<"$OUT"
profile_totals() { # JSON: the three totals on one line
  tr -d ' \t\n' <"$1" | sed 's/.*"total_on_grid":\[\([^]]*\)\].*/\1/' | tr ',' ' '
}
profile_near() { # "a b c" "x y z" TOL
  awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN{split(a,p," "); split(b,q," ");
    for(i=1;i<=3;i++) if ((p[i]-q[i])>t || (q[i]-p[i])>t || p[i]=="") exit 1}'
}
expect_true "the dipole profile of Skin1 integrates to Jensen's Rd (0.436, 0.227, 0.131)" -- \
  profile_near "$(profile_totals "$TMP/skin1-dipole.json")" "0.436 0.227 0.131" 0.001
expect_true "the CSV has a header and one row per bin" -- \
  test "$(sed -n 2p "$TMP/skin1-dipole.csv")" = "r_mm,R,R_se,G,G_se,B,B_se"
expect_true "the SVG is a complete document" -- grep -q "</svg>" "$TMP/skin1-dipole.svg"

# Monte Carlo: the same seed gives the same file whatever the thread count.
expect_ok -- "$LUCENT" profile marble --model mc --photons 20000 --threads 1 --out "$TMP/mc1"
expect_ok -- "$LUCENT" profile marble --model mc --photons 20000 --threads 2 --out "$TMP/mc2"
expect_true "profile --model mc: 1 and 2 threads give identical CSV" -- cmp "$TMP/mc1.csv" "$TMP/mc2.csv"
expect_ok -- "$LUCENT" profile marble --compare dipole,better-dipole,burley --out "$TMP/cmp" --sog 3
expect_true "--compare writes one table per model and one chart" -- \
  test -s "$TMP/cmp-dipole.csv" -a -s "$TMP/cmp-better-dipole.csv" -a -s "$TMP/cmp-burley.csv" -a -s "$TMP/cmp.svg"
expect_true "--sog records the Gaussians" -- grep -q '"sum_of_gaussians"' "$TMP/cmp-dipole.json"
expect_ok -- "$LUCENT" profile skin1 --model multipole --thickness 2 --out "$TMP/slab"
expect_ok -- "$LUCENT" profile skin1 --layers skin1:1,skin2:2 --model multipole --out "$TMP/layers"
# A layered slab is recorded and named by its layers (issue 35): the JSON's "layers", the default name.
expect_true "profile --layers records each layer's material and thickness" -- \
  python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); \
assert [(l["material"]["name"], l["thickness_mm"]) for l in d["layers"]] == [("Skin1", 1), ("Skin2", 2)]' \
  "$TMP/layers.json"
mkdir -p "$TMP/layers-default"
expect_ok -- "$LUCENT" profile --layers skin1:0.5,skin2:inf --model mc --photons 2000 --out "$TMP/layers-default/"
expect_true "profile --layers names the files after the layers" -- \
  test -s "$TMP/layers-default/Skin1-0.5mm_Skin2-mc.json" -a -s "$TMP/layers-default/Skin1-0.5mm_Skin2-mc.svg"
expect_true "profile --layers names the chart after the layers" -- \
  grep -q "Skin1 0.5mm + Skin2" "$TMP/layers-default/Skin1-0.5mm_Skin2-mc.svg"

# Bad input and usage.
expect_fail 1 "multipole: give the slab --thickness" -- "$LUCENT" profile skin1 --model multipole
expect_fail 1 "$FIXTURES/materials/negative.json: sigma_a[1]: must be >= 0" -- \
  "$LUCENT" profile "$FIXTURES/materials/negative.json" --model dipole --out "$TMP/neg"
expect_no_file "$TMP/neg.json" "$TMP/neg.csv" "$TMP/neg.svg"
expect_ok -- "$LUCENT" profile skin1 --model dipole --out "$TMP/newdir/prof/p"
expect_true "profile creates the folder of --out" -- test -s "$TMP/newdir/prof/p.json"
expect_fail 1 "only the last layer may be 'inf'" -- "$LUCENT" profile --layers skin1:inf,skin2:1
expect_fail 1 "thickness must be > 0" -- "$LUCENT" profile --layers skin1:-1
expect_fail 2 "unknown model 'dipol'" -- "$LUCENT" profile skin1 --model dipol
expect_fail 2 "--model takes one model" -- "$LUCENT" profile skin1 --model mc,dipole
expect_fail 2 "expected a material" -- "$LUCENT" profile --model dipole
expect_fail 2 "--photons needs a whole number > 0" -- "$LUCENT" profile skin1 --photons 0
expect_fail 2 "--sog needs a count from 1 to 16" -- "$LUCENT" profile skin1 --sog 17
expect_ok -- "$LUCENT" profile skin1 --model burley --burley-fit dmfp --out "$TMP/burley"
expect_fail 2 "--burley-fit must be searchlight, diffuse or dmfp" -- "$LUCENT" profile skin1 --model burley --burley-fit mfp2
