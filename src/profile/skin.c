/* The spectral skin (lucent/skin.h, docs/skin.md): each band a layered medium carried by the layered
 * multipole (multipole.c, through profile/layered.h) or the Monte Carlo (lucent/mc.h), the bands weighted
 * into linear sRGB per radius; the equivalent homogeneous medium; the three-coefficient shortcut. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/skin.h"
#include "profile/layered.h"

#define SKIN_DEEP_MIN 10.0  /* mm: the least thickness standing for a semi-infinite layer */
#define SKIN_DEEP_DECAYS 30 /* ... and at least this many 1 / sigma_tr of its slowest channel */

static const lucent_skin *skin_of(const lucent_material *m) { return &m->skin; }

static lucent_status check_skin(const lucent_material *m)
{
    if (m->skin.layer_count == 0)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: not a skin material", m->name[0] ? m->name : "material");
    lucent_status s = lucent_skin_validate(&m->skin, m->name);
    if (s == LUCENT_OK && !(m->eta >= LUCENT_MATERIAL_ETA_MIN && m->eta <= LUCENT_MATERIAL_ETA_MAX))
        s = lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: eta: must be in [%g, %g], got %g", m->name,
                         LUCENT_MATERIAL_ETA_MIN, LUCENT_MATERIAL_ETA_MAX, m->eta);
    return s;
}

/* One layer as a lucent_layer whose channel c is wavelength nm[c]; eta for every layer (the interfaces
 * inside are matched), air above and below. */
static void band_layer(const lucent_material *m, int i, const double nm[3], lucent_layer *dest)
{
    const lucent_skin_layer *l = &skin_of(m)->layer[i];
    memset(dest, 0, sizeof *dest);
    snprintf(dest->material.name, sizeof dest->material.name, "%s", lucent_skin_layer_name(l->kind));
    dest->material.eta = m->eta;
    double slowest = INFINITY;
    for (int c = 0; c < 3; c++) {
        double sa, ssp;
        lucent_skin_coefficients(skin_of(m), i, nm[c], &sa, &ssp);
        dest->material.sigma_a[c] = sa;
        dest->material.sigma_s[c] = ssp / (1.0 - l->g);
        dest->material.g[c] = l->g;
        slowest = fmin(slowest, sqrt(3.0 * sa * (sa + ssp))); /* sigma_tr */
    }
    dest->slab.thickness = l->thickness;
    if (!isfinite(l->thickness)) { /* semi-infinite: deep enough that nothing comes back from below */
        dest->slab.thickness = fmax(SKIN_DEEP_MIN, SKIN_DEEP_DECAYS / slowest);
        dest->slab.poles = 2;
    }
}

lucent_status lucent_skin_layers(const lucent_material *m, const double nm[3], lucent_layer *dest, int *count)
{
    lucent_status s = check_skin(m);
    if (s != LUCENT_OK) return s;
    for (int i = 0; i < m->skin.layer_count; i++) band_layer(m, i, nm, &dest[i]);
    *count = m->skin.layer_count;
    return LUCENT_OK;
}

lucent_status lucent_skin_mc_layers(const lucent_material *m, double nm, lucent_mc_layer *dest, int *count)
{
    lucent_status s = check_skin(m);
    if (s != LUCENT_OK) return s;
    for (int i = 0; i < m->skin.layer_count; i++) {
        const lucent_skin_layer *l = &m->skin.layer[i];
        double sa, ssp;
        lucent_skin_coefficients(&m->skin, i, nm, &sa, &ssp);
        dest[i] = (lucent_mc_layer){
            .n = m->eta, .sigma_a = sa, .sigma_s = ssp / (1.0 - l->g), .g = l->g, .thickness = l->thickness};
    }
    *count = m->skin.layer_count;
    return LUCENT_OK;
}

/* The bands packed three per set of layers: set i's channel c is band 3 i + c (the last set repeats its
 * last band in unused channels, with weight 0). sets has room for ceil(count / 3) * layer_count. */
static int band_sets(const lucent_material *m, const lucent_bands *b, lucent_layer *sets)
{
    int n = (b->count + 2) / 3, layers = m->skin.layer_count;
    for (int i = 0; i < n; i++) {
        double nm[3];
        for (int c = 0; c < 3; c++) nm[c] = b->center[3 * i + c < b->count ? 3 * i + c : b->count - 1];
        for (int l = 0; l < layers; l++) band_layer(m, l, nm, &sets[i * layers + l]);
    }
    return n;
}

/* weight[c (3 sets) + t] for stack t = band t (0 past the last band). */
static void band_weights(const lucent_bands *b, int sets, double *weight)
{
    for (int c = 0; c < 3; c++)
        for (int t = 0; t < 3 * sets; t++) weight[c * 3 * sets + t] = t < b->count ? b->rgb[c][t] : 0.0;
}

/* The multipole puts a layer's source at depth 1/sigma_t': a layer much thinner than that (an anatomical
 * epidermis of 0.1 mm in the red) comes out wrong (docs/skin.md). Logs one warning per call when some
 * finite layer is thinner than half its transport mean free path in some band. */
static void warn_thin(const lucent_material *m, const lucent_bands *b)
{
    for (int i = 0; i < m->skin.layer_count; i++) {
        const lucent_skin_layer *l = &m->skin.layer[i];
        double worst = 0.0, at = 0.0;
        for (int k = 0; isfinite(l->thickness) && k < b->count; k++) {
            double sa, ssp;
            lucent_skin_coefficients(&m->skin, i, b->center[k], &sa, &ssp);
            if (1.0 / (sa + ssp) > worst) worst = 1.0 / (sa + ssp), at = b->center[k];
        }
        if (worst > 2.0 * l->thickness)
            lucent_log(LUCENT_LOG_WARN,
                       "skin %s: the %s (%g mm) is thinner than half its transport mean free path (%.3g mm at %.0f "
                       "nm): the layered multipole is wrong there; the Monte Carlo (transport mc) takes it",
                       m->name, lucent_skin_layer_name(l->kind), l->thickness, worst, at);
    }
}

/* ---- totals and colour ---- */

/* F_c(k) of every band (f[band]), for the sets of band_sets. */
static void band_hats(const lucent_bands *b, const lucent_layer *sets, int layers, double k, double *f)
{
    for (int i = 0; i < (b->count + 2) / 3; i++) {
        double rt[3], td[3];
        layered_hat(sets + (size_t)i * (size_t)layers, layers, k, rt, td);
        for (int c = 0; c < 3 && 3 * i + c < b->count; c++) f[3 * i + c] = rt[c];
    }
}

static lucent_status make_sets(const lucent_material *m, const lucent_bands *b, lucent_layer **sets)
{
    int n = (b->count + 2) / 3;
    *sets = calloc((size_t)n * (size_t)m->skin.layer_count, sizeof **sets);
    if (!*sets) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: skin: out of memory", m->name);
    band_sets(m, b, *sets);
    lucent_status s = LUCENT_OK;
    for (int i = 0; i < n && s == LUCENT_OK; i++)
        s = layered_mix_check(*sets + (size_t)i * (size_t)m->skin.layer_count, m->skin.layer_count);
    if (s != LUCENT_OK) {
        free(*sets);
        *sets = NULL;
        return lucent_error_context(s, "%s: skin", m->name);
    }
    return LUCENT_OK;
}

/* The Monte Carlo total of every band (the truth the multipole approximates), from the cache when there. */
static lucent_status mc_totals(const lucent_material *m, const lucent_skin_desc *d, const lucent_bands *b, double *r,
                               double *se)
{
    uint64_t photons = d->photons ? d->photons : LUCENT_SKIN_COLOR_PHOTONS;
    char key[1024];
    int n = snprintf(key, sizeof key, "skin-colour v1 eta %.17g bands %d photons %llu seed %llu layers", m->eta,
                     b->count, (unsigned long long)photons, (unsigned long long)d->seed);
    for (int i = 0; i < m->skin.layer_count && n > 0 && (size_t)n < sizeof key; i++) {
        const lucent_skin_layer *l = &m->skin.layer[i];
        n += snprintf(key + n, sizeof key - (size_t)n, " [%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g]",
                      l->kind, l->thickness, l->melanin, l->eumelanin, l->blood, l->oxygenation, l->scatter,
                      l->f_rayleigh, l->b_mie, l->g);
    }
    if (lucent_cache_get(d->cache, "skin", key, "reflectance", b->count, r) &&
        lucent_cache_get(d->cache, "skin", key, "reflectance_se", b->count, se))
        return LUCENT_OK;
    for (int k = 0; k < b->count; k++) {
        lucent_mc_layer layers[LUCENT_SKIN_MAX_LAYERS];
        int count;
        lucent_mc_result res = {0};
        char label[48];
        snprintf(label, sizeof label, "Monte Carlo %.0f nm", b->center[k]);
        lucent_status s = lucent_skin_mc_layers(m, b->center[k], layers, &count);
        lucent_mc_desc md = {.layers = layers,
                             .layer_count = count,
                             .photons = photons,
                             .seed = d->seed * LUCENT_BANDS_MAX + (uint64_t)k,
                             .grid = {.dr = 1e3, .nr = 1}, /* totals only */
                             .pool = d->pool,
                             .label = label};
        if (s == LUCENT_OK) s = lucent_mc_run(&md, &res);
        if (s != LUCENT_OK) return lucent_error_context(s, "%s: skin colour (mc, %.0f nm)", m->name, b->center[k]);
        r[k] = res.rd, se[k] = res.rd_se;
        lucent_mc_result_free(&res);
    }
    lucent_cache_field f[2] = {{"reflectance", r, b->count}, {"reflectance_se", se, b->count}};
    lucent_cache_put(d->cache, "skin", key, f, 2);
    return LUCENT_OK;
}

lucent_status lucent_skin_color_of(const lucent_material *m, const lucent_skin_desc *desc, lucent_skin_color *dest)
{
    static const lucent_skin_desc zero = {0};
    const lucent_skin_desc *d = desc ? desc : &zero;
    const char *transport = d->transport ? d->transport : "multipole";
    bool mc = !strcmp(transport, "mc"), shortcut = !strcmp(transport, "shortcut");
    if (!mc && !shortcut && strcmp(transport, "multipole"))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "skin: unknown transport \"%s\" (multipole, mc, shortcut)",
                            transport);
    lucent_bands b;
    lucent_status s = check_skin(m);
    if (s == LUCENT_OK) s = lucent_bands_make(d->bands, &b);
    if (s != LUCENT_OK) return s;
    memset(dest, 0, sizeof *dest);
    dest->bands = b.count;
    memcpy(dest->center, b.center, sizeof b.center);
    if (shortcut) { /* three channels, no spectrum: the colour from the shortcut's totals */
        lucent_layer layers[LUCENT_SKIN_MAX_LAYERS];
        int count;
        double td[3];
        if ((s = lucent_skin_shortcut_layers(m, b.count, layers, &count)) == LUCENT_OK &&
            (s = layered_mix_check(layers, count)) == LUCENT_OK)
            layered_hat(layers, count, 0.0, dest->rgb, td);
        if (s != LUCENT_OK) return s;
        lucent_bands_rgb_to_xyz(&b, dest->rgb, dest->xyz);
        lucent_xyz_to_lab(dest->xyz, b.white_xyz, dest->lab);
        dest->ita = lucent_ita(dest->lab);
        dest->category = lucent_ita_category(dest->ita);
        return LUCENT_OK;
    }
    if (mc) {
        s = mc_totals(m, d, &b, dest->reflectance, dest->reflectance_se);
    } else {
        lucent_layer *sets = NULL;
        warn_thin(m, &b);
        s = make_sets(m, &b, &sets);
        if (s == LUCENT_OK) band_hats(&b, sets, m->skin.layer_count, 0.0, dest->reflectance);
        free(sets);
    }
    if (s != LUCENT_OK) return s;
    lucent_bands_xyz(&b, dest->reflectance, dest->xyz);
    lucent_bands_rgb(&b, dest->reflectance, dest->rgb);
    lucent_xyz_to_lab(dest->xyz, b.white_xyz, dest->lab);
    dest->ita = lucent_ita(dest->lab);
    dest->category = lucent_ita_category(dest->ita);
    return LUCENT_OK;
}

/* ---- the equivalent homogeneous medium ---- */

/* F(0) and the second moment <r^2> = -4 F''(0) / F(0) of a radial profile from its transform at k = 0,
 * h and 2 h (F(k) = F0 (1 - k^2 <r^2> / 4 + O(k^4)); Richardson's extrapolation removes the k^4 term). */
static double second_moment(double f0, double fh, double f2h, double h)
{
    double a = (16.0 * (fh - f0) - (f2h - f0)) / (12.0 * h * h); /* the k^2 coefficient */
    return -4.0 * a / f0;
}

#define MOMENT_K 2e-3 /* mm^-1: far below any sigma_tr of skin (>= 0.1 mm^-1) */

/* The half-space of unit sigma_t' and reduced albedo ap under the same multipole: total R, <r^2>. */
static void unit_half_space(double ap, double eta, double *r, double *r2)
{
    lucent_layer l;
    memset(&l, 0, sizeof l);
    l.material.eta = eta;
    for (int c = 0; c < 3; c++) l.material.sigma_a[c] = 1.0 - ap, l.material.sigma_s[c] = ap;
    double s = sqrt(3.0 * (1.0 - ap));
    l.slab.thickness = fmax(SKIN_DEEP_MIN, SKIN_DEEP_DECAYS / fmax(s, 1e-6));
    l.slab.poles = 2;
    double f[3][3], t[3];
    for (int k = 0; k < 3; k++) layered_hat(&l, 1, k * MOMENT_K, f[k], t);
    *r = f[0][0];
    *r2 = second_moment(f[0][0], f[1][0], f[2][0], MOMENT_K);
}

/* The reduced albedo whose unit half-space reflects r (bisection; R increases with alpha'). */
static double albedo_for(double r, double eta)
{
    double lo = 1e-6, hi = 1.0 - 1e-9, rr, r2;
    for (int it = 0; it < 60; it++) {
        double mid = 0.5 * (lo + hi);
        unit_half_space(mid, eta, &rr, &r2);
        if (rr < r)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

/* The layer whose g the equivalent medium takes: the dermis when there is one. */
static double equivalent_g(const lucent_skin *s)
{
    for (int i = 0; i < s->layer_count; i++)
        if (s->layer[i].kind == LUCENT_SKIN_DERMIS) return s->layer[i].g;
    return s->layer[s->layer_count - 1].g;
}

lucent_status lucent_skin_resolve(lucent_material *m)
{
    if (m->skin.layer_count == 0) return LUCENT_OK;
    lucent_bands b;
    lucent_layer *sets = NULL;
    lucent_status s = check_skin(m);
    if (s == LUCENT_OK) s = lucent_bands_make(0, &b);
    if (s == LUCENT_OK) s = make_sets(m, &b, &sets);
    if (s != LUCENT_OK) return s;
    double f[3][LUCENT_BANDS_MAX];
    for (int k = 0; k < 3; k++) band_hats(&b, sets, m->skin.layer_count, k * MOMENT_K, f[k]);
    free(sets);
    double g = equivalent_g(&m->skin);
    for (int c = 0; c < 3; c++) {
        double fc[3] = {0, 0, 0}, fa[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < b.count; j++) fc[k] += b.rgb[c][j] * f[k][j], fa[k] += fabs(b.rgb[c][j]) * f[k][j];
        /* the spread from the bands weighted by |W|: the signed weights' negative lobes (blue and green take
         * the red bands' long tails with a negative weight) make the signed moment unstable */
        double r2 = second_moment(fa[0], fa[1], fa[2], MOMENT_K);
        double ap = albedo_for(fmax(fc[0], 1e-6), m->eta), ru, r2u;
        unit_half_space(ap, m->eta, &ru, &r2u);
        double stp = sqrt(r2u / r2); /* <r^2> scales as 1 / sigma_t'^2 */
        m->sigma_a[c] = (1.0 - ap) * stp;
        m->sigma_s[c] = ap * stp / (1.0 - g);
        m->g[c] = g;
    }
    m->skin.resolved = 1;
    return LUCENT_OK;
}

/* ---- profiles ---- */

static lucent_status skin_grid(const lucent_material *m, const lucent_skin_desc *d, lucent_profile_grid *g)
{
    lucent_material eq = *m;
    lucent_status s = eq.skin.resolved ? LUCENT_OK : lucent_skin_resolve(&eq);
    if (s == LUCENT_OK) s = lucent_profile_grid_resolve(&d->grid, &eq, g);
    return s;
}

static lucent_status profile_multipole(const lucent_material *m, const lucent_bands *b, const lucent_profile_grid *g,
                                       lucent_profile **dest)
{
    lucent_layer *sets = NULL;
    lucent_status s = make_sets(m, b, &sets);
    if (s != LUCENT_OK) return s;
    int n = (b->count + 2) / 3;
    double *weight = malloc(sizeof *weight * 9u * (size_t)n);
    lucent_profile *pair[2] = {NULL, NULL};
    if (!weight) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: skin: out of memory", m->name);
    if (s == LUCENT_OK) band_weights(b, n, weight);
    if (s == LUCENT_OK) s = layered_profile_mix(sets, n, m->skin.layer_count, weight, g, pair);
    free(weight);
    free(sets);
    if (s != LUCENT_OK) return lucent_error_context(s, "%s: skin profile", m->name);
    lucent_profile_destroy(pair[1]);
    snprintf(pair[0]->model, sizeof pair[0]->model, "skin-multipole");
    *dest = pair[0];
    return LUCENT_OK;
}

static lucent_status profile_mc(const lucent_material *m, const lucent_skin_desc *d, const lucent_bands *b,
                                const lucent_profile_grid *g, lucent_profile **dest)
{
    lucent_status s = lucent_profile_create(g, "skin-mc", dest);
    double *var = s == LUCENT_OK ? calloc(3u * (size_t)g->count, sizeof *var) : NULL;
    if (s == LUCENT_OK && !var) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: skin: out of memory", m->name);
    for (int k = 0; k < b->count && s == LUCENT_OK; k++) {
        lucent_mc_layer layers[LUCENT_SKIN_MAX_LAYERS];
        int count;
        lucent_mc_result r = {0};
        char label[48];
        snprintf(label, sizeof label, "Monte Carlo %.0f nm", b->center[k]);
        s = lucent_skin_mc_layers(m, b->center[k], layers, &count);
        lucent_mc_desc md = {.layers = layers,
                             .layer_count = count,
                             .photons = d->photons ? d->photons : LUCENT_SKIN_MC_PHOTONS,
                             .seed = d->seed * LUCENT_BANDS_MAX + (uint64_t)k,
                             .grid = {.dr = g->dr, .nr = g->count},
                             .pool = d->pool,
                             .label = label};
        if (s == LUCENT_OK) s = lucent_mc_run(&md, &r);
        for (int c = 0; s == LUCENT_OK && c < 3; c++)
            for (int j = 0; j < g->count; j++) {
                double w = b->rgb[c][k];
                (*dest)->value[c][j] += w * r.rd_r[j];
                var[c * g->count + j] += w * w * r.rd_r_se[j] * r.rd_r_se[j];
            }
        lucent_mc_result_free(&r);
    }
    for (int c = 0; s == LUCENT_OK && c < 3; c++)
        for (int j = 0; j < g->count; j++) (*dest)->error[c][j] = sqrt(var[c * g->count + j]);
    free(var);
    if (s != LUCENT_OK) {
        lucent_profile_destroy(*dest);
        *dest = NULL;
        return lucent_error_context(s, "%s: skin profile (mc)", m->name);
    }
    return LUCENT_OK;
}

lucent_status lucent_profile_skin(const lucent_material *m, const lucent_skin_desc *desc, lucent_profile **dest)
{
    static const lucent_skin_desc zero = {0};
    const lucent_skin_desc *d = desc ? desc : &zero;
    *dest = NULL;
    const char *transport = d->transport ? d->transport : "multipole";
    bool mc = !strcmp(transport, "mc"), shortcut = !strcmp(transport, "shortcut");
    if (!mc && !shortcut && strcmp(transport, "multipole"))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "skin: unknown transport \"%s\" (multipole, mc, shortcut)",
                            transport);
    lucent_bands b;
    lucent_profile_grid g;
    lucent_status s = check_skin(m);
    if (s == LUCENT_OK) s = lucent_bands_make(d->bands, &b);
    if (s == LUCENT_OK) s = skin_grid(m, d, &g);
    if (s != LUCENT_OK) return s;
    if (shortcut) {
        lucent_layer layers[LUCENT_SKIN_MAX_LAYERS];
        lucent_profile *pair[2] = {NULL, NULL};
        int count;
        s = lucent_skin_shortcut_layers(m, b.count, layers, &count);
        if (s == LUCENT_OK) s = lucent_profile_layered(layers, count, &g, pair);
        if (s != LUCENT_OK) return lucent_error_context(s, "%s: skin shortcut", m->name);
        lucent_profile_destroy(pair[1]);
        snprintf(pair[0]->model, sizeof pair[0]->model, "skin-shortcut");
        *dest = pair[0];
        return LUCENT_OK;
    }
    if (!mc) warn_thin(m, &b);
    return mc ? profile_mc(m, d, &b, &g, dest) : profile_multipole(m, &b, &g, dest);
}

/* ---- the three-coefficient shortcut ---- */

lucent_status lucent_skin_shortcut_layers(const lucent_material *m, int bands, lucent_layer *dest, int *count)
{
    lucent_bands b;
    lucent_status s = check_skin(m);
    if (s == LUCENT_OK) s = lucent_bands_make(bands, &b);
    if (s != LUCENT_OK) return s;
    for (int i = 0; i < m->skin.layer_count; i++) {
        double sa[3] = {0, 0, 0}, ssp[3] = {0, 0, 0}, wsum[3] = {0, 0, 0};
        for (int k = 0; k < b.count; k++) {
            double a, sp;
            lucent_skin_coefficients(&m->skin, i, b.center[k], &a, &sp);
            for (int c = 0; c < 3; c++) {
                double w = fmax(b.rgb[c][k], 0.0); /* the channel's positive lobe */
                sa[c] += w * a, ssp[c] += w * sp, wsum[c] += w;
            }
        }
        double nm[3] = {550, 550, 550};
        band_layer(m, i, nm, &dest[i]); /* thickness, g, eta; coefficients replaced below */
        double slowest = INFINITY;
        for (int c = 0; c < 3; c++) {
            sa[c] /= wsum[c], ssp[c] /= wsum[c];
            dest[i].material.sigma_a[c] = sa[c];
            dest[i].material.sigma_s[c] = ssp[c] / (1.0 - m->skin.layer[i].g);
            slowest = fmin(slowest, sqrt(3.0 * sa[c] * (sa[c] + ssp[c])));
        }
        if (!isfinite(m->skin.layer[i].thickness))
            dest[i].slab.thickness = fmax(SKIN_DEEP_MIN, SKIN_DEEP_DECAYS / slowest);
    }
    *count = m->skin.layer_count;
    return LUCENT_OK;
}
