# Outputs under hostile use (issue 32 items 1 and 2), sourced by cli_test.sh ($LUCENT, $TMP, $FIXTURES).
# The rule (docs/architecture.md, "Outputs"; README "Where outputs go"): a character device, FIFO or socket is
# written through, never replaced; a symbolic link to a regular file replaces the file and keeps the link;
# a folder, a block device or a link to nothing is refused. Every output's folder is checked before the work.
O="$TMP/outputs"
mkdir -p "$O"
SC="$FIXTURES/scenes"

# ---- 1. devices, FIFOs, links ----
# A character device made here (never the system's /dev/null): written through, still a device after.
if mknod "$O/nul" c 1 3 2>/dev/null; then
  expect_ok -- "$LUCENT" materials --json --out "$O/nul"
  expect_true "a character device output stays a device (materials --out)" -- test -c "$O/nul"
  ln -s nul "$O/nul.png" && ln -s nul "$O/nul.exr"
  expect_ok -- "$LUCENT" trace "$SC/trace-small.json" --spp 1 --out "$O/nul.png" --exr "$O/nul.exr" --json "$O/t.json"
  expect_true "several outputs may name one device (through links); it stays a device" -- \
    eval 'test -c "$O/nul" && test -L "$O/nul.png" && test -L "$O/nul.exr"'
  expect_true "the regular output beside the device landed" -- test -s "$O/t.json"
  # repro-3 INDEX 1: an .mci whose output line names the device (as root, /dev/null became a regular file).
  printf '1.0\n1\n%s A\n1000\n0.01 0.01\n4 10 4\n1\n1.0\n1.0 1 10 0.75 0.1\n1.0\n' "$O/nul" >"$O/nul.mci"
  expect_ok -- "$LUCENT" mcml "$O/nul.mci"
  expect_true "an .mci's output line naming a character device: it stays a device" -- test -c "$O/nul"
else
  _report 0 "mknod of a character device in $O (the tests run as root: tests/CMakeLists.txt)"
fi
# A link to /dev/null is a device too: the link is kept, nothing replaces /dev/null.
ln -s /dev/null "$O/null-link"
expect_ok -- "$LUCENT" kernel skin1 --export json --out "$O/null-link"
expect_true "a link to /dev/null stays a link to it" -- test "$(readlink "$O/null-link")" = /dev/null
expect_true "/dev/null is still a character device" -- test -c /dev/null
# A FIFO: the sidecar is written through to its reader, and the FIFO stays.
mkfifo "$O/fifo"
(timeout 20 cat "$O/fifo" >"$O/fifo.got") &
reader=$!
expect_ok -- timeout 20 "$LUCENT" trace "$SC/trace-small.json" --spp 1 --out "$O/t.png" --json "$O/fifo"
wait $reader
expect_true "a FIFO output stays a FIFO" -- test -p "$O/fifo"
expect_true "the FIFO's reader got the sidecar" -- \
  python3 -c "import json,sys; assert json.load(open(sys.argv[1]))['spp'] == 1" "$O/fifo.got"
# /proc/self/fd/1 through a link: the output is the command's standard output.
ln -s /proc/self/fd/1 "$O/stdout"
expect_ok -- "$LUCENT" -q kernel skin1 --export json --out "$O/stdout"
expect_true "an output linked to /proc/self/fd/1 goes to stdout" -- grep -q '"format": "lucent-kernel-taps"' <<<"$OUT"
expect_true "the link to /proc/self/fd/1 stays a link" -- test -L "$O/stdout"
# A link to a regular file: the file is replaced, the link kept.
echo old >"$O/real.json"
ln -s real.json "$O/link.json"
expect_ok -- "$LUCENT" kernel skin1 --export json --out "$O/link.json"
expect_true "a link to a regular file stays a link" -- test "$(readlink "$O/link.json")" = real.json
expect_true "the file the link names holds the output" -- grep -q lucent-kernel-taps "$O/real.json"
expect_true "no temporary is left beside the link or the file" -- test "$(ls "$O" | grep -c tmp)" = 0
# Refused: a link to nothing, a block device, a folder.
ln -s nothing.json "$O/dangling.json"
expect_fail 1 "$O/dangling.json: cannot write: a symbolic link to nothing" -- \
  "$LUCENT" kernel skin1 --export json --out "$O/dangling.json"
expect_true "the dangling link stays" -- test -L "$O/dangling.json"
if mknod "$O/blk" b 7 200 2>/dev/null; then
  expect_fail 1 "$O/blk: cannot write: a block device" -- "$LUCENT" materials --json --out "$O/blk"
  expect_true "a block device output is not replaced" -- test -b "$O/blk"
else
  _report 0 "mknod of a block device in $O"
fi

# ---- 2. every output's folder is checked before the work ----
echo x >"$O/afile"
A="$O/afile"
nf="is not a folder"
# The trace would run 60 s (timeout 20 fails the case): the check comes first.
expect_fail 1 "$A/img.png: cannot create: $A $nf" -- \
  timeout 20 "$LUCENT" trace "$SC/trace-small.json" --spp 1000000 --time 60 --out "$A/img.png"
expect_fail 1 "$A/sub/t.exr: cannot create: $A $nf" -- \
  timeout 20 "$LUCENT" trace "$SC/trace-small.json" --time 60 --out "$O/t.png" --exr "$A/sub/t.exr"
expect_fail 1 "$A/p.json: cannot create: $A $nf" -- \
  timeout 20 "$LUCENT" profile skin1 --model mc --photons 1000000000 --out "$A/p"
expect_fail 1 "$A/k.json: cannot create" -- "$LUCENT" kernel skin1 --export json --out "$A/k.json"
expect_fail 1 "$A/pk: cannot create: $A $nf" -- timeout 20 "$LUCENT" pack skin1 --engine glsl --no-cache --no-fit --out "$A/pk"
expect_fail 1 "$A/c: cannot create: $A $nf" -- timeout 20 "${GLRUN[@]}" compare "$SC/sphere.json" --out "$A/c"
expect_fail 1 "$A/e: cannot create: $A $nf" -- timeout 20 "$LUCENT" kernel-eval skin1 --out "$A/e"
expect_fail 1 "$A/l.exr: cannot create" -- "$LUCENT" cdrf-lut --out "$A/l.exr"
expect_fail 1 "$A/f.json: cannot create" -- timeout 20 "$LUCENT" cdrf-fit skin1 --photons 100000000 --out "$A/f"
expect_fail 1 "$A/c.csv: cannot create" -- "$LUCENT" curvature "$FIXTURES/mesh/tetra.ply" --out "$A/c.csv"
expect_fail 1 "$A/uv.obj: cannot create" -- "$LUCENT" mesh-uv "$FIXTURES/mesh/tetra.ply" "$A/uv.obj"
expect_fail 1 "$A/c.pfm: cannot create" -- "$LUCENT" image convert "$FIXTURES/images/rgb8.png" "$A/c.pfm"
expect_fail 1 "$A/d.png: cannot create" -- \
  "$LUCENT" image diff "$FIXTURES/images/rgb8.png" "$FIXTURES/images/rgb8.png" --out "$A/d.png"
expect_fail 1 "$A/r.png: cannot create" -- "${GLRUN[@]}" render "$SC/sphere.json" --out "$A/r.png"
expect_fail 1 "$A/m.json: cannot create" -- "$LUCENT" materials --json --out "$A/m.json"
# mcml: an output line of the .mci under a file, found before the first run (2e9 photons).
printf '1.0\n1\n%s/x.mco A\n2000000000\n0.01 0.01\n10 10 5\n1\n1.0\n1.0 1 9 0.75 0.02\n1.0\n' "$A" >"$O/late.mci"
expect_fail 1 "$A/x.mco: cannot create" -- timeout 20 "$LUCENT" mcml "$O/late.mci"
# merge: the recorded command's outputs, checked before the merge's reduction.
expect_ok -- "$LUCENT" mcml "$FIXTURES/mcml/three_layers.mci" --out-dir "$O/parts" --seed 3 --part 1/2
expect_ok -- "$LUCENT" mcml "$FIXTURES/mcml/three_layers.mci" --out-dir "$O/parts" --seed 3 --part 2/2
expect_fail 1 "cannot create: $A $nf" -- "$LUCENT" merge "$O"/parts/*.part-*-of-2 -- --out-dir "$A/m"
# A read-only folder (as an unprivileged user: root writes anywhere).
mkdir -p "$O/ro" && chmod 555 "$O/ro" && chmod 755 "$O"
expect_fail 1 "$O/ro/t.png: cannot create: the folder $O/ro is not writable" -- \
  as_nobody timeout 20 "$LUCENT" trace "$SC/trace-small.json" --time 60 --out "$O/ro/t.png"
# An indirect input (the scene's material file) named as an output: refused as the scene is read, before the
# render, and the material survives.
cp "$FIXTURES/materials/jade.json" "$O/mat.json" && cp "$O/mat.json" "$O/mat.orig"
sed "s|\"skin1\"|\"$O/mat.json\"|" "$SC/trace-small.json" >"$O/scene.json"
expect_fail 1 "objects[0].material: $O/mat.json: this file is read by the command and named as one of its outputs" -- \
  timeout 20 "$LUCENT" trace "$O/scene.json" --time 60 --out "$O/i.png" --json "$O/mat.json"
expect_true "the scene's material survives --json naming it" -- cmp "$O/mat.json" "$O/mat.orig"
expect_no_file "$O/i.png"
# The set still orders a written-through output: it is written when the command succeeds, so a command ended
# part-way (SIGTERM in the second run of an .mci) writes nothing to the FIFO of its first run's output.
mkdir -p "$O/sigf" && mkfifo "$O/sigf/1.mco"
printf '1.0\n2\n1.mco A\n2000\n0.01 0.01\n10 10 5\n1\n1.0\n1.0 1 9 0.75 0.02\n1.0\n2.mco A\n2000000000\n0.01 0.01\n10 10 5\n1\n1.0\n1.0 1 9 0.75 0.02\n1.0\n' >"$O/sigf.mci"
(timeout 30 cat "$O/sigf/1.mco" >"$O/sigf.got") &
reader=$!
"$LUCENT" mcml "$O/sigf.mci" --out-dir "$O/sigf" >/dev/null 2>&1 &
pid=$!
sleep 2
kill -TERM $pid
wait $pid
rc=$?
expect_true "SIGTERM ends mcml (exit $rc) while its first output waits for a FIFO" -- test "$rc" -eq 143
timeout 10 bash -c ': >"$1"' _ "$O/sigf/1.mco" # an empty writer: the reader sees the end of file
wait $reader
expect_true "the FIFO got nothing from the interrupted command" -- test ! -s "$O/sigf.got"
expect_true "the FIFO stays a FIFO" -- test -p "$O/sigf/1.mco"
