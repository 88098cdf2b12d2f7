/* The error of a model against the truth (lucent/engine.h), the amplitude that minimises it, the 1-D
 * minimiser every family uses, and a result's parameter list and notes. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine/internal.h"
#include "lucent/image.h"

int eng_bins(const lucent_engine_target *t)
{
    int n = 0;
    for (int c = 0; c < 3; c++) n = t->bins[c] > n ? t->bins[c] : n;
    return n;
}

double eng_profile_error(const lucent_engine_target *t, int c, const double *model)
{
    const lucent_profile *p = t->profile;
    double num = 0.0, den = 0.0;
    for (int j = 0; j < t->bins[c]; j++) {
        double q = p->r[j] * p->value[c][j], m = p->r[j] * model[j];
        num += (m - q) * (m - q);
        den += q * q;
    }
    return den > 0.0 ? sqrt(num / den) : NAN;
}

double eng_amplitude(const lucent_engine_target *t, int c, const double *u, double tau, double *e_p, double *e_t)
{
    double a = tau > 0.0 ? t->rd[c] / tau : 0.0; /* T matched: the engine's albedo carries it */
    if (e_p) {
        double *m = malloc((size_t)t->bins[c] * sizeof *m);
        if (m) {
            for (int j = 0; j < t->bins[c]; j++) m[j] = a * u[j];
            *e_p = eng_profile_error(t, c, m);
        } else {
            *e_p = NAN;
        }
        free(m);
    }
    if (e_t) *e_t = 0.0;
    return a;
}

double eng_minimize_log(eng_fn f, void *ctx, double lo, double hi, int scan, double *fmin)
{
    double a = log(lo), b = log(hi), best_x = a, best = INFINITY;
    int n = scan < 3 ? 3 : scan, best_i = 0;
    for (int i = 0; i < n; i++) {
        double x = a + (b - a) * i / (n - 1), v = f(exp(x), ctx);
        if (v < best) best = v, best_x = x, best_i = i;
    }
    /* golden-section search in the scan's neighbouring interval */
    double step = (b - a) / (n - 1);
    double l = best_i > 0 ? best_x - step : best_x, h = best_i < n - 1 ? best_x + step : best_x;
    const double gr = 0.5 * (sqrt(5.0) - 1.0);
    double x1 = h - gr * (h - l), x2 = l + gr * (h - l), f1 = f(exp(x1), ctx), f2 = f(exp(x2), ctx);
    while (h - l > 1e-4) {
        if (f1 < f2)
            h = x2, x2 = x1, f2 = f1, x1 = h - gr * (h - l), f1 = f(exp(x1), ctx);
        else
            l = x1, x1 = x2, f1 = f2, x2 = l + gr * (h - l), f2 = f(exp(x2), ctx);
    }
    double x = f1 < f2 ? x1 : x2, v = f1 < f2 ? f1 : f2;
    if (best < v) x = best_x, v = best;
    if (fmin) *fmin = v;
    return exp(x);
}

/* ---- the result's parameters and texts ---- */

void eng_param(lucent_engine_fit_result *r, const char *name, const char *unit, int count, const double *v)
{
    if (r->param_count >= LUCENT_ENGINE_MAX_PARAMS) return;
    lucent_engine_param *p = &r->params[r->param_count++];
    *p = (lucent_engine_param){.name = name, .unit = unit ? unit : "", .count = count, .text = ""};
    for (int c = 0; c < count && c < 3; c++) p->value[c] = v[c];
}

void eng_param1(lucent_engine_fit_result *r, const char *name, const char *unit, double v)
{
    eng_param(r, name, unit, 1, &v);
}

void eng_param_text(lucent_engine_fit_result *r, const char *name, const char *text)
{
    if (r->param_count >= LUCENT_ENGINE_MAX_PARAMS) return;
    r->params[r->param_count++] = (lucent_engine_param){.name = name, .unit = "", .count = 0, .text = text};
}

static void append(char *dest, const char *fmt, va_list ap)
{
    size_t len = strlen(dest);
    if (len && len + 2 < LUCENT_ENGINE_TEXT_SIZE) strcpy(dest + len, "; "), len += 2;
    if (len < LUCENT_ENGINE_TEXT_SIZE) vsnprintf(dest + len, LUCENT_ENGINE_TEXT_SIZE - len, fmt, ap);
}

void eng_cannot(lucent_engine_fit_result *r, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    append(r->cannot, fmt, ap);
    va_end(ap);
}

void eng_note(lucent_engine_fit_result *r, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    append(r->notes, fmt, ap);
    va_end(ap);
}

const lucent_engine_param *lucent_engine_fit_param(const lucent_engine_fit_result *result, const char *name)
{
    for (int i = 0; result && name && i < result->param_count; i++)
        if (!strcmp(result->params[i].name, name)) return &result->params[i];
    return NULL;
}

lucent_status eng_finish(const lucent_engine_target *t, double *const model[3], const double total[3],
                         lucent_engine_fit_result *r)
{
    const lucent_profile *p = t->profile;
    lucent_profile *out = NULL;
    lucent_status s = lucent_profile_create(&(lucent_profile_grid){.dr = p->dr, .count = p->count},
                                            lucent_engine_name(r->engine), &out);
    if (s != LUCENT_OK) return s;
    double sum = 0.0, lab_model[3], lab_truth[3];
    for (int c = 0; c < 3; c++) {
        memcpy(out->value[c], model[c], (size_t)p->count * sizeof *model[c]);
        r->profile_error[c] = eng_profile_error(t, c, model[c]);
        sum += r->profile_error[c] * r->profile_error[c];
        r->total[c] = total[c];
    }
    r->profile_error_rms = sqrt(sum / 3.0);
    lucent_linear_srgb_to_lab(total, lab_model);
    lucent_linear_srgb_to_lab(t->rd, lab_truth);
    r->delta_e = lucent_ciede2000(lab_truth, lab_model);
    lucent_profile_destroy(r->profile);
    r->profile = out;
    return LUCENT_OK;
}

double eng_mean_g(const lucent_engine_target *t, bool *differs)
{
    const double *g = t->material.g;
    bool d = g[0] != g[1] || g[1] != g[2];
    for (int i = 1; i < t->layer_count; i++)
        for (int c = 0; c < 3; c++) d |= t->layers[i].material.g[c] != g[c];
    if (differs) *differs = d;
    return (g[0] + g[1] + g[2]) / 3.0;
}

void eng_cannot_common(const lucent_engine_target *t, lucent_engine_fit_result *r, bool has_g, bool has_eta)
{
    bool g_differs;
    double g = eng_mean_g(t, &g_differs);
    if (t->layer_count > 1) eng_cannot(r, "layers (%d): one homogeneous medium is fitted to the stack", t->layer_count);
    if (t->material.skin.layer_count > 0)
        eng_cannot(r, "layers (%d, a spectral skin): one homogeneous medium is fitted to its bands' truth",
                   t->material.skin.layer_count);
    if (!has_g && (g != 0.0 || g_differs))
        eng_cannot(r, "the phase function's g (the profile carries it)");
    else if (has_g && g_differs)
        eng_cannot(r, "a g per channel or layer (one g for all: their mean %.3g)", g);
    if (!has_eta) eng_cannot(r, "the boundary's eta %.3g (the profile carries it)", t->material.eta);
}

bool eng_hand_radius(const lucent_engine_target *t, double dest[3])
{
    lucent_material_derived d;
    lucent_material_derive(&t->material, &d);
    for (int c = 0; c < 3; c++) {
        dest[c] = d.mfp_diffuse[c];
        if (!(dest[c] > 0.0) || !isfinite(dest[c])) return false;
    }
    return true;
}
