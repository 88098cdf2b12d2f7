"""The checks of the Python API's arguments, before ctypes converts them (issue 32).

ctypes alone wraps 2**32 + 17 to 17 in a c_int, truncates 1.5 to 1, reads -5 as 2**64 - 5 in a
c_uint64, passes None as a NULL pointer and cuts a path at an embedded NUL byte. Every argument
of lucent's functions goes through one of the checkers below instead, driven by RULES: one table
of ranges, with messages that name the argument as the CLI's name its option.

The ranges come from the library at run time where it has them (the settings table of
lucent/settings.h: taps, rank, spp, seed, time_limit, the image height); the others are the CLI's
(tools/cmd_*.c) or limits of the library's headers and sources, copied here with their source
(tests/test_python_args.py checks each copy against the file it names)."""
import ctypes
import json
import math
import numbers
import os

# ---- the errors -------------------------------------------------------------------------------

ArgumentError = ValueError  # replaced by bind(): lucent.ArgumentError (a LucentError and a ValueError)
ArgumentTypeError = TypeError  # lucent.ArgumentTypeError (a LucentError and a TypeError)


def bind(error_class):
    """Makes the two error classes from lucent.LucentError (status 1: invalid argument)."""
    global ArgumentError, ArgumentTypeError

    def init(self, message):
        error_class.__init__(self, 1, message)

    ArgumentError = type("ArgumentError", (error_class, ValueError), {
        "__init__": init, "__doc__": "An argument out of its range, not finite or not whole (a LucentError)."})
    ArgumentTypeError = type("ArgumentTypeError", (error_class, TypeError), {
        "__init__": init, "__doc__": "An argument of the wrong type, None included (a LucentError)."})
    return ArgumentError, ArgumentTypeError


# ---- the table of ranges ------------------------------------------------------------------------

class Rule:
    """kind "int" or "real"; the inclusive range [lo, hi] (lo_open: (lo, hi]); zero: what 0 means
    when 0 is allowed outside the range (the default); odd: ints only; where: the range's source."""

    def __init__(self, kind, lo, hi, where, lo_open=False, zero=None, odd=False):
        self.kind, self.lo, self.hi, self.where = kind, lo, hi, where
        self.lo_open, self.zero, self.odd = lo_open, zero, odd


class _Setting(ctypes.Structure):  # lucent_setting (lucent/settings.h)
    _fields_ = [("key", ctypes.c_char_p), ("type", ctypes.c_int), ("offset", ctypes.c_size_t),
                ("size", ctypes.c_size_t), ("default", ctypes.c_double), ("lo", ctypes.c_double),
                ("hi", ctypes.c_double), ("def_text", ctypes.c_char_p), ("choice", ctypes.c_void_p),
                ("parse", ctypes.c_void_p), ("flags", ctypes.c_uint), ("doc", ctypes.c_char_p)]


_SETTING_INT, _SETTING_SEED, _SETTING_ODD = 1, 6, 1

# Copied limits, each with the file that defines it (tests/test_python_args.py reads them there).
COPIED = {
    "LUCENT_MC_MAX_PHOTONS": (1e12, "include/lucent/mc.h"),
    "LUCENT_MC_MIN_BIN": (1e-15, "include/lucent/mc.h"),
    "LUCENT_MC_MAX_EXTENT": (1e12, "include/lucent/mc.h"),
    "LUCENT_PROFILE_MAX_COUNT": (100000000, "src/profile/profile.c"),
    "LUCENT_CDRF_MAX_BINS": (720, "include/lucent/cdrf.h"),
    "LUCENT_CDRF_FIT_MAX_RADII": (16, "include/lucent/cdrf.h"),
    "LUCENT_POOL_MAX_THREADS": (256, "include/lucent/base.h"),
    "LUCENT_BANDS_MAX": (80, "include/lucent/spectral.h"),
    "LUCENT_ENGINE_MAX_LAYERS": (16, "include/lucent/engine.h"),
}
_C = {k: v[0] for k, v in COPIED.items()}

RULES = {}


def load(lib):
    """Fills RULES, reading the settings table of lib (liblucent.so)."""
    find = lib.lucent_setting_find
    find.restype, find.argtypes = ctypes.POINTER(_Setting), [ctypes.c_char_p, ctypes.c_void_p]

    def setting(key, **kw):
        p = find(key.encode(), None)
        s = p.contents
        kind = "int" if s.type in (_SETTING_INT, _SETTING_SEED) else "real"
        return Rule(kind, s.lo, s.hi, "render." + key, odd=bool(s.flags & _SETTING_ODD), **kw)

    def int_(lo, hi, where, **kw):
        return Rule("int", lo, hi, where, **kw)

    def real(lo, hi, where, **kw):
        return Rule("real", lo, hi, where, **kw)

    inf = math.inf
    RULES.update({
        # the settings table
        "taps": setting("taps"),
        "rank": setting("rank"),
        "spp": setting("spp"),
        "seed": setting("seed"),
        "time_limit": setting("time_limit", zero="no limit"),
        "height": setting("height"),
        # the Monte Carlo's limits (lucent/mc.h) and the CLI's "a whole number > 0" (cmd_profile.c)
        "photons": int_(1, _C["LUCENT_MC_MAX_PHOTONS"], "lucent profile --photons; LUCENT_MC_MAX_PHOTONS"),
        "fit_photons": int_(1, _C["LUCENT_MC_MAX_PHOTONS"], "lucent cdrf-fit --photons", zero="the default"),
        "dr": real(_C["LUCENT_MC_MIN_BIN"], _C["LUCENT_MC_MAX_EXTENT"], "LUCENT_MC_MIN_BIN, LUCENT_MC_MAX_EXTENT"),
        "bins": int_(1, _C["LUCENT_PROFILE_MAX_COUNT"], "lucent profile --bins"),
        "fit_bins": int_(2, _C["LUCENT_CDRF_MAX_BINS"], "lucent cdrf-fit --bins", zero="the default"),
        # kernels (cmd_kernel.c); range_mm: 0 is the kernel's own extent, at most a kilometre (the
        # largest length the CLI takes elsewhere, cdrf-fit's radii)
        "k": real(-inf, inf, "lucent kernel --k"),
        "range_mm": real(0, 1e6, "lucent kernel --range", lo_open=True, zero="the kernel's extent"),
        # the CDRF (cmd_cdrf.c)
        "width": int_(2, 8192, "lucent cdrf-lut --width"),
        "lut_height": int_(2, 8192, "lucent cdrf-lut --height"),
        "sigma_max": real(0, 100, "lucent cdrf-lut --sigma-max", lo_open=True),
        "radius": real(0, 1e6, "lucent cdrf-fit --radii", lo_open=True),
        "theta": real(-inf, inf, "radians"),
        "eta": real(-inf, inf, "lucent_material_validate checks its range"),
        "sigma": real(-inf, inf, "radians"),
        # spectral skins (lucent/spectral.h): 0 bands is LUCENT_BANDS_DEFAULT, 0 photons the default
        "bands": int_(1, _C["LUCENT_BANDS_MAX"], "LUCENT_BANDS_MAX", zero="the default"),
        "band_photons": int_(1, _C["LUCENT_MC_MAX_PHOTONS"], "LUCENT_MC_MAX_PHOTONS", zero="the default"),
        # curvature (cmd_curvature.c)
        "smooth": int_(0, 1000, "lucent curvature --smooth"),
        "mm_per_unit": real(0, inf, "lucent curvature --mm-per-unit", lo_open=True),
        # the pool (src/base/pool.c): 0 is LUCENT_THREADS or every core
        "threads": int_(1, _C["LUCENT_POOL_MAX_THREADS"], "LUCENT_POOL_MAX_THREADS", zero="every core"),
        # a kernel's width on a screen (lucent pack)
        "fov_y": real(0, 180, "degrees", lo_open=True),
        "depth_mm": real(0, inf, "mm", lo_open=True),
        "object_height_mm": real(0, inf, "mm", lo_open=True),
        # lucent pack (cmd_pack.c, the desc's checks in src/engine/pack.c)
        "screen": int_(1, 65536, "lucent pack --screen"),
        "lut_side": int_(2, 4096, "lucent pack --lut-size"),
        "kappa_max": real(0, 1e12, "lucent pack --kappa-max", lo_open=True),
        "distance_mm": real(0, 1e12, "lucent pack --distance", lo_open=True, zero="where the object fills the screen"),
        "roughness": real(0, 1, "lucent_pack_desc.roughness", lo_open=True, zero="0.3"),
        "pack_photons": int_(1, _C["LUCENT_MC_MAX_PHOTONS"], "lucent pack --sigma0-photons, --transmit-photons, "
                             "--fit-photons, --fit-model-photons", zero="the default"),
        # lucent fit (cmd_fit.c): T takes twice the profile's photons
        "engine_photons": int_(1, _C["LUCENT_MC_MAX_PHOTONS"] / 2, "lucent fit --photons", zero="the default"),
        "model_photons": int_(1, _C["LUCENT_MC_MAX_PHOTONS"], "lucent fit --model-photons", zero="the default"),
        "thickness": real(0, inf, "lucent fit --layers: mm, the last may be inf", lo_open=True),
    })


# ---- the checkers -------------------------------------------------------------------------------

def _shown(value):
    text = repr(value)
    return (text[:60] + "...") if len(text) > 63 else text


def _type_name(value):
    return "None" if value is None else type(value).__name__


def _range_text(r):
    if r.hi == math.inf:
        return "%s %g" % (">" if r.lo_open else ">=", r.lo)
    if r.kind == "real":
        return "in %s%g, %g]" % ("(" if r.lo_open else "[", r.lo, r.hi)
    return "from %d to %d" % (r.lo, r.hi)


def number(name, value, rule=None):
    """value as an int or float after the checks of RULES[rule or name]."""
    r = RULES[rule or name]
    want = "a whole number" if r.kind == "int" else "a number"
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ArgumentTypeError("%s: expected %s, got %s (%s)" % (name, want, _shown(value), _type_name(value)))
    try:
        x = int(value) if isinstance(value, numbers.Integral) and r.kind == "int" else float(value)
    except (OverflowError, ValueError):
        raise ArgumentError("%s: must be finite, got %s (too large for a float)" % (name, _shown(value)))
    if isinstance(x, float) and not math.isfinite(x):
        raise ArgumentError("%s: must be finite, got %s" % (name, _shown(value)))
    if r.kind == "int":
        if isinstance(x, float):
            if x != math.floor(x):
                raise ArgumentError("%s: expected a whole number, got %s" % (name, _shown(value)))
            x = int(x)
    if x == 0 and r.zero is not None:
        return x
    below = x <= r.lo if r.lo_open else x < r.lo
    if below or x > r.hi:
        zero = " (or 0: %s)" % r.zero if r.zero is not None else ""
        raise ArgumentError("%s: must be %s%s, got %s" % (name, _range_text(r), zero, _shown(value)))
    if r.odd and x % 2 == 0:
        raise ArgumentError("%s: must be odd, got %d" % (name, x))
    return x


def integer(name, value, rule=None):
    return int(number(name, value, rule))


def real(name, value, rule=None):
    return float(number(name, value, rule))


def optional(checker, name, value, *rule):
    """None stays None (the default); anything else goes through checker."""
    return None if value is None else checker(name, value, *rule)


def flag(name, value):
    """True or False (or 1, 0)."""
    if not isinstance(value, numbers.Integral) or value not in (0, 1):
        raise ArgumentTypeError("%s: expected True or False, got %s (%s)" % (name, _shown(value), _type_name(value)))
    return bool(value)


def _no_nul(name, data):
    if b"\0" in data:
        raise ArgumentError("%s: contains a NUL byte" % name)
    return data


def text(name, value):
    """A name (a model, a variant, a method) as bytes for a const char *."""
    if isinstance(value, bytes):
        return _no_nul(name, value)
    if not isinstance(value, str):
        raise ArgumentTypeError("%s: expected a string, got %s (%s)" % (name, _shown(value), _type_name(value)))
    return _no_nul(name, value.encode("utf-8"))


def path(name, value):
    """A file or folder name: str, bytes or os.PathLike (pathlib.Path), as bytes."""
    if not isinstance(value, (str, bytes, os.PathLike)):
        raise ArgumentTypeError("%s: expected a file path (str or pathlib.Path), got %s (%s)"
                                % (name, _shown(value), _type_name(value)))
    data = os.fsencode(value)
    if not data:
        raise ArgumentError("%s: the path is empty" % name)
    return _no_nul(name, data)


def spec(name, value):
    """A material: a preset's name, FILE.json or FILE.json#NAME (str or pathlib.Path), as bytes."""
    if isinstance(value, os.PathLike):
        return path(name, value)
    if not isinstance(value, (str, bytes)):
        raise ArgumentTypeError("%s: expected a material (a preset's name, FILE.json, FILE.json#NAME or a "
                                "lucent.Material), got %s (%s)" % (name, _shown(value), _type_name(value)))
    data = text(name, value)
    if not data:
        raise ArgumentError("%s: the material's name is empty" % name)
    return data


def three(name, value):
    """One number (every channel) or three (R, G, B), finite, as a list of 3 floats."""
    if isinstance(value, (str, bytes)) or not (isinstance(value, numbers.Real) or hasattr(value, "__len__")):
        raise ArgumentTypeError("%s: expected a number or three (R, G, B), got %s (%s)"
                                % (name, _shown(value), _type_name(value)))
    items = [value] * 3 if isinstance(value, numbers.Real) else list(value)
    if len(items) != 3:
        raise ArgumentError("%s: expected one number or three (R, G, B), got %d numbers" % (name, len(items)))
    out = []
    for c, x in enumerate(items):
        item = "%s[%d]" % (name, c)
        if isinstance(x, bool) or not isinstance(x, numbers.Real):
            raise ArgumentTypeError("%s: expected a number, got %s (%s)" % (item, _shown(x), _type_name(x)))
        try:
            x = float(x)
        except OverflowError:
            x = math.inf
        if not math.isfinite(x):
            raise ArgumentError("%s: must be finite, got %s" % (item, _shown(items[c])))
        out.append(x)
    return out


def reals(name, values, rule, at_most):
    """A non-empty sequence of at most at_most numbers, each checked by RULES[rule], as floats."""
    if isinstance(values, (str, bytes)) or not hasattr(values, "__len__"):
        raise ArgumentTypeError("%s: expected a list of numbers, got %s (%s)"
                                % (name, _shown(values), _type_name(values)))
    items = list(values)
    if not 1 <= len(items) <= at_most:
        raise ArgumentError("%s: expected 1 to %d numbers, got %d" % (name, at_most, len(items)))
    return [real("%s[%d]" % (name, i), x, rule) for i, x in enumerate(items)]


def pair(name, values, rule):
    """Two whole numbers (width, height), each checked by RULES[rule], as a tuple of ints."""
    if isinstance(values, (str, bytes)) or not hasattr(values, "__len__"):
        raise ArgumentTypeError("%s: expected (width, height), got %s (%s)" % (name, _shown(values), _type_name(values)))
    items = list(values)
    if len(items) != 2:
        raise ArgumentError("%s: expected (width, height), got %d numbers" % (name, len(items)))
    return tuple(integer("%s[%d]" % (name, i), x, rule) for i, x in enumerate(items))


def names(name, values):
    """A list of names (not one string, whose letters would each be a name), as a list of str."""
    if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
        raise ArgumentTypeError("%s: expected a list of names, got %s (%s)" % (name, _shown(values), _type_name(values)))
    return [text("%s[%d]" % (name, i), v).decode("utf-8") for i, v in enumerate(values)]


def layers(name, values, at_most):
    """[(material, thickness_mm), ...], top first: 1 to at_most layers, each thickness > 0 (the last may be
    float("inf")); the materials as given (lucent.material checks them)."""
    if isinstance(values, (str, bytes)) or not hasattr(values, "__len__"):
        raise ArgumentTypeError("%s: expected a list of (material, thickness_mm), got %s (%s)"
                                % (name, _shown(values), _type_name(values)))
    items = list(values)
    if not 1 <= len(items) <= at_most:
        raise ArgumentError("%s: expected 1 to %d layers, got %d" % (name, at_most, len(items)))
    out = []
    for i, item in enumerate(items):
        if isinstance(item, (str, bytes)) or not hasattr(item, "__len__") or len(item) != 2:
            raise ArgumentTypeError("%s[%d]: expected (material, thickness_mm), got %s (%s)"
                                    % (name, i, _shown(item), _type_name(item)))
        spec_, h = item
        if isinstance(h, numbers.Real) and not isinstance(h, bool) and h == math.inf:
            if i < len(items) - 1:
                raise ArgumentError("%s[%d] thickness: only the last layer may be inf" % (name, i))
            out.append((spec_, math.inf))
            continue
        out.append((spec_, real("%s[%d] thickness" % (name, i), h, "thickness")))
    return out


def overrides(name, values):
    """Scene overrides {"render.width": 256, "objects[0].material": "marble"} as KEY=VALUE bytes."""
    if values is None:
        return []
    if not isinstance(values, dict):
        raise ArgumentTypeError("%s: expected a dict {KEY: VALUE}, got %s (%s)"
                                % (name, _shown(values), _type_name(values)))
    out = []
    for k, v in values.items():
        key = text("%s key" % name, k).decode("utf-8")
        if not key or "=" in key:
            raise ArgumentError("%s: %r is not a KEY (no '=' in it)" % (name, key))
        if isinstance(v, bool):
            v = "true" if v else "false"
        elif isinstance(v, (list, tuple, dict)):
            v = json.dumps(v)
        elif isinstance(v, numbers.Real):
            if isinstance(v, numbers.Integral) and not isinstance(v, bool):
                v = int(v)  # exact, however large: the scene reader checks its range
            elif not math.isfinite(float(v)):
                raise ArgumentError("%s[%r]: must be finite, got %r" % (name, key, v))
        elif not isinstance(v, str):
            raise ArgumentTypeError("%s[%r]: expected a string, a number or a bool, got %s (%s)"
                                    % (name, key, _shown(v), _type_name(v)))
        out.append(_no_nul("%s[%r]" % (name, key), ("%s=%s" % (key, v)).encode("utf-8")))
    return out
