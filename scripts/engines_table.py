#!/usr/bin/env python3
"""The tables of docs/engines.md from scripts/engines_figures.sh's outputs: per scene and material, the
relative RMS error against the reference of each method and peer (fit and hand), the reference's noise,
and each peer's own noise (two seeds: their relative RMS difference over the object's pixels / sqrt 2).
Usage: engines_table.py OUT_DIR [LUCENT]"""
import json
import math
import os
import struct
import subprocess
import sys

out = sys.argv[1]
lucent = sys.argv[2] if len(sys.argv) > 2 else "build/lucent"
ROWS = [("burley:fit", "burley:hand", "Lucent `burley` (HDRP's sampling)"),
        ("blender-cycles-burley", "blender-cycles-burley:hand", "Cycles, Christensen-Burley"),
        ("blender-cycles", "blender-cycles:hand", "Cycles, Random Walk")]


def pfm(path):
    tmp = path + ".tmp.pfm"
    subprocess.run([lucent, "-q", "image", "convert", path, tmp], check=True, capture_output=True)
    d = open(tmp, "rb").read().split(b"\n", 3)
    os.unlink(tmp)
    w, h = map(int, d[1].split())
    return w, h, struct.unpack("<%df" % (3 * w * h), d[3][:12 * w * h])


def peer_noise(scene_dir, seed2_dir, stem):
    """Relative RMS difference of two seeds over the reference's lit object pixels, / sqrt 2."""
    w, h, ref = pfm(os.path.join(scene_dir, "reference.exr"))
    _, _, a = pfm(os.path.join(scene_dir, stem + ".exr"))
    _, _, b = pfm(os.path.join(seed2_dir, stem + ".exr"))
    bg = min(ref)  # the object: pixels well above the background
    num = den = 0.0
    for i in range(w * h):
        if sum(ref[3 * i:3 * i + 3]) > 3 * bg + 0.01:
            for c in range(3):
                num += (a[3 * i + c] - b[3 * i + c]) ** 2
                den += a[3 * i + c] ** 2
    return math.sqrt(num / den / 2) if den else float("nan")


def main():
    print("| scene | material | reference noise | method | fitted | hand mapping | the peer's own noise |")
    print("|---|---|---|---|---|---|---|")
    for scene in ("spheres-skin", "bunny-skin"):
        for material in ("skin1", "marble", "ketchup"):
            d = os.path.join(out, "%s-%s" % (scene, material))
            if not os.path.exists(os.path.join(d, "results.json")):
                continue
            runs = {}
            for run_dir in (d, d + "-methods"):  # the peers' run, and Lucent's methods' run
                if os.path.exists(os.path.join(run_dir, "results.json")):
                    r = json.load(open(os.path.join(run_dir, "results.json")))["scenes"][0]
                    for m in r["methods"]:
                        runs[m.get("method", m.get("name"))] = (m["rel_rms"], r["reference_noise"],
                                                                r["reference_spp"])
            for fit, hand, title in ROWS:
                if fit not in runs or hand not in runs:
                    continue
                err = {fit: runs[fit][0], hand: runs[hand][0]}
                noise, spp = runs[fit][1], runs[fit][2]
                pn = "-"
                if fit.startswith("blender"):
                    stem = fit.replace(":", "-")
                    seed2 = os.path.join(d + "-seed2", scene)
                    if os.path.exists(os.path.join(seed2, stem + ".exr")):
                        pn = "%.1f%% / %.1f%%" % (100 * peer_noise(os.path.join(d, scene), seed2, stem),
                                                  100 * peer_noise(os.path.join(d, scene), seed2,
                                                                   hand.replace(":", "-")))
                best = "**%.1f%%**" if err[fit] < err[hand] else "%.1f%%"
                print("| %s | %s | %.1f%% (%d spp) | %s | %s | %.1f%% | %s |" % (
                    scene, material, 100 * noise, spp, title, best % (100 * err[fit]), 100 * err[hand], pn))


main()
