# Cases for `lucent compare` (sourced by cli_test.sh: $LUCENT, $TMP, $FIXTURES, expect_ok, expect_fail,
# expect_true, expect_no_file). A tiny scene, few samples: this checks the harness, not the methods.
SC=$FIXTURES/scenes
if [ -n "${LUCENT_GL_SKIP:-}" ]; then
  echo "skip lucent compare cases: $LUCENT_GL_SKIP"
  return 0
fi

expect_ok -- "${GLRUN[@]}" compare "$SC/sphere.json" --methods lambert,ssss:svd2 --spp 8 --frames 2 --out "$TMP/cmp"
for f in report.html report.md report.csv results.json test-sphere/reference.png test-sphere/reference.exr \
         test-sphere/lambert.png test-sphere/ssss-svd2.exr test-sphere/ssss-svd2-error.png test-sphere/errors.svg \
         test-sphere/ssss-svd2-worst.png error-scale.png; do
  expect_true "compare wrote $f" -- test -s "$TMP/cmp/$f"
done
expect_true "compare says where the report is" -- grep -q "^wrote $TMP/cmp/report.html" <<<"$OUT"
expect_true "compare prints a ranked row per method" -- \
  test "$(grep -cE '^  =?[12] +(lambert|ssss:svd2) +[0-9.]+% +[0-9.]+% ' <<<"$OUT")" = 2
expect_true "lambert's frame is 1.00 x Lambert's" -- grep -qE '^  =?[12] +lambert .* 1\.00 ' <<<"$OUT"
expect_true "the CSV has a row per method" -- test "$(grep -c '^"test-sphere",' "$TMP/cmp/report.csv")" = 2
# reference, 2 methods, 2 error maps, the colour bar, 2 crops, the chart
expect_true "the HTML shows every image" -- test "$(grep -o '<img src=' "$TMP/cmp/report.html" | wc -l)" = 9
expect_true "the errors are finite percentages" -- \
  awk -F, 'NR > 1 {if (!($3 >= 0 && $3 < 10)) bad = 1} END {exit bad}' "$TMP/cmp/report.csv"
expect_true "net of the reference's noise: sqrt(error^2 - noise^2), never above the error" -- \
  awk -F, 'NR > 1 {want = $3 * $3 - $10 * $10; want = want > 0 ? sqrt(want) : 0
                   if (NF != 13 || $11 > $3 || (want - $11) ^ 2 > 1e-8 * (want * want + 1e-12)) bad = 1} END {exit bad}' \
  "$TMP/cmp/report.csv"

# Provenance (issue 35): version, revision, command line, date, machine and GL renderer in the report
# and results.json; the chart's time axis is logarithmic.
expect_true "the HTML names version, revision and date" -- \
  grep -qE 'Made by Lucent [0-9]+\.[0-9]+\.[0-9]+ \(revision [^)]+\) on [0-9]{4}-[0-9]{2}-[0-9]{2}T' "$TMP/cmp/report.html"
expect_true "the HTML gives the command line" -- grep -q "Command: <code>lucent compare .*sphere.json --methods lambert,ssss:svd2" "$TMP/cmp/report.html"
expect_true "the HTML names the machine and the GL renderer" -- grep -qE 'machine: [^;]+, [0-9]+ cores; GL renderer: .+' "$TMP/cmp/report.html"
for key in lucent_version revision command date machine cores gl_renderer; do
  expect_true "results.json's provenance has $key" -- grep -qE "\"$key\":[[:space:]]*[^[:space:]]" "$TMP/cmp/results.json"
done
expect_true "results.json's command is the one run" -- grep -q '"command":[[:space:]]*"lucent compare .*--spp 8 --frames 2' "$TMP/cmp/results.json"
expect_true "the chart's time axis is logarithmic" -- grep -q "logarithmic" "$TMP/cmp/test-sphere/errors.svg"
expect_true "the paired test is in results.json" -- grep -q '"paired_test"' "$TMP/cmp/results.json"
expect_true "FLIP and the worst 1% of pixels' share are beside the RMS in the terminal" -- grep -qE '^  =?[12] +lambert .* 0\.[0-9]{4} +[0-9]+\.[0-9]%$' <<<"$OUT"
expect_true "the worst 1% share is in results.json" -- grep -q '"worst_share"' "$TMP/cmp/results.json"

# The README's default methods are the command's (issue 35).
readme_defaults=$(awk '/^### `lucent compare`/{f=1; next} /^### /{f=0} f' "$TESTS/../README.md" | tr '\n' ' ' | \
  sed -n 's/.*(default: \([^)]*\)).*/\1/p' | tr -d '` ' )
help_defaults=$("$LUCENT" compare --help | sed -n 's/.*(default \([a-z0-9:+,]*\).*/\1/p' | head -1)
expect_true "the README lists the default methods of 'compare --help' ($help_defaults)" -- \
  test -n "$help_defaults" -a "$readme_defaults" = "$help_defaults"

# The method phase talks (issue 35): on a terminal each method has a bar with its name, frame k of n,
# the elapsed time and an ETA.
if command -v script >/dev/null; then
  printf -v cmdline '%q ' "${GLRUN[@]}" compare "$SC/sphere.json" --methods lambert,ssss:svd2 --spp 8 --frames 3 \
    --out "$TMP/cmp-tty"
  script -qec "$cmdline" /dev/null > "$TMP/tty.txt" 2>&1
  expect_true "on a terminal the method phase shows each method, frame k of n, elapsed and ETA" -- \
    grep -qE 'test-sphere 2/2 ssss:svd2 +\[[#.]+\] +[0-9.]+% frame [0-9] of 4 .* elapsed, ETA [0-9]+:[0-9]{2}' "$TMP/tty.txt"
else
  _report 0 "script (util-linux) is needed to test the terminal's progress"
fi

# tsd and points are not among the defaults; asked for on a software GL renderer, they are announced
# before any work with an estimate (here the run then fails on its scene, so it costs nothing).
if "$LUCENT" --version 2>/dev/null | grep -q "^gl .*llvmpipe"; then
  expect_fail 1 "warning: tsd is slow on a software GL renderer" -- "${GLRUN[@]}" compare "$SC/missing-mesh.json" \
    --methods lambert,tsd --frames 2 --spp 1 --out "$TMP/c7"
  expect_fail 1 "18 frames a scene (--frames 2 and the image's --samples 16)" -- "${GLRUN[@]}" compare \
    "$SC/missing-mesh.json" --methods tsd --frames 2 --spp 1 --out "$TMP/c7"
  expect_fail 1 "3 frames a scene (--frames 2 and the image's --samples 1)" -- "${GLRUN[@]}" compare \
    "$SC/missing-mesh.json" --methods tsd --frames 2 --samples 1 --spp 1 --out "$TMP/c7"
fi

# A reference reused (--reference): not traced again, the same errors; refused for another scene.
expect_ok -- "${GLRUN[@]}" compare "$SC/sphere.json" --methods lambert --reference "$TMP/cmp" --set render.taps=17 \
  --frames 1 --out "$TMP/cmp-reuse"
expect_true "--reference: the same reference (its spp) and lambert's error" -- bash -c \
  'grep -q "reference 8 spp" <<<"$0" && test "$(grep "^\"test-sphere\",\"lambert\"" "$1" | cut -d, -f3)" = "$(grep "^\"test-sphere\",\"lambert\"" "$2" | cut -d, -f3)"' \
  "$OUT" "$TMP/cmp/report.csv" "$TMP/cmp-reuse/report.csv"
expect_fail 1 "reference.json: objects[0].material: the reference was made with \"skin1\"" -- "${GLRUN[@]}" compare \
  "$SC/sphere.json" --set 'objects[0].material=skin2' --methods lambert --reference "$TMP/cmp" --out "$TMP/c6"
expect_no_file "$TMP/c6/report.html"

# A 1-spp reference cannot estimate its own noise: unknown, a warning in the terminal and the HTML,
# nothing ranked or bolded (issue 12, section 2).
expect_ok -- "${GLRUN[@]}" compare "$SC/sphere.json" --methods lambert,ssss:svd2 --spp 1 --frames 1 --out "$TMP/cmp1"
expect_true "1 spp: the noise is unknown in the terminal" -- grep -q "its noise unknown" <<<"$OUT"
expect_true "1 spp: the terminal warns" -- grep -q "warning: test-sphere: the reference has 1 spp" "$TMP/.stderr"
expect_true "1 spp: no rank in the terminal" -- test "$(grep -cE '^  - +(lambert|ssss:svd2) ' <<<"$OUT")" = 2
expect_true "1 spp: the HTML warns" -- grep -q 'class="warn"><b>Warning:</b> the reference has 1 sample per pixel' \
  "$TMP/cmp1/report.html"
expect_true "1 spp: no best in the HTML" -- bash -c '! grep -q "class=\"best\"" "$0"' "$TMP/cmp1/report.html"
expect_true "1 spp: the JSON's noise is null" -- grep -q '"reference_noise":[[:space:]]*null' "$TMP/cmp1/results.json"

# A method that cannot render a scene's material (the manual kernel's Table A.1 has no Skin2) is skipped
# with a warning naming the method and the scene; the run goes on and reports the others (issue 12).
expect_ok -- "${GLRUN[@]}" compare "$SC/sphere.json" --set 'objects[0].material=skin2' --methods ssss:manual,lambert \
  --spp 8 --frames 1 --out "$TMP/cmp-skip"
expect_true "skip: the terminal warns, naming method and scene" -- \
  grep -q "warning: ssss:manual skipped (scene test-sphere: object .*no Table A.1 parameters for 'Skin2'" "$TMP/.stderr"
expect_true "skip: the other method is reported" -- test "$(grep -c '^"test-sphere",' "$TMP/cmp-skip/report.csv")" = 1
expect_true "skip: the skipped one is not" -- bash -c '! grep -q "ssss:manual" "$0"' "$TMP/cmp-skip/report.csv"
expect_true "skip: the HTML names it and why" -- \
  grep -q "Not in the table:</b> <b>ssss:manual</b> (object .*Skin2" "$TMP/cmp-skip/report.html"
expect_true "skip: the Markdown names it" -- grep -q "Not in the table: ssss:manual (skipped: object" "$TMP/cmp-skip/report.md"
expect_true "skip: the JSON lists it" -- grep -q '"method":[[:space:]]*"ssss:manual"' "$TMP/cmp-skip/results.json"

# Failures: exit 1 (bad input) or 2 (bad usage), a message naming the cause, no report left behind.
expect_fail 2 "--methods: unknown method 'phong'" -- "${GLRUN[@]}" compare "$SC/sphere.json" --methods lambert,phong --out "$TMP/c1"
expect_fail 2 "give at least one scene file" -- "${GLRUN[@]}" compare --out "$TMP/c2"
expect_fail 2 "--spp needs a whole number >= 1" -- "${GLRUN[@]}" compare "$SC/sphere.json" --spp 0 --out "$TMP/c3"
expect_fail 2 "--samples needs a whole number from 1 to 256" -- "${GLRUN[@]}" compare "$SC/sphere.json" --samples 0 --out "$TMP/c3"
expect_fail 2 "--reference-runs needs 1 or 2" -- "${GLRUN[@]}" compare "$SC/sphere.json" --reference-runs 3 --out "$TMP/c3"
expect_fail 1 "objects[0].mesh: cannot open" -- "${GLRUN[@]}" compare "$SC/missing-mesh.json" --spp 1 --out "$TMP/c4"
expect_fail 1 "render.taps" -- "${GLRUN[@]}" compare "$SC/sphere.json" --set render.taps=4 --spp 1 --out "$TMP/c5"
expect_no_file "$TMP/c1/report.html" "$TMP/c2/report.html" "$TMP/c3/report.html" "$TMP/c4/report.html" "$TMP/c5/report.html"
