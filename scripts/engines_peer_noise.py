#!/usr/bin/env python3
"""The peers' own noise for docs/engines.md's rendered table (scripts/engines_figures_quick.sh's outputs):
for each peer image of a scene, its relative RMS error against the reference over compare's object mask
(lucent_compare_object_mask of the reference's coverage, so the errors equal compare's), the same for the
second seed's image, and the peer's own noise, sqrt(sum (a - b)^2 / 2 / sum ref^2) over the same pixels
(R, G, B together): the two seeds' difference is pure noise, each carrying half its variance.
Usage: engines_peer_noise.py LIBLUCENT SCENE_DIR SEED2_DIR STEM..."""
import ctypes
import math
import os
import sys


class Img(ctypes.Structure):  # lucent_image (lucent/image.h)
    _fields_ = [("width", ctypes.c_int), ("height", ctypes.c_int), ("channels", ctypes.c_int),
                ("data", ctypes.POINTER(ctypes.c_float))]


L = ctypes.CDLL(sys.argv[1])
L.lucent_image_load.argtypes = [ctypes.c_char_p, ctypes.POINTER(ctypes.POINTER(Img))]
L.lucent_compare_object_mask.argtypes = [ctypes.POINTER(Img), ctypes.POINTER(ctypes.c_float)]
L.lucent_compare_object_mask.restype = ctypes.c_uint64


def load(path):
    ptr = ctypes.POINTER(Img)()
    if L.lucent_image_load(path.encode(), ctypes.byref(ptr)) != 0:
        sys.exit("cannot read %s" % path)
    im = ptr.contents
    return [im.data[i] for i in range(im.width * im.height * im.channels)], im.channels


scene, seed2 = sys.argv[2], sys.argv[3]
cov = ctypes.POINTER(Img)()
L.lucent_image_load(os.path.join(scene, "reference-coverage.exr").encode(), ctypes.byref(cov))
n = cov.contents.width * cov.contents.height
mask = (ctypes.c_float * n)()
count = L.lucent_compare_object_mask(cov, mask)
ref, rc = load(os.path.join(scene, "reference.exr"))
for stem in sys.argv[4:]:
    (a, ac), (b, bc) = load(os.path.join(scene, stem + ".exr")), load(os.path.join(seed2, stem + ".exr"))
    num = den = ea = eb = 0.0
    for i in range(n):
        if mask[i] < 0.5:
            continue
        for c in range(3):
            r, x, y = ref[i * rc + c], a[i * ac + c], b[i * bc + c]
            num += (x - y) ** 2
            den += r * r
            ea += (x - r) ** 2
            eb += (y - r) ** 2
    print("%s: %d pixels; error %.2f%% (seed 2: %.2f%%); its own noise %.2f%%"
          % (stem, count, 100 * math.sqrt(ea / den), 100 * math.sqrt(eb / den), 100 * math.sqrt(num / 2 / den)))
