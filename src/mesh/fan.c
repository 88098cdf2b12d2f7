/* One walk around every vertex's fan of faces, shared by the curvature estimators:
 * - vertex normals with Max's weights (Max 1999, "Weights for computing vertex normals from
 *   facet normals": each corner adds (e1 x e2) / (|e1|^2 |e2|^2), exact for a sphere). The
 *   estimators difference normals, so this accuracy matters there. Where the weighted sum
 *   cancels (opposite sheets at a non-manifold vertex), the largest incident face's normal;
 * - boundary flags: v is on a boundary when some neighbour u is in exactly one of v's faces;
 * - the pairing of slots across shared edges (mesh_fan.pair). */
#include "mesh/internal.h"

typedef struct fan_job {
    const lucent_mesh *mesh;
    const mesh_adjacency *adj;
    const mesh_fan *out;
} fan_job;

/* The normal of v's largest incident face (twice its area, unnormalised). */
static void largest_face_normal(const lucent_mesh *m, const uint32_t *slot, uint32_t count, uint32_t v, double *n)
{
    const double *P = m->positions;
    double big = 0, e1[3], e2[3], x[3];
    n[0] = n[1] = n[2] = 0;
    for (uint32_t a = 0; a < count; a++) {
        uint32_t j, k;
        mesh_slot_others(m->faces, slot[a], &j, &k);
        v3_sub(P + 3 * j, P + 3 * v, e1), v3_sub(P + 3 * k, P + 3 * v, e2);
        v3_cross(e1, e2, x);
        double l2 = v3_dot(x, x);
        if (l2 > big) big = l2, n[0] = x[0], n[1] = x[1], n[2] = x[2];
    }
}

/* Max's weighted sum over the slots, each edge from v computed once: a paired slot's
 * previous vertex is its partner's next. Falls back to the largest face where it cancels.
 * (Edges in scalar arrays: written and read with the same width, so loads forward.) */
static void max_normal(const lucent_mesh *m, const uint32_t *slot, uint32_t count, uint32_t v,
                       const uint32_t *next, const uint32_t *prev, const uint8_t *pair, float *dest)
{
    const double *P = m->positions, px = P[3 * v], py = P[3 * v + 1], pz = P[3 * v + 2];
    double ex[MESH_FAN_MAX], ey[MESH_FAN_MAX], ez[MESH_FAN_MAX], el[MESH_FAN_MAX];
    double nx = 0, ny = 0, nz = 0, mag = 0;
    for (uint32_t a = 0; a < count; a++) {
        const double *q = P + 3 * (size_t)next[a];
        ex[a] = q[0] - px, ey[a] = q[1] - py, ez[a] = q[2] - pz;
        el[a] = ex[a] * ex[a] + ey[a] * ey[a] + ez[a] * ez[a];
    }
    for (uint32_t a = 0; a < count; a++) {
        double bx, by, bz, bl;
        if (pair[a] != MESH_UNPAIRED) {
            bx = ex[pair[a]], by = ey[pair[a]], bz = ez[pair[a]], bl = el[pair[a]];
        } else {
            const double *q = P + 3 * (size_t)prev[a];
            bx = q[0] - px, by = q[1] - py, bz = q[2] - pz, bl = bx * bx + by * by + bz * bz;
        }
        double w = el[a] * bl;
        if (!(w > 0)) continue;
        double x = ey[a] * bz - ez[a] * by, y = ez[a] * bx - ex[a] * bz, z = ex[a] * by - ey[a] * bx;
        double iw = 1 / w;
        nx += x * iw, ny += y * iw, nz += z * iw, mag += (x * x + y * y + z * z) * iw * iw;
    }
    double n[3] = {nx, ny, nz};
    if (!(v3_dot(n, n) > 1e-12 * mag)) largest_face_normal(m, slot, count, v, n);
    v3_normalize(n);
    for (int i = 0; i < 3; i++) dest[i] = (float)n[i];
}

/* The same for a fan of any size, without pairs (high valence, rare). */
static void max_normal_any(const lucent_mesh *m, const uint32_t *slot, uint32_t count, uint32_t v, float *dest)
{
    const double *P = m->positions, *p = P + 3 * v;
    double n[3] = {0, 0, 0}, mag = 0, e1[3], e2[3], x[3];
    for (uint32_t a = 0; a < count; a++) {
        uint32_t j, k;
        mesh_slot_others(m->faces, slot[a], &j, &k);
        v3_sub(P + 3 * j, p, e1), v3_sub(P + 3 * k, p, e2);
        double w = v3_dot(e1, e1) * v3_dot(e2, e2);
        if (!(w > 0)) continue;
        v3_cross(e1, e2, x);
        double iw = 1 / w;
        for (int i = 0; i < 3; i++) n[i] += x[i] * iw;
        mag += v3_dot(x, x) * iw * iw;
    }
    if (!(v3_dot(n, n) > 1e-12 * mag)) largest_face_normal(m, slot, count, v, n);
    v3_normalize(n);
    for (int i = 0; i < 3; i++) dest[i] = (float)n[i];
}

/* Pairs each slot's previous vertex with an unused slot's next vertex, one to one, through a
 * small open-addressing table of the next vertices (slot + 1; 0 empty). When every slot pairs,
 * every neighbour appears an even number of times, so none lies on a boundary. */
static int pair_slots(const uint32_t *next, const uint32_t *prev, uint32_t count, uint8_t *pair)
{
    enum { BITS = 7, SIZE = 1 << BITS }; /* count <= 32: at most a quarter full */
    uint8_t table[SIZE] = {0};
    uint32_t used = 0;
    int all = 1;
    for (uint32_t b = 0; b < count; b++) {
        uint32_t h = (next[b] * 2654435761u) >> (32 - BITS);
        while (table[h]) h = (h + 1) & (SIZE - 1);
        table[h] = (uint8_t)(b + 1);
    }
    for (uint32_t a = 0; a < count; a++) {
        uint32_t h = (prev[a] * 2654435761u) >> (32 - BITS), t;
        while ((t = table[h]) && (next[t - 1] != prev[a] || (used >> (t - 1) & 1))) h = (h + 1) & (SIZE - 1);
        if (t) used |= 1u << (t - 1), pair[a] = (uint8_t)(t - 1);
        else all = 0, pair[a] = MESH_UNPAIRED;
    }
    return all;
}

/* Exact test: some neighbour appears once among v's faces. */
static int any_single(const uint32_t *next, const uint32_t *prev, uint32_t count)
{
    for (uint32_t a = 0; a < 2 * count; a++) {
        uint32_t u = a < count ? next[a] : prev[a - count], seen = 0;
        for (uint32_t b = 0; b < count && seen < 2; b++) seen += (next[b] == u) + (prev[b] == u);
        if (seen == 1) return 1;
    }
    return 0;
}

/* The same for a fan of any size, reading the faces again (high valence, rare). */
static int any_single_slow(const uint32_t *faces, const uint32_t *slot, uint32_t count)
{
    for (uint32_t a = 0; a < 2 * count; a++) {
        uint32_t u, w, seen = 0;
        mesh_slot_others(faces, slot[a % count], &u, &w);
        if (a >= count) u = w;
        for (uint32_t b = 0; b < count && seen < 2; b++) {
            uint32_t x, y;
            mesh_slot_others(faces, slot[b], &x, &y);
            seen += (x == u) + (y == u);
        }
        if (seen == 1) return 1;
    }
    return 0;
}

/* Normal, boundary flag and (when wanted) slot pairs of vertex v. */
static void fan_vertex(const fan_job *j, uint32_t v)
{
    const mesh_adjacency *adj = j->adj;
    const uint32_t *slot = adj->corner + adj->start[v];
    uint32_t count = adj->start[v + 1] - adj->start[v], next[MESH_FAN_MAX], prev[MESH_FAN_MAX];
    uint8_t *out_pair = j->out->pair ? j->out->pair + adj->start[v] : NULL, pair[MESH_FAN_MAX];
    float *normal = j->out->normals + 3 * (size_t)v;
    if (count > MESH_FAN_MAX) {
        max_normal_any(j->mesh, slot, count, v, normal);
        j->out->flags[v] = any_single_slow(j->mesh->faces, slot, count) ? LUCENT_CURVATURE_BOUNDARY : 0;
        for (uint32_t a = 0; out_pair && a < count; a++) out_pair[a] = MESH_UNPAIRED;
        return;
    }
    for (uint32_t a = 0; a < count; a++) mesh_slot_others(j->mesh->faces, slot[a], next + a, prev + a);
    int closed = pair_slots(next, prev, count, pair);
    j->out->flags[v] = !closed && any_single(next, prev, count) ? LUCENT_CURVATURE_BOUNDARY : 0;
    max_normal(j->mesh, slot, count, v, next, prev, pair, normal);
    for (uint32_t a = 0; out_pair && a < count; a++) out_pair[a] = pair[a];
}

static lucent_status fan_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)thread;
    const fan_job *j = ctx;
    for (uint64_t v = begin; v < end; v++) fan_vertex(j, (uint32_t)v);
    return LUCENT_OK;
}

lucent_status mesh_fan_compute(const lucent_mesh *mesh, const mesh_adjacency *adj, lucent_pool *pool,
                               const mesh_fan *dest)
{
    fan_job job = {mesh, adj, dest};
    return lucent_parallel_for(pool, mesh->vertex_count, 4096, fan_chunk, &job);
}
