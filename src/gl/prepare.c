/* Everything a frame needs, prepared from the settings and rebuilt only when a setting it depends on
 * changed: targets (size), shadow maps (size), curvature (smoothing), the CDRF LUT (variant), sigma0
 * (source, variant), kernels and taps (profile, model, rank, taps), transmittance tables (profile). */
#include <math.h>
#include <string.h>

#include "gl/renderer_internal.h"

#define CHECK_RANGE(cond, ...) \
    if (!(cond)) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "render settings: " __VA_ARGS__)

lucent_status gl_settings_check(const lucent_render_settings *s)
{
    CHECK_RANGE(s->width >= 1 && s->width <= 16384 && s->height >= 1 && s->height <= 16384,
                "width and height must be 1..16384, got %d x %d", s->width, s->height);
    CHECK_RANGE(s->method >= 0 && s->method < LUCENT_METHOD_COUNT, "unknown method %d", (int)s->method);
    CHECK_RANGE(s->kernel_model >= 0 && s->kernel_model < LUCENT_KERNEL_MODEL_COUNT, "unknown kernel model %d",
                (int)s->kernel_model);
    CHECK_RANGE(s->kernel_rank >= 1 && s->kernel_rank <= LUCENT_KERNEL_MAX_RANK, "rank must be 1..16, got %d",
                s->kernel_rank);
    CHECK_RANGE(s->taps >= 1 && s->taps <= LUCENT_KERNEL_MAX_TAPS && s->taps % 2 == 1, "taps must be odd, 1..255, "
                "got %d", s->taps);
    CHECK_RANGE(s->strength >= 0 && s->strength <= 1, "strength must be in [0, 1], got %g", s->strength);
    CHECK_RANGE(s->width_scale > 0 && isfinite(s->width_scale), "width_scale must be > 0, got %g", s->width_scale);
    CHECK_RANGE(s->depth_filter >= 0 && s->depth_filter <= LUCENT_DEPTH_NONE, "unknown depth filter %d",
                (int)s->depth_filter);
    CHECK_RANGE(s->cdrf_variant == LUCENT_CDRF_KUBO || s->cdrf_variant == LUCENT_CDRF_COLLOMB,
                "unknown CDRF variant %d", (int)s->cdrf_variant);
    CHECK_RANGE(s->shadow_map_size >= 16 && s->shadow_map_size <= 16384, "shadow_map_size must be 16..16384, got %d",
                s->shadow_map_size);
    CHECK_RANGE(s->curvature_smooth >= 0 && s->curvature_smooth <= 16, "curvature_smooth must be 0..16, got %d",
                s->curvature_smooth);
    CHECK_RANGE(lucent_profile_source_known(s->profile), "unknown profile \"%s\" (dipole, better-dipole, burley, mc)",
                s->profile);
    CHECK_RANGE(isfinite(s->translucency_curvature), "translucency_curvature must be finite");
    return LUCENT_OK;
}

static lucent_status prepare_lut(lucent_renderer *r, const lucent_render_settings *s)
{
    if (!s->cdrf_lut || (r->lut_tex && r->lut_variant == (int)s->cdrf_variant)) return LUCENT_OK;
    lucent_cdrf_lut_desc d = lucent_cdrf_lut_defaults();
    d.variant = s->cdrf_variant;
    d.pool = r->desc.pool;
    lucent_image *lut = NULL;
    lucent_status st = lucent_cdrf_lut_build(&d, &lut);
    if (st != LUCENT_OK) return st;
    if (r->lut_tex) glDeleteTextures(1, &r->lut_tex);
    st = gl_texture_from_image(lut, GL_LINEAR, &r->lut_tex);
    lucent_image_destroy(lut);
    r->lut_variant = st == LUCENT_OK ? (int)s->cdrf_variant : -1;
    r->lut_sigma_max = d.sigma_max;
    return st;
}

static lucent_status prepare_transmit(lucent_renderer *r, const lucent_render_settings *s)
{
    char key[sizeof r->transmit_key];
    snprintf(key, sizeof key, "%s %d", s->profile, (int)s->transmittance);
    if (r->transmit_tex && !strcmp(r->transmit_key, key)) return LUCENT_OK;
    float rows[GLR_MAX_MATERIALS][GLR_TRANSMIT_SIZE * 3];
    for (int m = 0; m < r->material_count; m++) memcpy(rows[m], r->materials[m].transmit, sizeof rows[m]);
    if (r->transmit_tex) glDeleteTextures(1, &r->transmit_tex);
    r->transmit_tex = gl_texture(GL_RGB32F, GLR_TRANSMIT_SIZE, r->material_count, GL_LINEAR);
    glTextureSubImage2D(r->transmit_tex, 0, 0, 0, GLR_TRANSMIT_SIZE, r->material_count, GL_RGB, GL_FLOAT, rows);
    snprintf(r->transmit_key, sizeof r->transmit_key, "%s", key);
    return gl_check("uploading the transmittance tables");
}

static lucent_status prepare_blur(lucent_renderer *r, const lucent_render_settings *s)
{
    char key[sizeof r->blur_key];
    snprintf(key, sizeof key, "%s %.17g", r->materials[0].taps_key, s->width_scale);
    for (int m = 1; m < r->material_count; m++)
        snprintf(key + strlen(key), sizeof key - strlen(key), " %s", r->materials[m].taps_key);
    if (!strcmp(key, r->blur_key)) return LUCENT_OK;
    const lucent_taps *taps[GLR_MAX_MATERIALS];
    for (int m = 0; m < r->material_count; m++) taps[m] = r->materials[m].taps;
    lucent_status st = gl_blur_set_taps(&r->blur, taps, r->material_count, s->width_scale);
    if (st == LUCENT_OK) snprintf(r->blur_key, sizeof r->blur_key, "%s", key);
    return st;
}

lucent_status gl_prepare(lucent_renderer *r, const lucent_render_settings *s)
{
    bool cdrf = s->method == LUCENT_METHOD_CDRF || s->method == LUCENT_METHOD_CDRF_TRANSLUCENCY;
    bool ssss = s->method == LUCENT_METHOD_SSSS;
    bool transmit = s->method == LUCENT_METHOD_CDRF_TRANSLUCENCY || (ssss && s->translucency);
    lucent_status st = gl_targets_resize(r, s->width, s->height);
    if (st == LUCENT_OK) st = gl_shadows_resize(r, s->shadow_map_size);
    if (st == LUCENT_OK && cdrf) st = gl_meshes_curvature(r, s->curvature_smooth);
    if (st == LUCENT_OK && cdrf) st = prepare_lut(r, s);
    if (st == LUCENT_OK && cdrf) st = gl_objects_sigma0(r, s);
    if (st == LUCENT_OK && (ssss || transmit)) st = gl_materials_prepare(r, s, ssss, transmit);
    if (st == LUCENT_OK && transmit) st = prepare_transmit(r, s);
    if (st == LUCENT_OK && ssss) st = prepare_blur(r, s);
    return st;
}
