#!/usr/bin/env python3
"""Tests of the Python package (python/lucent) against the CLI, the literature and closed forms.
Usage: test_python.py LUCENT_BINARY SOURCE_DIR (the package is imported from SOURCE_DIR/python and
loads BINARY's folder's liblucent.so through LUCENT_LIBRARY). Runs with or without numpy."""
import json
import math
import os
import subprocess
import sys
import tempfile

lucent_bin, source = sys.argv[1], sys.argv[2]
build = os.path.dirname(os.path.abspath(lucent_bin))
os.environ.setdefault("LUCENT_LIBRARY", os.path.join(build, "liblucent.so"))
sys.path.insert(0, os.path.join(source, "python"))
import lucent  # noqa: E402

failed = 0


def check(what, ok, detail=""):
    global failed
    print(("ok   " if ok else "FAIL ") + what + ("" if ok else "  " + str(detail)))
    failed += 0 if ok else 1


def raises(fn, *words):
    try:
        fn()
    except lucent.LucentError as e:
        return all(w in e.message for w in words), e.message
    return False, "no exception"


tmp = tempfile.mkdtemp(prefix="lucent-py-")
print("python %s, numpy %s, %s" % (sys.version.split()[0], "yes" if lucent._np is not None else "no",
                                   lucent.library_path))

# The Monte Carlo profile of Skin1 equals the CLI's for the same seed, bit for bit: the CSV's text
# (%.9g) and the JSON's values (17 digits, which round-trip doubles exactly).
subprocess.run([lucent_bin, "-q", "profile", "skin1", "--model", "mc", "--photons", "20000", "--seed", "3",
                "--out", os.path.join(tmp, "skin1")], check=True)
p = lucent.profile("skin1", model="mc", photons=20000, seed=3)
rows = [r for r in open(os.path.join(tmp, "skin1.csv")).read().split("\n") if r and r[0].isdigit()]
mine = ["%.9g" % p.r[j] + "".join(",%.9g,%.9g" % (p.rd[c][j], p.se[c][j]) for c in range(3)) for j in range(p.count)]
check("MC profile of Skin1 = the CLI's CSV (%d rows)" % len(rows), rows == mine)
cli = json.load(open(os.path.join(tmp, "skin1.json")))
same = cli["r"] == list(p.r) and cli["total_on_grid"] == list(p.rd_total)
for c, ch in enumerate("RGB"):
    vals = [v for v in cli[ch].values() if isinstance(v, list)]
    same = same and any(v == list(p.rd[c]) for v in vals) and any(v == list(p.se[c]) for v in vals)
check("MC profile of Skin1 = the CLI's JSON, every double", same)
q = lucent.profile("skin1", model="mc", photons=20000, seed=3, threads=1)
check("the same profile on one thread", list(q.rd[1]) == list(p.rd[1]))

# The dipole's total: Jensen et al. 2001's Rd in closed form (Fdr polynomial, A = (1+Fdr)/(1-Fdr)),
# computed here from the Skin1 preset's coefficients; the grid (32 mean free paths) holds all but ~1e-5.
m = lucent.material("skin1")
eta = m.eta
fdr = -1.440 / eta ** 2 + 0.710 / eta + 0.668 + 0.0636 * eta
A = (1 + fdr) / (1 - fdr)
d = lucent.profile("skin1", model="dipole")
for c in range(3):
    ap = m.sigma_s[c] * (1 - m.g[c]) / (m.sigma_s[c] * (1 - m.g[c]) + m.sigma_a[c])
    s = math.sqrt(3 * (1 - ap))
    rd = ap / 2 * (1 + math.exp(-4 / 3 * A * s)) * math.exp(-s)
    check("dipole rd_total[%d] = Jensen's Rd %.6f" % (c, rd), abs(d.rd_total[c] - rd) < 1e-4 * rd, d.rd_total[c])
check("material().derived() rd = the closed form", abs(m.derived()["rd"][0] - d.rd_total[0]) < 1e-4)
check("eleven RGB presets, then the spectral skins, then the g 0.9 skins", len(lucent.materials()) == 21
      and lucent.materials()[0].name == "Apple" and lucent.materials()[11].name == "Skin-VeryLight"
      and lucent.materials()[19].name == "Skin1-g0.9")
skin = lucent.material("skin-light")
check("a spectral skin resolves to its equivalent medium", skin.sigma_a[0] > 0 and skin._c.skin.layer_count == 2)
col = lucent.skin_color("skin-light", bands=20)
sp = lucent.skin_profile("skin-light", bands=10, dr=0.05, bins=200)
check("a spectral skin's colour: ITA of its category, linear sRGB red above blue",
      col["category"] == lucent.skin_color("skin-light")["category"] and col["rgb"][0] > col["rgb"][2] > 0, col)
check("a spectral skin's profile (multipole, 10 bands)", sp.model == "skin-multipole" and sp.rd[0][0] > sp.rd[0][100] > 0)
for model in ("better-dipole", "burley"):
    b = lucent.profile("marble", model=model)
    check("%s profile of Marble: positive, decreasing" % model,
          all(x > 0 for x in b.rd[0][:50]) and b.rd[0][0] > b.rd[0][40])
own = lucent.material("jade", sigma_a=[0.05, 0.01, 0.06], sigma_s=[1.2, 1.6, 1.1], g=0.3, eta=1.6)
check("a material of one's own", own.name == "jade" and own.derived()["sigma_t"][0] == 1.25)

# Errors carry Lucent's message.
check("unknown preset raises, listing the presets", *raises(lambda: lucent.material("marbel"), "marbel", "Skin1"))
check("a missing material file raises, naming it", *raises(lambda: lucent.material(tmp + "/none.json"), "none.json"))
check("a bad material raises, naming the field",
      *raises(lambda: lucent.material("x", sigma_a=[-1, 0, 0], sigma_s=[1, 1, 1]), "sigma_a"))
check("unknown kernel model raises", *raises(lambda: lucent.kernel("skin1", model="svd9"), "svd9"))
check("even taps raise", *raises(lambda: lucent.kernel("skin1", taps=16), "odd"))

# Kernels: importance-sampled taps sum to 1 per channel (lucent/kernel.h); the width on screen is
# 2 R height / (2 tan(fov_y / 2) z), here computed from the pinhole camera.
k = lucent.kernel("marble", model="preint", taps=17)
sums = [sum(k.weights[c][0]) for c in range(3)]
check("17 taps summing to 1 per channel", k.taps == 17 and all(abs(x - 1) < 1e-9 for x in sums), sums)
check("radius = the largest |offset|", k.radius == max(abs(o) for o in k.offsets))
w = 2 * k.radius * 1080 / (2 * math.tan(math.radians(45) / 2) * 1000)
check("kernel width at 1 m on 1080 rows", abs(k.width_px(1080, 45, depth_mm=1000) - w) < 1e-9 * w)
out = subprocess.run([lucent_bin, "kernel", "marble", "--out", os.path.join(tmp, "k.json")], check=True,
                     capture_output=True, text=True).stdout
check("the CLI prints the same width", ("kernel width: %.2f px" % k.width_px()) in out, out)
check("svd rank 3: 3 passes", lucent.kernel("skin1", model="svd", rank=3, taps=9).rank == 3)

# The CDRF LUT: at sigma = 0 Kubo's CDRF is Lambert's max(cos theta, 0) (Kubo Eq. 2).
lut = lucent.cdrf_lut(width=9, height=5)
check("LUT shape 5 x 9 x 1", len(lut) == 5 and len(lut[0]) == 9 and len(lut[0][0]) == 1)
check("LUT row sigma = 0 is max(cos, 0)", all(abs(lut[0][i][0] - max(-1 + 2 * i / 8, 0)) < 1e-6 for i in range(9)))
check("cdrf(theta, 0) = cos theta", abs(lucent.cdrf(0.5, 0.0) - math.cos(0.5)) < 1e-12)
fit = lucent.cdrf_fit("skin1", radii=[5], photons=3000, bins=6)
check("cdrf_fit gives sigma0 and k_d per channel", len(fit["sigma0"]) == 3 and all(x > 0 for x in fit["kd"]), fit)

# Mesh curvature: a UV sphere of radius 2 has mean curvature 1/2 per unit (and 0.25 mm^-1 at 2 mm per unit).
obj = os.path.join(tmp, "sphere.obj")
with open(obj, "w") as f:
    n, mseg = 48, 96
    f.write("v 0 0 2\n")
    for i in range(1, n):
        t = math.pi * i / n
        for j in range(mseg):
            ph = 2 * math.pi * j / mseg
            f.write("v %.12f %.12f %.12f\n" % (2 * math.sin(t) * math.cos(ph), 2 * math.sin(t) * math.sin(ph), 2 * math.cos(t)))
    f.write("v 0 0 -2\n")
    ring = lambda i, j: 2 + (i - 1) * mseg + j % mseg
    for j in range(mseg):
        f.write("f 1 %d %d\n" % (ring(1, j), ring(1, j + 1)))
    for i in range(1, n - 1):
        for j in range(mseg):
            f.write("f %d %d %d\nf %d %d %d\n" % (ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j),
                                                  ring(i + 1, j + 1), ring(i, j + 1)))
    last = 2 + (n - 1) * mseg
    for j in range(mseg):
        f.write("f %d %d %d\n" % (ring(n - 1, j), last, ring(n - 1, j + 1)))
cv = lucent.curvature(obj, mm_per_unit=2.0)
mid = [cv["mean"][i] for i in range(len(cv["mean"])) if 20 * mseg < i < 28 * mseg]
check("sphere of radius 2 mm x 2: mean curvature 0.25 / mm", all(abs(x - 0.25) < 0.01 for x in mid), mid[:3])
check("a missing mesh raises, naming it", *raises(lambda: lucent.curvature(tmp + "/no.ply"), "no.ply"))

# MCML: van de Hulst's slab (MCML manual, Table 4.1): Rd 0.09739, Tt 0.66096; matched index, so no
# specular reflection at entry (Fresnel: ((n1 - n2) / (n1 + n2))^2 = 0).
runs = lucent.mcml(os.path.join(source, "tests/fixtures/mcml/vanhulst.mci"), out_dir=os.path.join(tmp, "mco"))
r = runs[0]
check("van de Hulst Rd 0.09739 within 4 SE", abs(r["rd"] - 0.09739) < 4 * r["rd_se"] + 2e-4, (r["rd"], r["rd_se"]))
check("van de Hulst Tt 0.66096 within 4 SE", abs(r["tt"] - 0.66096) < 4 * r["tt_se"] + 2e-4, (r["tt"], r["tt_se"]))
check("no specular at entry (matched index)", r["rsp"] == 0.0, r["rsp"])
check("the .mco is written", os.path.getsize(r["mco"]) > 1000)

# The SIMD path (docs/mcml.md, "SIMD paths"): by default the one `lucent --version` names; the scalar
# reference kernel on request, van de Hulst's slab again within 4 SE (other random numbers than the
# default path's when that is a SIMD one); an unknown name raises, listing the names.
ver = subprocess.run([lucent_bin, "--version"], capture_output=True, text=True).stdout
simd = [ln.split()[1] for ln in ver.splitlines() if ln.startswith("simd")]
check("lucent.isa() is the path lucent --version names", simd and lucent.isa() == simd[0], (lucent.isa(), simd))
default_path = lucent.isa()
check("lucent.isa('scalar') chooses the scalar kernel", lucent.isa("scalar") == "scalar")
rs = lucent.mcml(os.path.join(source, "tests/fixtures/mcml/vanhulst.mci"), write=False)[0]
check("scalar: van de Hulst Rd 0.09739 within 4 SE", abs(rs["rd"] - 0.09739) < 4 * rs["rd_se"] + 2e-4,
      (rs["rd"], rs["rd_se"]))
if default_path != "scalar":
    check("scalar and %s draw other random numbers" % default_path, rs["rd"] != r["rd"], (rs["rd"], r["rd"]))
check("an unknown path raises, listing the names", *raises(lambda: lucent.isa("sse9"), "sse9", "avx512"))
check("lucent.isa('auto') goes back to the default", lucent.isa("auto") == default_path)

# Rendering and tracing into arrays: the image equals the CLI's EXR of the same scene (same library,
# deterministic rasteriser); the path tracer's mean is positive over the object.
scene = os.path.join(source, "tests/fixtures/scenes/sphere.json")
sets = {"render.width": 32, "render.height": 24}
try:
    img, mask = lucent.render(scene, method="cdrf", settings=sets)
    subprocess.run([lucent_bin, "-q", "render", scene, "--method", "cdrf", "--set", "render.width=32", "--set",
                    "render.height=24", "--out", os.path.join(tmp, "r.png"), "--exr", os.path.join(tmp, "r.exr")],
                   check=True)
    info = subprocess.run([lucent_bin, "image", "info", os.path.join(tmp, "r.exr")], capture_output=True, text=True).stdout
    mean_r = float([ln.split()[-1] for ln in info.split("\n") if ln.strip().startswith("R ")][0])
    ours = sum(img[y][x][0] for y in range(24) for x in range(32)) / (24 * 32)
    check("render: 24 x 32 x 3, the CLI's mean red %.6g" % mean_r,
          len(img) == 24 and len(img[0]) == 32 and abs(ours - mean_r) < 1e-5 * max(mean_r, 1e-9), ours)
    check("render: the mask covers the sphere", 0.1 < sum(mask[y][x][0] for y in range(24) for x in range(32)) / 768 < 0.9)
except lucent.LucentError as e:
    check("render (needs OpenGL 4.5)", "OpenGL" in e.message or "EGL" in e.message, e.message)
tr, var = lucent.trace(os.path.join(source, "tests/fixtures/scenes/trace-small.json"), spp=2)
check("trace: an image with light on it", sum(tr[y][x][1] for y in range(len(tr)) for x in range(len(tr[0]))) > 0)
check("a bad scene override raises, naming it",
      *raises(lambda: lucent.trace(scene, settings={"objects[0].material": "unobtainium"}), "objects[0].material"))

# pack(): the files of `lucent pack` with the same arguments, byte for byte (the same library: the bake's
# Monte Carlo has fixed seeds), and the width the CLI prints.
few = ["--sigma0-photons", "500", "--transmit-photons", "100", "--lut-size", "8x8", "--object-height", "0.05m",
       "--fit-photons", "3000", "--fit-model-photons", "500"]
cli = subprocess.run([lucent_bin, "pack", "skin1", "--engine", "gles", "--no-cache", "--out", os.path.join(tmp, "pk-cli")]
                     + few, check=True, capture_output=True, text=True).stdout
r = lucent.pack("skin1", "gles", os.path.join(tmp, "pk-py"), object_height_mm=50, lut_size=(8, 8), sigma0_photons=500,
                transmit_photons=100, fit_photons=3000, fit_model_photons=500)
names = sorted(os.listdir(os.path.join(tmp, "pk-cli")))
same = names == sorted(os.listdir(os.path.join(tmp, "pk-py"))) and all(
    open(os.path.join(tmp, "pk-cli", n), "rb").read() == open(os.path.join(tmp, "pk-py", n), "rb").read() for n in names)
check("pack(): the CLI's %d files, byte for byte" % len(names), same and r["file_count"] == len(names) == 11, names)
check("pack(): the CLI's kernel width", "kernel width: %.2f px" % r["width_px"] in cli, (r, cli))
check("pack(): an unknown engine raises, naming it",
      *raises(lambda: lucent.pack("skin1", "wgsl", os.path.join(tmp, "pk-x")), "unknown engine 'wgsl'"))

# Engine parameters: fit() gives the CLI's numbers (same truth: the same seeds and photons); the hand mapping's
# HDRP scattering distance is 1 / sigma_tr of the material (Jensen 2001's sigma_tr = sqrt(3 sigma_a sigma_t'),
# computed here from the preset's coefficients); a stack says that its layers are beyond a homogeneous model.
r = lucent.fit("ketchup", engines=["unity-hdrp"], photons=20000)
subprocess.run([lucent_bin, "-q", "fit", "ketchup", "--engines", "unity-hdrp", "--photons", "20000", "--no-cache",
                "--out", os.path.join(tmp, "fit")], check=True)
cli = json.load(open(os.path.join(tmp, "fit.json")))
check("fit(): the CLI's parameters", r["engines"][0]["parameters"] == cli["engines"][0]["parameters"])
k = lucent.material("ketchup")
hand = {p["name"]: p["value"] for p in r["engines"][0]["hand_mapping"]["parameters"]}
for c in range(3):
    sig_tr = math.sqrt(3 * k.sigma_a[c] * (k.sigma_a[c] + k.sigma_s[c] * (1 - k.g[c])))
    check("fit(): the hand mapping's d = 1 / sigma_tr, channel %d" % c,
          abs(hand["Scattering Color"][c] * hand["Multiplier"] - 1 / sig_tr) < 1e-9 / sig_tr)
r = lucent.fit(layers=[("skin1", 0.5), ("skin2", float("inf"))], engines=["blender3-burley"], photons=5000)
check("fit(layers=...): the stack is what the model cannot express", "layers (2)" in r["engines"][0]["cannot_express"])
check("fit(): an unknown engine raises, naming the known ones",
      *raises(lambda: lucent.fit("skin1", engines=["unreal"]), "unknown engine", "unity-hdrp"))

print("%d failed" % failed)
sys.exit(1 if failed else 0)
