# shellcheck shell=bash
# --part K/N and `lucent merge` (docs/scale.md): sourced by tests/cli_test.sh ($LUCENT, $FIXTURES,
# $TMP, expect_*). No MPI needed. The expected outputs are the single run's own files: the parts
# cut the same chunks with the same RNG streams, so the merged outputs must equal them byte for byte.
dist_not() { ! "$@"; }
D="$TMP/dist"
mkdir -p "$D/one" "$D/parts" "$D/merged" "$D/bad"
MCI3="$FIXTURES/mcml/three_layers.mci"

# ---- mcml: 4 parts merged = one run ----
expect_ok -- "$LUCENT" mcml "$MCI3" --out-dir "$D/one" --quiet
for k in 1 2 3 4; do
  expect_ok -- "$LUCENT" mcml "$MCI3" --out-dir "$D/parts" --part "$k/4"
done
expect_true "a part writes OUTPUT.part-K-of-N, not the output" -- \
  test -f "$D/parts/three_layers.mco.part-3-of-4" -a ! -e "$D/parts/three_layers.mco"
expect_ok -- "$LUCENT" merge "$D"/parts/three_layers.mco.part-*-of-4 -- --out-dir "$D/merged"
expect_true "merge prints no photon rate: nothing was simulated (issue 35)" -- \
  eval 'grep -q "photons)" <<<"$OUT" && ! grep -q "photons/s" <<<"$OUT"'
expect_true "mcml: 4 merged parts give the single run's .mco byte for byte" -- \
  cmp "$D/one/three_layers.mco" "$D/merged/three_layers.mco"
expect_ok -- "$LUCENT" mcml "$MCI3" --out-dir "$D/one" --seed 7 --quiet
expect_true "another seed gives another .mco (the comparison above can fail)" -- \
  dist_not cmp -s "$D/one/three_layers.mco" "$D/merged/three_layers.mco"

# ---- merge refuses what is not one whole run ----
P="$D/parts/three_layers.mco"
expect_fail 1 "merge: part 4 of 4 is missing" -- "$LUCENT" merge "$P.part-1-of-4" "$P.part-2-of-4" "$P.part-3-of-4" \
  -- --out-dir "$D/bad"
expect_fail 1 "merge: part 2 of 4 given twice" -- "$LUCENT" merge "$P.part-1-of-4" "$P.part-2-of-4" \
  "$P.part-2-of-4" "$P.part-4-of-4" -- --out-dir "$D/bad"
expect_fail 1 "$MCI3: header: not a Lucent part file" -- "$LUCENT" merge "$MCI3"
# fixcrc FILE: its last 4 bytes become the CRC-32 of the others, as a part's checksum (src/base/dist.c), so
# that the damage below reaches the structure's checks rather than the checksum's.
fixcrc() { python3 -c 'import sys, zlib; f = sys.argv[1]; b = bytearray(open(f, "rb").read())
b[-4:] = zlib.crc32(bytes(b[:-4])).to_bytes(4, "little"); open(f, "wb").write(b)' "$1"; }
head -c 300 "$P.part-1-of-4" >"$D/bad/short.part" && fixcrc "$D/bad/short.part"
expect_fail 1 "$D/bad/short.part: tally 1:" -- "$LUCENT" merge "$D/bad/short.part"
head -c 300 "$P.part-1-of-4" >"$D/bad/crc.part"
expect_fail 1 "$D/bad/crc.part: the part's checksum does not match its contents" -- "$LUCENT" merge "$D/bad/crc.part"
# damaged headers and tails (the layout: docs/scale.md, src/base/dist.c)
cp "$P.part-1-of-4" "$D/bad/tail.part" && printf 'x....' >>"$D/bad/tail.part" && fixcrc "$D/bad/tail.part"
expect_fail 1 "$D/bad/tail.part: 5 bytes after the last tally" -- "$LUCENT" merge "$D/bad/tail.part"
cp "$P.part-1-of-4" "$D/bad/k.part" && printf '\005' | dd of="$D/bad/k.part" bs=1 seek=20 conv=notrunc 2>/dev/null
fixcrc "$D/bad/k.part"
expect_fail 1 "$D/bad/k.part: header: part 5 of 4" -- "$LUCENT" merge "$D/bad/k.part"
cp "$P.part-1-of-4" "$D/bad/order.part" && printf '\001\002\003\004' | dd of="$D/bad/order.part" bs=1 seek=16 \
  conv=notrunc 2>/dev/null
expect_fail 1 "$D/bad/order.part: header: written on a machine of another byte order" -- \
  "$LUCENT" merge "$D/bad/order.part"
expect_ok -- "$LUCENT" mcml "$MCI3" --out-dir "$D/parts" --part 4/4 --seed 9 --quiet
expect_fail 1 "are parts of different commands" -- "$LUCENT" merge "$P.part-1-of-4" "$P.part-2-of-4" \
  "$P.part-3-of-4" "$P.part-4-of-4" -- --out-dir "$D/bad"
expect_no_file "$D/bad/three_layers.mco"
expect_fail 2 "expected part files" -- "$LUCENT" merge
expect_fail 2 "--part 0/4: needs K/N with 1 <= K <= N" -- "$LUCENT" mcml "$MCI3" --part 0/4
expect_fail 2 "--part 5/4: needs K/N with 1 <= K <= N" -- "$LUCENT" mcml "$MCI3" --part 5/4
expect_fail 2 "--part needs K/N" -- "$LUCENT" mcml "$MCI3" --part 3
expect_fail 2 "--part goes with mcml, profile, cdrf-fit and trace" -- "$LUCENT" materials --part 1/2

# the inputs changed between the parts and the merge: refused, nothing written
cp "$MCI3" "$D/bad/in.mci"
for k in 1 2; do expect_ok -- "$LUCENT" mcml "$D/bad/in.mci" --out-dir "$D/bad" --part "$k/2" --quiet; done
sed -i 's/^20 30 6 /20 31 6 /' "$D/bad/in.mci"
expect_fail 1 "not the run the parts come from" -- "$LUCENT" merge "$D"/bad/three_layers.mco.part-*-of-2
expect_no_file "$D/bad/three_layers.mco"

# ---- profile --model mc: CSV and JSON ----
expect_ok -- "$LUCENT" profile skin1 --model mc --photons 8000 --bins 40 --out "$D/one/p" --quiet
for k in 1 2 3 4; do
  expect_ok -- "$LUCENT" profile skin1 --model mc --photons 8000 --bins 40 --out "$D/parts/p" --part "$k/4" --quiet
done
expect_ok -- "$LUCENT" merge "$D"/parts/p.json.part-*-of-4 -- --out "$D/merged/p"
expect_true "profile --model mc: 4 merged parts give the single run's CSV byte for byte" -- \
  cmp "$D/one/p.csv" "$D/merged/p.csv"
expect_true "... and its JSON" -- cmp "$D/one/p.json" "$D/merged/p.json"

# ---- cdrf-fit: the spheres' batches ----
expect_ok -- "$LUCENT" cdrf-fit skin1 --radii 2,5 --photons 2000 --bins 12 --out "$D/one/c" --quiet
for k in 1 2 3; do
  expect_ok -- "$LUCENT" cdrf-fit skin1 --radii 2,5 --photons 2000 --bins 12 --out "$D/parts/c" --part "$k/3" --quiet
done
expect_ok -- "$LUCENT" merge "$D"/parts/c.json.part-*-of-3 -- --out "$D/merged/c"
expect_true "cdrf-fit: 3 merged parts give the single run's CSV byte for byte" -- cmp "$D/one/c.csv" "$D/merged/c.csv"
expect_true "... and its JSON (the fit)" -- cmp "$D/one/c.json" "$D/merged/c.json"

# ---- trace: the tiles of every pass ----
SC="$FIXTURES/scenes/trace-small.json"
expect_ok -- "$LUCENT" trace "$SC" --spp 3 --out "$D/one/t.png" --exr "$D/one/t.exr" --variance "$D/one/tv.exr" --quiet
for k in 1 2 3 4; do
  expect_ok -- "$LUCENT" trace "$SC" --spp 3 --out "$D/parts/t.png" --exr "$D/parts/t.exr" --part "$k/4" --quiet
done
expect_true "trace: a part writes no image" -- test ! -e "$D/parts/t.png" -a ! -e "$D/parts/t.exr"
expect_ok -- "$LUCENT" merge "$D"/parts/t.png.part-*-of-4 -- --out "$D/merged/t.png" --exr "$D/merged/t.exr" \
  --variance "$D/merged/tv.exr"
expect_true "trace: 4 merged parts give the single run's EXR byte for byte" -- cmp "$D/one/t.exr" "$D/merged/t.exr"
expect_true "... and its variance EXR" -- cmp "$D/one/tv.exr" "$D/merged/tv.exr"
expect_true "... and its PNG" -- cmp "$D/one/t.png" "$D/merged/t.png"
expect_fail 1 "adaptive sampling needs the whole image after every pass" -- \
  "$LUCENT" trace "$SC" --spp 3 --adaptive --out "$D/bad/t.png" --part 1/2
expect_fail 1 "a time limit needs the whole image" -- \
  "$LUCENT" trace "$SC" --spp 3 --time 5 --out "$D/bad/t.png" --part 1/2
expect_no_file "$D/bad/t.png" "$D/bad/t.png.part-1-of-2"
