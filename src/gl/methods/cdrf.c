/* The CDRF (Kubo, Dobashi & Morishima, seed 000): Lambert's max(n.l, 0) replaced by the
 * curvature-dependent reflectance of sigma = sigma0 kappa (Kubo Eq. 4-5), read from the LUT of
 * section V or evaluated in closed form; sigma0 from the scene, from the diffuse colour (Kubo Eq. 6)
 * or fitted to Monte Carlo spheres of the material (baked, cached). cdrf+translucency adds the light
 * through thin parts modulated by the curvature, as the CDRF blog does. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/settings_table.h"
#include "gl/methods/surface.h"
#include "lucent/cdrf.h"

/* ---- the settings group ---- */

static const char *variant_name(int i)
{
    return i == LUCENT_CDRF_KUBO || i == LUCENT_CDRF_COLLOMB ? lucent_cdrf_variant_name((lucent_cdrf_variant)i) : NULL;
}

SETTINGS_NAMES(sigma0_names, "fit", "diffuse")

const char *lucent_sigma0_source_name(lucent_sigma0_source source)
{
    const char *n = sigma0_names((int)source);
    return n ? n : "unknown";
}

static const lucent_setting k_cdrf[] = {
    SETTING_CHOICE("cdrf_variant", cdrf.variant, "kubo", variant_name,
                   "Kubo's Gaussian-convolved Lambert, or the blog's closed-form fit (collomb)"),
    SETTING_BOOL("cdrf_lut", cdrf.lut, true, "read the CDRF from its LUT (false: the closed form)"),
    SETTING_CHOICE("sigma0", cdrf.sigma0, "fit", sigma0_names,
                   "sigma0 when an object gives none: fitted to Monte Carlo spheres, or d_c^2 (Kubo Eq. 6)"),
    SETTING_INT("curvature_smooth", cdrf.curvature_smooth, 1, 0, 16, 0, "n-ring smoothing of the vertex curvature"),
    SETTING_BOOL("cdrf_tail", cdrf.tail, true,
                 "past the terminator the material's profile (a sum of Gaussians) where it exceeds Kubo's Gaussian "
                 "of sigma0: the tail; objects that give sigma0 keep Kubo's alone"),
    SETTING_BOOL("curved_parts", cdrf.curved_parts, true,
                 "cdrf and ssss: light carried round curved parts, from the material's own Monte Carlo spheres "
                 "(exitance over theta and radius, behind the tracer's boundary), in place of Kubo's CDRF or "
                 "Lambert's max(n.l, 0); cdrf:kubo is Kubo's alone"),
};

const lucent_settings_group gl_cdrf_settings = SETTINGS_GROUP("cdrf", "the curvature-dependent reflectance", k_cdrf);

/* ---- the method ---- */

enum { CDRF_SOG = 8 };

typedef struct cdrf_object {
    double sigma0[3];                              /* mm */
    const char *sigma0_from;                       /* "scene", "fit", "fit (cache)", "diffuse" */
    int sog_count;                                 /* Gaussians of the tail (0: Kubo's one of sigma0) */
    float sog_sd[CDRF_SOG][3], sog_w[CDRF_SOG][3]; /* standard deviations (mm) and weights summing to 1 */
} cdrf_object;

typedef struct cdrf_state {
    GLuint program;
    GLuint lut_tex;
    int lut_variant; /* +1: 0 none */
    double lut_sigma_max;
    cdrf_object *objects;
    int object_count;
} cdrf_state;

static lucent_status prepare_lut(lucent_renderer *r, cdrf_state *st, const lucent_render_settings *s)
{
    if (!st->lut_sigma_max) st->lut_sigma_max = lucent_cdrf_lut_defaults().sigma_max;
    if (!s->cdrf.lut || (st->lut_tex && st->lut_variant == s->cdrf.variant + 1)) return LUCENT_OK;
    lucent_cdrf_lut_desc d = lucent_cdrf_lut_defaults();
    d.variant = (lucent_cdrf_variant)s->cdrf.variant;
    d.pool = r->desc.pool;
    lucent_image *lut = NULL;
    lucent_status e = lucent_cdrf_lut_build(&d, &lut);
    if (e != LUCENT_OK) return e;
    if (st->lut_tex) glDeleteTextures(1, &st->lut_tex);
    e = gl_texture_from_image(lut, GL_LINEAR, &st->lut_tex);
    lucent_image_destroy(lut);
    st->lut_variant = e == LUCENT_OK ? s->cdrf.variant + 1 : 0;
    st->lut_sigma_max = d.sigma_max;
    return e;
}

/* sigma0 per object (Kubo Eq. 4-6): the scene's, the diffuse colour's, or the material's fit. */
static lucent_status objects_sigma0(lucent_renderer *r, cdrf_state *st, const lucent_render_settings *s)
{
    const lucent_scene *sc = r->scene;
    bool fit = false;
    for (int i = 0; i < sc->object_count; i++)
        fit |= sc->objects[i].visible && !sc->objects[i].sigma0_set && s->cdrf.sigma0 == LUCENT_SIGMA0_FIT;
    lucent_bake_desc d = gl_renderer_bake_desc(r, s, LUCENT_BAKE_SIGMA0);
    lucent_status e = fit ? gl_tables_bake(&r->tables, &d, r->cache) : LUCENT_OK;
    if (e != LUCENT_OK) return lucent_error_context(e, "sigma0 fit");
    for (int i = 0; i < sc->object_count; i++) {
        const lucent_scene_object *o = &sc->objects[i];
        cdrf_object *c = &st->objects[i];
        if (!o->visible) continue;
        if (o->sigma0_set) {
            memcpy(c->sigma0, o->sigma0, sizeof c->sigma0);
            c->sigma0_from = "scene";
        } else if (s->cdrf.sigma0 == LUCENT_SIGMA0_DIFFUSE) {
            double a[3];
            gl_renderer_object_albedo(r, i, a);
            for (int k = 0; k < 3; k++) c->sigma0[k] = lucent_cdrf_sigma0_from_diffuse(a[k]); /* Kubo Eq. 6 */
            c->sigma0_from = "diffuse";
        } else {
            const lucent_baked *b = gl_tables_of(&r->tables, i);
            memcpy(c->sigma0, b->sigma0, sizeof c->sigma0);
            c->sigma0_from = b->sigma0_cached ? "fit (cache)" : "fit";
        }
    }
    return LUCENT_OK;
}

/* The tail (cdrf_tail): the material's profile as a sum of Gaussians with shared variances (d'Eon &
 * Luebke 2007, baked: lucent_sog_fit). A 2-D Gaussian of variance v convolved with light that varies
 * along one direction of the surface is the 1-D Gaussian of the same variance along it, so on the arc
 * of a sphere of curvature kappa the profile gives sum_k w_k CDRF(theta, sqrt(v_k) kappa) (Kubo Eq. 4-5
 * with each Gaussian's sigma0 = sqrt(v_k)), the weights normalised to 1 (the albedo is applied apart). */
static lucent_status objects_sog(lucent_renderer *r, cdrf_state *st, const lucent_render_settings *s)
{
    const lucent_scene *sc = r->scene;
    bool any = false;
    for (int i = 0; i < sc->object_count; i++) {
        st->objects[i].sog_count = 0;
        any |= s->cdrf.tail && sc->objects[i].visible && !sc->objects[i].sigma0_set;
    }
    if (!any) return LUCENT_OK;
    lucent_bake_desc d = gl_renderer_bake_desc(r, s, LUCENT_BAKE_SOG);
    d.sog_count = CDRF_SOG < 6 ? CDRF_SOG : 6;
    lucent_status e = gl_tables_bake(&r->tables, &d, r->cache);
    if (e != LUCENT_OK) return lucent_error_context(e, "cdrf tail");
    for (int i = 0; i < sc->object_count; i++) {
        const lucent_scene_object *o = &sc->objects[i];
        cdrf_object *c = &st->objects[i];
        if (!o->visible || o->sigma0_set) continue;
        const lucent_sog *g = &gl_tables_of(&r->tables, i)->sog;
        c->sog_count = g->count < CDRF_SOG ? g->count : CDRF_SOG;
        for (int ch = 0; ch < 3; ch++) {
            double total = 0;
            for (int k = 0; k < c->sog_count; k++) total += g->weight[ch][k];
            for (int k = 0; k < c->sog_count; k++) {
                c->sog_sd[k][ch] = (float)sqrt(g->variance[ch][k]);
                c->sog_w[k][ch] = (float)(total > 0 ? g->weight[ch][k] / total : k == 0);
            }
        }
    }
    return LUCENT_OK;
}

static lucent_status prepare(lucent_renderer *r, void *state, const lucent_render_settings *s, bool translucency)
{
    cdrf_state *st = state;
    if (!st->objects) {
        st->objects = calloc((size_t)r->scene->object_count, sizeof *st->objects);
        if (!st->objects) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
        st->object_count = r->scene->object_count;
    }
    lucent_status e = gl_meshes_curvature(&r->meshes, r->scene, s->cdrf.curvature_smooth, r->desc.pool);
    if (e == LUCENT_OK) e = prepare_lut(r, st, s);
    if (e == LUCENT_OK) e = objects_sigma0(r, st, s);
    if (e == LUCENT_OK) e = objects_sog(r, st, s);
    if (e == LUCENT_OK && translucency) e = gl_translucency_prepare(r, s);
    if (e == LUCENT_OK && s->cdrf.curved_parts) e = gl_curved_prepare(r, s);
    char defines[128];
    snprintf(defines, sizeof defines, "#define CDRF_LUT %d\n#define CDRF_VARIANT %d\n#define TRANSLUCENCY %d\n%s",
             s->cdrf.lut ? 1 : 0, s->cdrf.variant, translucency ? 1 : 0,
             s->cdrf.curved_parts ? "#define CURVED 1\n" : "");
    if (e == LUCENT_OK) e = gl_surface_program(r, "cdrf.frag.glsl", defines, &st->program);
    return e;
}

static lucent_status prepare_plain(lucent_renderer *r, void *state, const lucent_render_settings *s)
{
    return prepare(r, state, s, false);
}

static lucent_status prepare_translucent(lucent_renderer *r, void *state, const lucent_render_settings *s)
{
    return prepare(r, state, s, true);
}

static void object_uniforms(const lucent_renderer *r, const void *state, const lucent_render_settings *s, int i,
                            GLuint p)
{
    const cdrf_state *st = state;
    const lucent_scene_object *o = &r->scene->objects[i];
    const double *sigma0 = st->objects[i].sigma0;
    bool map_sigma0 = r->meshes.mesh[i].albedo_map && !o->sigma0_set && s->cdrf.sigma0 == LUCENT_SIGMA0_DIFFUSE;
    double reach = map_sigma0 ? 1 : fmax(sigma0[0], fmax(sigma0[1], sigma0[2]));
    const cdrf_object *c = &st->objects[i];
    int n = map_sigma0 ? 0 : c->sog_count;
    double tail = 0; /* the tail's reach: three of its widest standard deviations that carry light */
    for (int k = 0; k < n; k++)
        for (int ch = 0; ch < 3; ch++)
            if (c->sog_w[k][ch] > 0.01f) tail = fmax(tail, 3.0 * c->sog_sd[k][ch]);
    glUniform1i(glGetUniformLocation(p, "u_sog_count"), n);
    if (n) {
        glUniform3fv(glGetUniformLocation(p, "u_sog_sd"), n, &c->sog_sd[0][0]);
        glUniform3fv(glGetUniformLocation(p, "u_sog_w"), n, &c->sog_w[0][0]);
    }
    glUniform1f(glGetUniformLocation(p, "u_tail_reach"), (float)tail);
    glUniform3f(glGetUniformLocation(p, "u_sigma0"), (float)sigma0[0], (float)sigma0[1], (float)sigma0[2]);
    glUniform1i(glGetUniformLocation(p, "u_sigma0_from_map"), map_sigma0);
    glUniform1f(glGetUniformLocation(p, "u_cdrf_reach"), (float)(2 * reach)); /* two standard deviations, mm */
    glUniform1f(glGetUniformLocation(p, "u_lut_sigma_max"), (float)st->lut_sigma_max);
    gl_translucency_uniforms(r, s, i, p, false);
    glUniform1f(glGetUniformLocation(p, "u_convex_carried"), 1.0f); /* sigma0 is fitted to whole spheres */
    if (s->cdrf.curved_parts) gl_curved_uniforms(r, i, p);
}

static lucent_status draw(lucent_renderer *r, void *state, const lucent_render_settings *s)
{
    cdrf_state *st = state;
    gl_surface_draw(r, st->program, st->lut_tex, s, object_uniforms, st);
    gl_compose(r, s, 0);
    return LUCENT_OK;
}

static void object_info(const lucent_renderer *r, const void *state, int i, lucent_render_object_info *dest)
{
    (void)r;
    const cdrf_state *st = state;
    if (!st->objects || !st->objects[i].sigma0_from) return;
    memcpy(dest->sigma0, st->objects[i].sigma0, sizeof dest->sigma0);
    dest->sigma0_from = st->objects[i].sigma0_from;
}

static void release(void *state)
{
    cdrf_state *st = state;
    if (st->lut_tex) glDeleteTextures(1, &st->lut_tex);
    free(st->objects);
}

/* What objects_sigma0 bakes: the fit, when an object needs it; the spheres when asked. */
static unsigned bakes_plain(const lucent_renderer *r, const lucent_render_settings *s)
{
    bool fit = false;
    for (int i = 0; i < r->scene->object_count; i++)
        fit |= r->scene->objects[i].visible && !r->scene->objects[i].sigma0_set && s->cdrf.sigma0 == LUCENT_SIGMA0_FIT;
    return (fit ? LUCENT_BAKE_SIGMA0 : 0u) | (s->cdrf.curved_parts ? LUCENT_BAKE_SPHERES : 0u);
}

/* "cdrf:kubo", "cdrf:collomb": Kubo's function or the blog's alone (no curved parts); "cdrf:spheres":
 * the curved parts' factor (the default). */
static lucent_status variant(const char *text, lucent_render_settings *s)
{
    if (!strcmp(text, "spheres")) {
        s->cdrf.curved_parts = true;
        return LUCENT_OK;
    }
    lucent_cdrf_variant v;
    if (lucent_cdrf_variant_parse(text, &v) != LUCENT_OK)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "unknown cdrf variant '%s' (spheres, kubo, collomb)", text);
    s->cdrf.variant = (int)v, s->cdrf.curved_parts = false;
    return LUCENT_OK;
}

static unsigned bakes_translucent(const lucent_renderer *r, const lucent_render_settings *s)
{
    return bakes_plain(r, s) | gl_translucency_bakes(s, true);
}

const gl_method gl_method_cdrf = {
    .name = "cdrf",
    .settings = (const char *const[]){"cdrf_variant", "cdrf_lut", "sigma0", "curvature_smooth", "cdrf_tail",
                                      "curved_parts", NULL},
    .variant = variant,
    .variant_doc = "spheres (curved parts from the material's spheres, the default), kubo or collomb (alone)",
    .state_size = sizeof(cdrf_state),
    .bakes = bakes_plain,
    .prepare = prepare_plain,
    .draw = draw,
    .object_info = object_info,
    .release = release,
};

const gl_method gl_method_cdrf_translucency = {
    .name = "cdrf+translucency",
    .settings = (const char *const[]){"cdrf_variant", "cdrf_lut", "sigma0", "curvature_smooth", "cdrf_tail",
                                      "curved_parts", "transmittance", "translucency_curvature", NULL},
    .variant = variant,
    .variant_doc = "spheres (curved parts from the material's spheres, the default), kubo or collomb (alone)",
    .state_size = sizeof(cdrf_state),
    .bakes = bakes_translucent,
    .prepare = prepare_translucent,
    .draw = draw,
    .object_info = object_info,
    .release = release,
};
