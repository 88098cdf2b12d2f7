"""Loading liblucent.so and the C structures the Python API passes to it (ctypes).

The structures mirror include/lucent/*.h field by field; tests/test_python.py checks them against
the library (lucent_python_struct_sizes is not needed: every call here goes through a pointer to a
structure the C side fills or reads, and the tests compare results with the CLI's)."""
import ctypes
import ctypes.util
import glob
import os

c_double_p = ctypes.POINTER(ctypes.c_double)
c_float_p = ctypes.POINTER(ctypes.c_float)
c_void_p = ctypes.c_void_p
c_char_p = ctypes.c_char_p


def _candidates():
    """Where liblucent.so may be, in order: $LUCENT_LIBRARY; inside the package (pip install copies
    the build's library there); an installed prefix (PREFIX/lib/python3/site-packages/lucent ->
    PREFIX/lib); the repository's build/ (python/lucent -> build/); the loader's search path."""
    env = os.environ.get("LUCENT_LIBRARY")
    if env:
        yield env
    here = os.path.dirname(os.path.abspath(__file__))
    for d in (here, os.path.join(here, "..", "..", ".."), os.path.join(here, "..", "..", "build")):
        for name in ["liblucent.so"] + sorted(glob.glob(os.path.join(d, "liblucent.so.*")), reverse=True):
            path = os.path.normpath(os.path.join(d, name))
            if os.path.exists(path):
                yield path
    found = ctypes.util.find_library("lucent")
    if found:
        yield found


def load():
    tried = []
    for path in _candidates():
        try:
            return ctypes.CDLL(path), path
        except OSError as e:
            tried.append("%s (%s)" % (path, e))
    raise ImportError("lucent: cannot find liblucent.so; set LUCENT_LIBRARY to its path, or install Lucent "
                      "(make install PREFIX=...) and put PREFIX/lib/python3/site-packages on PYTHONPATH"
                      + ("; tried " + ", ".join(tried) if tried else ""))


class SkinLayer(ctypes.Structure):  # lucent_skin_layer (material.h)
    _fields_ = [("kind", ctypes.c_int), ("reserved", ctypes.c_int)] + [
        (n, ctypes.c_double) for n in ("thickness", "melanin", "eumelanin", "blood", "oxygenation", "scatter",
                                       "f_rayleigh", "b_mie", "g")]


class Skin(ctypes.Structure):  # lucent_skin (material.h)
    _fields_ = [("layer_count", ctypes.c_int), ("resolved", ctypes.c_int), ("layer", SkinLayer * 3)]


class Material(ctypes.Structure):  # lucent_material (material.h)
    _fields_ = [("name", ctypes.c_char * 64), ("sigma_a", ctypes.c_double * 3), ("sigma_s", ctypes.c_double * 3),
                ("g", ctypes.c_double * 3), ("eta", ctypes.c_double), ("skin", Skin)]


DERIVED_FIELDS = ["sigma_s_prime", "sigma_t", "sigma_t_prime", "albedo", "albedo_prime", "sigma_tr", "diffusion",
                  "mfp", "mfp_prime", "mfp_diffuse", "rd"]


class Derived(ctypes.Structure):  # lucent_material_derived
    _fields_ = [(n, ctypes.c_double * 3) for n in DERIVED_FIELDS] + [("fdr", ctypes.c_double), ("a", ctypes.c_double)]


class ProfileC(ctypes.Structure):  # lucent_profile (profile.h)
    _fields_ = [("count", ctypes.c_int), ("dr", ctypes.c_double), ("r", c_double_p), ("value", c_double_p * 3),
                ("error", c_double_p * 3), ("model", ctypes.c_char * 32)]


class Grid(ctypes.Structure):  # lucent_profile_grid
    _fields_ = [("dr", ctypes.c_double), ("count", ctypes.c_int)]


class SkinDesc(ctypes.Structure):  # lucent_skin_desc (skin.h)
    _fields_ = [("bands", ctypes.c_int), ("transport", c_char_p), ("photons", ctypes.c_uint64),
                ("seed", ctypes.c_uint64), ("pool", c_void_p), ("grid", Grid), ("cache", c_void_p)]


class SkinColor(ctypes.Structure):  # lucent_skin_color (skin.h)
    _fields_ = [("bands", ctypes.c_int), ("center", ctypes.c_double * 80), ("reflectance", ctypes.c_double * 80),
                ("reflectance_se", ctypes.c_double * 80), ("xyz", ctypes.c_double * 3), ("lab", ctypes.c_double * 3),
                ("rgb", ctypes.c_double * 3), ("ita", ctypes.c_double), ("category", c_char_p)]


class SourceDesc(ctypes.Structure):  # lucent_profile_source_desc
    _fields_ = [("source", c_char_p), ("photons", ctypes.c_uint64), ("seed", ctypes.c_uint64), ("pool", c_void_p),
                ("grid", Grid)]


class McLayer(ctypes.Structure):  # lucent_mc_layer (mc.h)
    _fields_ = [("n", ctypes.c_double), ("sigma_a", ctypes.c_double), ("sigma_s", ctypes.c_double),
                ("g", ctypes.c_double), ("thickness", ctypes.c_double)]


class McGrid(ctypes.Structure):  # lucent_mc_grid
    _fields_ = [("dr", ctypes.c_double), ("dz", ctypes.c_double), ("nr", ctypes.c_int), ("nz", ctypes.c_int),
                ("na", ctypes.c_int)]


class McDesc(ctypes.Structure):  # lucent_mc_desc
    _fields_ = [("layers", ctypes.POINTER(McLayer)), ("layer_count", ctypes.c_int), ("n_above", ctypes.c_double),
                ("n_below", ctypes.c_double), ("photons", ctypes.c_uint64), ("seed", ctypes.c_uint64),
                ("grid", McGrid), ("score_a_rz", ctypes.c_bool), ("last_bin_collects", ctypes.c_bool),
                ("batches", ctypes.c_int), ("pool", c_void_p), ("label", c_char_p)]


MC_ARRAYS = ["a_layer", "a_layer_se", "rd_r", "rd_r_se", "tt_r", "tt_r_se", "rd_a", "rd_a_se", "tt_a", "tt_a_se",
             "a_z", "a_z_se", "rd_ra", "tt_ra", "a_rz"]
MC_TOTALS = ["rsp", "rd", "rd_se", "a", "a_se", "tt", "tt_se", "balance", "balance_se", "rd_beyond", "tt_beyond",
             "a_z_beyond"]


class McResult(ctypes.Structure):  # lucent_mc_result
    _fields_ = ([("photons", ctypes.c_uint64), ("batches", ctypes.c_int), ("layer_count", ctypes.c_int),
                 ("grid", McGrid)] + [(n, ctypes.c_double) for n in MC_TOTALS] + [(n, c_double_p) for n in MC_ARRAYS])


class McmlRun(ctypes.Structure):  # lucent_mcml_run
    _fields_ = [("output", c_char_p), ("line", ctypes.c_int), ("layers", ctypes.POINTER(McLayer)), ("desc", McDesc)]


class McmlFile(ctypes.Structure):  # lucent_mcml_file
    _fields_ = [("version", ctypes.c_double), ("run_count", ctypes.c_int), ("runs", ctypes.POINTER(McmlRun))]


class Taps(ctypes.Structure):  # lucent_taps (kernel.h)
    _fields_ = [("count", ctypes.c_int), ("rank", ctypes.c_int), ("offset", c_double_p), ("weight", c_double_p * 3),
                ("sign", (ctypes.c_double * 16) * 3)]


class TapsDesc(ctypes.Structure):  # lucent_taps_desc
    _fields_ = [("count", ctypes.c_int), ("range", ctypes.c_double)]


class ManualParams(ctypes.Structure):  # lucent_manual_params
    _fields_ = [("sd_near", ctypes.c_double * 3), ("sd_far", ctypes.c_double * 3), ("w", ctypes.c_double)]


class KernelDesc(ctypes.Structure):  # lucent_kernel_desc
    _fields_ = [("model", ctypes.c_int), ("rank", ctypes.c_int), ("normalize", ctypes.c_bool), ("k", ctypes.c_double),
                ("b", ctypes.c_double), ("max_evaluations", ctypes.c_int), ("use_manual", ctypes.c_bool),
                ("manual", ManualParams), ("strength", ctypes.c_double * 3), ("falloff", ctypes.c_double * 3)]


class Image(ctypes.Structure):  # lucent_image (image.h)
    _fields_ = [("width", ctypes.c_int), ("height", ctypes.c_int), ("channels", ctypes.c_int), ("data", c_float_p)]


class LutDesc(ctypes.Structure):  # lucent_cdrf_lut_desc (cdrf.h)
    _fields_ = [("variant", ctypes.c_int), ("width", ctypes.c_int), ("height", ctypes.c_int),
                ("sigma_max", ctypes.c_double), ("pool", c_void_p)]


class FitDesc(ctypes.Structure):  # lucent_cdrf_material_fit_desc
    _fields_ = [("material", ctypes.POINTER(Material)), ("variant", ctypes.c_int), ("radii", c_double_p),
                ("radius_count", ctypes.c_int), ("photons", ctypes.c_uint64), ("bins", ctypes.c_int),
                ("roughness", ctypes.c_double), ("cone", ctypes.c_double), ("seed", ctypes.c_uint64),
                ("sigma0_max", ctypes.c_double), ("pool", c_void_p), ("label", c_char_p)]


FIT_FIELDS = ["sigma0", "kd", "rms", "chi2", "lambert_kd", "lambert_rms", "lambert_chi2"]


class Fit(ctypes.Structure):  # lucent_cdrf_fit
    _fields_ = [("variant", ctypes.c_int)] + [(n, ctypes.c_double * 3) for n in FIT_FIELDS]


class CurvatureDesc(ctypes.Structure):  # lucent_curvature_desc (mesh.h)
    _fields_ = [("method", ctypes.c_int), ("smooth_rings", ctypes.c_int), ("mm_per_unit", ctypes.c_double),
                ("pool", c_void_p), ("fast", ctypes.c_int)]


class Curvature(ctypes.Structure):  # lucent_curvature
    _fields_ = [("count", ctypes.c_size_t), ("k1", c_double_p), ("k2", c_double_p), ("mean", c_double_p),
                ("gauss", c_double_p), ("dir1", c_double_p), ("dir2", c_double_p),
                ("flags", ctypes.POINTER(ctypes.c_uint8)), ("invalid_count", ctypes.c_size_t)]


class SceneLoadDesc(ctypes.Structure):  # lucent_scene_load_desc (scene.h)
    _fields_ = [("overrides", ctypes.POINTER(c_char_p)), ("override_count", ctypes.c_int),
                ("skip_meshes", ctypes.c_bool)]


class RendererDesc(ctypes.Structure):  # lucent_renderer_desc (render.h)
    _fields_ = [("pool", c_void_p), ("cache_dir", c_char_p), ("sigma0_photons", ctypes.c_uint64),
                ("transmit_photons", ctypes.c_uint64), ("profile_photons", ctypes.c_uint64),
                ("boundary_photons", ctypes.c_uint64), ("sphere_photons", ctypes.c_uint64),
                ("sheet_photons", ctypes.c_uint64)]


class RenderResult(ctypes.Structure):  # lucent_render_result: the images, then what Python does not read
    _fields_ = [("image", ctypes.POINTER(Image)), ("mask", ctypes.POINTER(Image)), ("rest", ctypes.c_double * 512)]


class TracerDesc(ctypes.Structure):  # lucent_tracer_desc (trace.h)
    _fields_ = [("subsurface_only", ctypes.c_bool), ("boundary_nee_only", ctypes.c_bool), ("adaptive", ctypes.c_bool)]


class TraceDesc(ctypes.Structure):  # lucent_trace_desc
    _fields_ = [("spp", ctypes.c_int), ("seed", ctypes.c_uint64), ("pool", c_void_p), ("time_limit", ctypes.c_double),
                ("target_error", ctypes.c_double), ("label", c_char_p)]


class TraceResult(ctypes.Structure):  # lucent_trace_result: the images, spp, samples, seed, seconds, then more
    _fields_ = [("image", ctypes.POINTER(Image)), ("variance", ctypes.POINTER(Image)),
                ("coverage", ctypes.POINTER(Image)), ("spp", ctypes.c_uint64), ("samples", ctypes.c_uint64),
                ("seed", ctypes.c_uint64), ("seconds", ctypes.c_double), ("rest", ctypes.c_double * 64)]


class PackDesc(ctypes.Structure):  # lucent_pack_desc (pack.h)
    _fields_ = [("engine", ctypes.c_int), ("out", c_char_p), ("screen_width", ctypes.c_int),
                ("screen_height", ctypes.c_int), ("fov_y", ctypes.c_double), ("object_height_mm", ctypes.c_double),
                ("distance_mm", ctypes.c_double), ("settings", c_void_p), ("lut_width", ctypes.c_int),
                ("lut_height", ctypes.c_int), ("kappa_max", ctypes.c_double), ("sigma0_photons", ctypes.c_uint64),
                ("transmit_photons", ctypes.c_uint64), ("mesh", c_void_p), ("roughness", ctypes.c_double),
                ("cache", c_void_p), ("pool", c_void_p), ("fit_photons", ctypes.c_uint64),
                ("fit_model_photons", ctypes.c_uint64), ("no_fit", ctypes.c_bool)]


class PackResult(ctypes.Structure):  # lucent_pack_result
    _fields_ = [(n, ctypes.c_double) for n in ("radius_mm", "depth_mm", "pixels_per_mm", "width_px",
                                               "pixels_per_mm_at_1mm", "thickness_m")] + [("file_count", ctypes.c_int)]


class SlabDesc(ctypes.Structure):  # lucent_slab_desc (profile.h)
    _fields_ = [("thickness", ctypes.c_double), ("poles", ctypes.c_int), ("eta_above", ctypes.c_double),
                ("eta_below", ctypes.c_double)]


class Layer(ctypes.Structure):  # lucent_layer (profile.h)
    _fields_ = [("material", Material), ("slab", SlabDesc)]


class EngineTargetDesc(ctypes.Structure):  # lucent_engine_target_desc (engine.h)
    _fields_ = [("material", ctypes.POINTER(Material)), ("layers", ctypes.POINTER(Layer)), ("layer_count", ctypes.c_int),
                ("photons", ctypes.c_uint64), ("total_photons", ctypes.c_uint64), ("seed", ctypes.c_uint64),
                ("transmittance", ctypes.c_bool), ("pool", c_void_p), ("cache", c_void_p)]


class EngineFitDesc(ctypes.Structure):  # lucent_engine_fit_desc
    _fields_ = [("model_photons", ctypes.c_uint64), ("pool", c_void_p)]


class EngineReportDesc(ctypes.Structure):  # lucent_engine_report_desc
    _fields_ = [("target", EngineTargetDesc), ("engines", ctypes.POINTER(ctypes.c_int)), ("engine_count", ctypes.c_int),
                ("hand", ctypes.c_bool), ("fit", EngineFitDesc)]


def declare(lib):
    """Argument and result types of the functions the API calls."""
    P = ctypes.POINTER
    st = ctypes.c_int
    sigs = {
        "lucent_last_error": (c_char_p, []),
        "lucent_engine_parse": (st, [c_char_p, P(ctypes.c_int)]),
        "lucent_engine_report_create": (st, [P(EngineReportDesc), P(c_void_p)]),
        "lucent_engine_report_destroy": (None, [c_void_p]),
        "lucent_engine_report_json": (st, [c_void_p, P(c_void_p)]),
        "lucent_cache_create": (st, [c_char_p, P(c_void_p)]),
        "lucent_cache_destroy": (None, [c_void_p]),
        "lucent_clear_error": (None, []),
        "lucent_pool_create": (c_void_p, [ctypes.c_int]),
        "lucent_pool_destroy": (None, [c_void_p]),
        "lucent_log_set_sink": (None, [c_void_p, c_void_p, ctypes.c_int]),
        "lucent_material_preset_count": (ctypes.c_int, []),
        "lucent_material_preset": (st, [ctypes.c_int, P(Material)]),
        "lucent_material_resolve": (st, [c_char_p, P(Material)]),
        "lucent_skin_resolve": (st, [P(Material)]),
        "lucent_skin_color_of": (st, [P(Material), P(SkinDesc), P(SkinColor)]),
        "lucent_ciede2000": (ctypes.c_double, [c_double_p, c_double_p]),
        "lucent_profile_skin": (st, [P(Material), P(SkinDesc), P(P(ProfileC))]),
        "lucent_material_validate": (st, [P(Material)]),
        "lucent_material_derive": (None, [P(Material), P(Derived)]),
        "lucent_profile_grid_resolve": (st, [P(Grid), P(Material), P(Grid)]),
        "lucent_profile_create": (st, [P(Grid), c_char_p, P(P(ProfileC))]),
        "lucent_profile_destroy": (None, [P(ProfileC)]),
        "lucent_profile_total": (ctypes.c_double, [P(ProfileC), ctypes.c_int]),
        "lucent_profile_dipole": (st, [P(Material), P(Grid), P(P(ProfileC))]),
        "lucent_profile_better_dipole": (st, [P(Material), P(Grid), P(P(ProfileC))]),
        "lucent_profile_from_source": (st, [P(SourceDesc), P(Material), P(P(ProfileC))]),
        "lucent_mc_run": (st, [P(McDesc), P(McResult)]),
        "lucent_mc_result_free": (None, [P(McResult)]),
        "lucent_mcml_load": (st, [c_char_p, P(McmlFile)]),
        "lucent_mcml_file_free": (None, [P(McmlFile)]),
        "lucent_mcml_write": (st, [c_char_p, P(McmlRun), P(McResult)]),
        "lucent_kernel_model_parse": (st, [c_char_p, P(ctypes.c_int)]),
        "lucent_kernel_defaults": (KernelDesc, [ctypes.c_int]),
        "lucent_kernel2d_from_profile": (st, [P(ProfileC), c_void_p, P(c_void_p)]),
        "lucent_kernel2d_destroy": (None, [c_void_p]),
        "lucent_kernel_build": (st, [c_void_p, P(ProfileC), c_char_p, P(KernelDesc), P(c_void_p)]),
        "lucent_kernel_destroy": (None, [c_void_p]),
        "lucent_kernel_taps": (st, [c_void_p, P(TapsDesc), P(P(Taps))]),
        "lucent_taps_destroy": (None, [P(Taps)]),
        "lucent_taps_radius": (ctypes.c_double, [P(Taps)]),
        "lucent_screen_pixels_per_mm": (ctypes.c_double, [ctypes.c_int, ctypes.c_double, ctypes.c_double]),
        "lucent_image_destroy": (None, [P(Image)]),
        "lucent_image_load": (st, [c_char_p, P(P(Image))]),
        "lucent_cdrf_variant_parse": (st, [c_char_p, P(ctypes.c_int)]),
        "lucent_cdrf_eval": (ctypes.c_double, [ctypes.c_int, ctypes.c_double, ctypes.c_double]),
        "lucent_cdrf_lut_build": (st, [P(LutDesc), P(P(Image))]),
        "lucent_cdrf_fit_material": (st, [P(FitDesc), P(Fit), c_void_p]),
        "lucent_mesh_load": (st, [c_char_p, c_void_p, P(c_void_p)]),
        "lucent_mesh_destroy": (None, [c_void_p]),
        "lucent_mesh_curvature": (st, [c_void_p, P(CurvatureDesc), P(Curvature)]),
        "lucent_curvature_free": (None, [P(Curvature)]),
        "lucent_curvature_method_parse": (st, [c_char_p, P(ctypes.c_int)]),
        "lucent_scene_load": (st, [c_char_p, P(SceneLoadDesc), P(c_void_p)]),
        "lucent_scene_destroy": (None, [c_void_p]),
        "lucent_gl_create": (st, [c_void_p, P(c_void_p)]),
        "lucent_gl_destroy": (None, [c_void_p]),
        "lucent_renderer_create": (st, [c_void_p, c_void_p, P(RendererDesc), P(c_void_p)]),
        "lucent_renderer_destroy": (None, [c_void_p]),
        "lucent_render": (st, [c_void_p, c_void_p, P(RenderResult)]),
        "lucent_render_result_free": (None, [P(RenderResult)]),
        "lucent_tracer_create": (st, [c_void_p, P(TracerDesc), P(c_void_p)]),
        "lucent_tracer_destroy": (None, [c_void_p]),
        "lucent_tracer_render": (st, [c_void_p, P(TraceDesc), P(TraceResult)]),
        "lucent_trace_result_free": (None, [P(TraceResult)]),
        "lucent_trace_embree_version": (c_char_p, []),
        "lucent_image_openexr_version": (c_char_p, []),
        "lucent_cache_create": (st, [c_char_p, P(c_void_p)]),
        "lucent_cache_destroy": (None, [c_void_p]),
        "lucent_pack_engine_find": (st, [c_char_p, P(ctypes.c_int)]),
        "lucent_pack": (st, [P(Material), P(PackDesc), P(PackResult)]),
        "lucent_isa_parse": (st, [c_char_p, P(ctypes.c_int)]),
        "lucent_isa_set": (st, [ctypes.c_int]),
        "lucent_isa_active": (ctypes.c_int, []),
        "lucent_isa_name": (c_char_p, [ctypes.c_int]),
    }
    for name, (res, args) in sigs.items():
        f = getattr(lib, name)
        f.restype = res
        f.argtypes = args
