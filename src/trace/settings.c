/* The path tracer's settings group (lucent/settings.h), read by tracer.c and integrator.c. */
#include "base/settings_table.h"

SETTINGS_NAMES(boundary_model_names, "walter", "cycles3")
SETTINGS_NAMES(light_paths_names, "off", "auto", "all")

static const lucent_setting k_trace[] = {
    SETTING_INT("spp", trace.spp, 64, 1, 1 << 24, 0, "samples per pixel"),
    SETTING_SEED("seed", trace.seed, 1, 0, 9007199254740992.0, "the random seed (the image depends on it alone)"),
    SETTING_INT("max_bounces", trace.max_bounces, 64, 1, 100000, 0, "surface events per path"),
    SETTING_INT("max_scatter", trace.max_scatter, 100000, 1, 1 << 30, 0, "volume scattering events per path"),
    SETTING_REAL("time_limit", trace.time_limit, 0, 0, 1e9, "seconds of tracing at most (0: stop at spp)"),
    SETTING_CHOICE("boundary_model", trace.boundary_model, "walter", boundary_model_names,
                   "the rough boundary's BSDF: Walter et al. 2007 (physics), or cycles3, Blender 3.x Cycles' "
                   "Glass BSDF convention (a peer's, for side-by-side validation; docs/trace.md)"),
    SETTING_CHOICE("light_paths", trace.light_paths, "auto", light_paths_names,
                   "objects whose subsurface light is traced from the lights to the camera: auto (the dense "
                   "ones with a rough boundary), all (every rough one) or off (docs/trace.md)"),
    SETTING_REAL("photons", trace.photons, 1, 0, 1024, "light paths per pixel and pass (0: none)"),
    SETTING_BOOL("interreflection", trace.interreflection, true,
                 "light between surfaces: off ends a path where it meets a surface from outside after its first "
                 "(a diagnosis: the share of an image that light between surfaces carries, which no real-time "
                 "method models; docs/trace.md)"),
};

const lucent_settings_group tr_trace_settings = SETTINGS_GROUP("trace", "the path-traced reference", k_trace);
