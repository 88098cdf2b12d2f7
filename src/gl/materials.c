/* What the renderer derives from each distinct material: the radial profile (render.profile), the
 * separable kernel's taps (ssss), the transmittance through a thickness (translucency), and sigma0
 * (CDRF). Each is rebuilt only when a setting it depends on changed. */
#include <math.h>
#include <string.h>

#include "gl/renderer_internal.h"
#include "lucent/kernel.h"

static bool same_material(const lucent_material *a, const lucent_material *b)
{
    return !strcmp(a->name, b->name) && !memcmp(a->sigma_a, b->sigma_a, sizeof a->sigma_a) &&
           !memcmp(a->sigma_s, b->sigma_s, sizeof a->sigma_s) && !memcmp(a->g, b->g, sizeof a->g) && a->eta == b->eta;
}

lucent_status gl_materials_collect(lucent_renderer *r)
{
    for (int i = 0; i < r->scene->object_count; i++) {
        const lucent_material *m = &r->scene->objects[i].material;
        int k = 0;
        while (k < r->material_count && !same_material(&r->materials[k].m, m)) k++;
        if (k == GLR_MAX_MATERIALS)
            return lucent_error(LUCENT_ERR_UNSUPPORTED, "%s: more than %d distinct materials", r->scene->name,
                                GLR_MAX_MATERIALS);
        if (k == r->material_count) {
            memset(&r->materials[k], 0, sizeof r->materials[k]);
            r->materials[k].m = *m;
            r->materials[k].fit_variant = -1;
            r->material_count++;
        }
        r->meshes[i].material = k;
    }
    return LUCENT_OK;
}

/* ---- profile ---- */

static lucent_status build_profile(gl_material *g, const char *source, const lucent_renderer_desc *d)
{
    if (g->profile && !strcmp(g->profile_source, source)) return LUCENT_OK;
    lucent_profile_destroy(g->profile);
    lucent_taps_destroy(g->taps);
    g->profile = NULL, g->taps = NULL, g->taps_key[0] = '\0';
    if (g->transmit_model == LUCENT_TRANSMIT_PROFILE) g->transmit_range = 0; /* the slab's needs no profile */
    lucent_profile_source_desc pd = {.source = source, .photons = d->profile_photons, .seed = 1, .pool = d->pool};
    lucent_status s = lucent_profile_from_source(&pd, &g->m, &g->profile);
    if (s != LUCENT_OK) return lucent_error_context(s, "material %s: profile %s", g->m.name, source);
    snprintf(g->profile_source, sizeof g->profile_source, "%s", source);
    return LUCENT_OK;
}

/* ---- taps (Freude ch. 5 models through lucent/kernel.h) ---- */

static lucent_status build_taps(gl_material *g, const lucent_render_settings *s)
{
    char key[sizeof g->taps_key];
    snprintf(key, sizeof key, "%s/%s/%d/%d", g->profile_source, lucent_kernel_model_name(s->kernel_model),
             s->kernel_rank, s->taps);
    if (g->taps && !strcmp(key, g->taps_key)) return LUCENT_OK;
    lucent_taps_destroy(g->taps);
    g->taps = NULL;
    lucent_kernel2d *gt = NULL;
    lucent_kernel *k = NULL;
    lucent_kernel_desc kd = lucent_kernel_defaults(s->kernel_model);
    kd.rank = s->kernel_rank;
    lucent_status st = lucent_kernel2d_from_profile(g->profile, NULL, &gt);
    if (st == LUCENT_OK) st = lucent_kernel_build(gt, g->profile, g->m.name, &kd, &k);
    if (st == LUCENT_OK) st = lucent_kernel_taps(k, &(lucent_taps_desc){.count = s->taps}, &g->taps);
    lucent_kernel_destroy(k);
    lucent_kernel2d_destroy(gt);
    if (st != LUCENT_OK) return lucent_error_context(st, "material %s: kernel %s", g->m.name, key);
    snprintf(g->taps_key, sizeof g->taps_key, "%s", key);
    return LUCENT_OK;
}

/* ---- transmittance through a thickness s (docs/render.md, "Translucency") ----
 * render.transmittance "slab": transmit.c. "profile" (Jimenez 2010 with the material's profile):
 * light entering a uniformly lit back face of a slab of thickness s reaches the front point opposite
 * from every entry point at distance rho = sqrt(r^2 + s^2); with the profile R(rho) that is
 * integral 2 pi r R(sqrt(r^2 + s^2)) dr = integral_s^inf 2 pi rho R(rho) drho: the profile's power
 * outside radius s. With R piecewise constant over the bins (lucent_profile), bin k holding
 * [k dr, (k+1) dr], the tail is exact: T(s) = sum_{k > K} R_k pi ((k+1)^2 - k^2) dr^2
 * + R_K pi ((K+1)^2 dr^2 - s^2), K = floor(s / dr). Normalised by T(0), the total reflectance. */
static double tail(const lucent_profile *p, int c, double s)
{
    double dr = p->dr, t = 0;
    int K = (int)floor(s / dr);
    if (K >= p->count) return 0;
    for (int k = p->count - 1; k > K; k--) t += p->value[c][k] * M_PI * ((k + 1.0) * (k + 1.0) - (double)k * k) * dr * dr;
    return t + p->value[c][K] * M_PI * ((K + 1.0) * (K + 1.0) * dr * dr - s * s);
}

static lucent_status build_transmit(gl_material *g, lucent_transmittance_model model, const lucent_renderer_desc *d)
{
    if (g->transmit_range > 0 && g->transmit_model == (int)model) return LUCENT_OK;
    g->transmit_model = (int)model, g->transmit_range = 0;
    if (model == LUCENT_TRANSMIT_SLAB)
        return gl_transmit_slab(&g->m, d, GLR_TRANSMIT_SIZE, g->transmit, &g->transmit_range);
    const lucent_profile *p = g->profile;
    g->transmit_range = p->count * p->dr;
    for (int c = 0; c < 3; c++) {
        double t0 = tail(p, c, 0);
        for (int j = 0; j < GLR_TRANSMIT_SIZE; j++) {
            double s = g->transmit_range * j / (GLR_TRANSMIT_SIZE - 1), t = j == GLR_TRANSMIT_SIZE - 1 ? 0 : tail(p, c, s);
            g->transmit[3 * j + c] = t0 > 0 ? (float)fmax(t / t0, 0) : 0;
        }
    }
    return LUCENT_OK;
}

lucent_status gl_materials_prepare(lucent_renderer *r, const lucent_render_settings *s, bool taps, bool transmit)
{
    lucent_status st = LUCENT_OK;
    for (int i = 0; i < r->material_count && st == LUCENT_OK; i++) {
        gl_material *g = &r->materials[i];
        st = build_profile(g, s->profile, &r->desc);
        if (st == LUCENT_OK && taps) st = build_taps(g, s);
        if (st == LUCENT_OK && transmit) st = build_transmit(g, s->transmittance, &r->desc);
    }
    return st;
}

/* ---- sigma0 per object (Kubo Eq. 4-6) ---- */

static lucent_status object_sigma0(lucent_renderer *r, int i, const lucent_render_settings *s)
{
    const lucent_scene_object *o = &r->scene->objects[i];
    gl_mesh *m = &r->meshes[i];
    gl_material *g = &r->materials[m->material];
    if (o->sigma0_set) {
        memcpy(m->sigma0, o->sigma0, sizeof m->sigma0);
        m->sigma0_from = "scene";
    } else if (s->sigma0_source == LUCENT_SIGMA0_DIFFUSE) {
        for (int c = 0; c < 3; c++) m->sigma0[c] = lucent_cdrf_sigma0_from_diffuse(o->albedo[c]); /* Kubo Eq. 6 */
        m->sigma0_from = "diffuse";
    } else {
        if (g->fit_variant != (int)s->cdrf_variant) {
            lucent_status st = gl_sigma0_fit(&g->m, s->cdrf_variant, &r->desc, g->fit_sigma0, &g->fit_cached);
            if (st != LUCENT_OK) return lucent_error_context(st, "object \"%s\": sigma0 fit", o->name);
            g->fit_variant = (int)s->cdrf_variant;
        }
        memcpy(m->sigma0, g->fit_sigma0, sizeof m->sigma0);
        m->sigma0_from = g->fit_cached ? "fit (cache)" : "fit";
    }
    return LUCENT_OK;
}

lucent_status gl_objects_sigma0(lucent_renderer *r, const lucent_render_settings *s)
{
    lucent_status st = LUCENT_OK;
    for (int i = 0; i < r->scene->object_count && st == LUCENT_OK; i++)
        if (r->scene->objects[i].visible) st = object_sigma0(r, i, s);
    return st;
}

void gl_materials_free(lucent_renderer *r)
{
    for (int i = 0; i < r->material_count; i++) {
        lucent_profile_destroy(r->materials[i].profile);
        lucent_taps_destroy(r->materials[i].taps);
    }
    r->material_count = 0;
}
