/* Manual two-Gaussian model, Freude 2014 (5.21): a_m(x) = w G(x, tau_n) + (1 - w) G(x, tau_f),
 * with the parameters of Table A.1 as presets. */
#include <math.h>
#include <strings.h>

#include "kernel/internal.h"

typedef struct manual_preset {
    const char *name;
    lucent_manual_params params;
} manual_preset;

/* Freude 2014, Table A.1 (sqrt(tau_n), sqrt(tau_f) per RGB, w); read as mm. */
static const manual_preset k_presets[] = {
    {"Apple", {{0.0495, 0.0455, 0.0372}, {1.1, 1.08, 0.926}, 0.368}},
    {"Ketchup", {{0.0907, 0.0331, 0.0331}, {1.5, 0.118, 0.0966}, 0.665}},
    {"Marble", {{0.0371, 0.0207, 0.015}, {0.663, 0.616, 0.558}, 0.234}},
    {"Skin1", {{0.429, 0.211, 0.03}, {1.15, 0.69, 0.471}, 0.533}},
    {"Wholemilk", {{0.0846, 0.0846, 0.0583}, {1.5, 1.39, 1.17}, 0.407}},
};

lucent_status lucent_manual_preset(const char *material, lucent_manual_params *dest)
{
    for (size_t i = 0; material && i < sizeof k_presets / sizeof k_presets[0]; i++)
        if (strcasecmp(material, k_presets[i].name) == 0) {
            *dest = k_presets[i].params;
            return LUCENT_OK;
        }
    return lucent_error(LUCENT_ERR_NOT_FOUND,
                        "manual kernel: no Table A.1 parameters for '%s' (Apple, Ketchup, Marble, "
                        "Skin1, Wholemilk); give them explicitly",
                        material ? material : "");
}

static lucent_status check_params(const lucent_manual_params *m)
{
    for (int c = 0; c < 3; c++)
        if (!(m->sd_near[c] > 0) || !(m->sd_far[c] > 0) || !isfinite(m->sd_far[c]))
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                                "manual kernel: standard deviations must be > 0 (channel %d)", c);
    if (!(m->w >= 0 && m->w <= 1))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "manual kernel: w must be in [0, 1]");
    return LUCENT_OK;
}

lucent_status kernel_manual(const lucent_kernel2d *gt, const char *material, const lucent_kernel_desc *d,
                            lucent_kernel *k)
{
    lucent_manual_params m = d->manual;
    lucent_status st = d->use_manual ? LUCENT_OK : lucent_manual_preset(material, &m);
    if (st == LUCENT_OK) st = check_params(&m);
    if (st == LUCENT_OK) st = kernel_alloc(k, 1, gt ? gt->half : 200, gt ? gt->h : 0.025);
    if (st != LUCENT_OK) return st;
    k->gaussians = 2;
    for (int c = 0; c < 3; c++) {
        double vn = m.sd_near[c] * m.sd_near[c], vf = m.sd_far[c] * m.sd_far[c];
        k->gauss_variance[c][0][0] = vn;
        k->gauss_weight[c][0][0] = m.w / sqrt(2 * M_PI * vn);
        k->gauss_variance[c][0][1] = vf;
        k->gauss_weight[c][0][1] = (1 - m.w) / sqrt(2 * M_PI * vf);
    }
    kernel_sample_gaussians(k);
    for (int c = 0; c < 3; c++) kernel_unit_sum(k, c); /* normalised like every SSSS kernel */
    return LUCENT_OK;
}
