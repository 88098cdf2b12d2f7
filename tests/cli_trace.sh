# Cases for `lucent trace` (sourced by cli_test.sh: $LUCENT, $TMP, $FIXTURES, expect_ok, expect_fail,
# expect_true, expect_no_file).
SMALL="$FIXTURES/scenes/trace-small.json"
# json_has FILE KEY VALUE: the sidecar (cJSON's layout, one key per line) holds "KEY": VALUE.
json_has() { grep -q "^[[:space:]]*\"$2\":[[:space:]]*$3,\?$" "$1"; }

# A render: the PNG, the EXR, the variance and the sidecar, each complete; the sidecar says what made it.
expect_ok -- "$LUCENT" trace "$SMALL" --spp 4 --seed 3 --out "$TMP/t.png" --exr "$TMP/t.exr" --variance "$TMP/tv.exr"
for f in t.png t.exr tv.exr t.json; do expect_true "trace wrote $f" -- test -s "$TMP/$f"; done
expect_true "trace says what it wrote" -- grep -q "^wrote $TMP/t.json$" <<<"$OUT"
expect_true "trace reports samples and the relative standard error" -- \
  grep -q "^trace: 4 spp in .*relative standard error over the object: median" <<<"$OUT"
expect_ok -- "$LUCENT" image info "$TMP/t.exr"
expect_true "the EXR has the scene's size" -- grep -q "24x20" <<<"$OUT"
expect_true "the sidecar holds spp and seed" -- eval 'json_has "$TMP/t.json" spp 4 && json_has "$TMP/t.json" seed 3'
expect_true "the sidecar holds the time, the rate and the error summary" -- \
  eval 'grep -q "\"seconds\":" "$TMP/t.json" && grep -q "\"samples_per_second\":" "$TMP/t.json" && grep -q "\"rms\":" "$TMP/t.json"'
expect_true "the sidecar holds the scene" -- json_has "$TMP/t.json" name '"trace-small"'
# Overrides reach the render and the sidecar's scene; --json names the sidecar.
expect_ok -- "$LUCENT" trace "$SMALL" --spp 2 --set render.width=16 --set 'objects[0].roughness=0.2' \
  --out "$TMP/o.png" --json "$TMP/side.json"
expect_true "--set reaches the render and the sidecar" -- \
  eval 'json_has "$TMP/side.json" width 16 && json_has "$TMP/side.json" roughness 0.2'
# Same seed, same image, whatever the thread count.
expect_ok -- "$LUCENT" trace "$SMALL" --spp 3 --threads 1 --out "$TMP/a.png" --exr "$TMP/a.exr"
expect_ok -- "$LUCENT" trace "$SMALL" --spp 3 --threads 2 --out "$TMP/b.png" --exr "$TMP/b.exr"
expect_true "1 and 2 threads give the same EXR" -- cmp "$TMP/a.exr" "$TMP/b.exr"
expect_ok -- "$LUCENT" trace "$SMALL" --time 0.2 --spp 1000000 --subsurface-only --out "$TMP/timed.png"
expect_true "--time stops early" -- \
  awk -F'[:,]' '/"spp":/ {gsub(/[ \t]/, "", $2); n = $2 + 0; exit !(n > 0 && n < 1000000)}' "$TMP/timed.json"
expect_true "a time-limited trace without --adaptive does not call itself adaptive (issue 35)" -- \
  eval '! grep -q adaptive <<<"$OUT"' 
expect_true "the sidecar says subsurface only" -- json_has "$TMP/timed.json" subsurface_only true
expect_ok -- "$LUCENT" trace "$SMALL" --spp 6 --adaptive --out "$TMP/ad.png"
expect_true "--adaptive counts passes, not spp, and says how many samples it took (issue 35)" -- \
  grep -q "^trace: 6 adaptive passes ([0-9.]* samples per pixel on average)" <<<"$OUT"
expect_true "the sidecar says adaptive" -- json_has "$TMP/ad.json" adaptive true

# Refusal, bad input, bad usage; nothing partial is left.
expect_fail 1 "trace-smooth.json: lights[0] (a directional light with angular_radius 0, a delta light) can reach the inside of objects[0] \"glassy\" only through its smooth boundary" -- \
  "$LUCENT" trace "$FIXTURES/scenes/trace-smooth.json" --out "$TMP/refused.png"
expect_no_file "$TMP/refused.png" "$TMP/refused.json"
expect_ok -- "$LUCENT" trace "$FIXTURES/scenes/trace-smooth.json" --set 'lights[0].angular_radius=1' --spp 1 \
  --out "$TMP/disc.png"
expect_fail 1 "render.max_bounces" -- "$LUCENT" trace "$SMALL" --set render.max_bounces=0 --out "$TMP/x.png"
expect_fail 1 "objects[0].material" -- "$LUCENT" trace "$SMALL" --set 'objects[0].material=unobtainium' --out "$TMP/x.png"
: > "$TMP/plainfile-trace"
expect_fail 1 "$TMP/plainfile-trace/t.png" -- "$LUCENT" trace "$SMALL" --spp 1 --out "$TMP/plainfile-trace/t.png"
expect_fail 1 "nope.json" -- "$LUCENT" trace "$TMP/nope.json" --out "$TMP/x.png"
expect_no_file "$TMP/x.png" "$TMP/x.json"
expect_fail 2 "--out is required" -- "$LUCENT" trace "$SMALL"
expect_fail 2 "expected a scene file" -- "$LUCENT" trace --out "$TMP/x.png"
expect_fail 2 "--out '$TMP/x.jpg': use .png" -- "$LUCENT" trace "$SMALL" --out "$TMP/x.jpg"
expect_fail 2 "--exr '$TMP/x.png': use .exr" -- "$LUCENT" trace "$SMALL" --out "$TMP/x.png" --exr "$TMP/x.png"
expect_fail 2 "--spp needs a whole number" -- "$LUCENT" trace "$SMALL" --spp 0 --out "$TMP/x.png"
expect_fail 2 "--seed needs a whole number" -- "$LUCENT" trace "$SMALL" --seed -2 --out "$TMP/x.png"
expect_fail 2 "--time needs a number of seconds" -- "$LUCENT" trace "$SMALL" --time 0 --out "$TMP/x.png"
expect_fail 2 "--set needs KEY=VALUE" -- "$LUCENT" trace "$SMALL" --set camera --out "$TMP/x.png"
expect_fail 2 "unknown option '--frob'" -- "$LUCENT" trace "$SMALL" --frob --out "$TMP/x.png"
expect_fail 2 "unexpected argument" -- "$LUCENT" trace "$SMALL" "$SMALL" --out "$TMP/x.png"
expect_no_file "$TMP/x.png" "$TMP/x.jpg"
