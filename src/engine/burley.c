/* The Burley family (Christensen & Burley 2015, eq. 2: R(r) = A s (e^{-s r} + e^{-s r / 3}) / (8 pi r)),
 * with each engine's own mapping from its parameters to A and d = 1 / s:
 *   Unreal Engine 5, Subsurface Profile with Burley and "Enable Mean Free Path" (UE 5.x,
 *     Engine/Source/Runtime/Engine/Private/Rendering/BurleyNormalizedSSS.cpp and SubsurfaceProfile.cpp, read in
 *     public copies; UE itself was not run): the mean free path l = Mean Free Path Color x Distance (world
 *     units, cm) x World Unit Scale x 10 mm, s = GetPerpendicularScalingFactor(A) / l, the paper's eq. 5;
 *   Unity HDRP Diffusion Profile (DiffusionProfileSettings.cs: shapeParam = 1 / scatteringDistance): d =
 *     Scattering Color x Multiplier (mm); the albedo is the material's; transmission 0.25 tint (e^{-t/d} +
 *     3 e^{-t/(3d)}) (ComputeTransmittanceDisney);
 *   Blender's Cycles, Christensen-Burley (3.4's closure/bssrdf.h, shipped with Debian's blender:
 *     bssrdf_setup_radius scales the radius by 1 / (4 pi) and bssrdf_burley_eval takes it as d; the profile is
 *     cut at 16 d and renormalised, BURLEY_TRUNCATE); 4.x keeps the same closure with Weight, Radius x Scale.
 * Each uses lucent_profile_burley (src/profile/analytic.c) for the exact bin averages. */
#include <stdlib.h>
#include <string.h>

#include "engine/internal.h"

/* Cycles' truncation of the profile: 16 d, and 1 - e^{-16}/4 - 3 e^{-16/3}/4 of the energy inside. */
#define CYCLES_TRUNCATE 16.0
#define CYCLES_TRUNCATE_CDF 0.9963790093708328

double lucent_engine_unreal_scale(double albedo)
{
    return lucent_burley_scale(LUCENT_BURLEY_SEARCHLIGHT_MFP, albedo); /* Christensen & Burley eq. 5 */
}

double lucent_engine_unreal_s(double albedo, double mfp_color, double mfp_distance, double world_unit_scale)
{
    double l = mfp_color * mfp_distance * world_unit_scale * 10.0; /* mm */
    return l > 0.0 ? lucent_engine_unreal_scale(albedo) / l : NAN;
}

double lucent_engine_cycles_burley_d(double radius) { return radius * 0.25 / M_PI; }

double lucent_engine_hdrp_transmittance(double d, double t) { return 0.25 * (exp(-t / d) + 3.0 * exp(-t / (3.0 * d))); }

lucent_status eng_burley_unit(const lucent_engine_target *t, int n, double d, bool truncate, double *dest)
{
    const lucent_profile *p = t->profile;
    /* lucent_profile_burley takes l and its fit; with A = 1 and l = scale(1) d its s is 1 / d */
    lucent_burley_params bp = {.albedo = {1, 1, 1}, .fit = LUCENT_BURLEY_SEARCHLIGHT_MFP};
    for (int c = 0; c < 3; c++) bp.length[c] = lucent_burley_scale(LUCENT_BURLEY_SEARCHLIGHT_MFP, 1.0) * d;
    lucent_profile *u = NULL;
    lucent_status s = lucent_profile_burley(&bp, &(lucent_profile_grid){.dr = p->dr, .count = n}, &u);
    if (s != LUCENT_OK) return s;
    double cut = CYCLES_TRUNCATE * d;
    for (int j = 0; j < n; j++) {
        double v = u->value[0][j], r0 = j * p->dr, r1 = r0 + p->dr;
        if (truncate) { /* the bin's share inside the cut, by area */
            double inside = r1 <= cut ? 1.0 : r0 >= cut ? 0.0 : (cut * cut - r0 * r0) / (r1 * r1 - r0 * r0);
            v *= inside / CYCLES_TRUNCATE_CDF;
        }
        dest[j] = v;
    }
    lucent_profile_destroy(u);
    return LUCENT_OK;
}

/* ---- the fit of (A, d) per channel ---- */

typedef struct channel_fit {
    const lucent_engine_target *t;
    int c;
    bool truncate;
    double *u; /* scratch: eng_bins values */
    double a;  /* the amplitude at the last evaluation */
} channel_fit;

static double channel_error(double d, void *ctx)
{
    channel_fit *f = ctx;
    if (eng_burley_unit(f->t, f->t->bins[f->c], d, f->truncate, f->u) != LUCENT_OK) return INFINITY;
    double ep;
    f->a = eng_amplitude(f->t, f->c, f->u, 1.0, &ep, NULL);
    return ep * ep;
}

static lucent_status fit_channels(const lucent_engine_target *t, bool truncate, double albedo[3], double d[3])
{
    double *u = malloc((size_t)eng_bins(t) * sizeof *u);
    if (!u) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (int c = 0; c < 3; c++) {
        channel_fit f = {.t = t, .c = c, .truncate = truncate, .u = u};
        double lo = t->profile->dr / 8.0, hi = 4.0 * t->r99[c];
        d[c] = eng_minimize_log(channel_error, &f, lo, hi, 40, NULL);
        channel_error(d[c], &f);
        albedo[c] = fmin(f.a, 1.0);
    }
    free(u);
    return LUCENT_OK;
}

/* The model of (A, d) on the whole grid, its errors and its profile into r. */
static lucent_status evaluate(const lucent_engine_target *t, const double albedo[3], const double d[3], bool truncate,
                              lucent_engine_fit_result *r)
{
    int n = t->profile->count;
    double *m[3] = {malloc((size_t)n * sizeof(double)), malloc((size_t)n * sizeof(double)),
                    malloc((size_t)n * sizeof(double))};
    lucent_status s = m[0] && m[1] && m[2] ? LUCENT_OK : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (int c = 0; c < 3 && s == LUCENT_OK; c++) {
        s = eng_burley_unit(t, n, d[c], truncate, m[c]);
        for (int j = 0; s == LUCENT_OK && j < n; j++) m[c][j] *= albedo[c];
    }
    if (s == LUCENT_OK) s = eng_finish(t, m, albedo, r);
    r->burley.valid = true;
    memcpy(r->burley.albedo, albedo, sizeof r->burley.albedo);
    memcpy(r->burley.d, d, sizeof r->burley.d);
    for (int c = 0; c < 3; c++) free(m[c]);
    return s;
}

/* ---- each engine's parameters of (A, d) ---- */

static double max3(const double v[3]) { return fmax(v[0], fmax(v[1], v[2])); }

static void unreal_params(const lucent_engine_target *t, const double a[3], const double d[3],
                          lucent_engine_fit_result *r)
{
    const double wus = 0.1; /* the default World Unit Scale: one world unit (cm) of distance is 1 mm */
    double l[3], color[3];
    for (int c = 0; c < 3; c++) l[c] = lucent_engine_unreal_scale(a[c]) * d[c]; /* s = scale(A) / l */
    double distance = max3(l) / (wus * 10.0);
    for (int c = 0; c < 3; c++) color[c] = l[c] / max3(l);
    eng_param_text(r, "Enable Burley", "true");
    eng_param_text(r, "Enable Mean Free Path", "true");
    eng_param(r, "Surface Albedo", "", 3, a);
    eng_param(r, "Mean Free Path Color", "", 3, color);
    eng_param1(r, "Mean Free Path Distance", "world units (cm)", distance);
    eng_param1(r, "World Unit Scale", "", wus);
    eng_param1(r, "IOR", "", t->material.eta);
    eng_note(r, "l = Mean Free Path Color x Distance x World Unit Scale x 10 mm; with World Unit Scale 0.1 the "
                "distance reads in mm; the material's Base Color should equal Surface Albedo");
    eng_note(r, "UE stores the diffuse mean free path with a factor 1/0.6 (Dmfp2MfpMagicNumber); this follows the "
                "path tracer's reading, s = (1.85 - A + 7|A - 0.8|^3) / l");
    eng_cannot_common(t, r, false, false);
}

static void hdrp_transmission(const lucent_engine_target *t, const double d[3], lucent_engine_fit_result *r)
{
    double tint[3] = {1, 1, 1}, sum = 0.0;
    int n = 0;
    for (int c = 0; c < 3 && t->slab_count; c++) { /* least squares of the relative error: tint sum g/T / sum (g/T)^2 */
        double num = 0.0, den = 0.0;
        for (int i = 0; i < t->slab_count; i++) {
            double tv = t->slab_value[i][c], g = lucent_engine_hdrp_transmittance(d[c], t->slab_thickness[i]);
            if (tv < 1e-4) continue;
            num += g / tv, den += (g / tv) * (g / tv);
        }
        tint[c] = den > 0.0 ? fmin(num / den, 1.0) : 0.0;
        for (int i = 0; i < t->slab_count; i++) {
            double tv = t->slab_value[i][c], g = lucent_engine_hdrp_transmittance(d[c], t->slab_thickness[i]);
            if (tv < 1e-4) continue;
            sum += (tint[c] * g - tv) * (tint[c] * g - tv) / (tv * tv), n++;
        }
    }
    r->transmit_error = n ? sqrt(sum / n) : NAN;
    eng_param(r, "Transmission Tint", "", 3, tint);
    if (!t->slab_count)
        eng_note(r, "Transmission Tint not fitted (no slab transmittance: homogeneous materials with --transmittance)");
}

static void hdrp_params(const lucent_engine_target *t, const double a[3], const double d[3],
                        lucent_engine_fit_result *r)
{
    double color[3];
    for (int c = 0; c < 3; c++) color[c] = d[c] / max3(d);
    eng_param(r, "Scattering Color", "", 3, color);
    eng_param1(r, "Multiplier", "mm", max3(d));
    eng_param1(r, "World Scale", "", 1.0);
    eng_param1(r, "Index of Refraction", "", t->material.eta);
    hdrp_transmission(t, d, r);
    eng_param(r, "Base Color (the material's diffuse colour)", "", 3, a);
    eng_note(r, "scattering distance d = Scattering Color x Multiplier in mm (World Scale 1: a Unity unit is 1 m), "
                "s = 1/d; before HDRP 14 the one HDR colour Scattering Distance = d");
    eng_cannot_common(t, r, false, false);
}

static void blender_params(const lucent_engine_target *t, lucent_engine_id e, const double a[3], const double d[3],
                           lucent_engine_fit_result *r)
{
    double radius[3], g = eng_mean_g(t, NULL);
    for (int c = 0; c < 3; c++) radius[c] = 4.0 * M_PI * d[c]; /* d = radius / (4 pi) */
    eng_param_text(r, "Subsurface Method", "Christensen-Burley");
    eng_param(r, "Base Color", "", 3, a);
    if (e == LUCENT_ENGINE_BLENDER3_BURLEY) {
        eng_param1(r, "Subsurface", "", 1.0);
        eng_param(r, "Subsurface Color", "", 3, a);
        eng_param(r, "Subsurface Radius", "scene units (mm)", 3, radius);
        eng_param1(r, "Subsurface IOR", "", t->material.eta);
        eng_param1(r, "Subsurface Anisotropy", "", fmin(fmax(g, 0.0), 0.9));
        eng_note(r, "one Blender unit is 1 mm (Subsurface multiplies the radius: keep it 1); Christensen-Burley uses "
                    "neither Subsurface IOR nor Anisotropy");
    } else {
        double scale = max3(radius), color[3];
        for (int c = 0; c < 3; c++) color[c] = radius[c] / scale;
        eng_param1(r, "Subsurface Weight", "", 1.0);
        eng_param(r, "Subsurface Radius", "", 3, color);
        eng_param1(r, "Subsurface Scale", "scene units (mm)", scale);
        eng_param1(r, "IOR", "", t->material.eta);
        eng_note(r, "one Blender unit is 1 mm; the radius per channel is Radius x Scale");
    }
    eng_note(r, "Cycles: d = radius / (4 pi), the profile cut at 16 d (closure/bssrdf.h)");
    eng_cannot_common(t, r, false, false);
}

lucent_status eng_fit_burley(const lucent_engine_target *t, lucent_engine_id e, bool hand, lucent_engine_fit_result *r)
{
    bool cycles = e == LUCENT_ENGINE_BLENDER3_BURLEY || e == LUCENT_ENGINE_BLENDER4_BURLEY;
    double a[3], d[3];
    lucent_status s = LUCENT_OK;
    if (hand) { /* colour = T, radius = 1 / sigma_tr, read as each engine reads its radius */
        double radius[3];
        if (!eng_hand_radius(t, radius))
            return lucent_error(LUCENT_ERR_UNSUPPORTED,
                                "%s: hand mapping: %s does not absorb in some channel "
                                "(1 / sigma_tr is infinite)",
                                lucent_engine_name(e), t->material.name);
        for (int c = 0; c < 3; c++) {
            a[c] = t->rd[c];
            d[c] = e == LUCENT_ENGINE_UNREAL_BURLEY ? radius[c] / lucent_engine_unreal_scale(a[c])
                   : cycles                         ? lucent_engine_cycles_burley_d(radius[c])
                                                    : radius[c];
        }
    } else {
        s = fit_channels(t, cycles, a, d);
    }
    if (s == LUCENT_OK) s = evaluate(t, a, d, cycles, r);
    if (s != LUCENT_OK) return s;
    switch (e) {
    case LUCENT_ENGINE_UNREAL_BURLEY: unreal_params(t, a, d, r); break;
    case LUCENT_ENGINE_UNITY_HDRP: hdrp_params(t, a, d, r); break;
    default: blender_params(t, e, a, d, r); break;
    }
    return LUCENT_OK;
}
