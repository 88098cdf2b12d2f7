/* The engines whose profile is a separable screen-space blur:
 *   Unreal's legacy Subsurface Profile: Jimenez's separable kernel (Jimenez et al. 2015, the
 *     SeparableSSS code Unreal's SeparableSSS.cpp follows): d'Eon & Luebke's red skin Gaussians without the
 *     narrowest (lucent_sog_deon_skin, as src/kernel/jimenez.c), each evaluated at r / (0.001 + Falloff Color),
 *     weighted by Subsurface Color (the rest stays at the centre: a delta), offsets in mm times Scatter Radius
 *     (cm) x 10;
 *   Godot 4 (servers/rendering/renderer_rd/shaders/effects/subsurface_scattering.glsl, the 17-sample kernels
 *     of the default Medium quality): a horizontal and a vertical pass of taps at kernel.y x step in uv, step
 *     = strength / 3 x unit_size / depth with subsurface_scattering_depth_scale 1, unit_size = 1 / tan(fov_x /
 *     2) (ss_effects.cpp): kernel.y x strength x 2 / 3 world units along the view's width. Its 2-D profile is
 *     the product of the two passes, binned by radius; its transmittance (scene_forward_lights_inc.glsl,
 *     SSS()) exp(-(8.25 z / depth)^2) x Transmittance Color. */
#include <stdlib.h>
#include <string.h>

#include "engine/internal.h"

/* ---- Unreal's separable profile ---- */

/* The unit profile (total 1) of the five Gaussians stretched by w: G(v_g w^2), weights normalised. */
static lucent_status jimenez_unit(const lucent_engine_target *t, int n, double w, double *dest)
{
    lucent_sog skin, k = {.count = 5};
    lucent_sog_deon_skin(&skin);
    double sum = 0.0;
    for (int g = 1; g < 6; g++) sum += skin.weight[0][g];
    for (int c = 0; c < 3; c++)
        for (int g = 1; g < 6; g++) {
            k.variance[c][g - 1] = skin.variance[0][g] * w * w;
            k.weight[c][g - 1] = skin.weight[0][g] / sum;
        }
    lucent_profile *p = NULL;
    lucent_status s = lucent_profile_from_sog(&k, &(lucent_profile_grid){.dr = t->profile->dr, .count = n}, &p);
    if (s != LUCENT_OK) return s;
    memcpy(dest, p->value[0], (size_t)n * sizeof *dest);
    lucent_profile_destroy(p);
    return LUCENT_OK;
}

typedef struct sep_fit {
    const lucent_engine_target *t;
    int c;
    double *u;
    double a1, a0; /* the spread part and the delta at the last evaluation */
} sep_fit;

/* a1 p + a0 delta with a1 + a0 = T (the Base Color carries T), a1 in [0, T]: e_p is quadratic in a1. The
 * delta is the centre tap, its bin average a0 / (pi dr^2) in bin 0. */
static double sep_error(double w, void *ctx)
{
    sep_fit *f = ctx;
    const lucent_engine_target *t = f->t;
    const lucent_profile *p = t->profile;
    int c = f->c;
    if (jimenez_unit(t, t->bins[c], w, f->u) != LUCENT_OK) return INFINITY;
    double tot = t->rd[c], zz = 0, zy = 0, qq = 0;
    for (int j = 0; j < t->bins[c]; j++) { /* r (a1 p + (T - a1) delta) - q = a1 z - y */
        double q = p->r[j] * p->value[c][j], d = j == 0 ? p->r[0] / (M_PI * p->dr * p->dr) : 0;
        double z = p->r[j] * f->u[j] - d, y = q - tot * d;
        zz += z * z, zy += z * y, qq += q * q;
    }
    double a1 = zz > 0 ? fmin(fmax(zy / zz, 0.0), tot) : tot;
    f->a1 = a1, f->a0 = tot - a1;
    double e = 0.0;
    for (int j = 0; j < t->bins[c]; j++) {
        double q = p->r[j] * p->value[c][j],
               m = p->r[j] * (a1 * f->u[j] + (j == 0 ? f->a0 / (M_PI * p->dr * p->dr) : 0));
        e += (m - q) * (m - q);
    }
    return e / qq;
}

lucent_status eng_fit_separable(const lucent_engine_target *t, lucent_engine_fit_result *r)
{
    int n = t->profile->count;
    double w[3], a[3], strength[3];
    double *m[3] = {calloc((size_t)n, sizeof(double)), calloc((size_t)n, sizeof(double)),
                    calloc((size_t)n, sizeof(double))};
    double *u = malloc((size_t)n * sizeof *u);
    lucent_status s = m[0] && m[1] && m[2] && u ? LUCENT_OK : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (int c = 0; c < 3 && s == LUCENT_OK; c++) {
        sep_fit f = {.t = t, .c = c, .u = u};
        w[c] = eng_minimize_log(sep_error, &f, t->profile->dr / 4.0, 4.0 * t->r99[c], 40, NULL);
        sep_error(w[c], &f);
        a[c] = fmin(f.a1 + f.a0, 1.0);
        strength[c] = f.a1 + f.a0 > 0 ? f.a1 / (f.a1 + f.a0) : 0;
        s = jimenez_unit(t, n, w[c], m[c]);
        for (int j = 0; s == LUCENT_OK && j < n; j++) m[c][j] = a[c] * strength[c] * m[c][j];
        m[c][0] += a[c] * (1 - strength[c]) / (M_PI * t->profile->dr * t->profile->dr);
    }
    if (s == LUCENT_OK) s = eng_finish(t, m, a, r);
    if (s == LUCENT_OK) { /* Scatter Radius so that the widest channel's falloff is 1 */
        double wmax = fmax(w[0], fmax(w[1], w[2])), radius = wmax / (10.0 * 1.001), falloff[3];
        for (int c = 0; c < 3; c++) falloff[c] = fmax(w[c] / (10.0 * radius) - 0.001, 0.0);
        eng_param_text(r, "Enable Burley", "false");
        eng_param(r, "Subsurface Color", "", 3, strength);
        eng_param(r, "Falloff Color", "", 3, falloff);
        eng_param1(r, "Scatter Radius", "world units (cm)", radius);
        eng_param(r, "Base Color (the material's)", "", 3, a);
        eng_note(r, "the kernel's offsets (mm of Jimenez's skin profile) times Scatter Radius x 10: a Scatter Radius "
                    "of 0.1 is the measured skin's width");
        eng_cannot(r, "a profile of its own: one skin-shaped profile (d'Eon's red Gaussians) stretched per channel");
        eng_cannot_common(t, r, false, false);
    }
    for (int c = 0; c < 3; c++) free(m[c]);
    free(u);
    return s;
}

/* ---- Godot ---- */

enum { GODOT_TAPS = 9 };
/* subsurface_scattering.glsl, USE_17_SAMPLES: (weight, offset) and the skin kernel's RGB weights. */
static const double k_godot[GODOT_TAPS][2] = {{0.536343, 0.0},      {0.0324462, 0.03125}, {0.0582416, 0.125},
                                              {0.0571056, 0.28125}, {0.0347317, 0.5},     {0.0216301, 0.78125},
                                              {0.0144609, 1.125},   {0.0100386, 1.53125}, {0.00317394, 2.0}};
static const double k_godot_skin[GODOT_TAPS][3] = {
    {0.536343, 0.624624, 0.748867},      {0.0324462, 0.0656718, 0.0532821},     {0.0582416, 0.0659959, 0.0411329},
    {0.0571056, 0.0287432, 0.0172844},   {0.0347317, 0.0151085, 0.00871983},    {0.0216301, 0.00794618, 0.00376991},
    {0.0144609, 0.00317269, 0.00106399}, {0.0100386, 0.000914679, 0.000275702}, {0.00317394, 0.000134823, 3.77269e-05}};

double lucent_engine_godot_tap_distance(double tap_offset, double strength)
{
    return tap_offset * strength * 2.0 / 3.0;
}

double lucent_engine_godot_transmittance(double depth, double z)
{
    double d = 8.25 / depth * fabs(z);
    return exp(-d * d);
}

/* The unit 2-D profile of channel c: the two passes' normalised weights multiplied, binned by radius.
 * Each tap stands for the interval halfway to its neighbours (the taps sample a profile at quadratically
 * spaced offsets, a weight per interval, as Jimenez's kernels do), so a pair of taps covers a rectangle of
 * uniform density, spread over the bins by 8 x 8 sub-samples. strength: Godot's, one world unit being 1 m;
 * the grid in mm. */
static void godot_unit(const lucent_engine_target *t, int n, double strength, bool skin, int c, double *dest)
{
    enum { TAPS = 2 * GODOT_TAPS - 1, SUB = 8 };
    double w[TAPS], lo[TAPS], hi[TAPS], sum = 0.0, dr = t->profile->dr;
    for (int i = 0; i < TAPS; i++) { /* i = 0 .. 16: offsets -8 .. 8 */
        int k = abs(i - (GODOT_TAPS - 1)), sign = i < GODOT_TAPS - 1 ? -1 : 1;
        double o = k_godot[k][1], inner = k ? 0.5 * (o + k_godot[k - 1][1]) : -0.5 * k_godot[1][1];
        double outer = k + 1 < GODOT_TAPS ? 0.5 * (o + k_godot[k + 1][1]) : o + 0.5 * (o - k_godot[k - 1][1]);
        double l = sign > 0 ? inner : -outer, h = sign > 0 ? outer : -inner;
        if (k == 0) l = -0.5 * k_godot[1][1], h = 0.5 * k_godot[1][1];
        lo[i] = 1000.0 * lucent_engine_godot_tap_distance(l, strength);
        hi[i] = 1000.0 * lucent_engine_godot_tap_distance(h, strength);
        w[i] = skin ? k_godot_skin[k][c] : k_godot[k][0];
        sum += w[i];
    }
    memset(dest, 0, (size_t)n * sizeof *dest);
    for (int i = 0; i < TAPS; i++)
        for (int j = 0; j < TAPS; j++) {
            double e = w[i] * w[j] / (sum * sum) / (SUB * SUB);
            for (int a = 0; a < SUB; a++)
                for (int b = 0; b < SUB; b++) {
                    double x = lo[i] + (hi[i] - lo[i]) * (a + 0.5) / SUB, y = lo[j] + (hi[j] - lo[j]) * (b + 0.5) / SUB;
                    int bin = (int)(hypot(x, y) / dr);
                    if (bin < n) dest[bin] += e / (M_PI * (2 * bin + 1) * dr * dr);
                }
        }
}

typedef struct godot_fit {
    const lucent_engine_target *t;
    bool skin;
    double *u;
} godot_fit;

static double godot_error(double strength, void *ctx)
{
    godot_fit *f = ctx;
    double e = 0.0;
    for (int c = 0; c < 3; c++) {
        double ep;
        godot_unit(f->t, f->t->bins[c], strength, f->skin, c, f->u);
        eng_amplitude(f->t, c, f->u, 1.0, &ep, NULL);
        e += ep * ep;
    }
    return e;
}

/* Transmittance Depth (m) and Color: relative least squares over the slab samples. */
typedef struct godot_tr {
    const lucent_engine_target *t;
    double color[3];
    double rms;
} godot_tr;

static double godot_tr_error(double depth, void *ctx)
{
    godot_tr *f = ctx;
    double sum = 0.0;
    int n = 0;
    for (int c = 0; c < 3; c++) {
        double num = 0.0, den = 0.0;
        for (int i = 0; i < f->t->slab_count; i++) {
            double tv = f->t->slab_value[i][c],
                   g = lucent_engine_godot_transmittance(depth, f->t->slab_thickness[i] / 1000.0);
            if (tv >= 1e-4) num += g / tv, den += (g / tv) * (g / tv);
        }
        f->color[c] = den > 0 ? fmin(num / den, 1.0) : 0.0;
        for (int i = 0; i < f->t->slab_count; i++) {
            double tv = f->t->slab_value[i][c],
                   g = lucent_engine_godot_transmittance(depth, f->t->slab_thickness[i] / 1000.0);
            if (tv >= 1e-4) sum += (f->color[c] * g - tv) * (f->color[c] * g - tv) / (tv * tv), n++;
        }
    }
    f->rms = n ? sqrt(sum / n) : NAN;
    return n ? sum / n : 0.0;
}

static void godot_transmittance(const lucent_engine_target *t, lucent_engine_fit_result *r)
{
    if (!t->slab_count) {
        eng_param_text(r, "subsurf_scatter_transmittance_enabled", "false");
        eng_note(r, "transmittance not fitted (no slab transmittance: homogeneous materials with --transmittance)");
        return;
    }
    godot_tr f = {.t = t};
    double smax = t->slab_thickness[t->slab_count - 1] / 1000.0;
    double depth = eng_minimize_log(godot_tr_error, &f, smax / 100.0, smax * 10.0, 40, NULL);
    godot_tr_error(depth, &f);
    r->transmit_error = f.rms;
    eng_param_text(r, "subsurf_scatter_transmittance_enabled", "true");
    eng_param(r, "subsurf_scatter_transmittance_color", "", 3, f.color);
    eng_param1(r, "subsurf_scatter_transmittance_depth", "m", depth);
    eng_param1(r, "subsurf_scatter_transmittance_boost", "", 0.0);
}

lucent_status eng_fit_godot(const lucent_engine_target *t, lucent_engine_fit_result *r)
{
    int n = t->profile->count;
    double *u = malloc((size_t)n * sizeof *u), best = INFINITY, strength = 0;
    bool skin = false;
    if (!u) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    double reach = fmax(t->r99[0], fmax(t->r99[1], t->r99[2])) / 1000.0 / (2.0 * 2.0 / 3.0); /* strength at r99 */
    for (int mode = 0; mode < 2; mode++) {
        godot_fit f = {.t = t, .skin = mode == 1, .u = u};
        double e, k = eng_minimize_log(godot_error, &f, reach / 100.0, reach * 4.0, 40, &e);
        if (e < best) best = e, strength = k, skin = mode == 1;
    }
    double *m[3] = {calloc((size_t)n, sizeof(double)), calloc((size_t)n, sizeof(double)),
                    calloc((size_t)n, sizeof(double))},
           a[3];
    lucent_status s = m[0] && m[1] && m[2] ? LUCENT_OK : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (int c = 0; c < 3 && s == LUCENT_OK; c++) {
        godot_unit(t, t->bins[c], strength, skin, c, u);
        a[c] = fmin(eng_amplitude(t, c, u, 1.0, NULL, NULL), 1.0);
        godot_unit(t, n, strength, skin, c, m[c]);
        for (int j = 0; j < n; j++) m[c][j] *= a[c];
    }
    if (s == LUCENT_OK) s = eng_finish(t, m, a, r);
    if (s == LUCENT_OK) {
        eng_param(r, "albedo_color (linear)", "", 3, a);
        eng_param_text(r, "subsurf_scatter_enabled", "true");
        eng_param1(r, "subsurf_scatter_strength", "", strength);
        eng_param_text(r, "subsurf_scatter_skin_mode", skin ? "true" : "false");
        godot_transmittance(t, r);
        eng_param1(r, "subsurface_scattering_depth_scale (project)", "", 1.0);
        eng_param1(r, "subsurface_scattering_quality (project)", "", 1.0);
        eng_note(r, "one world unit is 1 m; the project's depth scale 1 makes the blur's width follow the depth (at "
                    "the default 0.01 it is a fixed share of the screen); quality 1: the 17-sample kernel");
        if (strength > 1.0) eng_note(r, "the strength above 1 is outside Godot's range [0, 1]");
        eng_cannot(r, "a width per channel (the kernel is grey, or skin-coloured in skin mode); the vertical pass is "
                      "narrower by the aspect ratio");
        eng_cannot_common(t, r, false, false);
    }
    for (int c = 0; c < 3; c++) free(m[c]);
    free(u);
    return s;
}
