#!/usr/bin/env bash
# `lucent view --script`: a scripted session orbits, switches among every method the renderer lists,
# changes the kernel width and the material, loads a reference and saves the scene; `lucent render`
# of the saved scene (and of its --set form) gives the viewer's last frame pixel for pixel. Resizing
# keeps a sphere round (its silhouette's width and height measured in the screenshot). Run in a
# window under Xvfb when xvfb-run is there, and headless (EGL surfaceless) always.
# Part "issue32" (run as its own test, so the two share the cores of ctest -j): the viewer under
# hostile use and a newcomer's window (issue 32 items 13-16, issue 35).
# Usage: view_test.sh path/to/lucent path/to/tests/fixtures [base|issue32] (default: both)
set -u
LUCENT=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
FIXTURES=$(cd "$2" && pwd)
TMP=$(mktemp -d "${TMPDIR:-/tmp}/lucent-view-XXXXXX")
trap 'rm -rf "$TMP"' EXIT
passed=0 failed=0
SPHERE=$FIXTURES/scenes/sphere.json
PART=${3:-all}

check() { # DESCRIPTION -- command...
  local what=$1; shift 2
  if "$@" >"$TMP/.out" 2>&1; then
    passed=$((passed + 1)); echo "ok   $what"
  else
    failed=$((failed + 1)); echo "FAIL $what"; sed 's/^/     /' "$TMP/.out" | tail -20
  fi
}
# fails SUBSTRING -- command...: exit 1 and the message on stderr.
fails() {
  local sub=$1; shift 2
  local err rc
  err=$("$@" 2>&1 >/dev/null); rc=$?
  if [ "$rc" = 1 ] && [[ "$err" == *"$sub"* ]]; then
    passed=$((passed + 1)); echo "ok   fails '$sub'"
  else
    failed=$((failed + 1)); echo "FAIL fails '$sub': exit $rc: $err"
  fi
}
# same_pixels A.exr B.exr: lucent image diff reports 0 in every channel.
same_pixels() {
  "$LUCENT" image diff "$1" "$2" | tee /dev/stderr | grep -Eq '^  all +0 +0$'
}

if [ "$PART" != issue32 ]; then
# Every method the renderer lists (the settings table's names for render.method).
methods=$("$LUCENT" render --settings | grep -A1 '^  method ' | tail -1 | sed 's/.*; //; s/,//g')
[ -n "$methods" ] || { echo "FAIL no methods listed"; exit 1; }

# A tiny path-traced reference of the sphere (4 spp): what load-reference reads.
"$LUCENT" -q trace "$SPHERE" --spp 4 --set render.width=64 --set render.height=40 --out "$TMP/ref.png" --exr "$TMP/ref.exr" ||
  { echo "FAIL lucent trace for the reference"; exit 1; }

session() { # MODE (window or headless) RUNNER...
  local mode=$1; shift
  local d=$TMP/$mode panel=0
  mkdir -p "$d"
  [ "$mode" = window ] && panel=380 # the panel's width: the view is the rest of the window
  {
    echo "# orbit, every method, the width, the material, a reference, a save"
    echo "resize $((panel + 64)) 40"
    echo "orbit 35 -12"
    echo "zoom 0.9"
    for m in $methods; do echo "method $m"; echo "print"; done
    echo "method ssss" # the taps exported below come with ssss, whatever the last method listed
    echo "light 0 25 10"
    echo "set width_scale=1.7"
    echo "material skin2"
    echo "material sigma_a=0.05,0.2,0.4 g=0.3"
    echo "load-reference $TMP/ref.exr"
    echo "print"
    echo "save-scene $d/saved.json"
    echo "screenshot $d/last.png"
    echo "export-taps $d/taps.json json"
    echo "quit"
  } >"$d/script.txt"
  check "$mode: the scripted session runs" -- "$@" "$LUCENT" view "$SPHERE" --script "$d/script.txt" --no-cache ${HEADLESS:-}
  for m in $methods; do
    check "$mode: it switched to $m" -- grep -q "^view: $m, frame 64x40" "$TMP/.out.session" 
  done
  check "$mode: it wrote the scene, its --set form, the PNG, the EXR and the taps" -- \
    test -s "$d/saved.json" -a -s "$d/saved.sets.txt" -a -s "$d/last.png" -a -s "$d/last.exr" -a -s "$d/taps.json"
  check "$mode: the saved scene holds the tuned width and material" -- \
    grep -q '"width_scale":[[:space:]]*1.7' "$d/saved.json"
  check "$mode: the relative RMS error against the reference is finite and > 0" -- \
    grep -Eq 'rel_rms (0\.[0-9]*[1-9]|[1-9])' "$TMP/.out.session"
  check "$mode: lucent render of the saved scene is the viewer's last frame" -- eval \
    '"$LUCENT" -q render "$d/saved.json" --no-cache --out "$d/render.exr" && same_pixels "$d/last.exr" "$d/render.exr"'
  check "$mode: the --set form on the original scene gives the same pixels" -- eval \
    'PATH="$(dirname "$LUCENT"):$PATH" bash -c "$(cat "$d/saved.sets.txt") -q --no-cache --out $d/sets.exr" &&
     same_pixels "$d/last.exr" "$d/sets.exr"'

  # Roundness: a wide and a tall view; the sphere's silhouette is as wide as it is tall.
  printf 'resize %d 100\nscreenshot %s/wide.png\nresize %d 150\nscreenshot %s/tall.png\nquit\n' \
    $((panel + 200)) "$d" $((panel + 100)) "$d" >"$d/round.txt"
  check "$mode: the resize session runs" -- "$@" "$LUCENT" -q view "$SPHERE" --script "$d/round.txt" --no-cache ${HEADLESS:-}
  if command -v python3 >/dev/null 2>&1; then
    for shape in wide tall; do
      "$LUCENT" -q image convert "$d/$shape.exr" "$d/$shape.pfm"
      check "$mode: $shape view (the image's own size) keeps the sphere round" -- python3 - "$d/$shape.pfm" "$shape" <<'PY'
import struct, sys
# The silhouette: pixels that differ from the background (the corner pixel), their bounding box.
f = open(sys.argv[1], "rb")
kind = f.readline().strip(); w, h = map(int, f.readline().split()); scale = float(f.readline())
n = 3 if kind == b"PF" else 1
data = struct.unpack(("<" if scale < 0 else ">") + "f" * (w * h * n), f.read(4 * w * h * n))
px = lambda x, y: data[(y * w + x) * n:(y * w + x) * n + n]
bg = px(0, 0)
xs, ys = [], []
for y in range(h):
    for x in range(w):
        if max(abs(a - b) for a, b in zip(px(x, y), bg)) > 1e-4:
            xs.append(x); ys.append(y)
bw, bh = max(xs) - min(xs) + 1, max(ys) - min(ys) + 1
# The sphere (radius 10 mm, 60 mm away, fov_y 30 degrees) spans 2 asin(10/60) of the vertical field:
# tan(asin(1/6)) / tan(15 deg) of the image's height (the perspective projection of its silhouette).
# A view narrower than the scene's image (48 x 40) widens the vertical field so that the scene's
# horizontal field fits: tan(fov_y / 2) grows by (48 / 40) / (w / h) (docs/view.md).
import math
widen = max(1.0, (48 / 40) / (w / h))
expect = h * math.tan(math.asin(10 / 60)) / (math.tan(math.radians(15)) * widen)
print(sys.argv[2], w, "x", h, ": silhouette", bw, "x", bh, "expected", round(expect, 2))
sys.exit(0 if abs(bw - bh) <= 1 and abs(bh - expect) <= 2 else 1)
PY
    done
  else
    echo "skip roundness: no python3"
  fi
}

# The session's stdout (print lines) goes to .out.session.
run_session() { "$@" >"$TMP/.out.session" 2>&1; local rc=$?; cat "$TMP/.out.session"; return $rc; }

HEADLESS=--headless session headless run_session
if command -v xvfb-run >/dev/null 2>&1; then
  session window run_session xvfb-run -a -s "-screen 0 1280x1024x24"
else
  echo "skip the window sessions: no xvfb-run"
fi

# A bake runs on a thread of its own: frames keep coming while it runs (the marble's slab
# transmittance, a Monte Carlo run of seconds without the cache, against frames of milliseconds).
printf 'async material marble\nframes 1\nquit\n' >"$TMP/async.txt"
check "frames are drawn while a new material bakes" -- eval \
  '"$LUCENT" view "$SPHERE" --script "$TMP/async.txt" --headless --no-cache | grep -q "^frame 1: redraw .* while baking"'

# A progressive trace in the background becomes the reference; its noise, and so the error of the
# method against it, falls as samples come (the trace's own noise goes as 1/sqrt(spp)).
printf 'trace-start\ntrace-wait 2\nprint\ntrace-wait 48\nprint\ntrace-stop\nquit\n' >"$TMP/trace.txt"
"$LUCENT" view "$SPHERE" --script "$TMP/trace.txt" --headless --no-cache >"$TMP/trace.out" 2>&1
e1=$(grep '^view:' "$TMP/trace.out" | sed -n '1s/.*rel_rms \([0-9.e+-]*\),.*/\1/p')
e2=$(grep '^view:' "$TMP/trace.out" | sed -n '2s/.*rel_rms \([0-9.e+-]*\),.*/\1/p')
check "the progressive trace is the reference, and the error falls with its samples ($e1 then $e2)" -- eval \
  'grep -q "reference progressive trace, [0-9]* spp" "$TMP/trace.out" && awk -v a="$e1" -v b="$e2" "BEGIN { exit !(b > 0 && b < a) }"'

# Hot reload: the scene file changes on disk, the viewer reads it again (here: another method). The last
# view line is the new method's (a bake's log line, from its own thread, may come after it).
cp "$SPHERE" "$TMP/watched.json"
printf 'print\nwait-reload 60\nprint\nquit\n' >"$TMP/reload.txt"
"$LUCENT" view "$TMP/watched.json" --script "$TMP/reload.txt" --headless --no-cache >"$TMP/reload.out" 2>&1 &
pid=$!
for _ in $(seq 600); do grep -q "^view:" "$TMP/reload.out" && break; sleep 0.1; done
sed 's/"method": "ssss"/"method": "lambert"/' "$SPHERE" >"$TMP/watched.tmp" && mv "$TMP/watched.tmp" "$TMP/watched.json"
wait $pid
check "a changed scene file is read again" -- eval \
  'grep -q "^view: ssss" "$TMP/reload.out" && grep -q "^reloaded" "$TMP/reload.out" && grep "^view:" "$TMP/reload.out" | tail -1 | grep -q "^view: lambert"'

# A spectral skin's melanin slider (docs/skin.md): more melanin bakes a darker skin whose blue falls more
# than its red (melanin absorbs more the shorter the wavelength: Donner & Jensen 2006's lambda^-3.33), so
# the lit sphere's mean B/R and G/R fall. The profile model of translucency keeps the bake short.
printf 'set transmittance=profile\nmaterial skin-light\nscreenshot %s/skin0.png\nmaterial melanin=0.05\nscreenshot %s/skin1.png\nsave-scene %s/skin.json\nquit\n' \
  "$TMP" "$TMP" "$TMP" >"$TMP/skin.txt"
check "the melanin of a spectral skin moves in a scripted session" -- \
  "$LUCENT" -q view "$SPHERE" --script "$TMP/skin.txt" --headless --no-cache
check "the saved scene keeps the skin's chromophores" -- grep -q '"melanin":[[:space:]]*0.05' "$TMP/skin.json"
if command -v python3 >/dev/null 2>&1; then
  "$LUCENT" -q image convert "$TMP/skin0.exr" "$TMP/skin0.pfm" && "$LUCENT" -q image convert "$TMP/skin1.exr" "$TMP/skin1.pfm"
  check "more melanin: a darker sphere, blue and green falling more than red" -- python3 - "$TMP/skin0.pfm" "$TMP/skin1.pfm" <<'PY'
import struct, sys
def mean(path):  # the mean colour of the pixels that differ from the background (the corner pixel)
    f = open(path, "rb")
    f.readline(); w, h = map(int, f.readline().split()); scale = float(f.readline())
    d = struct.unpack(("<" if scale < 0 else ">") + "f" * (w * h * 3), f.read(12 * w * h))
    bg, s, n = d[0:3], [0.0, 0.0, 0.0], 0
    for k in range(w * h):
        px = d[3 * k:3 * k + 3]
        if max(abs(a - b) for a, b in zip(px, bg)) > 1e-4:
            s, n = [s[c] + px[c] for c in range(3)], n + 1
    return [x / n for x in s]
a, b = mean(sys.argv[1]), mean(sys.argv[2])
print("melanin 0.009:", a, "melanin 0.05:", b)
sys.exit(0 if all(b[c] < a[c] for c in range(3)) and b[2] / b[0] < a[2] / a[0] and b[1] / b[0] < a[1] / a[0] else 1)
PY
fi

# Bad scripts: the file and the line named, exit 1.
printf 'orbit 10\n' >"$TMP/bad1.txt"
fails "bad1.txt: line 1 (orbit): usage: orbit YAW PITCH" -- "$LUCENT" view "$SPHERE" --script "$TMP/bad1.txt" --headless --no-cache
printf '# fine\nset taps=16\n' >"$TMP/bad2.txt"
fails "bad2.txt: line 2 (set): " -- "$LUCENT" view "$SPHERE" --script "$TMP/bad2.txt" --headless --no-cache
printf 'dance\n' >"$TMP/bad3.txt"
fails "line 1 (dance): unknown action 'dance'" -- "$LUCENT" view "$SPHERE" --script "$TMP/bad3.txt" --headless --no-cache
printf 'method phong\n' >"$TMP/bad4.txt"
fails "unknown method 'phong'" -- "$LUCENT" view "$SPHERE" --script "$TMP/bad4.txt" --headless --no-cache
printf 'load-reference %s/none.exr\n' "$TMP" >"$TMP/bad5.txt"
fails "none.exr" -- "$LUCENT" view "$SPHERE" --script "$TMP/bad5.txt" --headless --no-cache
fails "nofile.txt: cannot open" -- "$LUCENT" view "$SPHERE" --script "$TMP/nofile.txt" --headless --no-cache
# The command creates missing folders (issue 16), so the save fails under a plain file instead.
: >"$TMP/plainfile"
printf 'save-scene %s/plainfile/x.json\n' "$TMP" >"$TMP/bad6.txt"
fails "plainfile/x.json" -- "$LUCENT" view "$SPHERE" --script "$TMP/bad6.txt" --headless --no-cache
check "a failed save leaves nothing" -- test ! -e "$TMP/plainfile/x.json"

fi

if [ "$PART" != base ]; then
# ---- issue 32 items 13-16 and issue 35: the viewer under hostile use, and a newcomer's window ----
L="--set render.method=lambert" # no bake: these start in a second
REPRO=$FIXTURES/view

# 13: the frames render on a thread of their own. A points frame of 320 x 240 costs seconds on
# llvmpipe; while it renders the window keeps drawing (at least 10 frames a second over at least half
# a second of rendering, where the window drew one frame per rendered frame before), and a key tapped
# during it (pressed and released between two window frames, through the GLFW key callback) is not
# lost: R resets the orbited camera.
if command -v xvfb-run >/dev/null 2>&1; then
  printf 'resize 700 240\nmethod points\nprint\nasync orbit 30 0\nui-frames 1\nkey R\nui-frames 0.5\nprint\nquit\n' \
    >"$TMP/slow.txt"
  xvfb-run -a -s "-screen 0 1280x1024x24" "$LUCENT" view "$SPHERE" --script "$TMP/slow.txt" --no-cache \
    >"$TMP/slow.out" 2>&1
  cat "$TMP/slow.out"
  busy=$(grep '^ui-frames' "$TMP/slow.out" | head -1 | sed -n 's/.*rendered: [0-9]* in \([0-9.]*\) s (\([0-9.]*\) a second).*/\1 \2/p')
  check "13: while a points frame renders the window draws frames at its rate (${busy:-none}: >= 0.5 s, >= 10 a second)" -- \
    awk -v b="$busy" 'BEGIN { split(b, x, " "); exit !(x[1] >= 0.5 && x[2] >= 10) }'
  check "13: a key tapped during a slow frame registers (R: the camera is back home)" -- eval \
    '[ "$(grep "^view:" "$TMP/slow.out" | sed -n 1p | sed "s/.*camera \([^,]*\),.*/\1/")" = \
       "$(grep "^view:" "$TMP/slow.out" | sed -n 2p | sed "s/.*camera \([^,]*\),.*/\1/")" ]'
fi
# The same tap headless (no window: the key goes to the same queue).
printf 'orbit 30 0\nprint\nkey R\nprint\nquit\n' >"$TMP/tap.txt"
"$LUCENT" view "$SPHERE" --script "$TMP/tap.txt" --headless --no-cache $L >"$TMP/tap.out" 2>&1
check "13: headless, a tapped R resets the camera" -- eval \
  'grep "^view:" "$TMP/tap.out" | sed -n 2p | grep -q "camera 0 0 60," && ! grep "^view:" "$TMP/tap.out" | sed -n 1p | grep -q "camera 0 0 60,"'

# 14: a move that would make the camera non-finite is refused, and nothing is saved (repro-3 item 14).
mkdir -p "$TMP/out"
( cd "$TMP" && "$LUCENT" view "$SPHERE" --script "$REPRO/orbit-nan-save.txt" --headless --no-cache $L ) \
  >"$TMP/nan.out" 2>&1; rc=$?
check "14: orbit 1e308 1e308 is refused: exit 1, 'the camera would not be finite', no scene saved" -- eval \
  '[ $rc = 1 ] && grep -q "line 1 (orbit): orbit: the camera would not be finite" "$TMP/nan.out" && [ ! -e "$TMP/out/view-nan.json" ]'
printf 'zoom 1e308\nsave-scene %s/zoomed.json\n' "$TMP" >"$TMP/zoom.txt"
fails "line 1 (zoom): zoom: the camera would not be finite" -- "$LUCENT" view "$SPHERE" --script "$TMP/zoom.txt" --headless --no-cache $L
check "14: nothing saved after the refused zoom" -- test ! -e "$TMP/zoomed.json"
cp "$SPHERE" "$TMP/open.json"
printf 'orbit 10 0\nsave-scene %s/open.json\n' "$TMP" >"$TMP/self.txt"
fails "open.json is the open scene file: it would be overwritten" -- "$LUCENT" view "$TMP/open.json" --script "$TMP/self.txt" --headless --no-cache $L
check "14: the open scene file is unchanged" -- cmp -s "$SPHERE" "$TMP/open.json"
printf 'save-scene %s/self-script.txt\n' "$TMP" >"$TMP/self-script.txt"
fails "self-script.txt is the script" -- "$LUCENT" view "$SPHERE" --script "$TMP/self-script.txt" --headless --no-cache $L

# 15: the whole script is checked before its first line runs: a typo on line 4 fails at once, and the
# screenshot of line 1 is never written; a bake that fails ends the script with exit 1.
printf 'screenshot %s/early.png\nbench 50\nbench 50\norbt 10 0\n' "$TMP" >"$TMP/typo.txt"
t0=$(date +%s)
fails "typo.txt: line 4 (orbt): unknown action 'orbt'" -- "$LUCENT" view "$SPHERE" --script "$TMP/typo.txt" --headless --no-cache $L
check "15: the typo is found before line 1 runs (no screenshot; $(( $(date +%s) - t0 )) s)" -- test ! -e "$TMP/early.png"
printf 'material sigma_s_prime=1e300\nprint\n' >"$TMP/bake.txt"
fails "line 1 (material): bake failed:" -- "$LUCENT" view "$SPHERE" --script "$TMP/bake.txt" --headless --no-cache
# A scene whose first bake fails: exit 1 (it was tried again and again, for ever).
fails "bake failed: material dense:" -- timeout 120 "$LUCENT" view "$SPHERE" --script "$TMP/bake.txt" --headless --no-cache \
  --set 'objects[0].material={"name":"dense","units":"mm^-1","sigma_a":[0.01,0.01,0.01],"sigma_s":[1e300,1e300,1e300],"g":[0,0,0],"eta":1.3}'
# show error + screenshot saves the error map: against a reference that is the frame itself, the map
# of zero error (one colour wherever the object is); show reference + screenshot, after an orbit,
# saves the reference, not the orbited frame.
printf 'screenshot %s/frame.png\nload-reference %s/frame.exr\nshow error\nscreenshot %s/shown-err.png\norbit 25 0\nshow reference\nscreenshot %s/shown-ref.png\nshow image\nscreenshot %s/orbited.png\nquit\n' \
  "$TMP" "$TMP" "$TMP" "$TMP" "$TMP" >"$TMP/show.txt"
check "15: the show session runs" -- "$LUCENT" view "$SPHERE" --script "$TMP/show.txt" --headless --no-cache $L
check "15: show reference + screenshot saves the reference, pixel for pixel (not the orbited frame)" -- eval \
  'same_pixels "$TMP/frame.exr" "$TMP/shown-ref.exr" && ! same_pixels "$TMP/frame.exr" "$TMP/orbited.exr"'
if command -v python3 >/dev/null 2>&1; then
  "$LUCENT" -q image convert "$TMP/shown-err.exr" "$TMP/shown-err.pfm"
  "$LUCENT" -q image convert "$TMP/frame.exr" "$TMP/frame.pfm"
  check "15: show error + screenshot saves the error map (zero error: one colour over the object, not the frame)" -- \
    python3 - "$TMP/shown-err.pfm" "$TMP/frame.pfm" <<'PY'
import struct, sys
def pfm(path):
    f = open(path, "rb"); kind = f.readline().strip(); w, h = map(int, f.readline().split()); s = float(f.readline())
    n = 3 if kind == b"PF" else 1
    return w, h, n, struct.unpack(("<" if s < 0 else ">") + "f" * (w * h * n), f.read(4 * w * h * n))
w, h, n, err = pfm(sys.argv[1]); _, _, _, frame = pfm(sys.argv[2])
bg = frame[0:3]
obj = [i for i in range(w * h) if max(abs(frame[3 * i + c] - bg[c]) for c in range(3)) > 1e-4]
colours = {tuple(round(err[3 * i + c], 5) for c in range(3)) for i in obj}
print(len(obj), "object pixels, error-map colours there:", colours)
sys.exit(0 if obj and len(colours) == 1 and any(frame[3 * obj[0] + c] != err[3 * obj[0] + c] for c in range(3)) else 1)
PY
fi

# 16e: the messages of bad scripts name the line and the field.
printf 'print\nre\0set\n' >"$TMP/nul.txt"
fails "nul.txt: line 2: a NUL byte at column 3" -- "$LUCENT" view "$SPHERE" --script "$TMP/nul.txt" --headless --no-cache $L
printf 'material g=1\n' >"$TMP/g1.txt"
fails "line 1 (material): material: g=1: must be in (-1, 1)" -- "$LUCENT" view "$SPHERE" --script "$TMP/g1.txt" --headless --no-cache $L
printf 'async\n' >"$TMP/async1.txt"
fails "line 1 (async): async needs an action" -- "$LUCENT" view "$SPHERE" --script "$TMP/async1.txt" --headless --no-cache $L

# Issue 35: the default window fits its panel; labels fit or wrap (every section open: the widest
# item within the panel); side by side frames the object in both halves.
if command -v xvfb-run >/dev/null 2>&1; then
  printf 'panel\npanel all\nquit\n' >"$TMP/panel.txt"
  xvfb-run -a -s "-screen 0 1280x1024x24" "$LUCENT" view "$SPHERE" --set render.width=512 --set render.height=512 \
    --script "$TMP/panel.txt" --no-cache >"$TMP/panel.out" 2>&1
  cat "$TMP/panel.out"
  check "35: the default window is as tall as its panel needs (no scrolling)" -- eval \
    'grep "^panel:" "$TMP/panel.out" | awk "{ ok = \$3 + 0 <= \$10 + 0 } END { exit !ok }"'
  check "35: every label fits the panel or wraps (the widest item within it)" -- eval \
    'grep "^panel all:" "$TMP/panel.out" | awk "{ ok = \$15 + 0 <= \$18 + 0 } END { exit !ok }"'
fi
printf 'resize 120 150\nlayout side\nscreenshot %s/side.png\nquit\n' "$TMP" >"$TMP/side.txt"
check "35: the side-by-side session runs" -- "$LUCENT" view "$SPHERE" --script "$TMP/side.txt" --headless --no-cache $L
if command -v python3 >/dev/null 2>&1; then
  "$LUCENT" -q image convert "$TMP/side.exr" "$TMP/side.pfm"
  check "35: side by side frames the sphere whole and round in a 60 x 150 half" -- python3 - "$TMP/side.pfm" <<'PY'
import math, struct, sys
f = open(sys.argv[1], "rb"); kind = f.readline().strip(); w, h = map(int, f.readline().split()); s = float(f.readline())
n = 3 if kind == b"PF" else 1
d = struct.unpack(("<" if s < 0 else ">") + "f" * (w * h * n), f.read(4 * w * h * n))
px = lambda x, y: d[(y * w + x) * n:(y * w + x) * n + n]
bg = px(0, 0)
pts = [(x, y) for y in range(h) for x in range(w) if max(abs(a - b) for a, b in zip(px(x, y), bg)) > 1e-4]
xs, ys = [p[0] for p in pts], [p[1] for p in pts]
bw, bh = max(xs) - min(xs) + 1, max(ys) - min(ys) + 1
# The scene's image is 48 x 40; a half of 60 x 150 shows its horizontal field: tan(fov_y / 2) widened
# by (48 / 40) / (60 / 150), the sphere tan(asin(1/6)) / tan(15 deg) / 3 of the height (view_test's roundness).
expect = h * math.tan(math.asin(10 / 60)) / (math.tan(math.radians(15)) * (48 / 40) / (w / h))
inside = min(xs) > 0 and max(xs) < w - 1 and min(ys) > 0 and max(ys) < h - 1
print(w, "x", h, ": silhouette", bw, "x", bh, "expected", round(expect, 2), "inside" if inside else "cropped")
sys.exit(0 if inside and abs(bw - bh) <= 1 and abs(bw - expect) <= 2 else 1)
PY
fi

fi

echo "$passed passed, $failed failed"
[ "$failed" = 0 ]
