# shellcheck shell=bash
# `lucent mcml`: sourced by tests/cli_test.sh, which provides $LUCENT, $FIXTURES, $TMP,
# expect_ok, expect_fail, expect_true and expect_no_file.
MCI=$(cd "$FIXTURES/mcml" && pwd)

if "$LUCENT" mcml --help 2>&1 | grep -q "unknown command"; then
  _report 0 "mcml is registered in tools/main.c (the remaining mcml cases are skipped)"
else

mcml_not() { ! "$@"; }
# within3 VALUE SE EXPECTED: |VALUE - EXPECTED| <= 3 SE, SE > 0
within3() { awk -v v="$1" -v s="$2" -v e="$3" 'BEGIN { d = v - e; if (d < 0) d = -d; exit !(s > 0 && d <= 3 * s) }'; }
# mco_stat FILE NAME: "value se" from the .mco header line "# Rd x +- s, A x +- s, Tt x +- s"
mco_stat() { awk -v n="$2" '/^# Rd .* \+- /{ for (i = 2; i < NF; i++) if ($i == n) { v = $(i+1); s = $(i+3); sub(",", "", s); print v, s } }' "$1"; }
# mco_value FILE SECTION INDEX: the INDEX-th (1-based) line after the SECTION header
mco_value() { awk -v s="$2" -v k="$3" '$1 == s { f = 1; next } f { if (++i == k) { print $1; exit } }' "$1"; }

# ---- van de Hulst's slab: Rd 0.09739, Tt 0.66096 within 3 standard errors ----
mkdir -p "$TMP/mcml1" "$TMP/mcml2"
expect_ok -- "$LUCENT" mcml "$MCI/vanhulst.mci" --threads 1 --out-dir "$TMP/mcml1"
expect_true "mcml says what it wrote" -- grep -q "^wrote $TMP/mcml1/vanhulst.mco" <<<"$OUT"
read -r rd rd_se < <(mco_stat "$TMP/mcml1/vanhulst.mco" Rd)
read -r tt tt_se < <(mco_stat "$TMP/mcml1/vanhulst.mco" Tt)
expect_true "van de Hulst slab: Rd $rd +- $rd_se is within 3 SE of 0.09739" -- within3 "$rd" "$rd_se" 0.09739
expect_true "van de Hulst slab: Tt $tt +- $tt_se is within 3 SE of 0.66096" -- within3 "$tt" "$tt_se" 0.66096
expect_true "RAT's diffuse reflectance is the header's Rd" -- \
  awk -v v="$rd" '$1 == "RAT" { getline; getline; exit !($1 - v < 1e-6 && v - $1 < 1e-6) }' "$TMP/mcml1/vanhulst.mco"
for section in InParm RAT A_l A_z Rd_r Rd_a Tt_r Tt_a A_rz Rd_ra Tt_ra; do
  expect_true "the .mco has MCML's section $section" -- grep -q "^$section\b" "$TMP/mcml1/vanhulst.mco"
done
expect_true "A_z has nz = 20 values, Rd_r nr = 50, Rd_a na = 10" -- \
  awk '/^A_z /{s="z";next} /^Rd_r /{s="r";next} /^Rd_a /{s="a";next} /^$/{s=""} s{n[s]++}
       END{exit !(n["z"]==20 && n["r"]==50 && n["a"]==10)}' "$TMP/mcml1/vanhulst.mco"
expect_true "InParm is in cm, as in the .mci" -- grep -q "^1	10	90	0.75	0.02	# layer 1" "$TMP/mcml1/vanhulst.mco"
# identical files whatever the thread count
expect_ok -- "$LUCENT" mcml "$MCI/vanhulst.mci" --threads 2 --out-dir "$TMP/mcml2"
expect_true "the same seed with 1 and 2 threads gives identical files" -- \
  cmp "$TMP/mcml1/vanhulst.mco" "$TMP/mcml2/vanhulst.mco"
# ... on every SIMD path this CPU has (--isa; docs/mcml.md, "SIMD paths"): each path its own numbers,
# the same for 1 and 2 threads
for isa in scalar avx2 avx512; do
  if ! "$LUCENT" --isa "$isa" mcml --help >/dev/null 2>&1; then
    expect_fail 2 "--isa $isa: this CPU lacks it" -- "$LUCENT" --isa "$isa" mcml "$MCI/vanhulst.mci"
    echo "note: this CPU has no $isa path: its thread check is left out"
    continue
  fi
  mkdir -p "$TMP/mcml-$isa-1" "$TMP/mcml-$isa-2"
  expect_ok -- "$LUCENT" mcml "$MCI/vanhulst.mci" --isa "$isa" --threads 1 --out-dir "$TMP/mcml-$isa-1" -q
  expect_ok -- "$LUCENT" --isa="$isa" mcml "$MCI/vanhulst.mci" --threads 2 --out-dir "$TMP/mcml-$isa-2" -q
  expect_true "$isa: the same seed with 1 and 2 threads gives identical files" -- \
    cmp "$TMP/mcml-$isa-1/vanhulst.mco" "$TMP/mcml-$isa-2/vanhulst.mco"
  expect_true "$isa: the .mco names the kernel" -- grep -q "^# Written by Lucent .*(lucent mcml, the $isa kernel)" \
    "$TMP/mcml-$isa-1/vanhulst.mco"
  if [ "$isa" != scalar ]; then
    expect_true "$isa: its numbers are not the scalar kernel's" -- \
      mcml_not cmp -s <(grep -v "^# Written" "$TMP/mcml-$isa-1/vanhulst.mco") \
      <(grep -v "^# Written" "$TMP/mcml-scalar-1/vanhulst.mco")
  fi
done
expect_fail 2 "--isa needs auto, scalar, avx2 or avx512" -- "$LUCENT" --isa sse9 mcml "$MCI/vanhulst.mci"
expect_ok -- "$LUCENT" mcml "$MCI/vanhulst.mci" --seed 2 --out-dir "$TMP/mcml2" --quiet
expect_true "another seed gives another file" -- mcml_not cmp -s "$TMP/mcml1/vanhulst.mco" "$TMP/mcml2/vanhulst.mco"
expect_true "--quiet prints nothing" -- test -z "$OUT"

# ---- Giovanelli's half-space: Rsp + Rd = 0.2600 within 3 standard errors ----
expect_ok -- "$LUCENT" mcml "$MCI/giovanelli.mci" --out-dir "$TMP/mcml1"
read -r rd rd_se < <(mco_stat "$TMP/mcml1/giovanelli.mco" Rd)
rsp=$(mco_value "$TMP/mcml1/giovanelli.mco" RAT 1)
expect_true "Giovanelli half-space: Rsp $rsp + Rd $rd +- $rd_se is within 3 SE of 0.2600" -- \
  within3 "$(awk -v a="$rsp" -v b="$rd" 'BEGIN{print a + b}')" "$rd_se" 0.2600

# ---- several runs, several layers, comments; outputs where the .mci names them ----
(cd "$TMP" && "$LUCENT" mcml "$MCI/two_runs.mci" -q) >/dev/null 2>&1
expect_true "two runs write glass.mco and half.mco beside the working directory" -- \
  test -s "$TMP/glass.mco" -a -s "$TMP/half.mco"
expect_true "glass.mco has 3 layers in A_l" -- \
  awk '$1 == "A_l" { f = 1; next } f && /^$/ { exit !(n == 3) } f { n++ }' "$TMP/glass.mco"

# ---- malformed input: exit 1, the message names the file and the line; nothing written ----
bad_mci() { # FIXTURE MESSAGE
  expect_fail 1 "$MCI/$1: $2" -- "$LUCENT" mcml "$MCI/$1" --out-dir "$TMP/bad"
}
mkdir -p "$TMP/bad"
bad_mci missing_line.mci "line 13: unexpected end of file, expected n for the medium above"
bad_mci negative_thickness.mci "line 15: layer 1: thickness d must be > 0, got -0.02"
bad_mci bad_g.mci "line 15: layer 1: g must be in [-1, 1], got 1.5"
bad_mci low_n.mci "line 14: n for the medium above must be in [1, 10], got 0.9"
bad_mci too_many_bins.mci "line 10: too many radial bins (nr): 5e+06"
bad_mci bad_number.mci "line 8: expected the number of photons, got '2e5x'"
bad_mci extra_data.mci "line 17: unexpected data after the last of 1 run"
expect_true "no output for malformed input" -- test -z "$(ls -A "$TMP/bad")"
expect_fail 1 "$MCI/absent.mci" -- "$LUCENT" mcml "$MCI/absent.mci"
: > "$TMP/plainfile-mcml"
expect_fail 1 "$TMP/plainfile-mcml" -- "$LUCENT" mcml "$MCI/vanhulst.mci" --out-dir "$TMP/plainfile-mcml"

# ---- usage ----
expect_fail 2 "missing the input file" -- "$LUCENT" mcml
expect_fail 2 "unknown option '--frobnicate'" -- "$LUCENT" mcml "$MCI/vanhulst.mci" --frobnicate
expect_fail 2 "--seed needs a whole number" -- "$LUCENT" mcml "$MCI/vanhulst.mci" --seed x
expect_fail 2 "one input file" -- "$LUCENT" mcml a.mci b.mci
# ---- --compare: Lucent against real MCML 1.2.2 output (tests/fixtures/mcml/mco/README.md) ----
MCO=$MCI/mco
mkdir -p "$TMP/cmp"
expect_ok -- "$LUCENT" mcml --compare "$MCO/gcontrast_small.mco" --threads 1 -q \
  --csv "$TMP/cmp/c.csv" --json "$TMP/cmp/c.json"
for section in Rsp RAT A_l A_z Rd_r Rd_a Tt_r Tt_a summary:; do
  expect_true "--compare prints the section $section" -- grep -q "^$section " <<<"$OUT"
done
expect_true "--compare runs as many photons as MCML did and estimates MCML's SE from Lucent's" -- \
  grep -q "^Lucent (20000 photons, seed 1) against .*gcontrast_small.mco (MCML, 20000 photons)" <<<"$OUT"
expect_true "Rd, A and Tt are given in standard errors" -- \
  awk '$1 == "RAT" && $2 == "Rd" && $0 ~ / SE/ { f = 1 } END { exit !f }' <<<"$OUT"
expect_true "the CSV has a row per bin: 1 + 1 + 3 + 2 + 30 + 20 + 5 + 20 + 5 lines" -- \
  test "$(wc -l < "$TMP/cmp/c.csv")" = 87
expect_true "the JSON has the summary" -- grep -q '"beyond_3se"' "$TMP/cmp/c.json"
expect_ok -- "$LUCENT" mcml "$MCO/gcontrast_small.mci" --compare "$MCO/gcontrast_small.mco" \
  --photons 40000 --seed 3 --threads 2
expect_true "an .mci describing the .mco runs; --photons and --seed are Lucent's" -- \
  grep -q "^Lucent (40000 photons, seed 3) against" <<<"$OUT"
expect_true "MCML's SE is Lucent's x sqrt(40000 / 20000)" -- grep -q "Lucent's x 1.414" <<<"$OUT"
# a wrong total stands out
sed 's/^0.566199 /0.6 /' "$MCO/gcontrast_small.mco" > "$TMP/cmp/wrong_rd.mco"
expect_ok -- "$LUCENT" mcml --compare "$TMP/cmp/wrong_rd.mco" --threads 2
expect_true "Rd 0.6 instead of 0.5662 is beyond 3 SE" -- \
  awk '$1 == "RAT" && $2 == "Rd" && /beyond 3 SE/ { f = 1 } END { exit !f }' <<<"$OUT"
# an .mci of another simulation, malformed .mco files: exit 1, file and line named, nothing written
expect_fail 1 "vanhulst.mci: no run describes the simulation of $MCO/gcontrast_small.mco (run 1: the number of layers is 1, the .mco's is 2)" -- \
  "$LUCENT" mcml "$MCI/vanhulst.mci" --compare "$MCO/gcontrast_small.mco" --csv "$TMP/cmp/x.csv"
head -n 100 "$MCO/gcontrast_small.mco" > "$TMP/cmp/cut.mco"
expect_fail 1 "$TMP/cmp/cut.mco: line 101: unexpected end of file, expected Tt_r: 20 values (nr)" -- \
  "$LUCENT" mcml --compare "$TMP/cmp/cut.mco" --csv "$TMP/cmp/x.csv"
sed 's/^  2.3516E+00$/  2.3516E+0x/' "$MCO/gcontrast_small.mco" > "$TMP/cmp/bad.mco"
expect_fail 1 "$TMP/cmp/bad.mco: line 37: A_z: value 2: expected a number, got '2.3516E+0x'" -- \
  "$LUCENT" mcml --compare "$TMP/cmp/bad.mco" --json "$TMP/cmp/x.json"
expect_no_file "$TMP/cmp/x.csv" "$TMP/cmp/x.json"
expect_fail 1 "$MCO/absent.mco" -- "$LUCENT" mcml --compare "$MCO/absent.mco"
: > "$TMP/plainfile-csv"
expect_fail 1 "$TMP/plainfile-csv/c.csv" -- "$LUCENT" mcml --compare "$MCO/gcontrast_small.mco" --csv "$TMP/plainfile-csv/c.csv"
expect_fail 2 "--csv goes with --compare" -- "$LUCENT" mcml "$MCI/vanhulst.mci" --csv "$TMP/cmp/x.csv"
expect_fail 2 "--out-dir does not go with --compare" -- "$LUCENT" mcml --compare "$MCO/gcontrast_small.mco" --out-dir "$TMP"
expect_fail 2 "--photons needs a whole number in [1, 1e12]" -- "$LUCENT" mcml --compare "$MCO/gcontrast_small.mco" --photons 0
expect_fail 2 "--compare needs an MCML output file" -- "$LUCENT" mcml --compare
fi
