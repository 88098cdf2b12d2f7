/* The importance field that steers the walk (media.c, tr_walk_*): per object a grid of the gradient
 * of ln(fluence) of the light from the lights that have a direction (the environment adds little
 * gradient and is left out), per channel. A camera path's vertex at x finds light in proportion to
 * the fluence there, so the walk leans up its gradient (the exponential transform with a local
 * decay rate kappa = |grad ln phi| and direction u = grad / |grad|).
 *
 * The fluence comes from a light-tracing pre-pass with a fixed seed (a deterministic function of the
 * scene, whatever the thread count: photons in fixed chunks, each with its own tally summed in chunk
 * order): photons from each directional, point and sphere light enter the objects through their
 * boundaries (power weights: the BSDF's radiance scaling removed) and walk analogously in one
 * channel each; every collision adds w / sigma_t to its cell (the collision estimator of fluence).
 * Cells are divided by the share of their volume inside the object (counted by ray parity at
 * 2 x 2 x 2 points, a ray per row of them), smoothed over 3 x 3 x 3 cells, and differenced. Under a time
 * limit the pre-pass stops starting photon chunks and objects at its deadline (a quarter of the limit):
 * the objects left without a field walk unguided. The field only shapes sampling
 * densities: the estimate is unbiased whatever it holds. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/dist.h"
#include "trace/field.h"

enum { FIELD_CELLS = 16, CHUNKS = 64, MIN_PHOTONS = 1 << 16, MAX_PHOTONS = 1 << 20, MAX_COLLISIONS = 256 };
#define FIELD_SEED 0x6c7563656e74ull /* "lucent" */

typedef struct field_job {
    const lucent_tracer *tr;
    double *tally; /* [CHUNKS][objects][cells][3] */
    size_t per_chunk;
    double deadline; /* lucent_clock_seconds() after which no chunk starts (0: none) */
    lucent_progress *progress;
} field_job;

static size_t cell_count(const tr_field *f) { return (size_t)f->n[0] * (size_t)f->n[1] * (size_t)f->n[2]; }

/* The cell holding x, or -1 outside the grid. */
static long cell_of(const tr_field *f, v3 x)
{
    double p[3] = {x.x, x.y, x.z};
    long idx = 0, stride = 1;
    for (int a = 0; a < 3; a++) {
        long i = (long)floor((p[a] - f->lo[a]) / f->cell);
        if (i < 0 || i >= f->n[a]) return -1;
        idx += i * stride;
        stride *= f->n[a];
    }
    return idx;
}

static void setup_grid(const lucent_mesh *m, tr_field *f)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, ext = 0;
    for (size_t v = 0; v < m->vertex_count; v++)
        for (int a = 0; a < 3; a++)
            lo[a] = fmin(lo[a], m->positions[3 * v + a]), hi[a] = fmax(hi[a], m->positions[3 * v + a]);
    for (int a = 0; a < 3; a++) ext = fmax(ext, hi[a] - lo[a]);
    f->cell = fmax(ext, 1e-6) / (FIELD_CELLS - 2);
    for (int a = 0; a < 3; a++) {
        f->n[a] = (int)ceil((hi[a] - lo[a]) / f->cell) + 2;
        f->lo[a] = 0.5 * (lo[a] + hi[a]) - 0.5 * f->n[a] * f->cell;
    }
}

/* ---- photons ---- */

typedef struct photon {
    v3 p, d;
    double w;
    int medium, channel;
} photon;

/* Emits a photon from light l toward the scene's bounding sphere (the tracer's emit centre and radius). */
static bool emit(const lucent_tracer *tr, const tr_light *l, lucent_rng *rng, photon *ph)
{
    double u1 = lucent_rng_uniform(rng), u2 = lucent_rng_uniform(rng);
    if (l->type == LUCENT_LIGHT_DIRECTIONAL) {
        ph->p = tr_disc_start(v3_load(tr->emit_centre), tr->emit_radius, l->toward, u1, u2);
        ph->d = v3_neg(l->toward);
    } else if (l->type == LUCENT_LIGHT_POINT || l->type == LUCENT_LIGHT_SPHERE) {
        ph->p = l->position;
        ph->d = lucent_around(v3_make(0, 0, 1), 1.0 - 2.0 * u1, 2.0 * M_PI * u2);
        if (l->type == LUCENT_LIGHT_SPHERE) ph->p = v3_madd(ph->p, ph->d, l->radius * (1.0 + 1e-9));
    } else {
        return false;
    }
    ph->w = 1.0, ph->medium = -1;
    return true;
}

static void at_surface(const lucent_tracer *tr, photon *ph, const tr_hit *h, lucent_rng *rng)
{
    v3 y = v3_madd(ph->p, ph->d, h->t);
    tr_bsdf_sample bs;
    double u0 = lucent_rng_uniform(rng), u1 = lucent_rng_uniform(rng), u2 = lucent_rng_uniform(rng);
    bool inside = v3_dot(ph->d, h->n) > 0;
    if (!tr_bsdf_sample_dir(&tr->objects[h->object].boundary, h->n, v3_neg(ph->d), u0, u1, u2, &bs)) {
        ph->w = 0;
        return;
    }
    ph->w *= bs.weight / bs.scale; /* power, not radiance */
    if (bs.transmit) ph->medium = inside ? -1 : h->object;
    ph->p = v3_madd(y, h->n, v3_dot(bs.i, h->n) > 0 ? tr->eps : -tr->eps);
    ph->d = bs.i;
}

static void trace_photon(const lucent_tracer *tr, const tr_field *fields, double *tally, photon *ph, lucent_rng *rng)
{
    int c = ph->channel, collisions = 0;
    for (int events = 0; ph->w > 0 && events < 4 * MAX_COLLISIONS && collisions < MAX_COLLISIONS; events++) {
        tr_hit h;
        bool hit = tr_intersect(tr->geometry, ph->p, ph->d, 0.0, INFINITY, &h);
        if (!hit) return;
        if (ph->medium < 0) {
            at_surface(tr, ph, &h, rng);
            continue;
        }
        const tr_object *ob = &tr->objects[ph->medium];
        double t = -log(1.0 - lucent_rng_uniform(rng)) / ob->sigma_t[c];
        if (t >= h.t) {
            at_surface(tr, ph, &h, rng);
            continue;
        }
        ph->p = v3_madd(ph->p, ph->d, t);
        long cell = cell_of(&fields[ph->medium], ph->p);
        if (cell >= 0) tally[(fields[ph->medium].offset + (size_t)cell) * 3 + (size_t)c] += ph->w / ob->sigma_t[c];
        ph->w *= ob->sigma_s[c] / ob->sigma_t[c];
        ph->d = lucent_hg_sample(ph->d, ob->g[c], lucent_rng_uniform(rng), lucent_rng_uniform(rng));
        collisions++;
        if (ph->w < 0.05) ph->w = lucent_rng_uniform(rng) < 0.25 ? ph->w * 4.0 : 0.0;
    }
}

static const tr_light *pick_emitter(const lucent_tracer *tr, double u)
{
    double total = 0, acc = 0;
    for (int i = 0; i < tr->light_count; i++)
        if (tr->lights[i].type != LUCENT_LIGHT_ENVIRONMENT) total += tr->lights[i].select;
    for (int i = 0; i < tr->light_count; i++) {
        if (tr->lights[i].type == LUCENT_LIGHT_ENVIRONMENT) continue;
        acc += tr->lights[i].select;
        if (u * total < acc) return &tr->lights[i];
    }
    return tr->walk_target;
}

static lucent_status photon_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)thread;
    field_job *job = ctx;
    const lucent_tracer *tr = job->tr;
    double *tally = job->tally + chunk * job->per_chunk;
    if (job->deadline > 0 && lucent_clock_seconds() >= job->deadline) return LUCENT_OK; /* the run's time limit */
    lucent_rng rng;
    lucent_rng_init(FIELD_SEED, chunk, &rng);
    for (uint64_t i = begin; i < end; i++) {
        photon ph = {.channel = (int)(i % 3)};
        if (emit(tr, pick_emitter(tr, lucent_rng_uniform(&rng)), &rng, &ph))
            trace_photon(tr, tr->fields, tally, &ph, &rng);
    }
    lucent_progress_add(job->progress, 1);
    return LUCENT_OK;
}

/* The share of each cell inside its object, from 2 x 2 x 2 points per cell. The points of one row of the
 * grid (2 per cell along x) lie on one ray from the grid's low face, which is outside the object: a point is
 * inside when the ray crossed the object's surface an odd number of times before it (mesh holes make it
 * approximate, which only blurs the guidance). The ray ends at the grid's far face, so it meets only the
 * surfaces within the object's box: a row costs a few queries, whatever the rest of the scene holds (200
 * spheres in a line took 52 s for 8 queries per point, each walking every surface to the scene's end). */
void tr_field_inside_share(const lucent_tracer *tr, int object, const tr_field *f, float *dest)
{
    v3 d = v3_normalize(v3_make(1.0, 0.0123, 0.0071)); /* off the grid's axes: no grazing of aligned edges */
    double reach = f->n[0] * f->cell / d.x;
    enum { MAX_CROSSINGS = 256 };
    for (int k = 0; k < f->n[2]; k++)
        for (int j = 0; j < f->n[1]; j++) {
            float *row = dest + ((size_t)k * f->n[1] + j) * f->n[0];
            for (int i = 0; i < f->n[0]; i++) row[i] = 0;
            for (int s = 0; s < 4; s++) {
                v3 start = v3_make(f->lo[0], f->lo[1] + (j + 0.25 + 0.5 * (s & 1)) * f->cell,
                                   f->lo[2] + (k + 0.25 + 0.5 * (s >> 1)) * f->cell);
                double cross[MAX_CROSSINGS], t = 0;
                int n = 0;
                for (int q = 0; q < MAX_CROSSINGS && t < reach; q++) {
                    tr_hit h;
                    if (!tr_intersect(tr->geometry, v3_madd(start, d, t), d, 0.0, reach - t, &h)) break;
                    if (h.object == object) cross[n++] = t + h.t;
                    t += h.t + tr->eps;
                }
                for (int i = 0, c = 0; i < f->n[0]; i++)
                    for (int sx = 0; sx < 2; sx++) {
                        double ts = (i + 0.25 + 0.5 * sx) * f->cell / d.x;
                        while (c < n && cross[c] < ts) c++;
                        row[i] += (float)((c & 1) / 8.0);
                    }
            }
        }
}

static double at(const tr_field *f, const double *phi, int i, int j, int k, int c)
{
    i = i < 0 ? 0 : i >= f->n[0] ? f->n[0] - 1 : i;
    j = j < 0 ? 0 : j >= f->n[1] ? f->n[1] - 1 : j;
    k = k < 0 ? 0 : k >= f->n[2] ? f->n[2] - 1 : k;
    return phi[(((size_t)k * f->n[1] + j) * f->n[0] + i) * 3 + c];
}

/* Fluence per unit inside volume, smoothed over 3 x 3 x 3 cells (weighted by the inside share). */
static void smooth(const tr_field *f, const double *tally, const float *in, double *phi)
{
    for (int k = 0; k < f->n[2]; k++)
        for (int j = 0; j < f->n[1]; j++)
            for (int i = 0; i < f->n[0]; i++)
                for (int c = 0; c < 3; c++) {
                    double sum = 0, vol = 0;
                    for (int dk = -1; dk <= 1; dk++)
                        for (int dj = -1; dj <= 1; dj++)
                            for (int di = -1; di <= 1; di++) {
                                int ii = i + di, jj = j + dj, kk = k + dk;
                                if (ii < 0 || jj < 0 || kk < 0 || ii >= f->n[0] || jj >= f->n[1] || kk >= f->n[2])
                                    continue;
                                size_t q = ((size_t)kk * f->n[1] + jj) * f->n[0] + ii;
                                sum += tally[q * 3 + c], vol += in[q];
                            }
                    phi[(((size_t)k * f->n[1] + j) * f->n[0] + i) * 3 + c] = vol > 0.5 ? sum / vol : 0.0;
                }
}

/* grad ln phi by central differences (one-sided where a neighbour has no fluence). */
static void gradient(tr_field *f, const double *phi)
{
    int step[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int k = 0; k < f->n[2]; k++)
        for (int j = 0; j < f->n[1]; j++)
            for (int i = 0; i < f->n[0]; i++)
                for (int c = 0; c < 3; c++) {
                    float *g = f->grad + ((((size_t)k * f->n[1] + j) * f->n[0] + i) * 3 + c) * 3;
                    double p0 = at(f, phi, i, j, k, c);
                    for (int a = 0; a < 3; a++) {
                        int *s = step[a];
                        double pp = at(f, phi, i + s[0], j + s[1], k + s[2], c);
                        double pm = at(f, phi, i - s[0], j - s[1], k - s[2], c);
                        double lp = pp > 0 ? log(pp) : NAN, lm = pm > 0 ? log(pm) : NAN, l0 = p0 > 0 ? log(p0) : NAN;
                        double d = isfinite(lp) && isfinite(lm)   ? 0.5 * (lp - lm)
                                   : isfinite(lp) && isfinite(l0) ? lp - l0
                                   : isfinite(lm) && isfinite(l0) ? l0 - lm
                                                                  : 0.0;
                        g[a] = (float)(d / f->cell);
                    }
                }
}

typedef struct finish_job {
    const lucent_tracer *tr;
    const double *tally;
    double deadline;
    lucent_progress *progress;
} finish_job;

/* One object's field from the summed tallies; past the deadline it is left without one (no guidance). */
static lucent_status finish_object(void *ctx, uint64_t o, uint64_t begin, uint64_t end, int thread)
{
    (void)begin, (void)end, (void)thread;
    const finish_job *job = ctx;
    const lucent_tracer *tr = job->tr;
    if (job->deadline > 0 && lucent_clock_seconds() >= job->deadline) return LUCENT_OK;
    tr_field *f = &tr->fields[o];
    size_t n = cell_count(f);
    float *in = malloc(n * sizeof *in);
    double *phi = malloc(n * 3 * sizeof *phi);
    float *grad = malloc(n * 9 * sizeof *grad);
    if (!in || !phi || !grad) {
        free(in), free(phi), free(grad);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: out of memory for the guiding field");
    }
    tr_field_inside_share(tr, (int)o, f, in);
    smooth(f, job->tally + f->offset * 3, in, phi);
    f->grad = grad;
    gradient(f, phi);
    free(in), free(phi);
    lucent_progress_add(job->progress, 1);
    return LUCENT_OK;
}

lucent_status tr_field_build(lucent_tracer *tr, lucent_pool *pool, double deadline)
{
    if (!tr->walk_target || tr->object_count == 0) return LUCENT_OK;
    tr->fields = calloc((size_t)tr->object_count, sizeof *tr->fields);
    if (!tr->fields) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: out of memory");
    size_t cells = 0;
    for (int o = 0; o < tr->object_count; o++) {
        setup_grid(tr->scene->objects[tr->objects[o].scene_index].mesh, &tr->fields[o]);
        tr->fields[o].offset = cells;
        cells += cell_count(&tr->fields[o]);
    }
    field_job job = {.tr = tr, .per_chunk = cells * 3, .deadline = deadline};
    job.tally = calloc(CHUNKS * job.per_chunk, sizeof *job.tally);
    if (!job.tally) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: out of memory for the guiding field");
    /* 64 photons per pixel, within [2^16, 2^20]: a function of the scene alone */
    uint64_t pixels = (uint64_t)tr->render.view.width * (uint64_t)tr->render.view.height;
    uint64_t photons = pixels * 64 < MIN_PHOTONS ? MIN_PHOTONS : pixels * 64 > MAX_PHOTONS ? MAX_PHOTONS : pixels * 64;
    photons = (photons + CHUNKS - 1) / CHUNKS * CHUNKS;
    /* the bar counts the photons' chunks, then the objects */
    job.progress = lucent_progress_begin("guiding field", CHUNKS + (uint64_t)tr->object_count);
    lucent_progress_set_deadline(job.progress, deadline > 0 ? deadline - lucent_clock_seconds() : 0);
    /* MPI ranks share the chunks (lucent/dist.h); every rank needs the whole field, so each gets the
     * others' chunk tallies, exactly: the owner's values against -inf under a maximum. (The parts of
     * --part cannot talk: each builds the whole field, as the ranks inside a part share it.) */
    lucent_share share = {(uint64_t)lucent_dist_rank(), (uint64_t)lucent_dist_size()};
    lucent_status s = lucent_parallel_for_share(pool, photons, photons / CHUNKS, photon_chunk, &job, share);
    if (share.stride > 1) {
        for (uint64_t ch = 0; s == LUCENT_OK && ch < CHUNKS; ch++)
            if (ch % share.stride != share.offset)
                for (size_t i = 0; i < job.per_chunk; i++) job.tally[ch * job.per_chunk + i] = -INFINITY;
        s = lucent_dist_max_f64(s, job.tally, CHUNKS * job.per_chunk);
    }
    for (int ch = 1; s == LUCENT_OK && ch < CHUNKS; ch++)
        for (size_t i = 0; i < job.per_chunk; i++) job.tally[i] += job.tally[ch * job.per_chunk + i];
    finish_job fj = {tr, job.tally, deadline, job.progress};
    if (s == LUCENT_OK) s = lucent_parallel_for(pool, (uint64_t)tr->object_count, 1, finish_object, &fj);
    lucent_progress_end(job.progress);
    free(job.tally);
    return s;
}

void tr_field_destroy(lucent_tracer *tr)
{
    for (int o = 0; tr->fields && o < tr->object_count; o++) free(tr->fields[o].grad);
    free(tr->fields);
    tr->fields = NULL;
}

void tr_field_lookup(const lucent_tracer *tr, int object, v3 x, tr_transform *dest)
{
    const tr_object *ob = &tr->objects[object];
    memset(dest, 0, sizeof *dest);
    if (!tr->fields || !tr->fields[object].grad || ob->boundary.kind == TR_BOUNDARY_MATCHED) return;
    const tr_field *f = &tr->fields[object];
    long cell = cell_of(f, x);
    if (cell < 0) return;
    const float *g = f->grad + (size_t)cell * 9;
    for (int c = 0; c < 3; c++) {
        v3 gv = v3_make(g[3 * c], g[3 * c + 1], g[3 * c + 2]);
        double len = v3_length(gv);
        if (!(len > 0)) continue;
        dest->u[c] = v3_scale(gv, 1.0 / len);
        dest->b[c] = fmin(tr->walk_strength * len / ob->sigma_t[c], TR_WALK_B_MAX);
    }
}
