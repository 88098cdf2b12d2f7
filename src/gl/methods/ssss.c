/* ssss: Jimenez's screen-space separable subsurface scattering (Freude 2014, chapter 4,
 * Algorithm 4.1): the surface pass writes the Lambert irradiance (plus the light through thin parts)
 * with linear depth, the separable blur spreads it with the taps of the material's kernel (any
 * separable model of lucent/kernel.h, Freude chapter 5), the compose pass blends it by the strength
 * and adds the specular. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "base/settings_table.h"
#include "gl/blur.h"
#include "gl/methods/surface.h"

/* ---- the settings group ---- */

static const char *kernel_name(int i)
{
    return i >= 0 && i < LUCENT_KERNEL_MODEL_COUNT ? lucent_kernel_model_name((lucent_kernel_model)i) : NULL;
}

SETTINGS_NAMES(depth_filter_names, "follow", "gaussian", "none")

const char *lucent_depth_filter_name(lucent_depth_filter filter)
{
    const char *n = depth_filter_names((int)filter);
    return n ? n : "unknown";
}

/* "svd3" -> model svd, rank 3; "preint" -> rank 1. Only svd and sog take a rank. */
static lucent_status parse_kernel(const char *text, lucent_render_settings *dest)
{
    char name[32];
    lucent_kernel_model model;
    size_t len = strcspn(text, "0123456789");
    if (len == 0 || len >= sizeof name) {
        lucent_status s = lucent_kernel_model_parse(text, &model);
        if (s == LUCENT_OK) dest->ssss.kernel = (int)model, dest->ssss.rank = 1;
        return s;
    }
    memcpy(name, text, len);
    name[len] = '\0';
    int r = 1;
    if (text[len]) {
        char *end;
        long v = strtol(text + len, &end, 10);
        if (*end || v < 1 || v > LUCENT_KERNEL_MAX_RANK) return lucent_kernel_model_parse(text, &model);
        r = (int)v;
    }
    lucent_status s = lucent_kernel_model_parse(name, &model);
    if (s == LUCENT_OK && r > 1 && model != LUCENT_KERNEL_SVD && model != LUCENT_KERNEL_SOG)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel model '%s' has rank 1 only (svd and sog take a rank)",
                            name);
    if (s == LUCENT_OK) dest->ssss.kernel = (int)model, dest->ssss.rank = r;
    return s;
}

static const lucent_setting k_ssss[] = {
    {.key = "kernel",
     .type = LUCENT_SETTING_CHOICE,
     SETTING_AT_(ssss.kernel, true),
     .def_text = "preint",
     .choice = kernel_name,
     .parse = parse_kernel,
     .doc = "the separable kernel model (Freude ch. 5); svd3, sog4 give a rank too"},
    SETTING_INT("rank", ssss.rank, 1, 1, LUCENT_KERNEL_MAX_RANK, 0, "passes of the separable model (svd, sog)"),
    SETTING_INT("taps", ssss.taps, LUCENT_KERNEL_DEFAULT_TAPS, 1, LUCENT_KERNEL_MAX_TAPS, LUCENT_SETTING_ODD,
                "taps per 1-D pass"),
    SETTING_TEXT("profile", ssss.profile, "dipole", lucent_profile_source_name,
                 "the radial profile the kernel is built from"),
    SETTING_REAL("strength", ssss.strength, 1, 0, 1,
                 "blend of blurred and unblurred diffuse, times each object's sss_strength"),
    SETTING_REAL("width_scale", ssss.width_scale, 1, 1e-6, 1e6, "an artist's multiplier on the physical kernel width"),
    SETTING_CHOICE("depth_filter", ssss.depth_filter, "follow", depth_filter_names,
                   "depth awareness: Jimenez's follow-surface, a Gaussian weight, or none"),
};

const lucent_settings_group gl_ssss_settings = SETTINGS_GROUP("ssss", "the screen-space blur and its kernel", k_ssss);

/* ---- the method ---- */

typedef struct ssss_state {
    GLuint program;
    gl_blur blur;
    char blur_key[GLR_MAX_MATERIALS * LUCENT_BAKE_KEY_SIZE + 32];
} ssss_state;

static lucent_status variant(const char *text, lucent_render_settings *s) { return parse_kernel(text, s); }

/* Uploads the materials' taps when they (or the width scale) changed. */
static lucent_status prepare_blur(lucent_renderer *r, ssss_state *st, const lucent_render_settings *s)
{
    const gl_tables *t = &r->tables;
    char key[sizeof st->blur_key];
    snprintf(key, sizeof key, "%s %.17g", t->baked[0].taps_key, s->ssss.width_scale);
    for (int m = 1; m < t->count; m++)
        snprintf(key + strlen(key), sizeof key - strlen(key), " %s", t->baked[m].taps_key);
    if (!strcmp(key, st->blur_key)) return LUCENT_OK;
    const lucent_taps *taps[GLR_MAX_MATERIALS];
    for (int m = 0; m < t->count; m++) taps[m] = t->baked[m].taps;
    lucent_status e = gl_blur_set_taps(&st->blur, taps, t->count, s->ssss.width_scale);
    if (e == LUCENT_OK) snprintf(st->blur_key, sizeof st->blur_key, "%s", key);
    return e;
}

static lucent_status prepare(lucent_renderer *r, void *state, const lucent_render_settings *s)
{
    ssss_state *st = state;
    lucent_status e = st->blur.program ? LUCENT_OK : gl_blur_init(&st->blur);
    lucent_bake_desc d = gl_renderer_bake_desc(r, s, LUCENT_BAKE_TAPS);
    if (e == LUCENT_OK) e = gl_tables_bake(&r->tables, &d, r->cache);
    if (e == LUCENT_OK && s->translucency.enabled) e = gl_translucency_prepare(r, s);
    if (e == LUCENT_OK && s->cdrf.curved_parts) e = gl_curved_prepare(r, s);
    if (e == LUCENT_OK) e = gl_blur_resize(&st->blur, r->targets.width, r->targets.height);
    if (e == LUCENT_OK) e = prepare_blur(r, st, s);
    if (e == LUCENT_OK)
        e = gl_surface_program(r, "ssss.frag.glsl", s->cdrf.curved_parts ? "#define CURVED 1\n" : NULL, &st->program);
    return e;
}

static void object_uniforms(const lucent_renderer *r, const void *state, const lucent_render_settings *s, int i,
                            GLuint p)
{
    (void)state;
    glUniform1f(glGetUniformLocation(p, "u_strength"), (float)(r->scene->objects[i].sss_strength * s->ssss.strength));
    gl_translucency_uniforms(r, s, i, p, s->translucency.enabled);
    if (s->cdrf.curved_parts) gl_curved_uniforms(r, i, p);
}

static lucent_status draw(lucent_renderer *r, void *state, const lucent_render_settings *s)
{
    ssss_state *st = state;
    gl_surface_draw(r, st->program, 0, s, object_uniforms, st);
    double scale = lucent_screen_pixels_per_mm(r->targets.height, r->scene->camera.fov_y, 1) * s->ssss.width_scale;
    gl_blur_run(&st->blur, r->targets.diffuse, r->targets.depth, scale, s->ssss.depth_filter, &r->timer);
    gl_compose(r, s, st->blur.sum_tex);
    return LUCENT_OK;
}

static void object_info(const lucent_renderer *r, const void *state, int i, lucent_render_object_info *dest)
{
    (void)state;
    const lucent_baked *b = gl_tables_of(&r->tables, i);
    dest->kernel_range = b->taps ? gl_taps_radius(b->taps, 1) : 0;
}

static cJSON *taps_json(const lucent_material *m, const lucent_baked *b)
{
    const lucent_taps *t = b->taps;
    cJSON *k = cJSON_CreateObject();
    if (!k) return NULL;
    cJSON_AddStringToObject(k, "material", m->name);
    cJSON_AddStringToObject(k, "key", b->taps_key);
    cJSON_AddNumberToObject(k, "taps", t->count);
    cJSON_AddNumberToObject(k, "rank", t->rank);
    lucent_json_add_numbers(k, "offsets_mm", t->offset, t->count);
    static const char *const names[3] = {"weights_r", "weights_g", "weights_b"};
    static const char *const signs[3] = {"sign_r", "sign_g", "sign_b"};
    for (int c = 0; c < 3; c++) {
        lucent_json_add_numbers(k, names[c], t->weight[c], t->rank * t->count);
        lucent_json_add_numbers(k, signs[c], t->sign[c], t->rank);
    }
    return k;
}

/* Every material's taps: what an engine needs to reproduce the blur. */
static void sidecar(const lucent_renderer *r, const void *state, const lucent_render_settings *s, cJSON *root)
{
    (void)state, (void)s;
    cJSON *list = cJSON_AddArrayToObject(root, "kernels");
    for (int i = 0; list && i < r->tables.count; i++) {
        cJSON *k = r->tables.baked[i].taps ? taps_json(&r->tables.material[i], &r->tables.baked[i]) : NULL;
        if (k) cJSON_AddItemToArray(list, k);
    }
}

static void release(void *state) { gl_blur_free(&((ssss_state *)state)->blur); }

static unsigned bakes(const lucent_renderer *r, const lucent_render_settings *s)
{
    (void)r;
    return LUCENT_BAKE_TAPS | gl_translucency_bakes(s, s->translucency.enabled) |
           (s->cdrf.curved_parts ? LUCENT_BAKE_SPHERES : 0u);
}

const gl_method gl_method_ssss = {
    .name = "ssss",
    .settings = (const char *const[]){"kernel", "rank", "taps", "profile", "strength", "width_scale", "depth_filter",
                                      "translucency", "transmittance", "curved_parts", "curvature_smooth", NULL},
    .variant = variant,
    .variant_doc = "<model>[rank] with model svd, preint, guided, manual, sog, jimenez",
    .bakes = bakes,
    .state_size = sizeof(ssss_state),
    .prepare = prepare,
    .draw = draw,
    .object_info = object_info,
    .sidecar = sidecar,
    .release = release,
};
