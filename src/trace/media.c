/* Homogeneous media: the walk's sampling. The Henyey-Greenstein phase function and its sampling
 * are the library's one copy in base/optics.h (lucent_hg_phase, lucent_hg_sample). Free flights and
 * the hero-channel weights live in integrator.c, where the path state is. */
#include <math.h>

#include "trace/internal.h"

/* ---- the walk's sampling: an exponential transform up the fluence gradient ----
 * A camera path's vertex at x finds light in proportion to the fluence phi there. Modelling phi as
 * exp(kappa (x' - x) . u) near x (u and kappa from grad ln phi, field.c), the zero-variance choice of
 * the next free flight and direction (the exponential transform of deep-penetration neutron
 * transport; Krivanek & d'Eon 2014 for subsurface scattering) draws distances with
 *   sigma*(w) = sigma_t - kappa (w . u) = sigma_t (1 - b mu),  b = kappa / sigma_t,  mu = w . u,
 * and directions with density proportional to p(w) / sigma*(w); for g = 0 that is
 *   B(mu) = b / (2 pi (1 - b mu) ln((1 + b) / (1 - b))),
 * drawn by inverting its distribution: mu = (1 - (1 + b)^(1 - xi) (1 - b)^xi) / b. For g != 0 the walk
 * draws from the even mixture of the phase function and B. The weights f / p keep the estimate
 * unbiased whatever the field holds: it only moves samples toward the light (in the dark parts of
 * a lit object the walk no longer has to wander there by chance). */

static double b_pdf(double b, double mu)
{
    if (b < 1e-6) return 0.25 * M_1_PI;
    return b / (2.0 * M_PI * (1.0 - b * mu) * log((1.0 + b) / (1.0 - b)));
}

static double mix_of(const tr_object *ob, const tr_transform *tf, int k)
{
    return tf->b[k] > 0 ? (fabs(ob->g[k]) < 1e-3 ? 1.0 : 0.5) : 0.0;
}

double tr_walk_sigma(const tr_object *ob, const tr_transform *tf, int k, v3 w)
{
    return ob->sigma_t[k] * (1.0 - tf->b[k] * v3_dot(w, tf->u[k]));
}

double tr_walk_pdf(const tr_object *ob, const tr_transform *tf, int k, v3 d_in, v3 w)
{
    double m = mix_of(ob, tf, k), p = m < 1.0 ? lucent_hg_phase(v3_dot(d_in, w), ob->g[k]) : 0.0;
    return m > 0 ? (1.0 - m) * p + m * b_pdf(tf->b[k], v3_dot(w, tf->u[k])) : p;
}

void tr_walk_phase_pdf(const tr_object *ob, const tr_transform *tf, v3 d_in, v3 w, double f[3], double pdf[3])
{
    double mu = v3_dot(d_in, w);
    for (int k = 0; k < 3; k++) {
        /* the phase function once per distinct g; the analog walk's density is the phase function */
        f[k] = k > 0 && ob->g[k] == ob->g[k - 1] ? f[k - 1] : lucent_hg_phase(mu, ob->g[k]);
        pdf[k] = tf->b[k] > 0 ? tr_walk_pdf(ob, tf, k, d_in, w) : f[k];
    }
}

v3 tr_walk_sample(const tr_object *ob, const tr_transform *tf, int k, v3 d_in, double u0, double u1, double u2)
{
    double m = mix_of(ob, tf, k), b = tf->b[k];
    if (!(m > 0) || u0 >= m) return lucent_hg_sample(d_in, ob->g[k], u1, u2);
    double mu = b < 1e-6 ? 2.0 * u1 - 1.0 : (1.0 - pow(1.0 + b, 1.0 - u1) * pow(1.0 - b, u1)) / b;
    return lucent_around(tf->u[k], fmax(-1.0, fmin(1.0, mu)), 2.0 * M_PI * u2);
}
