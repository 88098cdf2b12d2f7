/* The truth an engine's model is fitted to (lucent/engine.h): a homogeneous material through the bake
 * room (its "mc" profile, its disk-cached Monte Carlo Rd and slab transmittance), a layered one by one
 * Monte Carlo run of the stack per channel. */
#include <stdlib.h>
#include <string.h>

#include "engine/internal.h"
#include "lucent/bake.h"
#include "lucent/mc.h"
#include "lucent/skin.h"

/* The truth's grid: Freude Table 6.1's bin width, and far enough to hold the tail, 8 / sigma_tr of the
 * slowest channel (diffusion's tail beyond it: e^-8 (1 + 8), 0.3%) when that passes the default's 32 reduced
 * mean free paths (Marble: 68 mm where the default stops at 15 mm, holding 97.8% of red's T). */
static void truth_grid(const lucent_material *m, lucent_profile_grid *dest)
{
    lucent_material_derived d;
    lucent_profile_grid_default(m, dest);
    lucent_material_derive(m, &d);
    double reach = 0.0;
    for (int c = 0; c < 3; c++) reach = fmax(reach, 8.0 * d.mfp_diffuse[c]);
    double count = ceil(fmin(reach, 1e4 * dest->count * dest->dr) / dest->dr);
    if (count > dest->count) dest->count = (int)fmin(count, LUCENT_MC_MAX_RADIAL_BINS);
}

/* A homogeneous material: its Monte Carlo profile (the profile API, on truth_grid) and, through the bake
 * room, its total T (disk-cached) and slab transmittance. */
static lucent_status bake_homogeneous(const lucent_engine_target_desc *d, lucent_engine_target *t)
{
    lucent_profile_source_desc pd = {.source = "mc", .photons = t->photons, .seed = t->seed, .pool = d->pool};
    truth_grid(&t->material, &pd.grid);
    lucent_status s = lucent_profile_from_source(&pd, &t->material, &t->profile);
    lucent_render_settings rs = lucent_render_settings_defaults();
    rs.translucency.transmittance = LUCENT_TRANSMIT_SLAB;
    bool skin = t->material.skin.layer_count > 0; /* its T: the bake's, its bands' Monte Carlo (cached) */
    lucent_bake_desc bd = {.what = (d->total_photons && !skin ? 0u : LUCENT_BAKE_RD) |
                                   (d->transmittance ? LUCENT_BAKE_TRANSMITTANCE : 0u),
                           .settings = &rs,
                           .pool = d->pool};
    lucent_baked b = {0};
    if (s == LUCENT_OK && bd.what) s = lucent_material_bake(&t->material, &bd, d->cache, &b);
    if (s == LUCENT_OK && (!d->total_photons || skin)) {
        memcpy(t->rd, b.rd, sizeof t->rd);
        memcpy(t->rd_se, b.rd_se, sizeof t->rd_se);
    }
    if (s == LUCENT_OK && d->total_photons && !skin)
        s = lucent_profile_mc_total(&t->material, d->total_photons, t->seed, d->pool, t->rd, t->rd_se);
    if (s == LUCENT_OK && d->transmittance) { /* the Monte Carlo half of the bake's table (beyond: diffusion) */
        int n = LUCENT_BAKE_TRANSMIT_SIZE, half = (n - 1) / 2;
        t->slab_count = LUCENT_ENGINE_SLAB_SAMPLES;
        for (int i = 0; i < t->slab_count; i++) {
            int j = 1 + (half - 1) * i / (t->slab_count - 1);
            t->slab_thickness[i] = b.transmit_range * j / (n - 1);
            for (int c = 0; c < 3; c++) t->slab_value[i][c] = b.transmittance[3 * j + c];
        }
    }
    lucent_baked_free(&b);
    return s;
}

/* Channel c of the stack, on the top material's default grid (Freude Table 6.1). */
static lucent_status run_layers(const lucent_engine_target_desc *d, lucent_engine_target *t, int c)
{
    lucent_mc_layer layers[LUCENT_ENGINE_MAX_LAYERS];
    for (int i = 0; i < t->layer_count; i++) {
        const lucent_material *m = &t->layers[i].material;
        layers[i] = (lucent_mc_layer){.n = m->eta,
                                      .sigma_a = m->sigma_a[c],
                                      .sigma_s = m->sigma_s[c],
                                      .g = m->g[c],
                                      .thickness = t->layers[i].slab.thickness};
    }
    static const char *const labels[] = {"truth R", "truth G", "truth B"};
    lucent_mc_result r = {0};
    lucent_status s = lucent_mc_run(&(lucent_mc_desc){.layers = layers,
                                                      .layer_count = t->layer_count,
                                                      .photons = t->photons,
                                                      .seed = 4 * t->seed + (uint64_t)c,
                                                      .grid = {.dr = t->profile->dr, .nr = t->profile->count},
                                                      .pool = d->pool,
                                                      .label = labels[c]},
                                    &r);
    if (s != LUCENT_OK) return s;
    for (int j = 0; j < t->profile->count; j++)
        t->profile->value[c][j] = r.rd_r[j], t->profile->error[c][j] = r.rd_r_se[j];
    t->rd[c] = r.rd, t->rd_se[c] = r.rd_se;
    lucent_mc_result_free(&r);
    return LUCENT_OK;
}

static lucent_status check_desc(const lucent_engine_target_desc *d)
{
    if (!d) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "engine target: no desc");
    if (!d->material && (!d->layers || d->layer_count < 1))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "engine target: give a material or layers");
    if (d->layers && (d->layer_count < 1 || d->layer_count > LUCENT_ENGINE_MAX_LAYERS))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "engine target: layer_count: 1 to %d layers, got %d",
                            LUCENT_ENGINE_MAX_LAYERS, d->layer_count);
    for (int i = 0; d->layers && i < d->layer_count; i++) {
        double h = d->layers[i].slab.thickness;
        if (!(h > 0.0) || (isinf(h) && i + 1 < d->layer_count))
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                                "engine target: layers[%d].thickness: > 0 mm, and only the last may be infinite", i);
        if (d->layers[i].material.skin.layer_count > 0)
            return lucent_error(
                LUCENT_ERR_INVALID_ARGUMENT,
                "engine target: layers[%d]: %s is a spectral skin, already layered: the layers take RGB "
                "materials",
                i, d->layers[i].material.name);
        lucent_status s = lucent_material_validate(&d->layers[i].material);
        if (s != LUCENT_OK) return lucent_error_context(s, "engine target: layers[%d]", i);
    }
    if (d->transmittance && d->layers && d->layer_count > 1)
        return lucent_error(LUCENT_ERR_UNSUPPORTED, "engine target: the slab transmittance of a stack is not computed");
    return LUCENT_OK; /* a homogeneous material is validated once resolved (a spectral skin: lucent/skin.h) */
}

/* r99, the counted bins, the coverage and the noise floor of each channel. */
static void summarise(lucent_engine_target *t)
{
    const lucent_profile *p = t->profile;
    for (int c = 0; c < 3; c++) {
        double sum = 0.0, num = 0.0, den = 0.0;
        int j = 0;
        t->bins[c] = p->count;
        for (; j < p->count; j++) {
            sum += p->value[c][j] * M_PI * (2 * j + 1) * p->dr * p->dr;
            if (sum >= 0.99 * t->rd[c] && t->bins[c] == p->count) t->bins[c] = j + 1;
        }
        t->coverage[c] = t->rd[c] > 0.0 ? sum / t->rd[c] : 0.0;
        t->r99[c] = t->bins[c] * p->dr;
        for (j = 0; j < t->bins[c]; j++) {
            double q = p->r[j] * p->value[c][j], e = p->r[j] * p->error[c][j];
            num += e * e, den += q * q;
        }
        t->noise[c] = den > 0.0 ? sqrt(num / den) : NAN;
    }
}

lucent_status lucent_engine_target_build(const lucent_engine_target_desc *desc, lucent_engine_target *dest)
{
    *dest = (lucent_engine_target){0};
    lucent_status s = check_desc(desc);
    if (s != LUCENT_OK) return s;
    lucent_engine_target *t = dest;
    t->photons = desc->photons ? desc->photons : LUCENT_BAKE_PROFILE_PHOTONS;
    t->seed = desc->seed ? desc->seed : 1;
    if (desc->layers) {
        t->layer_count = desc->layer_count;
        memcpy(t->layers, desc->layers, (size_t)desc->layer_count * sizeof *desc->layers);
        t->material = desc->layers[0].material;
    } else {
        t->layer_count = 1;
        t->material = *desc->material;
        s = lucent_skin_resolve(&t->material); /* a spectral skin: its equivalent medium beside its bands */
        if (s == LUCENT_OK) s = lucent_material_validate(&t->material);
        if (s != LUCENT_OK) return s;
        t->layers[0] = (lucent_layer){.material = t->material, .slab = {.thickness = INFINITY}};
    }
    if (t->layer_count == 1 && isinf(t->layers[0].slab.thickness)) {
        s = bake_homogeneous(desc, t);
    } else {
        lucent_profile_grid g;
        lucent_profile_grid_default(&t->material, &g);
        s = lucent_profile_create(&g, "mc", &t->profile);
        for (int c = 0; c < 3 && s == LUCENT_OK; c++) s = run_layers(desc, t, c);
    }
    if (s == LUCENT_OK) {
        for (int c = 0; c < 3 && s == LUCENT_OK; c++)
            if (!(t->rd[c] > 0.0))
                s = lucent_error(LUCENT_ERR_NUMERIC, "engine target: %s reflects nothing in channel %d",
                                 t->material.name, c);
    }
    if (s == LUCENT_OK) summarise(t);
    if (s != LUCENT_OK) lucent_engine_target_free(t);
    return s;
}

void lucent_engine_target_free(lucent_engine_target *target)
{
    if (!target) return;
    lucent_profile_destroy(target->profile);
    *target = (lucent_engine_target){0};
}
