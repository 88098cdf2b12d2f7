/* The reflectance and transmittance of a flat part of a material behind the path tracer's boundary
 * (lucent/profile.h, "The rough boundary's tables"; docs/render.md, "One boundary").
 *
 * A half-space (or a slab) of the material, its faces the rough dielectric of the path tracer: GGX
 * microfacets with the separable Smith G1 masking (Walter et al. 2007 eqs. 23, 33, 34), normals drawn
 * from the visible distribution (Heitz 2018), the unpolarised Fresnel reflectance at the microfacet
 * (Born & Wolf), all from base/optics.h, which the tracer's BSDF (src/trace/bsdf.c) assembles as well:
 * a photon meeting the face picks a visible microfacet, then reflects with probability F or refracts,
 * and the microfacet's outgoing ray survives the masking with probability G1 (single scattering among
 * the microfacets: what is masked is lost, as in the tracer). A smooth face (roughness 0) is Fresnel's.
 *
 * Estimators. Light arrives at cosine mu_i drawn within its incidence bin (cosine-weighted, so that a
 * bin holds the light of a uniform sky's ring), enters through the face's sampled microfacet with
 * weight (1 - F) G1(t) (the reflected part is the specular albedo, tallied apart), and walks with
 * implicit capture (weight times the single-scattering albedo at each collision), Henyey-Greenstein
 * scattering and Russian roulette; in a plane-parallel medium only the depth and the direction's
 * cosine to the normal matter. Each time it meets a face from inside it scores the expected light that
 * leaves, w times the face's exit kernel (the mean of (1 - F) G1(t) per exit bin for its internal
 * cosine, tabulated once per run from stratified microfacet draws; on a smooth face Fresnel's exact
 * refraction), into the lit face's reflectance or the far face's transmittance (by scattering order
 * 0, 1, more), and one drawn microfacet's reflection walks on with probability F G1(r): the same
 * expected value as drawing the exit, with the exit bins' noise gone. Bins are uniform in cosine; a bin's value
 * is the bin average of
 * pi f(mu_i, mu_o) (f the BRDF or BTDF of the light that entered, over azimuth): the scored weight
 * per arriving photon divided by the bin's projected solid angle over pi, hi^2 - lo^2.
 *
 * A sheet (lucent_sheet_run; docs/render.md, "Thin parts") is the same walk on a slab lit exactly along
 * its normal, with exit bins uniform in angle (the forward lobe of two rough faces is narrow) and the
 * unscattered crossing scored as its expectation, w e^(-sigma_t s / mu) (Beer-Lambert) times the far
 * face's exit kernel, at entry. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/optics.h"
#include "base/vec3.h"
#include "lucent/dist.h"
#include "lucent/mc.h"
#include "lucent/profile.h"

#define RR_THRESHOLD 1e-4
#define RR_SURVIVAL 0.1
#define MAX_EVENTS 100000000

enum {
    NB = LUCENT_BOUNDARY_BINS,
    NK = 256, /* the exit kernel's nodes: internal angles from the normal, uniform in [0, 90] degrees */
    KS = 64,  /* its strata per node and axis of the microfacet draw: KS^2 draws per node */
    NT = 256  /* the direct exit's optical depths, tau_j = TAU_MAX (j / (NT - 1))^2 */
};
#define TAU_MAX 24.0 /* beyond, e^-tau of the light goes straight out: nothing */

/* A chunk's tallies: reflected and transmitted (by order) per exit bin, then the totals (offsets for
 * nbo exit bins). */
#define T_REFLECT 0
#define T_TRANSMIT (job->nbo)
#define T_ORDER (2 * job->nbo)
#define T_SPECULAR (5 * job->nbo)
#define T_ABSORBED (5 * job->nbo + 1)
#define T_CAPPED (5 * job->nbo + 2)
#define T_STRIDE (5 * job->nbo + 3)

typedef struct boundary_job {
    lucent_boundary_desc d;
    /* The exit bins: NB uniform in cosine (the boundary's tables), or, for a sheet lit along its normal
     * (lucent_sheet_run), nbo uniform in the angle from the normal; nin incidence bins (1: along the
     * normal). */
    int nbo, nin;
    bool angle_bins;
    uint64_t per_batch;
    double *tally;
    /* The face's transmission from inside: exit[k][b], the mean weight (1 - F) G1(t) that light meeting
     * the face at an internal angle in node k, [k, k + 1) x 90 / NK degrees from the normal, carries out
     * into exit bin b. Nodes uniform in angle: near the normal the kernel changes with the angle, which
     * uniform cosines would resolve poorly (the last of 256 cosine nodes spans 5 degrees). */
    double *exit; /* [NK][nbo] */
    /* The direct exit after an isotropic scattering at optical depth tau below a face (the channel's
     * g = 0): direct[(c NT + j) nbo + b] = 1/2 int_0^1 e^(-tau_j / mu) exit(mu)[b] dmu. */
    double *direct;
    lucent_progress *progress;
} boundary_job;
static int exit_bin(const boundary_job *job, double mu)
{
    int b = job->angle_bins ? (int)(acos(fmax(-1.0, fmin(1.0, mu))) / (0.5 * M_PI) * job->nbo) : (int)(mu * job->nbo);
    return b < 0 ? 0 : b >= job->nbo ? job->nbo - 1 : b;
}

/* Crossing a face with travel direction d toward it (n: the face's normal on d's side, eta: the index
 * beyond over the index here) at microfacet m: the transmitted direction and weight (1 - F) G1(t), and
 * the reflected ones F G1(r); a direction on the wrong side of the face has weight 0. */
typedef struct crossing {
    v3 t, r;
    double wt, wr;
} crossing;

static crossing cross_face(v3 d, v3 n, v3 m, double eta, double alpha)
{
    crossing c = {.wt = 0, .wr = 0};
    double F = lucent_fresnel_dielectric(-v3_dot(d, m), eta, NULL);
    if (F < 1.0 && lucent_refract(d, m, eta, &c.t) && v3_dot(c.t, n) < 0)
        c.wt = (1.0 - F) * (alpha > 0 ? lucent_ggx_g1(v3_dot(c.t, n), alpha) : 1.0);
    c.r = lucent_reflect(d, m);
    if (v3_dot(c.r, n) > 0) c.wr = F * (alpha > 0 ? lucent_ggx_g1(v3_dot(c.r, n), alpha) : 1.0);
    return c;
}

/* The face's microfacet for travel direction d on the side whose outward normal is n: drawn from the
 * normals visible from -d (Heitz 2018), or n for a smooth face. */
static v3 facet(v3 d, v3 n, double alpha, double u1, double u2)
{
    return alpha > 0 ? lucent_ggx_sample_visible(v3_neg(d), n, alpha, u1, u2) : n;
}

/* Light inside travelling at cosine mu > 0 toward a face: the direction in the face's frame (the
 * face's normal on the inside is -z; by symmetry about it, azimuth 0). */
static v3 toward_face(double mu) { return v3_make(sqrt(fmax(0.0, 1.0 - mu * mu)), 0, mu); }

/* The exit kernel of a face: stratified microfacet draws, angles drawn within each node independently
 * of them (an angle tied to the strata correlates with the microfacet's tilt: that biased the exit bin
 * around the normal 3% low); a smooth face refracts exactly, averaged over the node's angles. */
static void build_exit_kernel(boundary_job *job)
{
    double eta = 1.0 / job->d.material->eta, alpha = job->d.roughness;
    v3 n = v3_make(0, 0, -1);
    lucent_rng rng;
    lucent_rng_init(job->d.seed, UINT64_MAX, &rng);
    for (int k = 0; k < NK; k++) {
        double *row = job->exit + (size_t)k * job->nbo;
        memset(row, 0, job->nbo * sizeof *row);
        for (int a = 0; a < KS; a++)
            for (int b = 0; b < KS; b++) {
                double mu = cos((k + lucent_rng_uniform(&rng)) / NK * (0.5 * M_PI));
                double u1 = (a + lucent_rng_uniform(&rng)) / KS, u2 = (b + lucent_rng_uniform(&rng)) / KS;
                v3 d = toward_face(mu);
                crossing c = cross_face(d, n, facet(d, n, alpha, u1, u2), eta, alpha);
                if (c.wt > 0) row[exit_bin(job, -v3_dot(c.t, n))] += c.wt / (KS * KS);
            }
    }
}

static double tau_node(int j) { return TAU_MAX * ((double)j / (NT - 1)) * ((double)j / (NT - 1)); }

/* The direct exit table of the isotropic channels (midpoint rule over the kernel's nodes). */
static void build_direct(boundary_job *job)
{
    for (int c = 0; c < 3; c++) {
        if (job->d.material->g[c] != 0) continue;
        for (int j = 0; j < NT; j++) {
            double *row = job->direct + ((size_t)c * NT + (size_t)j) * job->nbo, tau = tau_node(j);
            memset(row, 0, job->nbo * sizeof *row);
            for (int k = 0; k < NK; k++) {
                double th = (k + 0.5) / NK * (0.5 * M_PI), mu = cos(th), dmu = sin(th) * (0.5 * M_PI) / NK;
                double f = 0.5 * exp(-tau / mu) * dmu;
                if (f > 0)
                    for (int b = 0; b < job->nbo; b++) row[b] += f * job->exit[(size_t)k * job->nbo + b];
            }
        }
    }
}

/* Scores weight w times the direct exit at optical depth tau into out (and by_order), linear between
 * the table's depths. */
static void score_direct(const boundary_job *job, int ch, double tau, double w, double *out, double *by_order)
{
    if (tau >= TAU_MAX) return;
    double x = sqrt(tau / TAU_MAX) * (NT - 1);
    int j = (int)fmin(floor(x), NT - 2);
    double f = x - j;
    const double *a = job->direct + ((size_t)ch * NT + (size_t)j) * job->nbo, *b = a + job->nbo;
    for (int o = 0; o < job->nbo; o++) {
        double v = w * ((1 - f) * a[o] + f * b[o]);
        out[o] += v;
        if (by_order) by_order[o] += v;
    }
}

/* The walk meets a face from inside at cosine mu: scores the light that leaves (the exit kernel's
 * expectation) unless the direct exit was scored at the scattering it comes from, and keeps the
 * reflected part, drawn from one microfacet. top: the lit face. Returns the cosine the walk goes on
 * with (in the face's frame: negative, into the medium) and updates *w. */
static double meet_face(const boundary_job *job, double *tally, bool top, bool score, int order, double mu, double *w,
                        lucent_rng *rng)
{
    double eta = 1.0 / job->d.material->eta, alpha = job->d.roughness;
    v3 n = v3_make(0, 0, -1), d = toward_face(mu);
    if (score) {
        double *out = tally + (top ? T_REFLECT : T_TRANSMIT);
        double *by_order = top ? NULL : tally + T_ORDER + (order < 2 ? order : 2) * job->nbo;
        const double *row = job->exit + (size_t)fmin(acos(fmin(mu, 1.0)) / (0.5 * M_PI) * NK, NK - 1) * job->nbo;
        for (int b = 0; b < job->nbo; b++) out[b] += *w * row[b];
        if (by_order)
            for (int b = 0; b < job->nbo; b++) by_order[b] += *w * row[b];
    }
    double u1 = lucent_rng_uniform(rng), u2 = lucent_rng_uniform(rng);
    crossing c = cross_face(d, n, facet(d, n, alpha, u1, u2), eta, alpha);
    /* The reflection goes on with probability F G1(r) at the same weight (its expected weight, with
     * as many returns to the face as an analog walk makes: splitting its weight instead makes marble's
     * walks 7x longer for the same noise) */
    if (!(lucent_rng_uniform(rng) < c.wr)) *w = 0;
    return c.r.z;
}

/* One photon of channel ch arriving in incidence bin `bin`. The medium is z < 0 (to -thickness for a
 * slab); only the depth z and the direction's cosine mu with +z matter in a plane-parallel medium: a
 * Henyey-Greenstein deflection by cos t at azimuth phi gives mu' = mu cos t + sqrt(1 - mu^2) sin t cos phi.
 * An isotropic channel scores, at each scattering, the expected light that flies from there straight
 * out through each face (the direct exit table), and the faces then score only light that reaches them
 * after a reflection or none: the same expected value, without the noise of the rare flights that
 * meet a face around its normal, which the exit bins near the normal are made of. */
static void walk(const boundary_job *job, int ch, int bin, double *tally, lucent_rng *rng)
{
    const lucent_material *mat = job->d.material;
    double sa = mat->sigma_a[ch], ss = mat->sigma_s[ch], st = sa + ss, g = mat->g[ch];
    double albedo = st > 0 ? ss / st : 0, thick = job->d.thickness, alpha = job->d.roughness;
    bool nee = g == 0 && st > 0;
    double lo = (double)bin / job->nin, hi = (bin + 1.0) / job->nin;
    /* cosine-weighted in the bin; a sheet's light arrives along the normal */
    double mu0 = job->nin == 1 ? 1.0 : sqrt(lo * lo + lucent_rng_uniform(rng) * (hi * hi - lo * lo));
    v3 d = v3_make(sqrt(fmax(0.0, 1.0 - mu0 * mu0)), 0, -mu0), up = v3_make(0, 0, 1);
    double u1 = lucent_rng_uniform(rng), u2 = lucent_rng_uniform(rng);
    crossing c = cross_face(d, up, facet(d, up, alpha, u1, u2), mat->eta, alpha);
    tally[T_SPECULAR] += c.wr;
    double w = c.wt, z = 0, mu = c.t.z;
    int order = 0;
    bool scattered = false; /* the last event was a scattering (its direct exit is scored) */
    /* A sheet scores the unscattered crossing's expected exit at once, w e^(-sigma_t s / mu) times the far
     * face's exit kernel (Beer-Lambert), and not again when the walk's first flight reaches the far face:
     * the same expected value, without the noise of the few photons that cross a thick sheet unscattered. */
    bool crossing_scored = job->angle_bins && thick > 0 && w > 0 && mu < 0;
    if (crossing_scored) {
        double att = st > 0 ? exp(-st * thick / -mu) : 1.0;
        const double *row = job->exit + (size_t)fmin(acos(fmin(-mu, 1.0)) / (0.5 * M_PI) * NK, NK - 1) * job->nbo;
        for (int b = 0; b < job->nbo; b++) {
            tally[T_TRANSMIT + b] += w * att * row[b];
            tally[T_ORDER + b] += w * att * row[b];
        }
    }
    for (uint64_t events = 0; w > 0; events++) {
        if (events == MAX_EVENTS) {
            tally[T_CAPPED] += 1;
            return;
        }
        double s = st > 0 ? -log(1.0 - lucent_rng_uniform(rng)) / st : INFINITY;
        double zn = z + mu * s;
        if (zn >= 0) { /* the lit face, from inside */
            z = 0;
            mu = meet_face(job, tally, true, !(nee && scattered), order, mu, &w, rng);
            scattered = false;
            crossing_scored = false;
        } else if (thick > 0 && zn <= -thick) { /* the far face */
            z = -thick;
            mu = -meet_face(job, tally, false, !(nee && scattered) && !crossing_scored, order, -mu, &w, rng);
            scattered = false;
            crossing_scored = false;
        } else {
            z = zn;
            crossing_scored = false;
            tally[T_ABSORBED] += w * (1.0 - albedo);
            w *= albedo;
            order++;
            if (nee) {
                score_direct(job, ch, -z * st, w, tally + T_REFLECT, NULL);
                if (thick > 0)
                    score_direct(job, ch, (thick + z) * st, w, tally + T_TRANSMIT,
                                 tally + T_ORDER + (order < 2 ? order : 2) * job->nbo);
            }
            scattered = true;
            double ct = lucent_hg_sample_cos(g, lucent_rng_uniform(rng));
            double cp = cos(2.0 * M_PI * lucent_rng_uniform(rng));
            mu = fmax(-1.0, fmin(1.0, mu * ct + sqrt(fmax(0.0, (1.0 - mu * mu) * (1.0 - ct * ct))) * cp));
        }
        if (w > 0 && w < RR_THRESHOLD) w = lucent_rng_uniform(rng) < RR_SURVIVAL ? w / RR_SURVIVAL : 0;
    }
}

static lucent_status run_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)begin, (void)end, (void)thread;
    boundary_job *job = ctx;
    uint64_t per_channel = (uint64_t)job->nin * (uint64_t)job->d.batches;
    int ch = (int)(chunk / per_channel), bin = (int)(chunk % per_channel / (uint64_t)job->d.batches);
    double *tally = job->tally + chunk * T_STRIDE;
    lucent_rng rng;
    lucent_rng_init(job->d.seed, chunk, &rng);
    uint64_t pending = 0;
    for (uint64_t i = 0; i < job->per_batch; i++) {
        walk(job, ch, bin, tally, &rng);
        if (++pending == 1024) lucent_progress_add(job->progress, pending), pending = 0;
    }
    lucent_progress_add(job->progress, pending);
    return LUCENT_OK;
}

/* what: the run's name in messages ("boundary tables", "sheet tables") */
static lucent_status validate(const lucent_boundary_desc *d, const char *what)
{
    if (!d->material) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: no material", what);
    lucent_status s = lucent_material_validate(d->material);
    if (s != LUCENT_OK) return s;
    if (!(d->roughness >= 0) || d->roughness > 1)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: %s: roughness must be in [0, 1] (got %g)",
                            d->material->name, what, d->roughness);
    if (!(d->thickness >= 0))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: %s: thickness must be >= 0 mm (got %g)",
                            d->material->name, what, d->thickness);
    if (d->batches < 2 || d->batches > 4096)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: %s: batches must be in [2, 4096]", d->material->name,
                            what);
    for (int c = 0; c < 3; c++) {
        double st = d->material->sigma_a[c] + d->material->sigma_s[c];
        if (st > 0 && (st < LUCENT_MC_MIN_SIGMA_T || st > LUCENT_MC_MAX_SIGMA_T))
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                                "%s: sigma_t[%d] = %g mm^-1 is outside what the Monte Carlo can step (%g to %g mm^-1)",
                                d->material->name, c, st, LUCENT_MC_MIN_SIGMA_T, LUCENT_MC_MAX_SIGMA_T);
    }
    return LUCENT_OK;
}

/* Mean and standard error over the batches of the sum of slots k..k+count-1 of channel c, incidence
 * bin i, per photon. */
static void batch_stats_n(const boundary_job *job, int c, int i, int k, int count, double *mean, double *se)
{
    int B = job->d.batches;
    double sum = 0, sum2 = 0, n = (double)job->per_batch;
    for (int b = 0; b < B; b++) {
        size_t chunk = ((size_t)c * (size_t)job->nin + (size_t)i) * (size_t)B + (size_t)b;
        double x = 0;
        for (int j = 0; j < count; j++) x += job->tally[chunk * T_STRIDE + (size_t)(k + j)] / n;
        sum += x, sum2 += x * x;
    }
    *mean = sum / B;
    *se = sqrt(fmax(0.0, (sum2 / B - *mean * *mean) / (B - 1.0)));
}

/* Mean and standard error over the batches of slot k of channel c, incidence bin i, per photon. */
static void batch_stats(const boundary_job *job, int c, int i, int k, double *mean, double *se)
{
    batch_stats_n(job, c, i, k, 1, mean, se);
}

static void reduce(const boundary_job *job, lucent_boundary_result *r)
{
    for (int c = 0; c < 3; c++)
        for (int i = 0; i < NB; i++) {
            double m, se;
            for (int o = 0; o < NB; o++) {
                double lo = (double)o / NB, hi = (o + 1.0) / NB, solid = hi * hi - lo * lo;
                batch_stats(job, c, i, T_REFLECT + o, &m, &se);
                r->reflect[c][i][o] = m / solid, r->reflect_se[c][i][o] = se / solid;
                batch_stats(job, c, i, T_TRANSMIT + o, &m, &se);
                r->transmit[c][i][o] = m / solid, r->transmit_se[c][i][o] = se / solid;
                for (int k = 0; k < 3; k++) {
                    batch_stats(job, c, i, T_ORDER + k * NB + o, &m, &se);
                    r->transmit_order[k][c][i][o] = m / solid;
                }
            }
            batch_stats_n(job, c, i, T_REFLECT, NB, &r->reflect_total[c][i], &r->reflect_total_se[c][i]);
            batch_stats_n(job, c, i, T_TRANSMIT, NB, &r->transmit_total[c][i], &r->transmit_total_se[c][i]);
            batch_stats(job, c, i, T_SPECULAR, &r->specular[c][i], &r->specular_se[c][i]);
            batch_stats(job, c, i, T_ABSORBED, &r->absorbed[c][i], &r->absorbed_se[c][i]);
        }
}

/* Prepares job (its desc, nbo, nin and angle_bins set): the defaults, the checks, the tallies and the
 * face's kernels (freed by the caller, even on error). */
static lucent_status prepare_job(boundary_job *job, const char *label)
{
    lucent_boundary_desc *d = &job->d;
    if (!d->photons) d->photons = LUCENT_BOUNDARY_PHOTONS;
    if (!d->batches) d->batches = 8;
    if (!d->seed) d->seed = 1;
    lucent_status s = validate(d, label);
    if (s != LUCENT_OK) return s;
    job->per_batch = (d->photons + (uint64_t)d->batches - 1) / (uint64_t)d->batches;
    size_t chunks = (size_t)3 * (size_t)job->nin * (size_t)d->batches;
    job->tally = calloc(chunks * (size_t)T_STRIDE, sizeof *job->tally);
    job->exit = malloc((size_t)NK * (size_t)job->nbo * sizeof *job->exit);
    job->direct = malloc((size_t)3 * NT * (size_t)job->nbo * sizeof *job->direct);
    if (!job->tally || !job->exit || !job->direct)
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", label);
    build_exit_kernel(job);
    build_direct(job);
    return LUCENT_OK;
}

/* Runs the walks of a prepared job into job->tally (zeroed first). */
static lucent_status tally_job(boundary_job *job, const char *label)
{
    lucent_boundary_desc *d = &job->d;
    size_t chunks = (size_t)3 * (size_t)job->nin * (size_t)d->batches;
    memset(job->tally, 0, chunks * (size_t)T_STRIDE * sizeof *job->tally);
    job->progress = lucent_progress_begin(d->label ? d->label : label, chunks * job->per_batch);
    lucent_status s = lucent_parallel_for_share(d->pool, chunks, 1, run_chunk, job, lucent_dist_share());
    lucent_progress_end(job->progress);
    /* Each chunk writes its own slots, 0 in every other process: the sum over processes is exact. */
    s = lucent_dist_sum(s, LUCENT_DIST_F64, job->tally, chunks * (size_t)T_STRIDE);
    if (s == LUCENT_OK) {
        double capped = 0;
        for (size_t k = 0; k < chunks; k++) capped += job->tally[k * (size_t)T_STRIDE + (size_t)T_CAPPED];
        if (capped > 0)
            lucent_log(LUCENT_LOG_WARN, "%s: %s: %.0f photons reached the step limit; results are lower bounds",
                       d->material->name, label, capped);
    }
    return s;
}

lucent_status lucent_boundary_run(const lucent_boundary_desc *desc, lucent_boundary_result *dest)
{
    boundary_job job = {.d = *desc, .nbo = NB, .nin = NB};
    lucent_status s = prepare_job(&job, "boundary tables");
    if (s == LUCENT_OK) s = tally_job(&job, "boundary tables");
    if (s == LUCENT_OK) {
        memset(dest, 0, sizeof *dest);
        dest->photons = job.per_batch * (uint64_t)job.d.batches;
        reduce(&job, dest);
    }
    free(job.tally), free(job.exit), free(job.direct);
    return s;
}

/* A sheet's tallies into dest: the far face's exit bins, uniform in the angle from the normal, split
 * into the lobe (orders 0 and 1) and the rest. */
static void reduce_sheet(const boundary_job *job, lucent_sheet_result *dest)
{
    int B = job->d.batches, nbo = job->nbo;
    double n = (double)job->per_batch;
    memset(dest, 0, sizeof *dest);
    dest->photons = job->per_batch * (uint64_t)B;
    for (int c = 0; c < 3; c++) {
        for (int o = 0; o < LUCENT_SHEET_BINS; o++) {
            /* the bin's projected solid angle over pi: sin^2 hi - sin^2 lo */
            double lo = sin(o * (0.5 * M_PI) / LUCENT_SHEET_BINS);
            double hi = sin((o + 1) * (0.5 * M_PI) / LUCENT_SHEET_BINS);
            double solid = hi * hi - lo * lo, m, se;
            batch_stats_n(job, c, 0, 2 * nbo + o, 1, &m, &se);
            dest->unscattered[c][o] = m / solid;
            /* orders 0 and 1 together, then 2 and more: their batch means' standard errors */
            double sum = 0, sum2 = 0, sumd = 0, sumd2 = 0;
            for (int b = 0; b < B; b++) {
                const double *t = job->tally + ((size_t)c * (size_t)B + (size_t)b) * (size_t)T_STRIDE;
                double x = (t[2 * nbo + o] + t[3 * nbo + o]) / n, y = t[4 * nbo + o] / n;
                sum += x, sum2 += x * x, sumd += y, sumd2 += y * y;
            }
            double ml = sum / B, md = sumd / B;
            dest->lobe[c][o] = ml / solid;
            dest->lobe_se[c][o] = sqrt(fmax(0.0, (sum2 / B - ml * ml) / (B - 1.0))) / solid;
            dest->diffuse[c][o] = md / solid;
            dest->diffuse_se[c][o] = sqrt(fmax(0.0, (sumd2 / B - md * md) / (B - 1.0))) / solid;
        }
        batch_stats_n(job, c, 0, nbo, nbo, &dest->total[c], &dest->total_se[c]);
    }
}

/* A sheet lit along its normal (lucent/profile.h, "A sheet lit from behind"), at count thicknesses: the
 * face's kernels, which do not depend on the thickness, built once. */
lucent_status lucent_sheet_run_many(const lucent_sheet_desc *desc, const double *thickness, int count,
                                    lucent_sheet_result *dest)
{
    if (!desc->material) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "sheet tables: no material");
    for (int k = 0; k < count; k++)
        if (!(thickness[k] > 0))
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: sheet tables: thickness must be > 0 mm (got %g)",
                                desc->material->name, thickness[k]);
    if (count < 1)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: sheet tables: no thickness", desc->material->name);
    boundary_job job = {.d = {.material = desc->material,
                              .roughness = desc->roughness,
                              .thickness = thickness[0],
                              .photons = desc->photons ? desc->photons : LUCENT_SHEET_PHOTONS,
                              .batches = desc->batches,
                              .seed = desc->seed,
                              .pool = desc->pool,
                              .label = desc->label},
                        .nbo = LUCENT_SHEET_BINS,
                        .nin = 1,
                        .angle_bins = true};
    lucent_status s = prepare_job(&job, "sheet tables");
    uint64_t seed = job.d.seed;
    for (int k = 0; s == LUCENT_OK && k < count; k++) {
        job.d.thickness = thickness[k], job.d.seed = seed + (uint64_t)k; /* each thickness its own streams */
        s = tally_job(&job, "sheet tables");
        if (s == LUCENT_OK) reduce_sheet(&job, &dest[k]);
    }
    free(job.tally), free(job.exit), free(job.direct);
    return s;
}

lucent_status lucent_sheet_run(const lucent_sheet_desc *desc, lucent_sheet_result *dest)
{
    return lucent_sheet_run_many(desc, &desc->thickness, 1, dest);
}

double lucent_sheet_bin_angle(int bin) { return (bin + 0.5) * (0.5 * M_PI) / LUCENT_SHEET_BINS; }

double lucent_boundary_bin_cosine(int bin) { return (bin + 0.5) / LUCENT_BOUNDARY_BINS; }
