#!/usr/bin/env python3
"""Hostile arguments to the Python package (issue 32 items 11 and 12; ../shared/repro-3 items 8 and 9).

Every call runs in a child interpreter, one after the other, so that a call that kills the
interpreter (a NULL pointer in C, a wrapped count) fails this test, naming the call, instead of
killing the runner. Each case asserts the exception's class (TypeError or ValueError, both also a
lucent.LucentError; or a LucentError from the library) and the words of its message (the argument's
name), or, for the values that must work (pathlib.Path, whole floats, numpy integers), the result.
After the last call the child must still be alive.

The classes: None, a wrong type, out of range, NaN, huge ints (ctypes would wrap them), floats
where whole numbers are expected, 0 where the CLI refuses it, wrong-length lists, NUL bytes, the
C API's own NULL checks (called through ctypes), and the library limits _args.py copies, each
compared with the header or source that defines it.

Usage: test_python_args.py LUCENT_BINARY SOURCE_DIR (as tests/test_python.py)."""
import json
import os
import re
import subprocess
import sys
import tempfile

lucent_bin, source = sys.argv[1], sys.argv[2]
build = os.path.dirname(os.path.abspath(lucent_bin))
env = dict(os.environ)
env.setdefault("LUCENT_LIBRARY", os.path.join(build, "liblucent.so"))
env["PYTHONPATH"] = os.path.join(source, "python")
fx = os.path.join(source, "tests", "fixtures")
tmp = tempfile.mkdtemp(prefix="lucent-pyargs-")
mci = os.path.join(tmp, "tiny.mci")
with open(mci, "w") as f:
    f.write("1.0\n1\ntiny.mco A\n1000\n0.01 0.01\n4 10 4\n1\n1.0\n1.0 1 10 0.75 0.1\n1.0\n")

# (label, code, expected, words): expected is "type" (TypeError and LucentError), "value"
# (ValueError and LucentError), "lucent" (LucentError from the library) or "ok" (no exception;
# words are then a Python expression on the result `r` that must be true).
S = "S"  # the names the child's namespace defines
cases = [
    # -- None where a material, a scene, a file or a name is expected (repro-3 item 8: SIGSEGV)
    ("material(None)", "lucent.material(None)", "type", ["spec", "None"]),
    ("profile(None)", "lucent.profile(None, model='dipole')", "type", ["spec", "None"]),
    ("kernel(None)", "lucent.kernel(None)", "type", ["spec", "None"]),
    ("cdrf_fit(None)", "lucent.cdrf_fit(None, radii=[5], photons=1000)", "type", ["spec", "None"]),
    ("render(None)", "lucent.render(None)", "type", ["scene_path", "None"]),
    ("trace(None)", "lucent.trace(None)", "type", ["scene_path", "None"]),
    ("mcml(None)", "lucent.mcml(None)", "type", ["mci", "None"]),
    ("curvature(None)", "lucent.curvature(None)", "type", ["mesh_path", "None"]),
    ("kernel(model=None)", "lucent.kernel('skin1', model=None)", "type", ["model"]),
    ("kernel(profile=None)", "lucent.kernel('skin1', profile=None)", "type", ["profile"]),
    ("profile(model=None)", "lucent.profile('skin1', model=None)", "type", ["model"]),
    ("cdrf_lut(variant=None)", "lucent.cdrf_lut(variant=None, width=4, height=4)", "type", ["variant"]),
    ("cdrf(None, 0)", "lucent.cdrf(None, 0.0)", "type", ["theta"]),
    ("kernel(taps=None)", "lucent.kernel('skin1', taps=None)", "type", ["taps"]),
    ("trace(spp=None)", "lucent.trace(S, spp=None)", "type", ["spp"]),
    ("curvature(mm_per_unit=None)", "lucent.curvature(M, mm_per_unit=None)", "type", ["mm_per_unit"]),
    ("material(sigma_s=None) with sigma_a", "lucent.material('x', sigma_a=1)", "type", ["sigma_s"]),
    ("trace(settings={k: None})", "lucent.trace(S, settings={'render.spp': None})", "type", ["settings"]),
    ("mcml(out_dir=...) of None stays the default", "lucent.mcml(MCI, out_dir=None, write=False)", "ok",
     "len(r) == 1 and r[0]['mco'] is None"),
    # -- a wrong type
    ("material(3)", "lucent.material(3)", "type", ["spec", "int"]),
    ("kernel(taps='17')", "lucent.kernel('skin1', taps='17')", "type", ["taps", "str"]),
    ("kernel(taps=True)", "lucent.kernel('skin1', taps=True)", "type", ["taps", "bool"]),
    ("profile(photons='1e6')", "lucent.profile('skin1', photons='1e6')", "type", ["photons"]),
    ("trace(settings=[...])", "lucent.trace(S, settings=['render.spp=1'])", "type", ["settings", "dict"]),
    ("curvature(method=3)", "lucent.curvature(M, method=3)", "type", ["method"]),
    ("cdrf_fit(radii=5)", "lucent.cdrf_fit('skin1', radii=5)", "type", ["radii"]),
    ("cdrf_fit(radii='2,5')", "lucent.cdrf_fit('skin1', radii='2,5')", "type", ["radii"]),
    ("material(sigma_a='abc')", "lucent.material('x', sigma_a='abc', sigma_s=1)", "type", ["sigma_a"]),
    ("material(g=[0, 'a', 0])", "lucent.material('x', sigma_a=1, sigma_s=1, g=[0, 'a', 0])", "type", ["g[1]"]),
    ("mcml(write='yes')", "lucent.mcml(MCI, write='yes')", "type", ["write"]),
    ("mcml(write=2**63)", "lucent.mcml(MCI, write=2**63)", "type", ["write"]),
    # -- what fuzz/fuzz_python_args.py found: an out_dir that cannot be a folder raised OSError
    ("mcml(out_dir=a file)", "lucent.mcml(MCI, out_dir=MCI)", "lucent", ["cannot create the folder"]),
    ("mcml(out_dir='x' * 5000)", "lucent.mcml(MCI, out_dir=os.path.join(TMP, 'x' * 5000))", "lucent",
     ["cannot create the folder"]),
    # -- wrong-length lists (ctypes said "Can only assign sequence of same size")
    ("material(sigma_a=[1, 2])", "lucent.material('x', sigma_a=[1, 2], sigma_s=[1, 1, 1])", "value",
     ["sigma_a", "three", "got 2"]),
    ("material(g=[0] * 4)", "lucent.material('x', sigma_a=1, sigma_s=1, g=[0, 0, 0, 0])", "value", ["g", "got 4"]),
    ("cdrf_fit(radii=[])", "lucent.cdrf_fit('skin1', radii=[])", "value", ["radii", "got 0"]),
    ("cdrf_fit(17 radii)", "lucent.cdrf_fit('skin1', radii=[1] * 17)", "value", ["radii", "16", "got 17"]),
    # -- out of range, and 0 where the CLI refuses it (repro-3 item 9)
    ("kernel(taps=16)", "lucent.kernel('skin1', taps=16)", "value", ["taps", "odd"]),
    ("kernel(taps=0)", "lucent.kernel('skin1', taps=0)", "value", ["taps", "got 0"]),
    ("kernel(taps=-1)", "lucent.kernel('skin1', taps=-1)", "value", ["taps", "got -1"]),
    ("kernel(rank=0)", "lucent.kernel('skin1', model='svd', rank=0)", "value", ["rank"]),
    ("profile(photons=-5)", "lucent.profile('skin1', photons=-5)", "value", ["photons", "got -5"]),
    ("profile(photons=0)", "lucent.profile('skin1', photons=0)", "value", ["photons", "got 0"]),
    ("kernel(photons=0)", "lucent.kernel('skin1', photons=0)", "value", ["photons"]),
    ("cdrf_fit(photons=-1)", "lucent.cdrf_fit('skin1', radii=[2], photons=-1)", "value", ["photons", "-1"]),
    ("cdrf_fit(bins=1)", "lucent.cdrf_fit('skin1', radii=[2], bins=1)", "value", ["bins"]),
    ("cdrf_fit(radii=[0])", "lucent.cdrf_fit('skin1', radii=[0])", "value", ["radii[0]"]),
    ("cdrf_fit(radii=[5, -2])", "lucent.cdrf_fit('skin1', radii=[5, -2])", "value", ["radii[1]"]),
    ("cdrf_lut(width=1)", "lucent.cdrf_lut(width=1, height=4)", "value", ["width"]),
    ("cdrf_lut(sigma_max=0)", "lucent.cdrf_lut(width=4, height=4, sigma_max=0)", "value", ["sigma_max"]),
    ("trace(spp=0)", "lucent.trace(S, spp=0)", "value", ["spp"]),
    ("trace(time_limit=-1)", "lucent.trace(S, time_limit=-1)", "value", ["time_limit"]),
    ("kernel(range_mm=1e300)", "lucent.kernel('skin1', model='svd', range_mm=1e300)", "value", ["range_mm"]),
    ("kernel(range_mm=-1)", "lucent.kernel('skin1', range_mm=-1)", "value", ["range_mm"]),
    ("kernel(threads=-3)", "lucent.kernel('skin1', threads=-3)", "value", ["threads"]),
    ("kernel(threads=100000)", "lucent.kernel('skin1', threads=100000)", "value", ["threads"]),
    ("curvature(mm_per_unit=0)", "lucent.curvature(M, mm_per_unit=0)", "value", ["mm_per_unit"]),
    ("curvature(mm_per_unit=-1)", "lucent.curvature(M, mm_per_unit=-1)", "value", ["mm_per_unit"]),
    ("curvature(smooth=-1)", "lucent.curvature(M, smooth=-1)", "value", ["smooth"]),
    ("profile(dr=1e-300)", "lucent.profile('skin1', model='dipole', dr=1e-300)", "value", ["dr"]),
    ("profile(dr=1e300)", "lucent.profile('skin1', model='dipole', dr=1e300)", "value", ["dr"]),
    ("width_px(height=0)", "K.width_px(height=0)", "value", ["height"]),
    ("width_px(fov_y=0)", "K.width_px(fov_y=0)", "value", ["fov_y"]),
    ("width_px(depth_mm=-5)", "K.width_px(depth_mm=-5)", "value", ["depth_mm"]),
    ("mcml(seed=-1)", "lucent.mcml(MCI, seed=-1, write=False)", "value", ["seed"]),
    # -- the spectral skin's functions (docs/skin.md)
    ("skin_color(None)", "lucent.skin_color(None)", "type", ["spec", "None"]),
    ("skin_color(bands=2**32+20)", "lucent.skin_color('skin-light', bands=2**32 + 20)", "value", ["bands"]),
    ("skin_color(bands=-1)", "lucent.skin_color('skin-light', bands=-1)", "value", ["bands"]),
    ("skin_profile(photons=1.5)", "lucent.skin_profile('skin-light', photons=1.5)", "value", ["photons"]),
    ("skin_profile(transport=None)", "lucent.skin_profile('skin-light', transport=None)", "type", ["transport"]),
    ("skin_profile(transport='x')", "lucent.skin_profile('skin-light', transport='x')", "lucent", ["transport"]),
    ("ciede2000([1, 2], ...)", "lucent.ciede2000([1, 2], [0, 0, 0])", "value", ["lab1"]),
    ("ciede2000(..., nan)", "lucent.ciede2000([50, 0, 0], [50, float('nan'), 0])", "value", ["lab2[1]"]),
    # -- NaN and infinities
    ("kernel(k=nan)", "lucent.kernel('skin1', k=float('nan'))", "value", ["k:", "finite"]),
    ("kernel(range_mm=nan)", "lucent.kernel('skin1', range_mm=float('nan'))", "value", ["range_mm"]),
    ("curvature(mm_per_unit=nan)", "lucent.curvature(M, mm_per_unit=float('nan'))", "value", ["mm_per_unit"]),
    ("curvature(mm_per_unit=inf)", "lucent.curvature(M, mm_per_unit=float('inf'))", "value", ["mm_per_unit"]),
    ("cdrf(nan, 0)", "lucent.cdrf(float('nan'), 0.0)", "value", ["theta"]),
    ("cdrf_lut(sigma_max=nan)", "lucent.cdrf_lut(width=4, height=4, sigma_max=float('nan'))", "value", ["sigma_max"]),
    ("material(eta=nan)", "lucent.material('x', sigma_a=1, sigma_s=1, eta=float('nan'))", "value", ["eta"]),
    ("material(sigma_s=[1, nan, 1])", "lucent.material('x', sigma_a=1, sigma_s=[1, float('nan'), 1])", "value",
     ["sigma_s[1]"]),
    ("trace(time_limit=nan)", "lucent.trace(S, time_limit=float('nan'))", "value", ["time_limit"]),
    ("trace(settings={width: nan})", "lucent.trace(S, settings={'render.width': float('nan')})", "value",
     ["render.width"]),
    ("profile(dr=nan)", "lucent.profile('skin1', model='dipole', dr=float('nan'))", "value", ["dr"]),
    ("cdrf_fit(radii=[inf])", "lucent.cdrf_fit('skin1', radii=[float('inf')])", "value", ["radii[0]"]),
    # -- huge ints that ctypes would wrap (repro-3 item 9: 17 taps, rank 1, 5 bins, 4 wide, 1 spp)
    ("kernel(taps=2**32+17)", "lucent.kernel('skin1', taps=2**32 + 17)", "value", ["taps", "4294967313"]),
    ("kernel(rank=2**32+1)", "lucent.kernel('skin1', model='svd', rank=2**32 + 1)", "value", ["rank"]),
    ("profile(bins=2**32+5)", "lucent.profile('skin1', model='dipole', bins=2**32 + 5)", "value", ["bins"]),
    ("cdrf_lut(width=2**32+4)", "lucent.cdrf_lut(width=2**32 + 4, height=4)", "value", ["width"]),
    ("trace(spp=2**32+1)", "lucent.trace(S, spp=2**32 + 1)", "value", ["spp"]),
    ("trace(seed=2**64+1)", "lucent.trace(S, seed=2**64 + 1)", "value", ["seed"]),
    ("profile(photons=2**64-5)", "lucent.profile('skin1', photons=2**64 - 5)", "value", ["photons"]),
    ("kernel(threads=2**31)", "lucent.kernel('skin1', threads=2**31)", "value", ["threads"]),
    ("curvature(smooth=2**32)", "lucent.curvature(M, smooth=2**32)", "value", ["smooth"]),
    ("curvature(mm_per_unit=10**400)", "lucent.curvature(M, mm_per_unit=10**400)", "value", ["mm_per_unit"]),
    ("material(sigma_a=10**400)", "lucent.material('x', sigma_a=10**400, sigma_s=1)", "value", ["sigma_a[0]"]),
    ("trace(settings={width: 10**400})", "lucent.trace(S, settings={'render.width': 10**400})", "lucent",
     ["render.width"]),
    # -- floats where whole numbers are expected: 1.5 is refused, 17.0 is 17 (the CLI takes "1e6")
    ("profile(photons=1.5)", "lucent.profile('skin1', photons=1.5)", "value", ["photons", "whole", "1.5"]),
    ("kernel(taps=17.5)", "lucent.kernel('skin1', taps=17.5)", "value", ["taps", "whole"]),
    ("trace(spp=2.5)", "lucent.trace(S, spp=2.5)", "value", ["spp", "whole"]),
    ("kernel(taps=9.0) gives 9 taps", "lucent.kernel('skin1', taps=9.0)", "ok", "r.taps == 9"),
    ("kernel(taps=17) gives 17 taps", "lucent.kernel('skin1', taps=17)", "ok", "r.taps == 17"),
    ("kernel(rank=3)", "lucent.kernel('skin1', model='svd', rank=3, taps=9)", "ok", "r.rank == 3"),
    # -- paths: pathlib.Path accepted wherever a path is; a NUL byte refused
    ("curvature(Path)", "lucent.curvature(pathlib.Path(M))", "ok", "len(r['mean']) == 4"),
    ("mcml(Path, out_dir=Path)", "lucent.mcml(pathlib.Path(MCI), out_dir=pathlib.Path(TMP) / 'mco')", "ok",
     "os.path.getsize(r[0]['mco']) > 100"),
    ("material(Path)", "lucent.material(pathlib.Path(FX) / 'materials' / 'jade.json')", "ok",
     "r.sigma_a[0] > 0"),
    ("trace(Path)", "lucent.trace(pathlib.Path(S), spp=1)", "ok", "len(r[0]) > 0"),
    ("curvature('a\\0b')", "lucent.curvature('tetra\\0.ply')", "value", ["mesh_path", "NUL"]),
    ("material('skin1\\0x')", "lucent.material('skin1\\0x')", "value", ["spec", "NUL"]),
    ("curvature('')", "lucent.curvature('')", "value", ["mesh_path", "empty"]),
    # -- fit() and pack() (issue 30): every argument checked before ctypes sees it
    ("fit(None)", "lucent.fit(None)", "type", ["spec", "None"]),
    ("fit(photons=-1)", "lucent.fit('skin1', photons=-1)", "value", ["photons", "-1"]),
    ("fit(photons=2**64)", "lucent.fit('skin1', photons=2**64)", "value", ["photons"]),
    ("fit(model_photons=1.5)", "lucent.fit('skin1', model_photons=1.5)", "value", ["model_photons", "whole"]),
    ("fit(seed=-1)", "lucent.fit('skin1', seed=-1)", "value", ["seed"]),
    ("fit(engines='unity-hdrp')", "lucent.fit('skin1', engines='unity-hdrp')", "type", ["engines", "list"]),
    ("fit(engines=[None])", "lucent.fit('skin1', engines=[None])", "type", ["engines[0]"]),
    ("fit(hand='yes')", "lucent.fit('skin1', hand='yes')", "type", ["hand"]),
    ("fit(transmittance=2)", "lucent.fit('skin1', transmittance=2)", "type", ["transmittance"]),
    ("fit(cache_dir=3)", "lucent.fit('skin1', cache_dir=3)", "type", ["cache_dir"]),
    ("fit(layers='skin1:1')", "lucent.fit(layers='skin1:1')", "type", ["layers"]),
    ("fit(layers=[])", "lucent.fit(layers=[])", "value", ["layers", "1 to 16", "got 0"]),
    ("fit(17 layers)", "lucent.fit(layers=[('skin1', 1)] * 17)", "value", ["layers", "got 17"]),
    ("fit(layers=[(m,)])", "lucent.fit(layers=[('skin1', 1), ('skin2',)])", "type", ["layers[1]"]),
    ("fit(layers=[(m, -1), ...])", "lucent.fit(layers=[('skin1', -1), ('skin2', float('inf'))])", "value",
     ["layers[0] thickness"]),
    ("fit(layers=[(m, nan), ...])", "lucent.fit(layers=[('skin1', float('nan')), ('skin2', float('inf'))])",
     "value", ["layers[0] thickness", "finite"]),
    ("fit(layers=[(m, inf), (m, 1)])", "lucent.fit(layers=[('skin1', float('inf')), ('skin2', 1)])", "value",
     ["layers[0]", "only the last"]),
    ("fit(layers=[(None, 1)])", "lucent.fit(layers=[(None, 1)])", "type", ["spec", "None"]),
    ("fit(layers=[a spectral skin, ...])", "lucent.fit(layers=[('skin-light', 0.25), ('skin2', float('inf'))])",
     "lucent", ["layers[0]", "spectral skin"]),
    ("fit(layers=[(m, 0.5), (m, inf)], engines=[...])",
     "lucent.fit(layers=[('skin1', 0.5), ('skin2', float('inf'))], engines=['unity-hdrp'], photons=2000, hand=False)",
     "ok", "r['engines'][0]['engine'] == 'unity-hdrp' and 'layers (2)' in r['engines'][0]['cannot_express']"),
    ("pack(None, ...)", "lucent.pack(None, 'json', TMP)", "type", ["spec", "None"]),
    ("pack(engine=None)", "lucent.pack('skin1', None, TMP)", "type", ["engine"]),
    ("pack(out=None)", "lucent.pack('skin1', 'json', None)", "type", ["out", "None"]),
    ("pack(out='a\\0b')", "lucent.pack('skin1', 'json', 'a\\0b')", "value", ["out", "NUL"]),
    ("pack(screen=1920)", "lucent.pack('skin1', 'json', TMP, screen=1920)", "type", ["screen"]),
    ("pack(screen=(0, 10))", "lucent.pack('skin1', 'json', TMP, screen=(0, 10))", "value", ["screen[0]"]),
    ("pack(screen=(2**32+5, 10))", "lucent.pack('skin1', 'json', TMP, screen=(2**32 + 5, 10))", "value",
     ["screen[0]"]),
    ("pack(screen=(1, 2, 3))", "lucent.pack('skin1', 'json', TMP, screen=(1, 2, 3))", "value", ["screen", "got 3"]),
    ("pack(lut_size=(1, 4))", "lucent.pack('skin1', 'json', TMP, lut_size=(1, 4))", "value", ["lut_size[0]"]),
    ("pack(fov=nan)", "lucent.pack('skin1', 'json', TMP, fov=float('nan'))", "value", ["fov"]),
    ("pack(fov=0)", "lucent.pack('skin1', 'json', TMP, fov=0)", "value", ["fov"]),
    ("pack(object_height_mm=-1)", "lucent.pack('skin1', 'json', TMP, object_height_mm=-1)", "value",
     ["object_height_mm"]),
    ("pack(distance_mm=inf)", "lucent.pack('skin1', 'json', TMP, distance_mm=float('inf'))", "value",
     ["distance_mm"]),
    ("pack(kappa_max=0)", "lucent.pack('skin1', 'json', TMP, kappa_max=0)", "value", ["kappa_max"]),
    ("pack(roughness=2)", "lucent.pack('skin1', 'json', TMP, roughness=2)", "value", ["roughness"]),
    ("pack(sigma0_photons=-5)", "lucent.pack('skin1', 'json', TMP, sigma0_photons=-5)", "value",
     ["sigma0_photons", "-5"]),
    ("pack(fit_photons=2**64)", "lucent.pack('skin1', 'json', TMP, fit_photons=2**64)", "value", ["fit_photons"]),
    ("pack(fit_model_photons=0.5)", "lucent.pack('skin1', 'json', TMP, fit_model_photons=0.5)", "value",
     ["fit_model_photons", "whole"]),
    ("pack(fit='no')", "lucent.pack('skin1', 'json', TMP, fit='no')", "type", ["fit"]),
    ("pack(mesh=3)", "lucent.pack('skin1', 'json', TMP, mesh=3)", "type", ["mesh"]),
    ("pack(threads=-1)", "lucent.pack('skin1', 'json', TMP, threads=-1)", "value", ["threads"]),
    ("pack(Path, fit=False)",
     "lucent.pack('skin1', 'json', pathlib.Path(TMP) / 'pk', fit=False, sigma0_photons=300, transmit_photons=100, "
     "lut_size=(4, 4))", "ok", "r['file_count'] == 8 and 'Left out' in open(os.path.join(TMP, 'pk', 'README.md')).read()"),
    # -- the C API's own NULL checks, through ctypes (what Python reaches)
    ("C: lucent_material_resolve(NULL)", "C(L.lucent_material_resolve(None, ctypes.byref(lucent._lib.Material())))",
     "lucent", ["NULL"]),
    ("C: lucent_mcml_load(NULL)", "C(L.lucent_mcml_load(None, ctypes.byref(lucent._lib.McmlFile())))", "lucent",
     ["NULL"]),
    ("C: lucent_mesh_load(NULL)", "C(L.lucent_mesh_load(None, None, ctypes.byref(ctypes.c_void_p())))", "lucent",
     ["NULL"]),
    ("C: lucent_scene_load(NULL)", "C(L.lucent_scene_load(None, None, ctypes.byref(ctypes.c_void_p())))", "lucent",
     ["NULL"]),
    ("C: lucent_image_load(NULL)",
     "C(L.lucent_image_load(None, ctypes.byref(ctypes.POINTER(lucent._lib.Image)())))", "lucent", ["NULL"]),
    ("C: lucent_kernel_model_parse(NULL)", "C(L.lucent_kernel_model_parse(None, ctypes.byref(ctypes.c_int())))",
     "lucent", []),
    ("C: lucent_curvature_method_parse(NULL)",
     "C(L.lucent_curvature_method_parse(None, ctypes.byref(ctypes.c_int())))", "lucent", []),
]
if "--list" in sys.argv:
    print("\n".join(c[0] for c in cases))
    sys.exit(0)

child = r'''
import ctypes, json, os, pathlib, sys
import lucent
L = lucent._L
S, M, MCI, FX, TMP = sys.argv[1:6]
K = lucent.kernel("skin1")
def C(status):
    lucent._check(status)
cases = json.loads(sys.stdin.read())
for i, (label, code, expected, words) in enumerate(cases):
    if i < int(sys.argv[6]):
        continue
    print(json.dumps({"start": i}), flush=True)
    out = {"i": i}
    try:
        r = eval(code)
        out["ok"] = bool(eval(words)) if expected == "ok" else None
        if expected != "ok":
            out["returned"] = repr(r)[:100]
    except Exception as e:
        out["exc"] = type(e).__name__
        out["type_error"] = isinstance(e, TypeError)
        out["value_error"] = isinstance(e, ValueError)
        out["lucent_error"] = isinstance(e, lucent.LucentError)
        out["message"] = str(e)
    print(json.dumps(out), flush=True)
print(json.dumps({"alive": True}), flush=True)
'''


def run_children():
    """Runs the cases in child interpreters; when one dies, the next child starts after the call that
    killed it. Returns {case index: result}, {case index: how the child died} and whether the
    last child ended alive."""
    results, deaths, at = {}, {}, 0
    while at < len(cases):
        p = subprocess.run([sys.executable, "-c", child, os.path.join(fx, "scenes", "trace-small.json"),
                            os.path.join(fx, "mesh", "tetra.ply"), mci, fx, tmp, str(at)],
                           input=json.dumps([list(c[:3]) + [c[3]] for c in cases]), capture_output=True, text=True,
                           env=env, timeout=240)
        started, alive = None, False
        for line in p.stdout.splitlines():
            try:
                d = json.loads(line)
            except ValueError:
                continue
            if "start" in d:
                started = d["start"]
            elif "alive" in d:
                alive = True
            else:
                results[d["i"]] = d
        if alive and p.returncode == 0:
            return results, deaths, True
        if started is None or started in deaths:
            deaths[at] = "the child did not start (exit %d): %s" % (p.returncode, p.stderr[-600:])
            return results, deaths, False
        deaths[started] = "the interpreter died in this call (exit %d): %s" % (p.returncode, p.stderr[-300:])
        at = started + 1
    return results, deaths, False


failed = 0


def check(what, ok, detail=""):
    global failed
    print(("ok   " if ok else "FAIL ") + what + ("" if ok else "  " + str(detail)))
    failed += 0 if ok else 1


results, deaths, alive = run_children()
for i, (label, code, expected, words) in enumerate(cases):
    d = results.get(i)
    if d is None:
        check(label, False, deaths.get(i, "no result"))
        continue
    if expected == "ok":
        check("%s works" % label, d.get("ok") is True, d)
        continue
    if "exc" not in d:
        check(label, False, "no exception: returned %s" % d.get("returned"))
        continue
    cls = {"type": d["type_error"] and d["lucent_error"], "value": d["value_error"] and d["lucent_error"],
           "lucent": d["lucent_error"]}[expected]
    named = all(w in d["message"] for w in words)
    check("%s raises %s: %s" % (label, d["exc"], d["message"]), cls and named,
          "expected a %s error naming %s" % (expected, words))
check("the interpreter is alive after every call", alive and not deaths, "%d calls killed it" % len(deaths))

# The limits _args.py copies from the library: each equals the definition in the file it names.
sys.path.insert(0, os.path.join(source, "python"))
os.environ.setdefault("LUCENT_LIBRARY", env["LUCENT_LIBRARY"])
from lucent import _args  # noqa: E402

for name, (value, where) in _args.COPIED.items():
    text = open(os.path.join(source, where)).read()
    m = re.search(r"\b%s\b\s*(?:=\s*)?\(?([0-9.eE+-]+)" % name, text)
    got = float(m.group(1)) if m else None
    check("%s = %g as in %s" % (name, value, where), got == float(value), got)

print("%d failed" % failed)
sys.exit(1 if failed else 0)
