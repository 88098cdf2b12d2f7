/* The sphere experiment of Kubo et al. (Figure 6): a translucent sphere under a directional light
 * from the side (+x), seen from the front (+z). Light is traced from the light through a smooth
 * (Fresnel) or rough (GGX microfacet, Walter et al. 2007; visible normals, Heitz 2018) dielectric
 * boundary, random-walks inside (Henyey-Greenstein phase function, implicit capture, Russian
 * roulette), and every time it meets the boundary from inside the transmitted part of its weight is
 * scored (weight splitting, as MCML does) while the reflection walks on with probability F G1 at the
 * same weight: its expected weight with as many returns to the boundary as an analog walk makes
 * (splitting the weight there too made marble's walks about 7x longer for the same noise).
 *
 * Estimator. Sphere and light are symmetric under rotations about the x axis, so the outgoing
 * radiance field is too: L(R p, R w) = L(p, w). An exit at p in direction w is rotated about x until
 * p lies on the visible equator (y = 0, z > 0); it counts when the rotated direction lies within
 * the cone of half-angle delta around the camera direction +z. For the band of exit points whose
 * normal makes an angle in [theta_a, theta_b] with the light, the mean radiance is
 *   L = Phi / (2 pi r^2 Int_{theta_a}^{theta_b} sin theta C(theta) dtheta),
 * C(theta) = Int_cone max(n(theta) . w, 0) dw, with n(theta) = (cos theta, 0, sin theta) and Phi the
 * scored power (each photon carries pi r^2 / N for unit irradiance). C is integrated numerically, so
 * bins at grazing view (theta near 0 or pi), where part of the cone lies below the surface, are
 * normalised correctly. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/optics.h"
#include "base/vec3.h"
#include "lucent/cdrf.h"
#include "lucent/dist.h"
#include "lucent/mc.h"

#define RR_THRESHOLD 1e-4
#define RR_SURVIVAL 0.1
#define MAX_EVENTS 1000000

/* Henyey-Greenstein: a new travel direction from d (base/optics.h), two draws in order. */
static v3 hg_scatter(v3 d, double g, lucent_rng *rng)
{
    double u1 = lucent_rng_uniform(rng), u2 = lucent_rng_uniform(rng);
    return lucent_hg_sample(d, g, u1, u2);
}

/* A GGX microfacet normal visible from wi about n (base/optics.h), two draws in order. */
static v3 ggx_sample(v3 wi, v3 n, double alpha, lucent_rng *rng)
{
    double u1 = lucent_rng_uniform(rng), u2 = lucent_rng_uniform(rng);
    return lucent_ggx_sample_visible(wi, n, alpha, u1, u2);
}

/* ---- one run ---- */

typedef struct sphere_job {
    lucent_cdrf_sphere_desc d;
    uint64_t per_batch;
    int stride;    /* doubles per (channel, batch): 3 bins + 4 */
    double *tally; /* [3 * batches][stride]: bins, then entered, exited, absorbed, capped, exitance bins,
                      flow bins */
    double cos_cone;
    lucent_progress *progress;
} sphere_job;

typedef struct photon {
    v3 p, d;
    double w;
    int order;
} photon;

/* Scores weight w leaving at p (on the sphere) in direction t (outside). */
static void score(const sphere_job *job, double *tally, v3 p, v3 t, double w)
{
    double theta = acos(fmax(-1.0, fmin(1.0, p.x / job->d.radius)));
    int bin = (int)(theta / M_PI * job->d.bins);
    if (bin >= job->d.bins) bin = job->d.bins - 1;
    tally[job->d.bins + 4 + bin] += w; /* the exitance, every direction */
    /* the flow: t . f, f the unit tangent at p away from the light (the light comes from +x) */
    v3 n = v3_scale(p, 1.0 / job->d.radius), f = v3_add(v3_make(-1, 0, 0), v3_scale(n, n.x));
    double fl = v3_length(f);
    if (fl > 1e-9) tally[2 * job->d.bins + 4 + bin] += w * v3_dot(t, f) / fl;
    double rho = sqrt(p.y * p.y + p.z * p.z);
    if (!(rho > 0)) return;
    double tz = (p.y * t.y + p.z * t.z) / rho; /* t rotated about x with p onto (x, 0, rho) */
    if (tz < job->cos_cone) return;
    tally[bin] += w;
}

/* Enters at the lit hemisphere; returns the transmitted weight (0: reflected or lost). */
static double enter(const sphere_job *job, photon *ph, lucent_rng *rng)
{
    double r = job->d.radius, eta = job->d.material->eta, alpha = job->d.roughness;
    double rho = r * sqrt(lucent_rng_uniform(rng)), phi = 2.0 * M_PI * lucent_rng_uniform(rng);
    ph->p = v3_make(sqrt(fmax(0.0, r * r - rho * rho)), rho * cos(phi), rho * sin(phi));
    v3 n = v3_scale(ph->p, 1.0 / r), d = v3_make(-1, 0, 0), m = n, t;
    double w = 1.0;
    ph->d = d, ph->w = 0, ph->order = 0;
    if (alpha > 0) m = ggx_sample(v3_scale(d, -1.0), n, alpha, rng);
    if (!lucent_refract(d, m, eta, &t)) return 0;
    w = 1.0 - lucent_fresnel_dielectric(-v3_dot(d, m), eta, NULL);
    if (alpha > 0) {
        if (v3_dot(t, n) >= 0) return 0;
        w *= lucent_ggx_g1(v3_dot(t, n), alpha);
    }
    ph->d = t;
    ph->w = w;
    ph->order = 0;
    return w;
}

/* Meets the boundary from inside at ph->p: scores the transmitted part; the reflection goes on with
 * probability F G1 (Russian roulette on the reflected weight). Returns the exiting weight. */
static double leave(const sphere_job *job, double *tally, photon *ph, lucent_rng *rng)
{
    double r = job->d.radius, eta = job->d.material->eta, alpha = job->d.roughness;
    v3 n = v3_scale(ph->p, 1.0 / r), nin = v3_scale(n, -1.0), m = nin, t;
    if (alpha > 0) m = ggx_sample(v3_scale(ph->d, -1.0), nin, alpha, rng);
    double f = lucent_fresnel_dielectric(-v3_dot(ph->d, m), 1.0 / eta, NULL), out = 0;
    if (f < 1.0 && lucent_refract(ph->d, m, 1.0 / eta, &t) && v3_dot(t, n) > 0) {
        out = ph->w * (1.0 - f) * (alpha > 0 ? lucent_ggx_g1(v3_dot(t, n), alpha) : 1.0);
        if (job->d.max_order == 0 || ph->order <= job->d.max_order) score(job, tally, ph->p, t, out);
    }
    v3 rd = lucent_reflect(ph->d, m);
    if (v3_dot(rd, n) >= 0) {
        ph->w = 0; /* a microfacet reflection that points out of the sphere: lost */
    } else {
        double keep = f * (alpha > 0 ? lucent_ggx_g1(v3_dot(rd, n), alpha) : 1.0);
        if (!(lucent_rng_uniform(rng) < keep)) ph->w = 0;
        ph->d = rd;
    }
    return out;
}

/* Distance from p (inside) along d to the sphere. */
static double to_boundary(v3 p, v3 d, double r)
{
    double b = v3_dot(p, d), c = v3_dot(p, p) - r * r, disc = b * b - c;
    double t = -b + sqrt(fmax(0.0, disc));
    return t > 0 ? t : 0;
}

static void trace(const sphere_job *job, int ch, double *tally, lucent_rng *rng)
{
    const lucent_material *mat = job->d.material;
    double sa = mat->sigma_a[ch], ss = mat->sigma_s[ch], st = sa + ss, g = mat->g[ch];
    double albedo = st > 0 ? ss / st : 0, r = job->d.radius;
    int bins = job->d.bins;
    photon ph = {.w = 0};
    double w0 = enter(job, &ph, rng);
    tally[bins] += w0;
    int events = 0;
    for (; ph.w > 0 && events < MAX_EVENTS; events++) {
        double s = st > 0 ? -log(1.0 - lucent_rng_uniform(rng)) / st : INFINITY;
        double db = to_boundary(ph.p, ph.d, r);
        if (s < db) {
            ph.p = v3_add(ph.p, v3_scale(ph.d, s));
            tally[bins + 2] += ph.w * (1.0 - albedo);
            ph.w *= albedo;
            ph.order++;
            if (ph.w > 0) ph.d = hg_scatter(ph.d, g, rng);
        } else {
            ph.p = v3_scale(v3_normalize(v3_add(ph.p, v3_scale(ph.d, db))), r);
            tally[bins + 1] += leave(job, tally, &ph, rng);
        }
        if (ph.w > 0 && ph.w < RR_THRESHOLD) ph.w = lucent_rng_uniform(rng) < RR_SURVIVAL ? ph.w / RR_SURVIVAL : 0;
    }
    if (ph.w > 0 && events == MAX_EVENTS) tally[bins + 3] += 1; /* stopped at the step limit, unscored */
}

static lucent_status run_batch(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)begin, (void)end, (void)thread;
    sphere_job *job = ctx;
    int ch = (int)(chunk / (uint64_t)job->d.batches);
    double *tally = job->tally + chunk * (uint64_t)job->stride;
    lucent_rng rng;
    lucent_rng_init(job->d.seed, chunk, &rng);
    uint64_t pending = 0;
    for (uint64_t i = 0; i < job->per_batch; i++) {
        trace(job, ch, tally, &rng);
        if (++pending == 1024) lucent_progress_add(job->progress, pending), pending = 0;
    }
    lucent_progress_add(job->progress, pending);
    return LUCENT_OK;
}

/* ---- normalisation ---- */

/* C(theta) = Int_cone max(n . w, 0) dw, midpoint rule in (alpha, beta). */
static double cone_projected(double theta, double delta)
{
    enum { NA = 24, NB = 48 };
    double ct = cos(theta), stt = sin(theta), da = delta / NA, db = 2.0 * M_PI / NB, sum = 0;
    for (int i = 0; i < NA; i++) {
        double a = (i + 0.5) * da, sa = sin(a), ca = cos(a);
        for (int j = 0; j < NB; j++) {
            double c = ct * sa * cos((j + 0.5) * db) + stt * ca;
            if (c > 0) sum += c * sa;
        }
    }
    return sum * da * db;
}

/* Int_{theta_a}^{theta_b} sin theta C(theta) dtheta. */
static double band_norm(double ta, double tb, double delta)
{
    enum { NT = 16 };
    double h = (tb - ta) / NT, sum = 0;
    for (int k = 0; k < NT; k++) {
        double t = ta + (k + 0.5) * h;
        sum += sin(t) * cone_projected(t, delta);
    }
    return sum * h;
}

static lucent_status validate(const lucent_cdrf_sphere_desc *d)
{
    if (!d->material) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "CDRF sphere: no material");
    lucent_status s = lucent_material_validate(d->material);
    if (s != LUCENT_OK) return s;
    if (!(d->radius >= LUCENT_CDRF_SPHERE_MIN_RADIUS && d->radius <= LUCENT_CDRF_SPHERE_MAX_RADIUS))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "CDRF sphere: radius must be in [%g, %g] mm (got %g)",
                            LUCENT_CDRF_SPHERE_MIN_RADIUS, LUCENT_CDRF_SPHERE_MAX_RADIUS, d->radius);
    if (!(d->roughness >= 0) || d->roughness > 1)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "CDRF sphere: roughness must be in [0, 1] (got %g)",
                            d->roughness);
    if (d->bins < 1 || d->bins > LUCENT_CDRF_MAX_BINS)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "CDRF sphere: bins must be in [1, %d]", LUCENT_CDRF_MAX_BINS);
    if (!(d->cone > 0) || d->cone > 0.5 * M_PI)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "CDRF sphere: cone must be in (0, pi/2] radians");
    if (d->batches < 2 || d->batches > 4096)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "CDRF sphere: batches must be in [2, 4096]");
    if (d->max_order < 0) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "CDRF sphere: max_order must be >= 0");
    for (int c = 0; c < 3; c++) {
        double sa = d->material->sigma_a[c], ss = d->material->sigma_s[c], st = sa + ss;
        if (st > 0 && (st < LUCENT_MC_MIN_SIGMA_T || st > LUCENT_MC_MAX_SIGMA_T))
            return lucent_error(
                LUCENT_ERR_INVALID_ARGUMENT,
                "%s: %s[%d]: sigma_t = sigma_a + sigma_s = %g mm^-1 is outside what the Monte Carlo can "
                "step (%g to %g mm^-1)",
                d->material->name, ss >= sa ? "sigma_s" : "sigma_a", c, st, LUCENT_MC_MIN_SIGMA_T,
                LUCENT_MC_MAX_SIGMA_T);
    }
    return LUCENT_OK;
}

static void reduce(const sphere_job *job, lucent_cdrf_sphere_result *dest)
{
    int B = job->d.batches, bins = job->d.bins;
    double n = (double)job->per_batch;
    for (int j = 0; j < bins; j++) {
        double ta = M_PI * j / bins, tb = M_PI * (j + 1) / bins;
        double norm = 2.0 * n * band_norm(ta, tb, job->d.cone);
        dest->theta[j] = 0.5 * (ta + tb);
        for (int c = 0; c < 3; c++) {
            double sum = 0, sum2 = 0;
            for (int b = 0; b < B; b++) {
                double x = job->tally[(size_t)(c * B + b) * (size_t)job->stride + (size_t)j] / norm;
                sum += x, sum2 += x * x;
            }
            double mean = sum / B, var = (sum2 / B - mean * mean) * B / (B - 1.0);
            dest->radiance[c][j] = mean;
            dest->radiance_se[c][j] = sqrt(fmax(0.0, var) / B);
            /* the exitance: the band's power over its area, 2 pi r^2 (cos ta - cos tb), for unit irradiance
             * (each photon carries pi r^2 / n: the power per photon over the band's area) */
            double e = 0, area = 2.0 * (cos(ta) - cos(tb)); /* over pi r^2 */
            for (int b = 0; b < B; b++)
                e += job->tally[(size_t)(c * B + b) * (size_t)job->stride + (size_t)(bins + 4 + j)];
            dest->exitance[c][j] = e / (n * B) / area;
            double fsum = 0;
            for (int b = 0; b < B; b++)
                fsum += job->tally[(size_t)(c * B + b) * (size_t)job->stride + (size_t)(2 * bins + 4 + j)];
            dest->flow[c][j] = e > 0 ? fsum / e : 0;
        }
    }
    for (int c = 0; c < 3; c++) {
        double e[3] = {0, 0, 0};
        for (int b = 0; b < B; b++)
            for (int k = 0; k < 3; k++)
                e[k] += job->tally[(size_t)(c * B + b) * (size_t)job->stride + (size_t)(bins + k)];
        dest->entered[c] = e[0] / (n * B);
        dest->exited[c] = e[1] / (n * B);
        dest->absorbed[c] = e[2] / (n * B);
    }
}

lucent_status lucent_cdrf_sphere_run(const lucent_cdrf_sphere_desc *desc, lucent_cdrf_sphere_result *dest)
{
    sphere_job job = {.d = *desc};
    lucent_cdrf_sphere_desc *d = &job.d;
    if (!d->photons) d->photons = 200000;
    if (!d->bins) d->bins = 36;
    if (d->cone == 0) d->cone = 0.2;
    if (!d->batches) d->batches = 32;
    lucent_status s = validate(d);
    if (s != LUCENT_OK) return s;
    job.per_batch = (d->photons + (uint64_t)d->batches - 1) / (uint64_t)d->batches;
    job.stride = 3 * d->bins + 4; /* bins, entered, exited, absorbed, packets stopped at the step limit,
                                     exitance bins, flow bins */
    job.cos_cone = cos(d->cone);
    job.tally = calloc((size_t)(3 * d->batches) * (size_t)job.stride, sizeof *job.tally);
    if (!job.tally) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "CDRF sphere: out of memory");
    job.progress = lucent_progress_begin(d->label ? d->label : "CDRF sphere", 3 * job.per_batch * (uint64_t)d->batches);
    s = lucent_parallel_for_share(d->pool, 3 * (uint64_t)d->batches, 1, run_batch, &job, lucent_dist_share());
    lucent_progress_end(job.progress);
    /* Each batch writes its own slots, 0 in every other process: the sum over processes (lucent/dist.h)
     * adds zeros only, so it is exact. */
    s = lucent_dist_sum(s, LUCENT_DIST_F64, job.tally, (size_t)(3 * d->batches) * (size_t)job.stride);
    if (s == LUCENT_OK) {
        memset(dest, 0, sizeof *dest);
        dest->bins = d->bins;
        dest->radius = d->radius;
        dest->photons = job.per_batch * (uint64_t)d->batches;
        reduce(&job, dest);
        double capped = 0;
        for (int b = 0; b < 3 * d->batches; b++)
            capped += job.tally[(size_t)b * (size_t)job.stride + (size_t)d->bins + 3];
        if (capped > 0)
            lucent_log(LUCENT_LOG_WARN,
                       "%s: %.0f photons reached the step limit (%d steps): the medium barely absorbs; results are "
                       "lower bounds",
                       d->label ? d->label : "CDRF sphere", capped, MAX_EVENTS);
    }
    free(job.tally);
    return s;
}
