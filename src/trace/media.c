/* Homogeneous media: the Henyey-Greenstein phase function (Henyey & Greenstein 1941,
 * "Diffuse radiation in the galaxy", ApJ 93, eq. 3)
 *   p(mu) = (1 - g^2) / (4 pi (1 + g^2 - 2 g mu)^(3/2)),
 * mu the cosine between the travel directions before and after scattering, and its sampling by
 * inverting the cumulative distribution:
 *   mu = (1 + g^2 - ((1 - g^2) / (1 - g + 2 g u))^2) / (2 g)   (mu = 2u - 1 for g = 0).
 * Free flights and the hero-channel weights live in integrator.c, where the path state is. */
#include <math.h>

#include "trace/internal.h"

double tr_hg_eval(double mu, double g)
{
    double k = 1.0 + g * g - 2.0 * g * mu;
    return TR_INV_4PI * (1.0 - g * g) / (k * sqrt(k));
}

v3 tr_hg_sample(v3 d, double g, double u1, double u2)
{
    double mu;
    if (fabs(g) < 1e-6) {
        mu = 2.0 * u1 - 1.0;
    } else {
        double q = (1.0 - g * g) / (1.0 - g + 2.0 * g * u1);
        mu = (1.0 + g * g - q * q) / (2.0 * g);
    }
    return v3_around(d, fmax(-1.0, fmin(1.0, mu)), 2.0 * TR_PI * u2);
}
