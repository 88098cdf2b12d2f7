/* Light paths: the subsurface light of dense objects traced from the lights to the camera.
 *
 * A camera path through a dense medium (marble: albedo 0.999, diffusion length 4 to 9 mm) gathers
 * light from next-event estimates at every vertex near the boundary, but all of them land in the one
 * pixel it started from. A photon from a light walks the same way (the same code, integrator.c, with
 * the camera as the target of its next-event estimates: tr->camera_light, a point "light" at the eye
 * whose intensity is the camera's importance), and its estimates land in the pixels where the
 * boundary points they pass through appear: one walk feeds the many pixels its diffusion reaches
 * (Veach 1997, section 10.2: light tracing with connections to the lens; Arvo & Kirk 1990 call the
 * estimator particle tracing). By reciprocity, the estimates through the boundary and their multiple
 * importance sampling are the camera paths' with the roles swapped; the radiance BTDF is evaluated
 * with its arguments reversed and divided by eta^2 (nee.c), and a photon carries power, so the
 * boundary's radiance scaling does not apply to it (integrator.c).
 *
 * The two estimators split the paths, so that each path is counted once: the light paths take every
 * path that leaves an object they serve straight toward the camera from the light-path lights
 * (camera <- boundary point, refracted out <- the walk inside <- ... <- light); a camera path whose
 * first refracting surface is such an object and that refracts into it leaves those lights to them
 * (it picks among the others, tr_light.select_cam, and finds none of theirs). Reflection off the
 * boundary toward the camera, and everything after it, stays with the camera paths.
 *
 * Served: with render.light_paths auto, the dense objects with a rough boundary (tr_object.dense);
 * lights: all of them (directional ones, sun discs included; point and sphere lights; the
 * environment); not with the comparison modes (boundary_nee_only, plain_flights, nee_every_vertex)
 * or under MPI. Each pass traces render.photons photons per pixel, drawn from the lights in
 * proportion to their power toward the scene (through a disc that covers it; from a point or sphere
 * light, into the cone that holds its bounding sphere); a pass's connections make one image, and its
 * estimate and variance per pixel come from those per-pass images (film.c), added to the camera
 * paths' (independent).
 * Connections are kept per chunk of photons and added in chunk order, so the image depends on the
 * seed and the number of passes only (not on the thread count). */
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/dist.h"
#include "trace/film.h"

enum { LP_CHUNKS = 64 };
#define LP_STREAM (1ull << 62) /* photon streams: (LP_STREAM | pass << 32 | photon), apart from the camera's */

/* ---- which lights and objects ---- */

static bool light_eligible(const tr_light *l)
{
    return l->type == LUCENT_LIGHT_DIRECTIONAL || l->type == LUCENT_LIGHT_ENVIRONMENT ||
           l->type == LUCENT_LIGHT_POINT || l->type == LUCENT_LIGHT_SPHERE;
}

/* 1 - cos of the half-angle of the cone from x that holds the scene's bounding sphere grown by
 * `grow`, and its axis (2: every direction, when x lies within that sphere). */
static double scene_cone(const lucent_tracer *tr, v3 x, double grow, v3 *axis)
{
    v3 to = v3_sub(v3_load(tr->emit_centre), x);
    double d = v3_length(to), R = tr->emit_radius + grow;
    *axis = d > 0 ? v3_scale(to, 1.0 / d) : v3_make(0, 0, 1);
    if (!(d > R)) return 2.0;
    double sin2 = (R / d) * (R / d);
    return sin2 / (1.0 + sqrt(1.0 - sin2)); /* 1 - cos, accurate for small angles */
}

/* Power emitted toward the scene per unit of the light's radiance (directional: irradiance, through
 * the emission disc; point: intensity, into the cone that holds the scene; sphere of radius r: its
 * projected area pi r^2 times the cone from its centre that holds the scene grown by r, which holds
 * every direction in which a point of the light sees the scene). */
static double emit_factor(const lucent_tracer *tr, const tr_light *l)
{
    double disc = M_PI * tr->emit_radius * tr->emit_radius;
    v3 axis;
    if (l->type == LUCENT_LIGHT_POINT) return 2.0 * M_PI * scene_cone(tr, l->position, 0.0, &axis);
    if (l->type == LUCENT_LIGHT_SPHERE)
        return M_PI * l->radius * l->radius * 2.0 * M_PI * scene_cone(tr, l->position, l->radius, &axis);
    if (l->type == LUCENT_LIGHT_ENVIRONMENT) return 4.0 * M_PI * disc;
    return l->delta ? disc : l->solid_angle * disc;
}

static uint64_t pass_photons(const lucent_tracer *tr);

/* The entry grid: cubes over the scene's bounds (grown by 2%), res along the longest side, res^2 about
 * a 64th of a pass's photons (an object's surface crosses some 3 res^2 cells: about ten arrivals per
 * cell and pass where every photon arrives), between 4 and TR_ENTRY_RES (24 from 192 x 192 pixels). */
static void entry_grid(lucent_tracer *tr, const double lo[3], const double hi[3])
{
    double size = 0, res = round(sqrt((double)pass_photons(tr) / 64.0));
    res = res < 4 ? 4 : res > TR_ENTRY_RES ? TR_ENTRY_RES : res;
    for (int a = 0; a < 3; a++) size = fmax(size, hi[a] - lo[a]);
    tr->entry_h = size > 0 ? 1.02 * size / res : 1.0;
    for (int a = 0; a < 3; a++) {
        double mid = lo[a] <= hi[a] ? 0.5 * (lo[a] + hi[a]) : 0.0;
        int n = (int)ceil(1.02 * (hi[a] - lo[a]) / tr->entry_h);
        tr->entry_n[a] = n < 1 ? 1 : n > (int)res ? (int)res : n;
        tr->entry_lo[a] = mid - 0.5 * tr->entry_n[a] * tr->entry_h;
    }
}

void tr_light_paths_setup(lucent_tracer *tr)
{
    const lucent_tracer_desc *d = &tr->desc;
    int mode = tr->render.trace.light_paths;
    bool allowed = mode != LUCENT_LIGHT_PATHS_OFF && !d->boundary_nee_only && !d->plain_flights &&
                   !d->nee_every_vertex && !lucent_dist_active() && tr->render.trace.photons > 0;
    bool any = false;
    for (int o = 0; o < tr->object_count; o++) {
        tr_object *ob = &tr->objects[o];
        ob->light_paths =
            allowed && ob->boundary.kind == TR_BOUNDARY_ROUGH && (mode == LUCENT_LIGHT_PATHS_ALL || ob->dense);
        any |= ob->light_paths;
    }
    double lo[3], hi[3];
    lucent_scene_bounds(tr->scene, lo, hi);
    for (int a = 0; a < 3; a++) tr->emit_centre[a] = 0.5 * (lo[a] + hi[a]);
    tr->emit_radius = lo[0] <= hi[0] ? 0.5 * v3_length(v3_sub(v3_load(hi), v3_load(lo))) * 1.01 + tr->eps : 1.0;
    double rest = 0, acc = 0;
    bool lights = false;
    for (int i = 0; i < tr->light_count; i++) {
        tr_light *l = &tr->lights[i];
        l->light_paths = any && light_eligible(l) && tr_luminance(l->radiance) > 0;
        l->power = l->light_paths ? tr_luminance(l->radiance) * emit_factor(tr, l) : 0;
        lights |= l->light_paths;
        if (!l->light_paths) rest += l->select;
    }
    tr->light_paths = lights;
    entry_grid(tr, lo, hi);
    tr->camera_side_lights = 0;
    for (int i = 0; i < tr->light_count; i++) {
        tr_light *l = &tr->lights[i];
        l->select_cam = l->light_paths || !(rest > 0) ? 0.0 : l->select / rest; /* a dark light's select is 0 */
        acc += l->select_cam;
        tr->select_cdf_cam[i] = acc;
        tr->camera_side_lights += l->select_cam > 0;
    }
    const double *eye = tr->scene->camera.position;
    tr->camera_light = (tr_light){.type = LUCENT_LIGHT_POINT,
                                  .scene_index = -1,
                                  .radiance = {1, 1, 1},
                                  .position = v3_load(eye),
                                  .delta = true,
                                  .select = 1.0};
}

/* ---- the entry grid ---- */

int tr_entry_cell(const lucent_tracer *tr, v3 y)
{
    double p[3];
    v3_store(y, p);
    int c[3];
    for (int a = 0; a < 3; a++) {
        double u = (p[a] - tr->entry_lo[a]) / tr->entry_h;
        if (!(u >= 0 && u < tr->entry_n[a])) return -1;
        c[a] = (int)u;
    }
    return (c[2] * tr->entry_n[1] + c[1]) * tr->entry_n[0] + c[0];
}

/* ---- the camera's importance and the splats ---- */

long tr_light_paths_importance(const lucent_tracer *tr, v3 y, double le[3])
{
    const lucent_camera *cam = &tr->scene->camera;
    int w = tr->render.view.width, h = tr->render.view.height;
    double px, py, cosa, p[3];
    v3_store(y, p);
    if (!lucent_camera_project(cam, w, h, p, &px, &py, &cosa)) return -1;
    double side = 2.0 * tan(0.5 * cam->fov_y * M_PI / 180) / h; /* a pixel's side at unit distance */
    double importance = 1.0 / (side * side * cosa * cosa * cosa);
    for (int c = 0; c < 3; c++) le[c] *= importance;
    return (long)py * w + (long)px;
}

typedef struct splat_item {
    uint32_t pixel;
    double v[3];
} splat_item;

struct tr_splats {
    splat_item *items;
    size_t n, cap;
    bool failed; /* out of memory */
};

void tr_splat(struct tr_splats *s, long pixel, const double value[3])
{
    if (s->n == s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 1024;
        splat_item *grown = realloc(s->items, cap * sizeof *grown);
        if (!grown) {
            s->failed = true;
            return;
        }
        s->items = grown, s->cap = cap;
    }
    splat_item *it = &s->items[s->n++];
    it->pixel = (uint32_t)pixel;
    memcpy(it->v, value, sizeof it->v);
}

/* ---- a pass of photons ---- */

typedef struct lp_moments {
    double m2[TR_MAX_LIGHTS]; /* per light: its photons' sums of squared connections, times share^2 */
    uint64_t n[TR_MAX_LIGHTS];
} lp_moments;

/* A photon's first arrival (tr_photon_entry), for the entry grid's sums (fold). */
typedef struct lp_entry {
    int cell;
    bool went_on;
    double m2, cost; /* its squared connections at pick and entry probability 1; its scatterings */
} lp_entry;

typedef struct lp_entries {
    lp_entry *items;
    size_t n, cap;
    bool failed;
} lp_entries;

typedef struct lp_job {
    const lucent_tracer *tr;
    struct tr_splats *lists; /* one per chunk */
    lp_entries *entries;     /* one per chunk */
    const float *q;          /* the entry roulette's probabilities (NULL: none this pass) */
    lp_moments *moments;     /* one per chunk */
    tr_stats *stats;         /* one per thread */
    uint64_t pass, per_chunk;
    double share[TR_MAX_LIGHTS], deadline;
    uint64_t first[TR_MAX_LIGHTS + 1]; /* light l's photons are first[l] .. first[l + 1] - 1 (strata) */
    double shift[TR_MAX_LIGHTS][4];    /* the random shift of each light's point set in this pass */
    _Atomic bool cut;
} lp_job;

#define LP_POWER_SHARE 0.2 /* the part of the photons drawn in proportion to power once measured */

/* Each light's share of a pass's photons. The first pass draws them in proportion to the lights'
 * power. A light's photons add to the image's variance about M_l / share_l, M_l the mean over its
 * photons of the sum of their squared connections at share 1 (one pixel's variance is the second
 * moment of what lands there, less the squared mean, small for sparse connections), so the shares
 * that minimise sum_l M_l / share_l under sum_l share_l = 1 go as sqrt(M_l) (the cost per photon
 * differed by 1.4x at most between the dragon's lights and is left out). Later passes take
 * LP_POWER_SHARE of the power shares and the rest in proportion to sqrt(M_l) measured over the
 * passes so far: a pass's shares depend on earlier passes only, so each pass is an unbiased
 * estimate (the photons' weights divide by their light's share), and the image on the seed and the
 * passes only. On the dragon (256 x 256) they put 0.62, 0.18, 0.20 of the photons on the low sun,
 * the back light and the environment from the second pass on, against 0.49, 0.30, 0.20 by power. */
static void emitter_shares(const lucent_tracer *tr, const tr_film *f, double share[TR_MAX_LIGHTS])
{
    double total = 0, root[TR_MAX_LIGHTS] = {0}, roots = 0;
    for (int i = 0; i < tr->light_count; i++) {
        total += tr->lights[i].power;
        if (tr->lights[i].power > 0 && f->light_n[i] > 0) root[i] = sqrt(f->light_m2[i] / (double)f->light_n[i]);
        roots += root[i];
    }
    bool measured = f->light_passes > 0 && roots > 0;
    for (int i = 0; i < tr->light_count; i++) {
        double p = total > 0 ? tr->lights[i].power / total : 0;
        share[i] = measured ? LP_POWER_SHARE * p + (1.0 - LP_POWER_SHARE) * root[i] / roots : p;
    }
}

#define ENTRY_MIN_PHOTONS 32 /* photons that went on from a cell before its probability is measured */
#define ENTRY_Q_MIN 0.2 /* the least entry probability (0.05 gave half the cost and 1.25x the noise on the dragon) */

/* The entry roulette's probability per cell of the entry grid; false when nothing is measured yet (q
 * is then 1 everywhere). A photon that arrives at a served object in cell c goes on with probability
 * q_c (weighted by 1 / q_c). If the photons that arrive there bring M_c (the mean of their squared
 * connections at q = 1) and cost S_c (their scatterings, plus 1 for the arrival), the cells add
 * V = sum_c a_c M_c / q_c to the variance (a_c arrivals) and C = sum_c a_c (1 + q_c S_c) to the cost;
 * at fixed cost V is least for q_c proportional to sqrt(M_c / S_c) (the optimum of Russian roulette
 * and splitting for efficiency, as in Vorba and Krivanek 2016), so q_c = clamp(lambda sqrt(M_c / S_c),
 * ENTRY_Q_MIN, 1), with the lambda of least V C over a geometric ladder (and lambda infinite: no
 * roulette). Photons that arrive nowhere and the camera paths are left out of C. A pass's
 * probabilities depend on earlier passes only, so each pass stays unbiased (as the light shares). On
 * the dragon, the photons that enter where the camera does not see their light were 38% of the walks'
 * scatterings. */
static double entry_ratio(const tr_film *f, int c)
{
    double n = f->entry_n[c] ? f->entry_n[c] : 1;
    return sqrt(f->entry_m2[c] / (f->entry_cost[c] + n)); /* sqrt(M_c / S_c), S_c with the arrival's 1 */
}

/* q_c for lambda: 1 until ENTRY_MIN_PHOTONS went on from the cell. */
static double entry_q(const tr_film *f, int c, double lambda)
{
    if (f->entry_n[c] < ENTRY_MIN_PHOTONS) return 1.0;
    return fmin(1.0, fmax(ENTRY_Q_MIN, lambda * entry_ratio(f, c)));
}

static bool entry_probabilities(const tr_film *f, float *q)
{
    double r_max = 0;
    for (int c = 0; c < TR_ENTRY_CELLS; c++)
        if (f->entry_n[c] >= ENTRY_MIN_PHOTONS) r_max = fmax(r_max, entry_ratio(f, c));
    if (!(r_max > 0)) return false;
    double best = INFINITY, best_lambda = INFINITY;
    for (int k = 0; k <= 64; k++) {
        double lambda = k < 64 ? exp2(0.25 * k) / r_max : INFINITY, V = 0, C = 0;
        for (int c = 0; c < TR_ENTRY_CELLS; c++) {
            if (!f->entry_arrived[c]) continue;
            double n = f->entry_n[c] ? f->entry_n[c] : 1, M = f->entry_m2[c] / n, S = f->entry_cost[c] / n + 1.0;
            double qc = entry_q(f, c, lambda);
            V += f->entry_arrived[c] * M / qc, C += f->entry_arrived[c] * (1.0 + qc * S);
        }
        if (V * C < best) best = V * C, best_lambda = lambda;
    }
    if (!isfinite(best_lambda)) return false;
    for (int c = 0; c < TR_ENTRY_CELLS; c++) q[c] = (float)entry_q(f, c, best_lambda);
    return true;
}

/* A pass's photons are stratified. Light l takes a block of them, first[l] .. first[l + 1] - 1, whose
 * bounds are share_l's cumulative sums times the photon count, less one random offset in [0, 1) for the
 * pass (systematic sampling: each light gets its share of the photons to within one, and in expectation
 * exactly; a photon's weight divides by its light's share as before). Within a block, the four numbers
 * that set where photon j of n starts and goes (emit) are the Hammersley point
 * ((j + 1/2) / n, phi_2(j), phi_3(j), phi_5(j)), phi_b the base-b radical inverse, shifted modulo 1 by
 * a random vector per light and pass (Cranley and Patterson 1976): every photon's numbers are still
 * uniform, so the pass is an unbiased estimate, and the passes stay independent, so the variance of the
 * mean still comes from their spread; but the photons of a pass no longer bunch up on the object by
 * chance. A light without a share gets no photons (its weight would divide by 0). */
static void strata(lp_job *job, const lucent_tracer *tr, uint64_t photons)
{
    lucent_rng rng;
    lucent_rng_init(tr->film->seed, LP_STREAM | job->pass << 32 | 0xFFFFFFFFull, &rng);
    double offset = lucent_rng_uniform(&rng), acc = 0;
    int last = -1; /* the last light with a share: it takes the block's end (rounding) */
    for (int l = 0; l < tr->light_count; l++)
        if (job->share[l] > 0) last = l;
    job->first[0] = 0;
    for (int l = 0; l < tr->light_count; l++) {
        acc += job->share[l];
        double edge = l >= last ? (double)photons : ceil(acc * (double)photons - offset);
        uint64_t e = edge < (double)job->first[l] ? job->first[l] : edge > (double)photons ? photons : (uint64_t)edge;
        job->first[l + 1] = job->share[l] > 0 ? e : job->first[l]; /* none for a light without a share */
        for (int k = 0; k < 4; k++) job->shift[l][k] = lucent_rng_uniform(&rng);
    }
}

/* The base-b radical inverse of j: its digits mirrored about the point. */
static double radical_inverse(uint64_t j, unsigned b)
{
    double r = 0, f = 1.0 / b;
    for (; j; j /= b, f /= b) r += (double)(j % b) * f;
    return r;
}

/* Photon i's light (-1: none), and its four stratified numbers. */
static int stratum(const lp_job *job, int lights, uint64_t i, double u[4])
{
    for (int l = 0; l < lights; l++) {
        if (i >= job->first[l + 1]) continue;
        uint64_t j = i - job->first[l], n = job->first[l + 1] - job->first[l];
        double x[4] = {((double)j + 0.5) / (double)n, radical_inverse(j, 2), radical_inverse(j, 3),
                       radical_inverse(j, 5)};
        for (int k = 0; k < 4; k++) u[k] = fmod(x[k] + job->shift[l][k], 1.0);
        return l;
    }
    return -1;
}

/* What a photon adds to the sum of the pixels' second moments: over the pixels its connections (items
 * from `from` on) land in, the square of their sum there (a photon's connections from nearby vertices
 * often share a pixel, and then add before they are squared). */
static double squared_connections(const struct tr_splats *s, size_t from)
{
    double m2 = 0;
    for (size_t k = from; k < s->n; k++) {
        bool seen = false;
        for (size_t j = from; j < k && !seen; j++) seen = s->items[j].pixel == s->items[k].pixel;
        if (seen) continue;
        double v[3] = {0, 0, 0};
        for (size_t j = k; j < s->n; j++)
            if (s->items[j].pixel == s->items[k].pixel)
                for (int c = 0; c < 3; c++) v[c] += s->items[j].v[c];
        m2 += v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    }
    return m2;
}

/* A photon from light l: its start o and direction d, all of equal power, from the four uniform
 * numbers u of its stratum. Directional: toward the scene, uniformly (u2, u3) in a sun disc's cone;
 * environment: uniform (u2, u3) over the sphere; both from a start uniform (u0, u1) on the disc of
 * radius emit_radius perpendicular to d, 2 radii before the centre (all of the scene lies behind the
 * disc). Point: from its position, uniformly (u0, u1) in the cone that holds the scene's bounding
 * sphere. Sphere of radius r and radiance L: d uniform (u0, u1) in the cone of emit_factor, then a
 * point uniform (u2, u3) on the disc of radius r through the centre perpendicular to d, lifted onto
 * the light's half facing d: the power L cos dA dw that the light sends along d is L dA_perp dw over
 * that disc (dA_perp = cos dA), so the photons' density follows it. */
static void emit(const lucent_tracer *tr, const tr_light *l, const double u[4], v3 *o, v3 *d)
{
    bool from_position = l->type == LUCENT_LIGHT_POINT || l->type == LUCENT_LIGHT_SPHERE;
    double u1 = from_position ? u[0] : u[2], u2 = from_position ? u[1] : u[3];
    if (from_position) {
        double r = l->type == LUCENT_LIGHT_SPHERE ? l->radius : 0.0;
        v3 axis, t, b;
        double omc = scene_cone(tr, l->position, r, &axis);
        *d = lucent_around(axis, 1.0 - u1 * omc, 2.0 * M_PI * u2);
        double rho = r * sqrt(u[2]), phi = 2.0 * M_PI * u[3];
        lucent_basis(*d, &t, &b);
        v3 x = v3_add(v3_scale(t, rho * cos(phi)), v3_scale(b, rho * sin(phi)));
        x = v3_madd(x, *d, sqrt(fmax(0.0, r * r - rho * rho)));
        *o = v3_add(l->position, v3_scale(x, 1.0 + 1e-9)); /* just outside the light */
        return;
    }
    if (l->type == LUCENT_LIGHT_ENVIRONMENT)
        *d = lucent_around(v3_make(0, 0, 1), 1.0 - 2.0 * u1, 2.0 * M_PI * u2);
    else if (l->delta)
        *d = v3_neg(l->toward);
    else
        *d = v3_neg(lucent_around(l->toward, 1.0 - u1 * (1.0 - l->cos_cone), 2.0 * M_PI * u2));
    *o = tr_disc_start(v3_load(tr->emit_centre), tr->emit_radius, v3_neg(*d), u[0], u[1]);
}

static void entry_push(lp_entries *s, const lp_entry *e)
{
    if (s->n == s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 256;
        lp_entry *grown = realloc(s->items, cap * sizeof *grown);
        if (!grown) {
            s->failed = true;
            return;
        }
        s->items = grown, s->cap = cap;
    }
    s->items[s->n++] = *e;
}

static lucent_status photon_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    lp_job *job = ctx;
    const lucent_tracer *tr = job->tr;
    if (job->deadline > 0 && (atomic_load(&job->cut) || lucent_clock_seconds() >= job->deadline)) {
        atomic_store(&job->cut, true);
        return LUCENT_OK;
    }
    double photons = (double)(job->per_chunk * LP_CHUNKS);
    lp_moments *mo = &job->moments[chunk];
    tr_stats stats = {0}; /* on this thread's stack (film.c's pass_tile says why) */
    for (uint64_t i = begin; i < end; i++) {
        lucent_rng rng;
        lucent_rng_init(tr->film->seed, LP_STREAM | job->pass << 32 | i, &rng);
        double u[4];
        int k = stratum(job, tr->light_count, i, u);
        if (k < 0) continue;
        const tr_light *l = &tr->lights[k];
        v3 o, d;
        emit(tr, l, u, &o, &d);
        double y = tr_luminance(l->radiance), beta[3] = {l->radiance[0] / y, l->radiance[1] / y, l->radiance[2] / y};
        size_t from = job->lists[chunk].n;
        uint64_t scatters = stats.scatters;
        tr_photon_entry e = {.q = job->q, .cell = -1};
        tr_trace_light_path(tr, o, d, beta, l->power / (job->share[k] * photons), &rng, &job->lists[chunk], &e, &stats);
        double m2 = squared_connections(&job->lists[chunk], from) * job->share[k] * job->share[k];
        mo->m2[k] += m2, mo->n[k]++;
        if (e.arrived && e.cell >= 0)
            entry_push(&job->entries[chunk], &(lp_entry){.cell = e.cell,
                                                         .went_on = e.went_on,
                                                         .m2 = m2 * e.q_cell * e.q_cell,
                                                         .cost = (double)(stats.scatters - scatters)});
    }
    tr_film_add_stats(&job->stats[thread], &stats);
    return LUCENT_OK;
}

/* Photons in a pass of light paths (0: none served). */
static uint64_t pass_photons(const lucent_tracer *tr)
{
    if (!tr->light_paths) return 0;
    double n = tr->render.trace.photons * (double)tr->render.view.width * (double)tr->render.view.height;
    uint64_t per_chunk = (uint64_t)ceil(n / LP_CHUNKS);
    return (per_chunk ? per_chunk : 1) * LP_CHUNKS;
}

/* Adds the pass's connections and each light's moments (emitter_shares), chunk by chunk so that the
 * sums do not depend on the thread count, to the film's light-path sums (film.c). */
static void fold(const lp_job *job, tr_film *f, double *image)
{
    size_t n = (size_t)f->width * (size_t)f->height;
    memset(image, 0, n * 3 * sizeof *image);
    for (int ch = 0; ch < LP_CHUNKS; ch++)
        for (size_t i = 0; i < job->lists[ch].n; i++)
            for (int c = 0; c < 3; c++)
                image[job->lists[ch].items[i].pixel * 3 + (size_t)c] += job->lists[ch].items[i].v[c];
    for (size_t p = 0; p < n; p++) {
        double *a = f->light + p * TR_FILM_ACC, y = 0;
        for (int c = 0; c < 3; c++) {
            double v = image[p * 3 + (size_t)c];
            a[c] += v, a[3 + c] += v * v, y += tr_film_luminance[c] * v;
        }
        a[6] += y * y;
    }
    for (int ch = 0; ch < LP_CHUNKS; ch++)
        for (int i = 0; i < job->tr->light_count; i++)
            f->light_m2[i] += job->moments[ch].m2[i], f->light_n[i] += job->moments[ch].n[i];
    for (int ch = 0; ch < LP_CHUNKS; ch++)
        for (size_t i = 0; i < job->entries[ch].n; i++) {
            const lp_entry *e = &job->entries[ch].items[i];
            f->entry_arrived[e->cell]++;
            if (!e->went_on) continue;
            f->entry_n[e->cell]++, f->entry_m2[e->cell] += e->m2, f->entry_cost[e->cell] += e->cost;
        }
    f->light_passes++;
}

lucent_status tr_light_pass(const lucent_tracer *tr, tr_film *f, lucent_pool *pool, double deadline, bool *cut)
{
    *cut = false;
    uint64_t photons = pass_photons(tr);
    if (!photons) return LUCENT_OK;
    int threads = pool ? lucent_pool_threads(pool) : 1;
    lp_job job = {.tr = tr, .pass = f->light_passes, .per_chunk = photons / LP_CHUNKS, .deadline = deadline};
    emitter_shares(tr, f, job.share);
    strata(&job, tr, photons);
    float *q = malloc(TR_ENTRY_CELLS * sizeof *q);
    job.q = q && entry_probabilities(f, q) ? q : NULL;
    job.entries = calloc(LP_CHUNKS, sizeof *job.entries);
    job.lists = calloc(LP_CHUNKS, sizeof *job.lists);
    job.moments = calloc(LP_CHUNKS, sizeof *job.moments);
    job.stats = calloc((size_t)threads, sizeof *job.stats);
    double *image = malloc((size_t)f->width * (size_t)f->height * 3 * sizeof *image);
    lucent_status s = q && job.entries && job.lists && job.moments && job.stats && image
                          ? LUCENT_OK
                          : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: out of memory");
    if (s == LUCENT_OK) s = lucent_parallel_for(pool, photons, job.per_chunk, photon_chunk, &job);
    for (int ch = 0; s == LUCENT_OK && job.lists && ch < LP_CHUNKS; ch++)
        if (job.lists[ch].failed || job.entries[ch].failed)
            s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: out of memory for light paths");
    *cut = atomic_load(&job.cut);
    if (s == LUCENT_OK && !*cut) fold(&job, f, image); /* a cut pass is dropped whole: unbiased */
    for (int t = 0; job.stats && t < threads; t++) tr_film_add_stats(&f->stats, &job.stats[t]);
    for (int ch = 0; job.lists && ch < LP_CHUNKS; ch++) free(job.lists[ch].items);
    for (int ch = 0; job.entries && ch < LP_CHUNKS; ch++) free(job.entries[ch].items);
    free(job.lists), free(job.entries), free(job.moments), free(job.stats), free(image), free(q);
    return s;
}
