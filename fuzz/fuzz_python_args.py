#!/usr/bin/env python3
"""A random-argument fuzzer of the Python package's argument conversion (issue 32: the ctypes border).

libFuzzer cannot drive Python, so this draws calls itself: each public function with each argument
either a cheap valid value or, with probability 0.35, a hostile one (None, bools, huge and negative
ints, NaN and infinities, floats for counts, strings with NUL bytes, empty strings, bytes, paths,
lists of the wrong length, nested containers, objects of other types). The calls run in a child
interpreter, restarted whenever a call kills it. A finding is a call that kills the interpreter or
raises anything but lucent.LucentError, TypeError or ValueError (an unchecked conversion:
OverflowError, ctypes.ArgumentError, AttributeError ...). A call that outlives its time limit is a
valid but expensive one (photons=4294967313) and is counted, not a finding.

Usage: fuzz/fuzz_python_args.py LIBLUCENT.so SECONDS [SEED]
  With an ASan build's library (build-asan/liblucent.so) it runs the children with the ASan runtime
  preloaded, so that a memory error in C reached from Python is a death, hence a finding.
Findings: build-fuzz/python_args/finding-N.py (the call, runnable); exit 1 when there is one."""
import json
import os
import queue
import random
import subprocess
import sys
import tempfile
import threading
import time

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)
library, seconds = os.path.abspath(sys.argv[1]), float(sys.argv[2])
seed = int(sys.argv[3]) if len(sys.argv) > 3 else 1
fx = os.path.join(root, "tests", "fixtures")
out = os.path.join(root, "build-fuzz", "python_args")
os.makedirs(out, exist_ok=True)
tmp = tempfile.mkdtemp(prefix="lucent-pyfuzz-")
mci = os.path.join(tmp, "tiny.mci")
with open(mci, "w") as f:
    f.write("1.0\n1\ntiny.mco A\n500\n0.01 0.01\n4 10 4\n1\n1.0\n1.0 1 10 0.75 0.1\n1.0\n")

# Python expressions (evaluated in the child, where lucent, pathlib and the paths are defined).
HOSTILE = ["None", "True", "False", "0", "-1", "1", "3", "17", "2**31", "2**32 + 17", "2**63", "2**64 - 5", "-2**63",
           "10**400", "1.5", "0.0", "-0.0", "1e-300", "1e300", "float('nan')", "float('inf')", "-float('inf')",
           "''", "'x'", "'skin1'", "'a\\0b'", "b'skin1'", "b'\\xff\\xfe'", "'\\udcff'", "[]", "[1]", "[1, 2]",
           "[1, 2, 3]", "[1, 2, 3, 4]", "[float('nan')] * 3", "['a', 'b', 'c']", "[None, 1, 2]", "[[1], [2], [3]]",
           "{}", "{'render.width': None}", "{'render.width': float('nan')}", "{'a\\0': 1}", "{1: 2}",
           "{'render.spp': [1, 2]}", "{'objects[0].material': {'x': 1}}", "pathlib.Path('/')",
           "pathlib.Path(FX)", "pathlib.Path(MCI)", "object()", "lucent", "(1, 2, 3)", "range(3)",
           "__import__('fractions').Fraction(1, 3)", "__import__('decimal').Decimal('1.5')", "1j", "'1e6'",
           "bytearray(b'x')", "'/proc/self/mem'", "'/dev/zero'", "'/'", "'x' * 5000"]
SAFE = {
    "spec": "'skin1'", "model": None, "photons": "2000", "seed": "1", "dr": "None", "bins": "None", "threads": "1",
    "mci": "MCI", "out_dir": "TMP", "write": "False", "rank": "1", "taps": "9", "profile": "'dipole'", "k": "1.0",
    "range_mm": "0.0", "theta": "0.5", "sigma": "0.2", "variant": "'kubo'", "width": "8", "height": "8",
    "sigma_max": "3.0", "radii": "[5]", "mesh_path": "M", "method": None, "smooth": "0", "mm_per_unit": "1.0",
    "scene_path": "S", "settings": "None", "spp": "1", "time_limit": "0", "sigma_a": "None", "sigma_s": "None",
    "g": "0.0", "eta": "1.3", "fov_y": "45.0", "depth_mm": "None", "object_height_mm": "1800.0",
}
MODELS = {"profile": "'dipole'", "kernel": "'preint'", "curvature": "'rusinkiewicz'", "render": "None"}
FUNCTIONS = {
    "material": ["spec", "sigma_a", "sigma_s", "g", "eta"],
    "profile": ["spec", "model", "photons", "seed", "dr", "bins", "threads"],
    "mcml": ["mci", "seed", "out_dir", "threads", "write"],
    "kernel": ["spec", "model", "rank", "taps", "profile", "photons", "seed", "k", "range_mm", "threads"],
    "cdrf": ["theta", "sigma", "variant"],
    "cdrf_lut": ["variant", "width", "height", "sigma_max", "threads"],
    "cdrf_fit": ["spec", "radii", "photons", "bins", "seed", "variant", "threads"],
    "curvature": ["mesh_path", "method", "smooth", "mm_per_unit", "threads"],
    "trace": ["scene_path", "spp", "seed", "settings", "threads", "time_limit"],
    "K.width_px": ["height", "fov_y", "depth_mm", "object_height_mm"],
}


def draw(rng):
    fn = rng.choice(sorted(FUNCTIONS))
    args = []
    for p in FUNCTIONS[fn]:
        safe = MODELS.get(fn) if p in ("model", "method") else SAFE[p]
        if fn == "material" and p in ("sigma_a", "sigma_s") and rng.random() < 0.5:
            safe = "[0.1, 0.2, 0.3]"
        v = rng.choice(HOSTILE) if rng.random() < 0.35 else safe
        if fn == "profile" and p == "model" and v == safe and rng.random() < 0.3:
            v = "'mc'"
        if v is not None:
            args.append("%s=%s" % (p, v))
    target = "K.width_px" if fn == "K.width_px" else "lucent." + fn
    return "%s(%s)" % (target, ", ".join(args))


CHILD = r'''
import json, os, pathlib, sys
import lucent
S, M, MCI, FX, TMP = sys.argv[1:6]
os.chdir(TMP)
K = lucent.kernel("skin1")
print(json.dumps({"ready": True}), flush=True)
for line in sys.stdin:
    code = line.rstrip("\n")
    print(json.dumps({"start": code}), flush=True)
    try:
        eval(code)
        r = {"ok": True}
    except (lucent.LucentError, TypeError, ValueError) as e:
        r = {"ok": True, "raised": type(e).__name__}
    except BaseException as e:
        r = {"ok": False, "raised": type(e).__name__, "message": str(e)[:300]}
    print(json.dumps(r), flush=True)
'''


def child_env():
    env = dict(os.environ, LUCENT_LIBRARY=library, PYTHONPATH=os.path.join(root, "python"))
    ldd = subprocess.run(["ldd", library], capture_output=True, text=True).stdout
    asan = [ln.split("=>")[1].split()[0] for ln in ldd.splitlines() if "libasan" in ln and "=>" in ln]
    if asan:  # an ASan library: the runtime must come first; leaks of the interpreter are not ours
        env["LD_PRELOAD"] = asan[0]
        env["ASAN_OPTIONS"] = "detect_leaks=0:abort_on_error=1"
        env["UBSAN_OPTIONS"] = "halt_on_error=1:print_stacktrace=1"
    return env


def start():
    """A child interpreter, once it imported lucent (its start is not counted in a call's time)."""
    p = subprocess.Popen([sys.executable, "-c", CHILD, os.path.join(fx, "scenes", "trace-small.json"),
                          os.path.join(fx, "mesh", "tetra.ply"), mci, fx, tmp], stdin=subprocess.PIPE,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=child_env(), bufsize=1)
    line = p.stdout.readline()
    if '"ready"' not in line:
        sys.exit("python_args: the child did not start: %s" % p.stderr.read()[-2000:])
    p.lines = queue.Queue()

    def pump():  # the child's lines, as they come (None at its end)
        for ln in p.stdout:
            p.lines.put(ln)
        p.lines.put(None)

    threading.Thread(target=pump, daemon=True).start()
    return p


def main():
    rng = random.Random(seed)
    limit = 5.0  # seconds a call may take (the child's start included)
    end = time.time() + seconds
    calls = raised = timeouts = restarts = 0
    findings = []
    p = start()
    while time.time() < end:
        code = draw(rng)
        p.stdin.write(code + "\n")
        p.stdin.flush()
        result, deadline = None, time.time() + limit
        while result is None:
            try:
                line = p.lines.get(timeout=max(0.01, deadline - time.time()))
            except queue.Empty:
                break
            if line is None:
                break
            d = json.loads(line)
            if "start" not in d:
                result = d
        calls += 1
        if result is None:
            dead = p.poll() is not None
            if not dead:
                timeouts += 1
                if os.environ.get("VERBOSE"):
                    print("slow:", code, flush=True)
                p.kill()
            p.wait()
            if dead:
                err = p.stderr.read()[-2000:]
                findings.append((code, "the interpreter died (exit %d): %s" % (p.returncode, err)))
            restarts += 1
            p = start()
            continue
        if not result["ok"]:
            findings.append((code, "%s: %s" % (result["raised"], result.get("message", ""))))
        elif "raised" in result:
            raised += 1
    p.stdin.close()
    p.kill()
    p.wait()
    for i, (code, why) in enumerate(findings):
        with open(os.path.join(out, "finding-%d.py" % i), "w") as f:
            f.write("# %s\nimport lucent, pathlib\n%s\n" % (why.replace("\n", "\n# "), code))
        print("FINDING %s\n   %s" % (code, why[:400]))
    print("python_args: %d calls in %.0f s (%.1f/s), %d raised a checked error, %d timed out (valid but slow), "
          "%d restarts, %d findings (seed %d, %s)" % (calls, seconds, calls / seconds, raised, timeouts, restarts,
                                                      len(findings), seed, library))
    return 1 if findings else 0


sys.exit(main())
