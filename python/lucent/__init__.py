"""Lucent from Python: materials, diffuse reflectance profiles (Monte Carlo and analytic), MCML
files, separable kernels and their taps, the CDRF look-up table and its sigma0 fit, mesh curvature,
and rendering or path tracing a scene into an array, over liblucent.so (ctypes).

Arrays come back as numpy arrays when numpy is importable, else as lists (images: nested lists
[row][column][channel]). Units are Lucent's: mm, mm^-1, R_d in mm^-2. A failure raises
lucent.LucentError with Lucent's message (naming the file and the field). docs/python.md."""
import ctypes
import math

from . import _args, _lib

__version__ = "0.1.0"

try:
    import numpy as _np
except ImportError:  # numpy is optional
    _np = None

_L, library_path = _lib.load()
_lib.declare(_L)
_L.lucent_log_set_sink(None, None, 4)  # the library never prints; nothing is wanted here

STATUS_NAMES = {1: "invalid argument", 2: "out of memory", 3: "I/O", 4: "parse", 5: "unsupported",
                6: "not found", 7: "GL", 8: "internal"}


class LucentError(Exception):
    """A failure of the library: .status (lucent_status), .message (what the CLI prints)."""

    def __init__(self, status, message):
        super().__init__(message)
        self.status, self.message = status, message


ArgumentError, ArgumentTypeError = _args.bind(LucentError)  # ValueError / TypeError and LucentError
_args.load(_L)  # the table of argument ranges (_args.RULES)


def _check(status):
    if status != 0:
        msg = _L.lucent_last_error()
        raise LucentError(status, msg.decode("utf-8", "replace") if msg else "failed (status %d)" % status)


def _b(text):
    return text.encode("utf-8") if isinstance(text, str) else text


def _array(values, shape=None):
    """A numpy array (float64) when numpy is there, else a list (nested by shape)."""
    vals = list(values)
    if _np is not None:
        a = _np.array(vals, dtype=float)
        return a.reshape(shape) if shape else a
    if shape and len(shape) > 1:
        step = len(vals) // shape[0]
        return [_array(vals[i * step:(i + 1) * step], shape[1:]) for i in range(shape[0])]
    return vals


def _doubles(ptr, n):
    return _array(ptr[:n]) if n else _array([])


_pools = {}


def _pool(threads):
    """A worker pool of `threads` (0: LUCENT_THREADS or all cores), kept for the process."""
    t = _args.integer("threads", threads)
    if t not in _pools:
        _pools[t] = _L.lucent_pool_create(t)
    return _pools[t]


# ---- materials ------------------------------------------------------------------------------

class Material:
    """A homogeneous medium: sigma_a, sigma_s (mm^-1), g per RGB channel and eta. derived() gives
    Jensen et al. 2001's quantities (sigma_t, albedo, rd, mfp, ...)."""

    def __init__(self, c):
        self._c = c

    name = property(lambda self: self._c.name.decode())
    sigma_a = property(lambda self: tuple(self._c.sigma_a))
    sigma_s = property(lambda self: tuple(self._c.sigma_s))
    g = property(lambda self: tuple(self._c.g))
    eta = property(lambda self: self._c.eta)

    def derived(self):
        d = _lib.Derived()
        _L.lucent_material_derive(ctypes.byref(self._c), ctypes.byref(d))
        out = {n: tuple(getattr(d, n)) for n in _lib.DERIVED_FIELDS}
        out["fdr"], out["a"] = d.fdr, d.a
        return out

    def __repr__(self):
        return "Material(%r, sigma_a=%r, sigma_s=%r, g=%r, eta=%r)" % (self.name, self.sigma_a, self.sigma_s,
                                                                        self.g, self.eta)


def material(spec, sigma_a=None, sigma_s=None, g=0.0, eta=1.3):
    """A preset ("skin1", "marble"), FILE.json or FILE.json#NAME; or, with sigma_a and sigma_s
    (mm^-1, three each), a material of your own named spec."""
    if isinstance(spec, Material):
        return spec
    name = _args.spec("spec", spec)
    c = _lib.Material()
    if sigma_a is None:
        if sigma_s is not None:
            raise ArgumentTypeError("sigma_a: expected a number or three (R, G, B) with sigma_s, got None")
        _check(_L.lucent_material_resolve(name, ctypes.byref(c)))
        _check(_L.lucent_skin_resolve(ctypes.byref(c)))  # a spectral skin's equivalent medium (docs/skin.md)
    else:
        if sigma_s is None:
            raise ArgumentTypeError("sigma_s: expected a number or three (R, G, B) with sigma_a, got None")
        c.name = name[:63]
        c.sigma_a[:], c.sigma_s[:] = _args.three("sigma_a", sigma_a), _args.three("sigma_s", sigma_s)
        c.g[:], c.eta = _args.three("g", g), _args.real("eta", eta)
        _check(_L.lucent_material_validate(ctypes.byref(c)))
    return Material(c)


def materials():
    """The presets: Jensen et al. 2001's eleven measured materials, then the spectral skins."""
    out = []
    for i in range(_L.lucent_material_preset_count()):
        c = _lib.Material()
        _check(_L.lucent_material_preset(i, ctypes.byref(c)))
        _check(_L.lucent_skin_resolve(ctypes.byref(c)))
        out.append(Material(c))
    return out


# ---- profiles -------------------------------------------------------------------------------

class Profile:
    """R_d(r) on radial bins: r (bin centres, mm), rd and se (3 x bins, mm^-2), dr, model, and
    rd_total (per channel: the reflectance the bins carry, sum rd pi ((j+1)^2 - j^2) dr^2)."""

    def __init__(self, p):
        c = p.contents
        n = c.count
        self.model, self.dr, self.count = c.model.decode(), c.dr, n
        self.r = _doubles(c.r, n)
        self.rd = _array([v for ch in range(3) for v in c.value[ch][:n]], (3, n))
        self.se = _array([v for ch in range(3) for v in c.error[ch][:n]], (3, n))
        self.rd_total = tuple(_L.lucent_profile_total(p, ch) for ch in range(3))

    def __repr__(self):
        return "Profile(%s, %d bins of %.4g mm, rd_total=%s)" % (self.model, self.count, self.dr,
                                                                  tuple(round(x, 6) for x in self.rd_total))


def _grid(m, dr, bins):
    g = _lib.Grid(dr or 0.0, bins or 0)
    _check(_L.lucent_profile_grid_resolve(ctypes.byref(g), ctypes.byref(m._c), ctypes.byref(g)))
    return g


def _take_profile(fn):
    p = ctypes.POINTER(_lib.ProfileC)()
    _check(fn(ctypes.byref(p)))
    try:
        return Profile(p)
    finally:
        _L.lucent_profile_destroy(p)


def profile(spec, model="mc", photons=1000000, seed=1, dr=None, bins=None, threads=0):
    """The radial profile of a half-space of the material: model "mc" (Monte Carlo with MCML's
    physics: channel c uses seed 4 seed + c, as `lucent profile`; the same result for any thread
    count), "dipole", "better-dipole" or "burley". Grid: Freude Table 6.1 unless dr/bins."""
    m = material(spec)
    model = _args.text("model", model).decode()
    dr, bins = _args.optional(_args.real, "dr", dr), _args.optional(_args.integer, "bins", bins)
    photons, seed = _args.integer("photons", photons), _args.integer("seed", seed)
    _pool(threads)
    g = _grid(m, dr, bins)
    if m._c.skin.layer_count > 0:  # a spectral skin, band by band (docs/skin.md)
        return skin_profile(m, transport="mc" if model == "mc" else model, photons=3 * int(photons) // 20,
                            seed=seed, dr=dr, bins=bins, threads=threads)
    if model == "mc":
        return _profile_mc(m, g, photons, seed, threads)
    if model == "dipole":
        return _take_profile(lambda dest: _L.lucent_profile_dipole(ctypes.byref(m._c), ctypes.byref(g), dest))
    if model == "better-dipole":
        return _take_profile(lambda dest: _L.lucent_profile_better_dipole(ctypes.byref(m._c), ctypes.byref(g), dest))
    if model == "burley":
        if dr or bins:
            raise LucentError(1, "burley: the profile comes on the default grid only (no dr, bins)")
        d = _lib.SourceDesc(b"burley", 0, 0, None)
        return _take_profile(lambda dest: _L.lucent_profile_from_source(ctypes.byref(d), ctypes.byref(m._c), dest))
    raise LucentError(1, "unknown profile model \"%s\" (mc, dipole, better-dipole, burley)" % model)


def _skin_args(transport, bands, photons, seed):
    """The checked arguments of skin_profile and skin_color: transport as bytes, the counts as ints."""
    transport = _args.text("transport", transport)
    if transport not in (b"multipole", b"mc", b"shortcut"):
        raise LucentError(1, "transport: unknown transport \"%s\" (multipole, mc, shortcut)" % transport.decode())
    return (transport, _args.integer("bands", bands), _args.integer("photons", photons, "band_photons"),
            _args.integer("seed", seed))


def skin_profile(spec, transport="multipole", bands=0, photons=0, seed=1, dr=None, bins=None, threads=0):
    """The linear sRGB profile of a spectral skin (docs/skin.md): every band carried by the layered
    "multipole" or the "mc" (photons per band), weighted per radius through CIE 1931 under D65."""
    m = material(spec)
    transport, bands, photons, seed = _skin_args(transport, bands, photons, seed)
    dr, bins = _args.optional(_args.real, "dr", dr), _args.optional(_args.integer, "bins", bins)
    g = _lib.Grid(float(dr or 0), int(bins or 0))
    d = _lib.SkinDesc(bands=bands, transport=transport, photons=photons, seed=seed, pool=_pool(threads), grid=g)
    return _take_profile(lambda dest: _L.lucent_profile_skin(ctypes.byref(m._c), ctypes.byref(d), dest))


def skin_color(spec, transport="multipole", bands=0, photons=0, seed=1, threads=0):
    """A spectral skin's total diffuse reflectance per band and its colour under D65 (transport
    "multipole", "mc", or "shortcut": the three-coefficient shortcut): a dict with center (nm),
    reflectance, xyz, lab, rgb (linear sRGB), ita (degrees) and category."""
    m = material(spec)
    transport, bands, photons, seed = _skin_args(transport, bands, photons, seed)
    d = _lib.SkinDesc(bands=bands, transport=transport, photons=photons, seed=seed, pool=_pool(threads))
    c = _lib.SkinColor()
    _check(_L.lucent_skin_color_of(ctypes.byref(m._c), ctypes.byref(d), ctypes.byref(c)))
    n = c.bands
    return {"center": tuple(c.center[:n]), "reflectance": tuple(c.reflectance[:n]), "xyz": tuple(c.xyz),
            "lab": tuple(c.lab), "rgb": tuple(c.rgb), "ita": c.ita, "category": c.category.decode()}


def ciede2000(lab1, lab2):
    """The CIEDE2000 colour difference of two CIELAB colours (Sharma, Wu & Dalal 2005)."""
    a, b = (ctypes.c_double * 3)(*_args.three("lab1", lab1)), (ctypes.c_double * 3)(*_args.three("lab2", lab2))
    return _L.lucent_ciede2000(a, b)


def _profile_mc(m, g, photons, seed, threads):
    """What `lucent profile MATERIAL --model mc` does, channel by channel (tools/cmd_profile.c)."""
    p = ctypes.POINTER(_lib.ProfileC)()
    _check(_L.lucent_profile_create(ctypes.byref(g), b"mc", ctypes.byref(p)))
    try:
        labels = [b"Monte Carlo R", b"Monte Carlo G", b"Monte Carlo B"]
        for c in range(3):
            layer = _lib.McLayer(m.eta, m.sigma_a[c], m.sigma_s[c], m.g[c], math.inf)
            d = _lib.McDesc(layers=ctypes.pointer(layer), layer_count=1, photons=photons, seed=4 * seed + c,
                            grid=_lib.McGrid(dr=g.dr, nr=g.count), pool=_pool(threads), label=labels[c])
            r = _lib.McResult()
            _check(_L.lucent_mc_run(ctypes.byref(d), ctypes.byref(r)))
            pc = p.contents
            for j in range(g.count):
                pc.value[c][j], pc.error[c][j] = r.rd_r[j], r.rd_r_se[j]
            _L.lucent_mc_result_free(ctypes.byref(r))
        return Profile(p)
    finally:
        _L.lucent_profile_destroy(p)


# ---- MCML -----------------------------------------------------------------------------------

def mcml(mci, seed=1, out_dir=None, threads=0, write=True):
    """Runs every run of an MCML input file (.mci) as `lucent mcml` does (run k with seed + k) and
    writes the .mco files it names (inside out_dir when given). Returns per run a dict with the
    totals (rsp, rd, a, tt and their standard errors), rd_r (per mm^2) and the .mco path."""
    import os
    mci, seed = _args.path("mci", mci), _args.integer("seed", seed)
    out_dir, write = _args.optional(_args.path, "out_dir", out_dir), _args.flag("write", write)
    _pool(threads)
    f = _lib.McmlFile()
    _check(_L.lucent_mcml_load(mci, ctypes.byref(f)))
    out = []
    try:
        for k in range(f.run_count):
            run = f.runs[k]
            run.desc.seed = int(seed) + k
            run.desc.pool = _pool(threads)
            name = run.output
            path = os.path.join(out_dir, os.path.basename(name)) if out_dir else name
            r = _lib.McResult()
            s = _L.lucent_mc_run(ctypes.byref(run.desc), ctypes.byref(r))
            if s != 0:
                _check(s)
            try:
                if write:
                    if out_dir:
                        try:
                            os.makedirs(out_dir, exist_ok=True)
                        except OSError as e:  # a LucentError naming the folder, as the library would
                            raise LucentError(3, "%s: cannot create the folder: %s" % (os.fsdecode(out_dir),
                                                                                       e.strerror or e))
                    _check(_L.lucent_mcml_write(path, ctypes.byref(run), ctypes.byref(r)))
                res = {n: getattr(r, n) for n in _lib.MC_TOTALS}
                res["photons"], res["mco"] = r.photons, os.fsdecode(path) if write else None
                res["rd_r"] = _doubles(r.rd_r, r.grid.nr)
                res["dr"] = r.grid.dr
                out.append(res)
            finally:
                _L.lucent_mc_result_free(ctypes.byref(r))
    finally:
        _L.lucent_mcml_file_free(ctypes.byref(f))
    return out


# ---- kernels and taps -------------------------------------------------------------------------

class Kernel:
    """Importance-sampled taps of a separable kernel: offsets (mm), weights (3 x rank x taps),
    signs (3 x rank), radius (the largest |offset|, mm); width_px(...) on a screen."""

    def __init__(self, t, model):
        c = t.contents
        self.model, self.taps, self.rank = model, c.count, c.rank
        self.offsets = _doubles(c.offset, c.count)
        n = c.rank * c.count
        self.weights = _array([v for ch in range(3) for v in c.weight[ch][:n]], (3, c.rank, c.count))
        self.signs = _array([c.sign[ch][p] for ch in range(3) for p in range(c.rank)], (3, c.rank))
        self.radius = _L.lucent_taps_radius(t)

    def width_px(self, height=1080, fov_y=45.0, depth_mm=None, object_height_mm=1800.0):
        """The kernel's full width in pixels at depth_mm (default: where an object of
        object_height_mm fills the screen's height), as `lucent pack` prints it."""
        height, fov_y = _args.integer("height", height), _args.real("fov_y", fov_y)
        if depth_mm is None:
            depth_mm = _args.real("object_height_mm", object_height_mm) / (2 * math.tan(math.radians(fov_y) / 2))
        depth_mm = _args.real("depth_mm", depth_mm)
        return 2 * self.radius * _L.lucent_screen_pixels_per_mm(height, fov_y, depth_mm)


def kernel(spec, model="preint", rank=1, taps=17, profile="dipole", photons=1000000, seed=1, k=1.0, range_mm=0.0,
           threads=0):
    """A separable kernel of the material as `lucent kernel` builds it (Freude 2014, ch. 5):
    model svd, preint, guided, manual, sog or jimenez; taps per pass (odd)."""
    model = _args.text("model", model).decode()
    m = material(spec) if model != "jimenez" or spec else None
    profile = _args.text("profile", profile)
    photons, seed, rank, taps = (_args.integer(n, v) for n, v in
                                 (("photons", photons), ("seed", seed), ("rank", rank), ("taps", taps)))
    k, range_mm = _args.real("k", k), _args.real("range_mm", range_mm)
    _pool(threads)
    mi = ctypes.c_int()
    _check(_L.lucent_kernel_model_parse(model.encode(), ctypes.byref(mi)))
    p = ctypes.POINTER(_lib.ProfileC)()
    gt, kern, t = ctypes.c_void_p(), ctypes.c_void_p(), ctypes.POINTER(_lib.Taps)()
    try:
        if m is not None:
            d = _lib.SourceDesc(profile, photons, seed, _pool(threads))
            _check(_L.lucent_profile_from_source(ctypes.byref(d), ctypes.byref(m._c), ctypes.byref(p)))
            _check(_L.lucent_kernel2d_from_profile(p, None, ctypes.byref(gt)))
        desc = _lib.KernelDesc(model=mi.value, rank=rank, k=k)
        _check(_L.lucent_kernel_build(gt, p if p else None, _b(m.name) if m else None, ctypes.byref(desc),
                                      ctypes.byref(kern)))
        td = _lib.TapsDesc(taps, range_mm)
        _check(_L.lucent_kernel_taps(kern, ctypes.byref(td), ctypes.byref(t)))
        return Kernel(t, model)
    finally:
        _L.lucent_taps_destroy(t)
        _L.lucent_kernel_destroy(kern)
        _L.lucent_kernel2d_destroy(gt)
        _L.lucent_profile_destroy(p)


# ---- CDRF ------------------------------------------------------------------------------------

def _variant(name):
    v = ctypes.c_int()
    _check(_L.lucent_cdrf_variant_parse(_args.text("variant", name), ctypes.byref(v)))
    return v.value


def _image(ptr):
    c = ptr.contents
    n = c.width * c.height * c.channels
    shape = (c.height, c.width, c.channels)
    if _np is not None:
        return _np.ctypeslib.as_array(c.data, shape=(n,)).astype(_np.float32).reshape(shape)
    return _array(c.data[:n], shape)


def cdrf(theta, sigma, variant="kubo"):
    """Kubo's CDRF at theta (radians) and sigma = sigma0 kappa (radians)."""
    return _L.lucent_cdrf_eval(_variant(variant), _args.real("theta", theta), _args.real("sigma", sigma))


def cdrf_lut(variant="kubo", width=256, height=256, sigma_max=3.0, threads=0):
    """The CDRF look-up table (height x width x 1): column i is cos theta = -1 + 2 i / (width - 1),
    row j (from the top) sigma = sigma_max j / (height - 1)."""
    width, height = _args.integer("width", width), _args.integer("height", height, "lut_height")
    d = _lib.LutDesc(_variant(variant), width, height, _args.real("sigma_max", sigma_max), _pool(threads))
    img = ctypes.POINTER(_lib.Image)()
    _check(_L.lucent_cdrf_lut_build(ctypes.byref(d), ctypes.byref(img)))
    try:
        return _image(img)
    finally:
        _L.lucent_image_destroy(img)


def cdrf_fit(spec, radii=(2.0, 5.0, 10.0, 20.0), photons=0, bins=0, seed=1, variant="kubo", threads=0):
    """Fits sigma0 (mm) and k_d per channel to Monte Carlo spheres of the material (Kubo Fig. 6),
    as `lucent cdrf-fit`. Returns a dict: sigma0, kd, rms, chi2 and Lambert's lambert_kd, ..."""
    m = material(spec)
    radii = _args.reals("radii", radii, "radius", _args.COPIED["LUCENT_CDRF_FIT_MAX_RADII"][0])
    photons, bins = _args.integer("photons", photons, "fit_photons"), _args.integer("bins", bins, "fit_bins")
    rs = (ctypes.c_double * len(radii))(*radii)
    d = _lib.FitDesc(material=ctypes.pointer(m._c), variant=_variant(variant), radii=rs, radius_count=len(radii),
                     photons=photons, bins=bins, seed=_args.integer("seed", seed), pool=_pool(threads))
    f = _lib.Fit()
    _check(_L.lucent_cdrf_fit_material(ctypes.byref(d), ctypes.byref(f), None))
    return {n: tuple(getattr(f, n)) for n in _lib.FIT_FIELDS}


# ---- mesh curvature ----------------------------------------------------------------------------

def curvature(mesh_path, method="rusinkiewicz", smooth=0, mm_per_unit=1.0, threads=0):
    """Per-vertex curvature of a mesh file (PLY, gzipped PLY, OBJ, glTF), in mm^-1: a dict of
    k1, k2, mean, gauss (arrays over the vertices), flags, invalid_count."""
    mesh_path, method = _args.path("mesh_path", mesh_path), _args.text("method", method)
    smooth, mm_per_unit = _args.integer("smooth", smooth), _args.real("mm_per_unit", mm_per_unit)
    _pool(threads)
    mi = ctypes.c_int()
    _check(_L.lucent_curvature_method_parse(method, ctypes.byref(mi)))
    mesh = ctypes.c_void_p()
    _check(_L.lucent_mesh_load(mesh_path, None, ctypes.byref(mesh)))
    c = _lib.Curvature()
    try:
        d = _lib.CurvatureDesc(mi.value, smooth, mm_per_unit, _pool(threads), 0)
        _check(_L.lucent_mesh_curvature(mesh, ctypes.byref(d), ctypes.byref(c)))
        n = c.count
        out = {k: _doubles(getattr(c, k), n) for k in ("k1", "k2", "mean", "gauss")}
        out["flags"] = list(c.flags[:n])
        out["invalid_count"] = c.invalid_count
        return out
    finally:
        _L.lucent_curvature_free(ctypes.byref(c))
        _L.lucent_mesh_destroy(mesh)


# ---- scenes --------------------------------------------------------------------------------------

def _scene(path, settings):
    path, items = _args.path("scene_path", path), _args.overrides("settings", settings)
    arr = (ctypes.c_char_p * max(len(items), 1))(*items)
    d = _lib.SceneLoadDesc(arr, len(items), False)
    sc = ctypes.c_void_p()
    _check(_L.lucent_scene_load(path, ctypes.byref(d), ctypes.byref(sc)))
    return sc


def render(scene_path, method=None, settings=None, threads=0, cache_dir=None):
    """Renders a scene file with OpenGL (as `lucent render`); settings are scene overrides
    {"render.width": 256, "objects[0].material": "marble"}. Returns (image, mask): linear RGB
    radiance height x width x 3 and the object mask height x width x 1."""
    if settings is not None and not isinstance(settings, dict):
        _args.overrides("settings", settings)  # raises, naming the argument
    settings = dict(settings or {})
    if method is not None:
        settings["render.method"] = _args.text("method", method).decode()
    cache_dir = _args.optional(_args.path, "cache_dir", cache_dir)
    _pool(threads)
    sc = _scene(scene_path, settings)
    ctx, r = ctypes.c_void_p(), ctypes.c_void_p()
    res = _lib.RenderResult()
    try:
        _check(_L.lucent_gl_create(None, ctypes.byref(ctx)))
        rd = _lib.RendererDesc(_pool(threads), cache_dir, 0, 0, 0)
        _check(_L.lucent_renderer_create(ctx, sc, ctypes.byref(rd), ctypes.byref(r)))
        _check(_L.lucent_render(r, None, ctypes.byref(res)))
        return _image(res.image), _image(res.mask)
    finally:
        _L.lucent_render_result_free(ctypes.byref(res))
        _L.lucent_renderer_destroy(r)
        _L.lucent_gl_destroy(ctx)
        _L.lucent_scene_destroy(sc)


def trace(scene_path, spp=16, seed=1, settings=None, threads=0, time_limit=0):
    """Path-traces a scene file (as `lucent trace`). Returns (image, variance): the mean linear RGB
    radiance and its variance, height x width x 3 each. time_limit: seconds (0: none)."""
    spp, seed = _args.integer("spp", spp), _args.integer("seed", seed)
    time_limit = _args.real("time_limit", time_limit)
    _pool(threads)
    sc = _scene(scene_path, settings)
    tr = ctypes.c_void_p()
    res = _lib.TraceResult()
    try:
        _check(_L.lucent_tracer_create(sc, ctypes.byref(_lib.TracerDesc()), ctypes.byref(tr)))
        d = _lib.TraceDesc(spp, seed, _pool(threads), time_limit if time_limit > 0 else -1.0, 0.0, b"trace")
        _check(_L.lucent_tracer_render(tr, ctypes.byref(d), ctypes.byref(res)))
        return _image(res.image), _image(res.variance)
    finally:
        _L.lucent_trace_result_free(ctypes.byref(res))
        _L.lucent_tracer_destroy(tr)
        _L.lucent_scene_destroy(sc)


def pack(spec, engine, out, screen=(1920, 1080), fov=45.0, object_height_mm=1800.0, distance_mm=0.0,
         lut_size=(64, 64), kappa_max=1.0, sigma0_photons=0, transmit_photons=0, mesh=None, roughness=0.3,
         cache_dir=None, threads=0, fit=True, fit_photons=0, fit_model_photons=0):
    """Writes the engine pack of a material into the folder out, as `lucent pack` (docs/pack.md):
    engine "glsl", "gles", "vulkan", "hlsl" or "json"; the screen (width, height) in pixels with
    vertical field of view fov (degrees); the object's height (its mesh in material.gltf, a sphere
    unless mesh names a mesh file) and the depth the kernel's width is measured at (distance_mm, 0:
    where the object fills the screen's height). The renderer's default settings. The README's engine
    parameters are fitted as fit() fits them (fit_photons, fit_model_photons: its photons and
    model_photons, 0: the defaults; fit=False leaves them out). Returns a dict:
    radius_mm, depth_mm, pixels_per_mm, width_px, pixels_per_mm_at_1mm, thickness_m, file_count."""
    m = material(spec)
    engine_name, out_path = _args.text("engine", engine), _args.path("out", out)
    width, height = _args.pair("screen", screen, "screen")
    lut_w, lut_h = _args.pair("lut_size", lut_size, "lut_side")
    fov, height_mm = _args.real("fov", fov, "fov_y"), _args.real("object_height_mm", object_height_mm)
    distance_mm, kappa_max = _args.real("distance_mm", distance_mm), _args.real("kappa_max", kappa_max)
    roughness, fit = _args.real("roughness", roughness), _args.flag("fit", fit)
    photons = [_args.integer(n, v, "pack_photons") for n, v in (("sigma0_photons", sigma0_photons),
               ("transmit_photons", transmit_photons), ("fit_photons", fit_photons),
               ("fit_model_photons", fit_model_photons))]
    mesh, cache_dir = _args.optional(_args.path, "mesh", mesh), _args.optional(_args.path, "cache_dir", cache_dir)
    pool = _pool(threads)
    e = ctypes.c_int()
    _check(_L.lucent_pack_engine_find(engine_name, ctypes.byref(e)))
    mp, cache = ctypes.c_void_p(), ctypes.c_void_p()
    try:
        if mesh:
            _check(_L.lucent_mesh_load(mesh, None, ctypes.byref(mp)))
        if cache_dir:
            _check(_L.lucent_cache_create(cache_dir, ctypes.byref(cache)))
        d = _lib.PackDesc(e.value, out_path, width, height, fov, height_mm, distance_mm, None, lut_w, lut_h, kappa_max,
                          photons[0], photons[1], mp, roughness, cache, pool, photons[2], photons[3], not fit)
        r = _lib.PackResult()
        _check(_L.lucent_pack(ctypes.byref(m._c), ctypes.byref(d), ctypes.byref(r)))
        return {n: getattr(r, n) for n, _ in _lib.PackResult._fields_}
    finally:
        _L.lucent_mesh_destroy(mp)
        _L.lucent_cache_destroy(cache)


# ---- engines ----------------------------------------------------------------------------------

def fit(spec=None, layers=None, engines=None, photons=0, model_photons=0, seed=1, transmittance=False, hand=True,
        cache_dir=None, threads=0):
    """Each engine's subsurface parameters fitted to a material's truth, as `lucent fit` (docs/engines.md):
    a dict with "truth" (T, r99, the profile's noise) and "engines", a list of per-engine dicts with
    "engine", "parameters" (name, value, unit, in the engine's own terms), "profile_error", "delta_e2000",
    "cannot_express", "notes" and, with hand, "hand_mapping" (radius = 1/sigma_tr, colour = T).
    spec: a material (preset, FILE.json, FILE.json#NAME or a Material); layers: [(spec, thickness_mm), ...]
    top first, the last may be float("inf"); a spectral skin as spec is fitted through its equivalent medium,
    in layers it is refused. engines: names ("unreal-burley", "unity-hdrp", "blender3-burley", ..., "gltf";
    None: all). photons: the truth's profile photons per channel (0: 200000; given, T takes twice as
    many, else the bake's 400000, kept in cache_dir)."""
    import json
    photons, model_photons = _args.integer("photons", photons, "engine_photons"), _args.integer(
        "model_photons", model_photons)
    seed, transmittance, hand = _args.integer("seed", seed), _args.flag("transmittance", transmittance), _args.flag(
        "hand", hand)
    cache_dir = _args.optional(_args.path, "cache_dir", cache_dir)
    ids = []
    for name in _args.optional(_args.names, "engines", engines) or []:
        e = ctypes.c_int()
        _check(_L.lucent_engine_parse(_b(name), ctypes.byref(e)))
        ids.append(e.value)
    d = _lib.EngineReportDesc()
    keep = []
    if layers is not None:
        layers = _args.layers("layers", layers, _args.COPIED["LUCENT_ENGINE_MAX_LAYERS"][0])
        arr = (_lib.Layer * len(layers))()
        for i, (lspec, thickness) in enumerate(layers):
            arr[i].material = material(lspec)._c
            arr[i].slab.thickness = thickness
        d.target.layers, d.target.layer_count = arr, len(layers)
        keep.append(arr)
    else:
        m = material(spec)
        d.target.material = ctypes.pointer(m._c)
        keep.append(m)
    d.target.photons = photons
    d.target.total_photons = 2 * photons
    d.target.seed = seed
    d.target.transmittance = transmittance
    d.target.pool = d.fit.pool = _pool(threads)
    d.fit.model_photons = model_photons
    d.hand = hand
    if ids:
        d.engines, d.engine_count = (ctypes.c_int * len(ids))(*ids), len(ids)
    cache = ctypes.c_void_p()
    if cache_dir:
        _check(_L.lucent_cache_create(cache_dir, ctypes.byref(cache)))
        d.target.cache = cache
    report, text = ctypes.c_void_p(), ctypes.c_void_p()
    try:
        _check(_L.lucent_engine_report_create(ctypes.byref(d), ctypes.byref(report)))
        _check(_L.lucent_engine_report_json(report, ctypes.byref(text)))
        return json.loads(ctypes.string_at(text).decode("utf-8"))
    finally:
        if text:
            _libc_free(text)
        _L.lucent_engine_report_destroy(report)
        _L.lucent_cache_destroy(cache)


def _libc_free(ptr):
    libc = ctypes.CDLL(None)
    libc.free.argtypes = [ctypes.c_void_p]
    libc.free(ptr)


def versions():
    """What the library links: {"lucent", "embree", "openexr", "library"}."""
    return {"lucent": __version__, "embree": _L.lucent_trace_embree_version().decode(),
            "openexr": _L.lucent_image_openexr_version().decode(), "library": library_path}


def isa(name=None):
    """The Monte Carlo's SIMD path (docs/mcml.md, "SIMD paths"): with a name ("auto", "scalar", "avx2",
    "avx512") chooses it for the process, as the CLI's --isa (raises when the CPU lacks it); returns
    the path in use."""
    if name is not None:
        v = ctypes.c_int()
        _check(_L.lucent_isa_parse(_b(name), ctypes.byref(v)))
        _check(_L.lucent_isa_set(v.value))
    return _L.lucent_isa_name(_L.lucent_isa_active()).decode()


__all__ = ["LucentError", "ArgumentError", "ArgumentTypeError", "Material", "material", "materials", "Profile", "profile", "skin_profile", "skin_color", "ciede2000", "mcml", "Kernel", "kernel",
           "cdrf", "cdrf_lut", "cdrf_fit", "curvature", "render", "trace", "pack", "fit", "versions", "isa"]
