/* A lattice of distances to the nearest surface over a dense object, filled as walks reach it.
 *
 * The distance to the nearest surface, D(x), is 1-Lipschitz: |D(x) - D(v)| <= |x - v|. So every
 * lattice vertex v whose distance is known gives the lower bound D(v) - |x - v| at any point x, and
 * the largest of those over the eight corners of x's cell is one too: a sphere about x that holds no
 * surface, the safe sphere of integrator.c, for eight lookups instead of a BVH search. A vertex's
 * distance comes from one distance query (tr_distance_bound, capped at the lattice's reach) the
 * first time a walk needs it; the value depends only on the vertex, so which thread fills it, and
 * when, changes nothing (the images stay bit for bit the same on any thread count). Values are
 * stored as floats rounded down (still lower bounds). Points outside the lattice get 0 (no sphere).
 * Memory: calloc'd, so only the pages of the cells walks visit are ever touched; stored in bricks of
 * 4 x 4 x 4 vertices (256 bytes), so that a cell's eight corners mostly share two cache lines instead
 * of lying on four (a lookup waits on its loads: 58% of its own time on the dragon before). */
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "trace/internal.h"

/* 128 MB of floats at most (allocated zeroed: only the pages walks reach are touched): at marble's
 * mean free path, a bounding box of 2.5e7 mm^3 (40 x 30 x 20 cm) keeps the spacing; a larger object's
 * spacing grows to fit, and its spheres are looser by the larger cell diagonal. */
enum { DEPTH_MAX_VERTICES = 1 << 25 };

struct tr_depth {
    double lo[3], h, cap;
    int n[3];            /* vertices per axis */
    size_t bricks[2];    /* bricks along x, and in an xy layer */
    _Atomic uint32_t *d; /* per vertex: 0 unknown, else the float bits of the distance (-1: none) */
};

tr_depth *tr_depth_create(const double lo[3], const double hi[3], double h, double cap)
{
    double size[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
    if (!(h > 0 && isfinite(h) && isfinite(size[0] + size[1] + size[2]) && cap > 0)) return NULL;
    for (;;) { /* counted in double, whole bricks: no overflow */
        double count = 1;
        for (int i = 0; i < 3; i++) count *= 4 * ceil((ceil(size[i] / h) + 2) / 4);
        if (count <= DEPTH_MAX_VERTICES) break;
        h *= 1.25;
    }
    tr_depth *z = calloc(1, sizeof *z);
    if (!z) return NULL;
    for (int i = 0; i < 3; i++) z->n[i] = (int)(ceil(size[i] / h) + 2);
    z->h = h, z->cap = cap;
    for (int i = 0; i < 3; i++) z->lo[i] = lo[i] - 0.5 * h;
    size_t nb[3] = {(size_t)(z->n[0] + 3) / 4, (size_t)(z->n[1] + 3) / 4, (size_t)(z->n[2] + 3) / 4};
    z->bricks[0] = nb[0], z->bricks[1] = nb[0] * nb[1];
    z->d = calloc(z->bricks[1] * nb[2] * 64, sizeof *z->d);
    if (!z->d) {
        free(z);
        return NULL;
    }
    return z;
}

void tr_depth_destroy(tr_depth *z)
{
    if (!z) return;
    free((void *)z->d);
    free(z);
}

/* Where vertex (i, j, k) is stored: its brick, then its place in the brick (x fastest). */
static size_t vertex_slot(const tr_depth *z, int i, int j, int k)
{
    size_t brick = ((size_t)(k >> 2) * z->bricks[1] + (size_t)(j >> 2) * z->bricks[0] + (size_t)(i >> 2));
    return brick * 64 + (size_t)((k & 3) << 4 | (j & 3) << 2 | (i & 3));
}

/* Fills vertex (i, j, k) with a query (its distance rounded down to a float); its stored bits. */
static uint32_t vertex_fill(const tr_depth *z, const tr_geometry *g, int i, int j, int k)
{
    v3 v = v3_make(z->lo[0] + i * z->h, z->lo[1] + j * z->h, z->lo[2] + k * z->h);
    double d = tr_distance_bound(g, v, z->cap, NULL);
    float f = (float)d;
    if ((double)f > d) f = nextafterf(f, 0.0f);
    if (!(f > 0)) f = -1.0f;
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    atomic_store_explicit(z->d + vertex_slot(z, i, j, k), bits, memory_order_relaxed);
    return bits;
}

static double lattice_bound(const tr_depth *z, const tr_geometry *g, v3 x, bool fill)
{
    double u[3] = {(x.x - z->lo[0]) / z->h, (x.y - z->lo[1]) / z->h, (x.z - z->lo[2]) / z->h}, f[3];
    int c[3];
    for (int a = 0; a < 3; a++) {
        if (!(u[a] >= 0 && u[a] < z->n[a] - 1)) return 0.0;
        c[a] = (int)u[a], f[a] = u[a] - c[a];
    }
    uint32_t bits[8]; /* the eight loads first, so that they wait together */
    for (int corner = 0; corner < 8; corner++)
        bits[corner] = atomic_load_explicit(
            z->d + vertex_slot(z, c[0] + (corner & 1), c[1] + (corner >> 1 & 1), c[2] + (corner >> 2)),
            memory_order_relaxed);
    /* the best of D(v) - |x - v| over the corners; the square root only for a corner that improves it */
    double best = 0.0;
    for (int corner = 0; corner < 8; corner++) {
        int di = corner & 1, dj = corner >> 1 & 1, dk = corner >> 2;
        double ex = f[0] - di, ey = f[1] - dj, ez = f[2] - dk, r2 = (ex * ex + ey * ey + ez * ez) * z->h * z->h;
        if (!bits[corner]) {
            if (!fill) continue;
            bits[corner] = vertex_fill(z, g, c[0] + di, c[1] + dj, c[2] + dk);
        }
        float df;
        memcpy(&df, &bits[corner], sizeof df);
        double d = df, m = d - best;
        if (m > 0 && m * m > r2) best = d - sqrt(r2);
    }
    return best;
}

double tr_depth_bound(const tr_depth *z, const tr_geometry *g, v3 x) { return lattice_bound(z, g, x, true); }

double tr_depth_known_bound(const tr_depth *z, v3 x) { return lattice_bound(z, NULL, x, false); }

/* Sphere tracing (Hart 1996) through the known vertices: each step is the lattice's bound at the
 * point reached, less the margin, so the ray from x meets no surface before the t returned. It stops
 * once past t_stop, after FREE_RUN_STEPS steps, or once a step would be below FREE_RUN_SMALL of the
 * spacing (within a cell diagonal of a surface the bound is mostly 0). */
#define FREE_RUN_STEPS 32
#define FREE_RUN_SMALL 0.05 /* of the spacing: 0.1 mean free path at the spacing of 2 */

double tr_depth_free_run(const tr_depth *z, v3 x, v3 w, double t, double t_stop, double margin)
{
    double small = FREE_RUN_SMALL * z->h;
    for (int i = 0; i < FREE_RUN_STEPS && t <= t_stop; i++) {
        double r = tr_depth_known_bound(z, v3_madd(x, w, t)) - margin;
        if (!(r > small)) break;
        t += r;
    }
    return t;
}

/* Spacing and reach in mean free paths of the object's least sigma_t: on the dragon in marble, a
 * spacing of 1.5 and of 2 gave the same time to 5% (one seed each, docs/trace.md). */
#define DEPTH_SPACING_MFP 2.0
#define DEPTH_REACH_MFP 8.0 /* a query that finds nothing nearer (a deep vertex) costs more the further it looks */

lucent_status tr_depth_setup(lucent_tracer *tr)
{
    if (tr->desc.plain_flights) return LUCENT_OK;
    for (int o = 0; o < tr->object_count; o++) {
        tr_object *ob = &tr->objects[o];
        const lucent_mesh *m = tr->scene->objects[ob->scene_index].mesh;
        if (!ob->dense || !m || !m->vertex_count) continue;
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (size_t v = 0; v < m->vertex_count; v++)
            for (int a = 0; a < 3; a++) {
                lo[a] = fmin(lo[a], m->positions[3 * v + a]);
                hi[a] = fmax(hi[a], m->positions[3 * v + a]);
            }
        double mfp = 1.0 / ob->sigma_t_min, h = DEPTH_SPACING_MFP * mfp;
        ob->depth = tr_depth_create(lo, hi, h, DEPTH_REACH_MFP * mfp + sqrt(3.0) * h);
        if (!ob->depth)
            return lucent_error(LUCENT_ERR_OUT_OF_MEMORY,
                                "trace: objects[%d]: cannot make its depth lattice (out of memory)", ob->scene_index);
    }
    return LUCENT_OK;
}
