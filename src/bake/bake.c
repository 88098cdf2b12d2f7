/* What a renderer needs from a material (lucent/bake.h), each part rebuilt only when the settings it
 * depends on changed, the Monte Carlo parts kept in the disk cache. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/bake.h"
#include "lucent/cdrf.h"
#include "lucent/skin.h"

const char *lucent_transmittance_name(lucent_transmittance_model model)
{
    static const char *const names[] = {"slab", "profile"};
    return model >= 0 && model < (int)(sizeof names / sizeof names[0]) ? names[model] : "unknown";
}

/* The desc with its zeros resolved. */
static lucent_bake_desc resolve(const lucent_bake_desc *d, lucent_render_settings *defaults)
{
    lucent_bake_desc r = *d;
    if (!r.settings) *defaults = lucent_render_settings_defaults(), r.settings = defaults;
    if (!r.profile_photons) r.profile_photons = LUCENT_BAKE_PROFILE_PHOTONS;
    if (!r.transmit_photons) r.transmit_photons = LUCENT_BAKE_TRANSMIT_PHOTONS;
    if (!r.sigma0_photons) r.sigma0_photons = LUCENT_BAKE_SIGMA0_PHOTONS;
    if (!r.sog_count) r.sog_count = 6;
    if (!r.boundary_photons) r.boundary_photons = LUCENT_BAKE_BOUNDARY_PHOTONS;
    if (!r.sphere_photons) r.sphere_photons = LUCENT_BAKE_SPHERE_PHOTONS;
    if (!r.sheet_photons) r.sheet_photons = LUCENT_BAKE_SHEET_PHOTONS;
    if (r.what & LUCENT_BAKE_SPHERES) r.what |= LUCENT_BAKE_BOUNDARY;
    if (r.what & (LUCENT_BAKE_TAPS | LUCENT_BAKE_SOG)) r.what |= LUCENT_BAKE_PROFILE;
    if ((r.what & LUCENT_BAKE_TRANSMITTANCE) && r.settings->translucency.transmittance == LUCENT_TRANSMIT_PROFILE)
        r.what |= LUCENT_BAKE_PROFILE;
    return r;
}

/* FNV-1a of a skin's layers (doubles and ints, no padding): a spectral skin's part of a cache key. */
static unsigned long long skin_hash(const lucent_skin *s)
{
    const unsigned char *p = (const unsigned char *)s->layer;
    unsigned long long h = 1469598103934665603ull;
    for (size_t i = 0; i < (size_t)s->layer_count * sizeof s->layer[0]; i++) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

/* The material's optical parameters as text: part of every cache key. A spectral skin adds its layers'
 * hash (its sigma_a, sigma_s and g are its equivalent medium). */
static void material_key(const lucent_material *m, char *dest, size_t size)
{
    int n = snprintf(dest, size, "%s sa %.17g %.17g %.17g ss %.17g %.17g %.17g g %.17g %.17g %.17g eta %.17g", m->name,
                     m->sigma_a[0], m->sigma_a[1], m->sigma_a[2], m->sigma_s[0], m->sigma_s[1], m->sigma_s[2], m->g[0],
                     m->g[1], m->g[2], m->eta);
    if (m->skin.layer_count > 0 && n > 0 && (size_t)n < size)
        snprintf(dest + n, size - (size_t)n, " skin %d %016llx", m->skin.layer_count, skin_hash(&m->skin));
}

/* ---- profile ---- */

static lucent_status bake_profile(const lucent_material *m, const lucent_bake_desc *d, lucent_baked *b)
{
    const char *source = d->settings->ssss.profile;
    if (b->profile && !strcmp(b->profile_key, source)) return LUCENT_OK;
    lucent_profile_destroy(b->profile);
    b->profile = NULL, b->profile_key[0] = '\0', b->have &= ~(unsigned)LUCENT_BAKE_PROFILE;
    lucent_profile_source_desc pd = {.source = source, .photons = d->profile_photons, .seed = 1, .pool = d->pool};
    lucent_status s = lucent_profile_from_source(&pd, m, &b->profile);
    if (s != LUCENT_OK) return lucent_error_context(s, "material %s: profile %s", m->name, source);
    snprintf(b->profile_key, sizeof b->profile_key, "%s", source);
    b->have |= LUCENT_BAKE_PROFILE;
    return LUCENT_OK;
}

/* ---- taps (Freude ch. 5 models through lucent/kernel.h) ---- */

static lucent_status bake_taps(const lucent_material *m, const lucent_bake_desc *d, lucent_baked *b)
{
    const lucent_ssss_settings *ss = &d->settings->ssss;
    char key[LUCENT_BAKE_KEY_SIZE];
    if (snprintf(key, sizeof key, "%.64s/%s/%d/%d", b->profile_key,
                 lucent_kernel_model_name((lucent_kernel_model)ss->kernel), ss->rank, ss->taps) >= (int)sizeof key)
        return lucent_error(LUCENT_ERR_INTERNAL, "bake: taps key too long");
    if (b->taps && !strcmp(key, b->taps_key)) return LUCENT_OK;
    lucent_taps_destroy(b->taps);
    b->taps = NULL, b->taps_key[0] = '\0', b->have &= ~(unsigned)LUCENT_BAKE_TAPS;
    lucent_kernel2d *gt = NULL;
    lucent_kernel *k = NULL;
    lucent_kernel_desc kd = lucent_kernel_defaults((lucent_kernel_model)ss->kernel);
    kd.rank = ss->rank;
    lucent_status st = lucent_kernel2d_from_profile(b->profile, NULL, &gt);
    if (st == LUCENT_OK) st = lucent_kernel_build(gt, b->profile, m->name, &kd, &k);
    if (st == LUCENT_OK) st = lucent_kernel_taps(k, &(lucent_taps_desc){.count = ss->taps}, &b->taps);
    lucent_kernel_destroy(k);
    lucent_kernel2d_destroy(gt);
    if (st != LUCENT_OK) return lucent_error_context(st, "material %s: kernel %s", m->name, key);
    snprintf(b->taps_key, sizeof b->taps_key, "%s", key);
    b->have |= LUCENT_BAKE_TAPS;
    return LUCENT_OK;
}

/* The Monte Carlo's SIMD path in a cache key (its numbers are its own: docs/mcml.md, "SIMD paths"),
 * nothing for the scalar path, whose keys stay those of earlier versions. */
static const char *mc_path_key(void)
{
    static const char *const keys[LUCENT_ISA_COUNT] = {"", "", " isa avx2", " isa avx512"};
    lucent_isa isa = lucent_isa_active();
    return isa < LUCENT_ISA_COUNT ? keys[isa] : "";
}

/* ---- transmittance (docs/render.md, "Translucency") ---- */

/* The slab's samples, from the cache or the Monte Carlo. The key is the one of earlier versions, so
 * their cache files stay valid. */
static lucent_status slab_samples(const lucent_material *m, const lucent_bake_desc *d, lucent_cache *cache,
                                  lucent_slab_transmittance *t)
{
    char mat[512], key[640];
    material_key(m, mat, sizeof mat);
    snprintf(key, sizeof key, "slab-transmittance v1 %s photons %llu samples %d seed 1%s", mat,
             (unsigned long long)d->transmit_photons, LUCENT_SLAB_SAMPLES, mc_path_key());
    lucent_slab_transmittance_grid(m, t);
    if (lucent_cache_get(cache, "transmittance", key, "transmittance", 3 * LUCENT_SLAB_SAMPLES, &t->value[0][0]))
        return LUCENT_OK;
    double t0 = lucent_clock_seconds();
    lucent_status s = lucent_slab_transmittance_run(m, d->transmit_photons, d->pool, t);
    if (s != LUCENT_OK) return s;
    lucent_log(LUCENT_LOG_INFO, "slab transmittance of %s: %d thicknesses to %.3g mm in %.1f s", m->name,
               LUCENT_SLAB_SAMPLES, t->s_max, lucent_clock_seconds() - t0);
    lucent_cache_field f[2] = {{"thickness_mm", t->thickness, LUCENT_SLAB_SAMPLES},
                               {"transmittance", &t->value[0][0], 3 * LUCENT_SLAB_SAMPLES}};
    lucent_cache_put(cache, "transmittance", key, f, 2);
    return LUCENT_OK;
}

static lucent_status table_from_slab(const lucent_material *m, const lucent_bake_desc *d, lucent_cache *cache,
                                     lucent_baked *b)
{
    lucent_slab_transmittance t;
    lucent_status s = slab_samples(m, d, cache, &t);
    if (s != LUCENT_OK) return s;
    const int n = LUCENT_BAKE_TRANSMIT_SIZE;
    b->transmit_range = 2 * t.s_max; /* the table runs to where T is e^-10 of thin: nothing visible beyond */
    for (int j = 0; j < n; j++)
        for (int c = 0; c < 3; c++)
            b->transmittance[3 * j + c] =
                j == n - 1 ? 0.0f : (float)lucent_slab_transmittance_eval(&t, c, b->transmit_range * j / (n - 1));
    return LUCENT_OK;
}

/* Jimenez 2010 with the material's profile: T(s) / T(0), the profile's power outside radius s. */
static void table_from_profile(const lucent_profile *p, lucent_baked *b)
{
    const int n = LUCENT_BAKE_TRANSMIT_SIZE;
    b->transmit_range = p->count * p->dr;
    for (int c = 0; c < 3; c++) {
        double t0 = lucent_profile_tail(p, c, 0);
        for (int j = 0; j < n; j++) {
            double s = b->transmit_range * j / (n - 1), t = j == n - 1 ? 0 : lucent_profile_tail(p, c, s);
            b->transmittance[3 * j + c] = t0 > 0 ? (float)fmax(t / t0, 0) : 0;
        }
    }
}

static lucent_status bake_transmittance(const lucent_material *m, const lucent_bake_desc *d, lucent_cache *cache,
                                        lucent_baked *b)
{
    lucent_transmittance_model model = d->settings->translucency.transmittance;
    char key[LUCENT_BAKE_KEY_SIZE];
    snprintf(key, sizeof key, "%s%s%.64s", lucent_transmittance_name(model),
             model == LUCENT_TRANSMIT_PROFILE ? " " : "", model == LUCENT_TRANSMIT_PROFILE ? b->profile_key : "");
    if ((b->have & LUCENT_BAKE_TRANSMITTANCE) && !strcmp(key, b->transmit_key)) return LUCENT_OK;
    b->have &= ~(unsigned)LUCENT_BAKE_TRANSMITTANCE, b->transmit_key[0] = '\0', b->transmit_range = 0;
    lucent_status s = LUCENT_OK;
    if (model == LUCENT_TRANSMIT_SLAB)
        s = table_from_slab(m, d, cache, b);
    else
        table_from_profile(b->profile, b);
    if (s != LUCENT_OK) return s;
    snprintf(b->transmit_key, sizeof b->transmit_key, "%s", key);
    b->have |= LUCENT_BAKE_TRANSMITTANCE;
    return LUCENT_OK;
}

/* ---- sigma0 (Kubo Fig. 6: Monte Carlo spheres of the material, fitted) ---- */

static void sigma0_cache_key(const lucent_material *m, lucent_cdrf_variant v, uint64_t photons, char *dest, size_t size)
{
    static const double radii[LUCENT_CDRF_FIT_RADIUS_COUNT] = LUCENT_CDRF_FIT_RADII;
    char mat[512], list[128] = "";
    material_key(m, mat, sizeof mat);
    for (int i = 0; i < LUCENT_CDRF_FIT_RADIUS_COUNT; i++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%g", i ? "," : "", radii[i]);
    snprintf(dest, size, "v3 %s %s photons %llu radii %s bins %d seed 1", mat, lucent_cdrf_variant_name(v),
             (unsigned long long)photons, list, LUCENT_BAKE_SIGMA0_BINS);
}

static lucent_status bake_sigma0(const lucent_material *m, const lucent_bake_desc *d, lucent_cache *cache,
                                 lucent_baked *b)
{
    lucent_cdrf_variant v = (lucent_cdrf_variant)d->settings->cdrf.variant;
    if ((b->have & LUCENT_BAKE_SIGMA0) && !strcmp(b->sigma0_key, lucent_cdrf_variant_name(v))) return LUCENT_OK;
    b->have &= ~(unsigned)LUCENT_BAKE_SIGMA0, b->sigma0_key[0] = '\0';
    char key[1024]; /* room for the longest material key (511) and radius list (127) */
    sigma0_cache_key(m, v, d->sigma0_photons, key, sizeof key);
    b->sigma0_cached = lucent_cache_get(cache, "sigma0", key, "sigma0_mm", 3, b->sigma0) &&
                       lucent_cache_get(cache, "sigma0", key, "kd", 3, b->kd);
    if (!b->sigma0_cached) {
        double t0 = lucent_clock_seconds();
        lucent_cdrf_fit fit;
        lucent_cdrf_material_fit_desc fd = {.material = m,
                                            .variant = v,
                                            .photons = d->sigma0_photons,
                                            .bins = LUCENT_BAKE_SIGMA0_BINS,
                                            .seed = 1,
                                            .pool = d->pool,
                                            .label = "CDRF sigma0 fit"};
        lucent_status s = lucent_cdrf_fit_material(&fd, &fit, NULL);
        if (s != LUCENT_OK) return s;
        memcpy(b->sigma0, fit.sigma0, sizeof b->sigma0);
        memcpy(b->kd, fit.kd, sizeof b->kd);
        lucent_log(LUCENT_LOG_INFO, "sigma0 of %s (%s): %.3g %.3g %.3g mm, fitted in %.1f s", m->name,
                   lucent_cdrf_variant_name(v), b->sigma0[0], b->sigma0[1], b->sigma0[2], lucent_clock_seconds() - t0);
        lucent_cache_field f[4] = {
            {"sigma0_mm", fit.sigma0, 3}, {"kd", fit.kd, 3}, {"rms", fit.rms, 3}, {"lambert_rms", fit.lambert_rms, 3}};
        lucent_cache_put(cache, "sigma0", key, f, 4);
    }
    snprintf(b->sigma0_key, sizeof b->sigma0_key, "%s", lucent_cdrf_variant_name(v));
    b->have |= LUCENT_BAKE_SIGMA0;
    return LUCENT_OK;
}

/* ---- rd: the total diffuse reflectance of a half-space, by the profile's Monte Carlo ---- */

static lucent_status bake_rd(const lucent_material *m, const lucent_bake_desc *d, lucent_cache *cache, lucent_baked *b)
{
    if (b->have & LUCENT_BAKE_RD) return LUCENT_OK;
    if (m->skin.layer_count > 0) { /* a spectral skin: its bands' Monte Carlo totals through the colour weights */
        lucent_skin_color c;
        lucent_bands bands;
        lucent_skin_desc sd = {
            .transport = "mc", .photons = LUCENT_BAKE_SKIN_RD_PHOTONS, .seed = 1, .pool = d->pool, .cache = cache};
        lucent_status s = lucent_skin_color_of(m, &sd, &c);
        if (s == LUCENT_OK) s = lucent_bands_make(c.bands, &bands);
        if (s != LUCENT_OK) return lucent_error_context(s, "material %s: total diffuse reflectance", m->name);
        for (int i = 0; i < 3; i++) {
            double var = 0.0;
            for (int k = 0; k < c.bands; k++) var += pow(bands.rgb[i][k] * c.reflectance_se[k], 2);
            b->rd[i] = c.rgb[i], b->rd_se[i] = sqrt(var);
        }
        b->rd_cached = false;
        b->have |= LUCENT_BAKE_RD;
        return LUCENT_OK;
    }
    char mat[512], key[640];
    material_key(m, mat, sizeof mat);
    snprintf(key, sizeof key, "%s photons %d seed 1%s", mat, (int)LUCENT_BAKE_RD_PHOTONS, mc_path_key());
    b->rd_cached =
        lucent_cache_get(cache, "rd", key, "rd", 3, b->rd) && lucent_cache_get(cache, "rd", key, "rd_se", 3, b->rd_se);
    if (!b->rd_cached) {
        lucent_status s = lucent_profile_mc_total(m, LUCENT_BAKE_RD_PHOTONS, 1, d->pool, b->rd, b->rd_se);
        if (s != LUCENT_OK) return lucent_error_context(s, "material %s: total diffuse reflectance", m->name);
        lucent_cache_field f[2] = {{"rd", b->rd, 3}, {"rd_se", b->rd_se, 3}};
        lucent_cache_put(cache, "rd", key, f, 2);
    }
    b->have |= LUCENT_BAKE_RD;
    return LUCENT_OK;
}

/* ---- the profile as a sum of Gaussians (d'Eon & Luebke 2007: shared variances, RGB weights) ---- */

static lucent_status bake_sog(const lucent_material *m, const lucent_bake_desc *d, lucent_baked *b)
{
    char key[LUCENT_BAKE_KEY_SIZE];
    snprintf(key, sizeof key, "%.64s/%d", b->profile_key, d->sog_count);
    if ((b->have & LUCENT_BAKE_SOG) && !strcmp(key, b->sog_key)) return LUCENT_OK;
    b->have &= ~(unsigned)LUCENT_BAKE_SOG, b->sog_key[0] = '\0';
    if (d->sog_count < 1 || d->sog_count > LUCENT_SOG_MAX)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "material %s: sum of Gaussians: 1 to %d Gaussians, got %d",
                            m->name, LUCENT_SOG_MAX, d->sog_count);
    lucent_sog_desc sd = {.count = d->sog_count, .shared_variances = true};
    lucent_status s = lucent_sog_fit(b->profile, &sd, &b->sog);
    if (s != LUCENT_OK) return lucent_error_context(s, "material %s: sum of Gaussians", m->name);
    snprintf(b->sog_key, sizeof b->sog_key, "%s", key);
    b->have |= LUCENT_BAKE_SOG;
    return LUCENT_OK;
}

/* ---- boundary: the path tracer's rough boundary on a half-space (docs/render.md, "One boundary") ---- */

enum { BB = LUCENT_BOUNDARY_BINS };

/* The methods' albedo, exit curve and entry factor (lucent/bake.h) from the table of pi f and its
 * standard errors, made symmetric first: light and viewer both outside, the reflectance is reciprocal
 * (Helmholtz; the boundary's BSDF keeps the generalised reciprocity of Walter et al. 2007 eq. 21,
 * azimuth averaging keeps it), f(mu_i, mu_o) = f(mu_o, mu_i), so the table and its transpose are two
 * estimates of the same values; their inverse-variance mean has less variance than either (the exit
 * bins near the normal, fed by a narrow cone inside, are the noisiest: their transposes help most). */
static void boundary_factors(const double (*reflect)[BB][BB], const double (*se)[BB][BB], lucent_baked *b)
{
    for (int c = 0; c < 3; c++) {
        double exit[BB], albedo = 0; /* exit[o]: pi f under uniform light, int pi f(mu_i, mu_o) 2 mu_i dmu_i */
        double sym[BB][BB];
        for (int i = 0; i < BB; i++)
            for (int o = 0; o < BB; o++) {
                double va = se[c][i][o] * se[c][i][o], vb = se[c][o][i] * se[c][o][i];
                sym[i][o] = va + vb > 0 ? (reflect[c][i][o] * vb + reflect[c][o][i] * va) / (va + vb)
                                        : 0.5 * (reflect[c][i][o] + reflect[c][o][i]);
            }
        for (int o = 0; o < BB; o++) {
            exit[o] = 0;
            for (int i = 0; i < BB; i++) exit[o] += sym[i][o] * (2.0 * i + 1.0) / (BB * BB);
            albedo += exit[o] * (2.0 * o + 1.0) / (BB * BB);
        }
        b->boundary_albedo[c] = albedo;
        for (int o = 0; o < BB; o++) {
            double e = albedo > 0 ? exit[o] / albedo : 1.0;
            b->boundary[(BB * BB + o) * 3 + c] = (float)e;
            for (int i = 0; i < BB; i++)
                b->boundary[((size_t)i * BB + o) * 3 + c] = exit[o] > 0 ? (float)(sym[i][o] / exit[o]) : 1.0f;
        }
    }
}

static lucent_status bake_boundary(const lucent_material *m, const lucent_bake_desc *d, lucent_cache *cache,
                                   lucent_baked *b)
{
    char key[LUCENT_BAKE_KEY_SIZE];
    snprintf(key, sizeof key, "%.17g/%llu", d->roughness, (unsigned long long)d->boundary_photons);
    if ((b->have & LUCENT_BAKE_BOUNDARY) && !strcmp(key, b->boundary_key)) return LUCENT_OK;
    b->have &= ~(unsigned)LUCENT_BAKE_BOUNDARY, b->boundary_key[0] = '\0';
    char mat[512], ckey[768];
    material_key(m, mat, sizeof mat);
    snprintf(ckey, sizeof ckey, "boundary v1 %s roughness %.17g photons %llu bins %d seed 1", mat, d->roughness,
             (unsigned long long)d->boundary_photons, BB);
    double(*reflect)[BB][BB] = malloc(6 * sizeof *reflect), (*se)[BB][BB] = reflect ? reflect + 3 : NULL;
    if (!reflect) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    b->boundary_cached = lucent_cache_get(cache, "boundary", ckey, "reflect", 3 * BB * BB, &reflect[0][0][0]) &&
                         lucent_cache_get(cache, "boundary", ckey, "reflect_se", 3 * BB * BB, &se[0][0][0]);
    lucent_status s = LUCENT_OK;
    if (!b->boundary_cached) {
        lucent_boundary_result *r = malloc(sizeof *r);
        double t0 = lucent_clock_seconds();
        s = r ? lucent_boundary_run(&(lucent_boundary_desc){.material = m,
                                                            .roughness = d->roughness,
                                                            .photons = d->boundary_photons,
                                                            .seed = 1,
                                                            .pool = d->pool,
                                                            .label = "the boundary's tables"},
                                    r)
              : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
        if (s == LUCENT_OK) {
            memcpy(reflect, r->reflect, 3 * sizeof *reflect);
            memcpy(se, r->reflect_se, 3 * sizeof *se);
            lucent_log(LUCENT_LOG_INFO, "boundary tables of %s at roughness %g in %.1f s", m->name, d->roughness,
                       lucent_clock_seconds() - t0);
            lucent_cache_field f[2] = {{"reflect", &r->reflect[0][0][0], 3 * BB * BB},
                                       {"reflect_se", &r->reflect_se[0][0][0], 3 * BB * BB}};
            lucent_cache_put(cache, "boundary", ckey, f, 2);
        }
        free(r);
    }
    if (s == LUCENT_OK) {
        boundary_factors((const double(*)[BB][BB])reflect, (const double(*)[BB][BB])se, b);
        b->boundary_roughness = d->roughness;
        snprintf(b->boundary_key, sizeof b->boundary_key, "%s", key);
        b->have |= LUCENT_BAKE_BOUNDARY;
    }
    free(reflect);
    return s == LUCENT_OK ? s : lucent_error_context(s, "material %s: boundary tables", m->name);
}

/* ---- sheet: the thin parts' light (docs/render.md, "Thin parts") ---- */

enum { SHR = LUCENT_BAKE_SHEET_ROWS, SHB = LUCENT_SHEET_BINS };

static lucent_status bake_sheet(const lucent_material *m, const lucent_bake_desc *d, lucent_cache *cache,
                                lucent_baked *b)
{
    char key[LUCENT_BAKE_KEY_SIZE];
    snprintf(key, sizeof key, "%.17g/%llu", d->roughness, (unsigned long long)d->sheet_photons);
    if ((b->have & LUCENT_BAKE_SHEET) && !strcmp(key, b->sheet_key)) return LUCENT_OK;
    b->have &= ~(unsigned)LUCENT_BAKE_SHEET, b->sheet_key[0] = '\0';
    lucent_material_derived md;
    lucent_material_derive(m, &md);
    double tr = fmin(md.sigma_tr[0], fmin(md.sigma_tr[1], md.sigma_tr[2]));
    double range = 5.0 / fmax(tr, 1e-3);
    char mat[512], ckey[768];
    material_key(m, mat, sizeof mat);
    snprintf(ckey, sizeof ckey, "sheet v2 %s roughness %.17g photons %llu rows %d to %.17g bins %d seed 1", mat,
             d->roughness, (unsigned long long)d->sheet_photons, SHR, range, SHB);
    double *tab = malloc(2 * SHR * SHB * 3 * sizeof *tab);
    if (!tab) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    b->sheet_cached = lucent_cache_get(cache, "sheet", ckey, "sheet", 2 * SHR * SHB * 3, tab);
    lucent_status s = LUCENT_OK;
    if (!b->sheet_cached) {
        lucent_sheet_result *r = malloc(SHR * sizeof *r);
        double t0 = lucent_clock_seconds(), thick[SHR];
        for (int j = 0; j < SHR; j++) thick[j] = range * ((j + 1.0) / SHR) * ((j + 1.0) / SHR);
        s = r ? lucent_sheet_run_many(&(lucent_sheet_desc){.material = m,
                                                           .roughness = d->roughness,
                                                           .photons = d->sheet_photons,
                                                           .seed = 1,
                                                           .pool = d->pool,
                                                           .label = "the thin parts' sheets"},
                                      thick, SHR, r)
              : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
        for (int j = 0; s == LUCENT_OK && j < SHR; j++)
            for (int o = 0; o < SHB; o++)
                for (int c = 0; c < 3; c++) {
                    tab[((size_t)j * SHB + o) * 3 + c] = r[j].lobe[c][o];
                    tab[((size_t)(SHR + j) * SHB + o) * 3 + c] = r[j].diffuse[c][o];
                }
        free(r);
        if (s == LUCENT_OK) {
            lucent_log(LUCENT_LOG_INFO, "sheet tables of %s at roughness %g: %d thicknesses to %.3g mm in %.1f s",
                       m->name, d->roughness, SHR, range, lucent_clock_seconds() - t0);
            lucent_cache_field f[1] = {{"sheet", tab, 2 * SHR * SHB * 3}};
            lucent_cache_put(cache, "sheet", ckey, f, 1);
        }
    }
    if (s == LUCENT_OK) {
        for (size_t k = 0; k < (size_t)2 * SHR * SHB * 3; k++) b->sheet[k] = (float)fmax(tab[k], 0.0);
        b->sheet_range = range;
        snprintf(b->sheet_key, sizeof b->sheet_key, "%s", key);
        b->have |= LUCENT_BAKE_SHEET;
    }
    free(tab);
    return s == LUCENT_OK ? s : lucent_error_context(s, "material %s: sheet tables", m->name);
}

/* ---- spheres: the curved parts' exitance (docs/render.md, "Curved parts") ---- */

enum { SR = LUCENT_BAKE_SPHERE_RADII, SB = LUCENT_BAKE_SPHERE_BINS };

/* The half-space's exitance per unit irradiance at incidence cosine mu, a(mu): albedo x the entry
 * factor's mean over exit (lucent/bake.h), linear in mu between the incidence bins' centres. */
static double half_space_albedo(const lucent_baked *b, int c, double mu)
{
    double y = fmin(fmax(mu * BB - 0.5, 0), BB - 1);
    int i0 = (int)fmin(floor(y), BB - 2);
    double f = y - i0, a[2] = {0, 0};
    for (int k = 0; k < 2; k++)
        for (int o = 0; o < BB; o++)
            a[k] += b->boundary[((size_t)(i0 + k) * BB + o) * 3 + c] * b->boundary[(BB * BB + o) * 3 + c] *
                    (2.0 * o + 1.0) / (BB * BB);
    return b->boundary_albedo[c] * ((1 - f) * a[0] + f * a[1]);
}

static double sphere_r0(const lucent_material *m)
{
    lucent_material_derived md;
    lucent_material_derive(m, &md);
    double tr = fmax(md.sigma_tr[0], fmax(md.sigma_tr[1], md.sigma_tr[2]));
    return 0.25 / fmax(tr, 1e-3);
}

static void spheres_table(const double (*exitance)[SR][SB], const double (*flow)[SR][SB], lucent_baked *b)
{
    size_t beta = (size_t)(SR + 1) * SB * 3; /* the second half: beta */
    for (int c = 0; c < 3; c++)
        for (int j = 0; j < SB; j++) {
            double ta = M_PI * j / SB, tb = M_PI * (j + 1) / SB;
            double flat = (sin(fmin(tb, M_PI / 2)) - sin(fmin(ta, M_PI / 2))) / (tb - ta); /* mean of max(cos, 0) */
            double a = half_space_albedo(b, c, fmax(cos(0.5 * (ta + tb)), 0));
            for (int k = 0; k < SR; k++) {
                b->spheres[((size_t)k * SB + j) * 3 + c] = a > 0 ? (float)(exitance[c][k][j] / a) : 0.0f;
                b->spheres[beta + ((size_t)k * SB + j) * 3 + c] = (float)(4.0 * flow[c][k][j]);
            }
            b->spheres[((size_t)SR * SB + j) * 3 + c] = (float)flat;
            b->spheres[beta + ((size_t)SR * SB + j) * 3 + c] = 0.0f;
        }
}

static lucent_status bake_spheres(const lucent_material *m, const lucent_bake_desc *d, lucent_cache *cache,
                                  lucent_baked *b)
{
    char key[LUCENT_BAKE_KEY_SIZE];
    snprintf(key, sizeof key, "%.64s/%llu", b->boundary_key, (unsigned long long)d->sphere_photons);
    if ((b->have & LUCENT_BAKE_SPHERES) && !strcmp(key, b->spheres_key)) return LUCENT_OK;
    b->have &= ~(unsigned)LUCENT_BAKE_SPHERES, b->spheres_key[0] = '\0';
    char mat[512], ckey[768];
    material_key(m, mat, sizeof mat);
    double r0 = sphere_r0(m);
    snprintf(ckey, sizeof ckey, "spheres v2 %s roughness %.17g photons %llu radii %d from %.17g bins %d seed 1", mat,
             d->roughness, (unsigned long long)d->sphere_photons, SR, r0, SB);
    double(*exitance)[SR][SB] = malloc(6 * sizeof *exitance), (*flow)[SR][SB] = exitance ? exitance + 3 : NULL;
    if (!exitance) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    b->spheres_cached = lucent_cache_get(cache, "spheres", ckey, "exitance", 3 * SR * SB, &exitance[0][0][0]) &&
                        lucent_cache_get(cache, "spheres", ckey, "flow", 3 * SR * SB, &flow[0][0][0]);
    lucent_status s = LUCENT_OK;
    if (!b->spheres_cached) {
        double t0 = lucent_clock_seconds();
        for (int k = 0; k < SR && s == LUCENT_OK; k++) {
            lucent_cdrf_sphere_result r;
            lucent_cdrf_sphere_desc sd = {.material = m,
                                          .radius = r0 * pow(2.0, 0.5 * k),
                                          .roughness = d->roughness,
                                          .photons = d->sphere_photons,
                                          .bins = SB,
                                          .batches = 8,
                                          .seed = 1 + (uint64_t)k,
                                          .pool = d->pool,
                                          .label = "curved parts: Monte Carlo spheres"};
            s = lucent_cdrf_sphere_run(&sd, &r);
            for (int c = 0; s == LUCENT_OK && c < 3; c++) {
                memcpy(exitance[c][k], r.exitance[c], sizeof exitance[c][k]);
                memcpy(flow[c][k], r.flow[c], sizeof flow[c][k]);
            }
        }
        if (s == LUCENT_OK) {
            lucent_log(LUCENT_LOG_INFO, "spheres of %s at roughness %g: %d radii from %.3g mm in %.1f s", m->name,
                       d->roughness, SR, r0, lucent_clock_seconds() - t0);
            lucent_cache_field f[2] = {{"exitance", &exitance[0][0][0], 3 * SR * SB},
                                       {"flow", &flow[0][0][0], 3 * SR * SB}};
            lucent_cache_put(cache, "spheres", ckey, f, 2);
        }
    }
    if (s == LUCENT_OK) {
        spheres_table((const double(*)[SR][SB])exitance, (const double(*)[SR][SB])flow, b);
        b->sphere_r0 = r0;
        snprintf(b->spheres_key, sizeof b->spheres_key, "%s", key);
        b->have |= LUCENT_BAKE_SPHERES;
    }
    free(exitance);
    return s == LUCENT_OK ? s : lucent_error_context(s, "material %s: curved parts", m->name);
}

lucent_status lucent_material_bake(const lucent_material *material, const lucent_bake_desc *desc, lucent_cache *cache,
                                   lucent_baked *baked)
{
    lucent_render_settings defaults;
    lucent_bake_desc d = resolve(desc, &defaults);
    lucent_status s = LUCENT_OK;
    lucent_material resolved;
    if (material->skin.layer_count > 0 && !material->skin.resolved) { /* its equivalent medium, for the parts
                                                                          that read coefficients */
        resolved = *material;
        if ((s = lucent_skin_resolve(&resolved)) != LUCENT_OK)
            return lucent_error_context(s, "material %s", material->name);
        material = &resolved;
    }
    if (d.what & LUCENT_BAKE_PROFILE) s = bake_profile(material, &d, baked);
    if (s == LUCENT_OK && (d.what & LUCENT_BAKE_TAPS)) s = bake_taps(material, &d, baked);
    if (s == LUCENT_OK && (d.what & LUCENT_BAKE_TRANSMITTANCE)) s = bake_transmittance(material, &d, cache, baked);
    if (s == LUCENT_OK && (d.what & LUCENT_BAKE_SIGMA0)) s = bake_sigma0(material, &d, cache, baked);
    if (s == LUCENT_OK && (d.what & LUCENT_BAKE_SOG)) s = bake_sog(material, &d, baked);
    if (s == LUCENT_OK && (d.what & LUCENT_BAKE_RD)) s = bake_rd(material, &d, cache, baked);
    if (s == LUCENT_OK && (d.what & LUCENT_BAKE_BOUNDARY)) {
        if (!(d.roughness >= 0) || d.roughness > 1)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                                "material %s: boundary roughness must be in [0, 1] (got %g)", material->name,
                                d.roughness);
        s = bake_boundary(material, &d, cache, baked);
    }
    if (s == LUCENT_OK && (d.what & LUCENT_BAKE_SPHERES)) s = bake_spheres(material, &d, cache, baked);
    if (s == LUCENT_OK && (d.what & LUCENT_BAKE_SHEET)) {
        if (!(d.roughness >= 0) || d.roughness > 1)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "material %s: sheet roughness must be in [0, 1] (got %g)",
                                material->name, d.roughness);
        s = bake_sheet(material, &d, cache, baked);
    }
    return s;
}

lucent_status lucent_baked_copy(const lucent_baked *src, lucent_baked *dest)
{
    if (src == dest) return LUCENT_OK;
    lucent_baked_free(dest);
    *dest = *src;
    dest->profile = NULL, dest->taps = NULL;
    lucent_status s = src->profile ? lucent_profile_clone(src->profile, &dest->profile) : LUCENT_OK;
    if (s == LUCENT_OK && src->taps) s = lucent_taps_clone(src->taps, &dest->taps);
    if (s != LUCENT_OK) lucent_baked_free(dest);
    return s;
}

void lucent_baked_free(lucent_baked *baked)
{
    if (!baked) return;
    lucent_profile_destroy(baked->profile);
    lucent_taps_destroy(baked->taps);
    memset(baked, 0, sizeof *baked);
}
