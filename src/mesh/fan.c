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
    v3 p = v3_load(P + 3 * v);
    double big = 0;
    n[0] = n[1] = n[2] = 0;
    for (uint32_t a = 0; a < count; a++) {
        uint32_t j, k;
        mesh_slot_others(m->faces, slot[a], &j, &k);
        v3 x = v3_cross(v3_sub(v3_load(P + 3 * j), p), v3_sub(v3_load(P + 3 * k), p));
        double l2 = v3_dot(x, x);
        if (l2 > big) big = l2, v3_store(x, n);
    }
}

/* One vertex's fan (at most MESH_FAN_MAX slots), walked twice. The first walk reads each slot's
 * next and previous vertices, the edge to the next one (scalar arrays, written and read with the
 * same width so that loads forward) and enters the next vertex in a small open-addressing table
 * (slot + 1; 0 empty). The second pairs each slot's previous vertex with an unused slot's next
 * vertex, one to one, through the table, and adds the slot's term of Max's sum, its second edge
 * being its partner's. Few loops: each loop's exit costs a misprediction per vertex. */
enum { PREFETCH_SLOTS = 16 };                          /* about 3 vertices ahead */
enum { TABLE_BITS = 6, TABLE_SIZE = 1 << TABLE_BITS }; /* at most half full */
typedef struct fan_local {
    uint32_t next[MESH_FAN_MAX], prev[MESH_FAN_MAX];
    double ex[MESH_FAN_MAX], ey[MESH_FAN_MAX], ez[MESH_FAN_MAX], el[MESH_FAN_MAX];
    union {
        uint8_t table[TABLE_SIZE];
        uint64_t words[TABLE_SIZE / 8]; /* cleared word by word: memset would be a call */
    } t;
} fan_local;

static inline uint32_t table_hash(uint32_t u) { return (u * 2654435761u) >> (32 - TABLE_BITS); }

static void first_walk(const lucent_mesh *m, const mesh_adjacency *adj, uint32_t v, fan_local *F)
{
    uint32_t first = adj->start[v], count = adj->start[v + 1] - first;
    const uint32_t *slot = adj->corner + first;
    const double *P = m->positions, *p = P + 3 * (size_t)v;
    for (int i = 0; i < TABLE_SIZE / 8; i++) F->t.words[i] = 0;
    for (uint32_t a = 0; a < count; a++) {
        __builtin_prefetch(P + 3 * (size_t)mesh_prefetch_slot(adj, m->faces, first + a, PREFETCH_SLOTS));
        mesh_slot_others(m->faces, slot[a], F->next + a, F->prev + a);
        const double *q = P + 3 * (size_t)F->next[a];
        F->ex[a] = q[0] - p[0], F->ey[a] = q[1] - p[1], F->ez[a] = q[2] - p[2];
        F->el[a] = F->ex[a] * F->ex[a] + F->ey[a] * F->ey[a] + F->ez[a] * F->ez[a];
        uint32_t h = table_hash(F->next[a]);
        while (F->t.table[h]) h = (h + 1) & (TABLE_SIZE - 1);
        F->t.table[h] = (uint8_t)(a + 1);
    }
}

/* An unused slot whose next vertex is u (marked used), or MESH_UNPAIRED. */
static uint32_t find_partner(const fan_local *F, uint32_t u, uint32_t *used)
{
    uint32_t h = table_hash(u), t;
    while ((t = F->t.table[h]) && (F->next[t - 1] != u || (*used >> (t - 1) & 1))) h = (h + 1) & (TABLE_SIZE - 1);
    if (!t) return MESH_UNPAIRED;
    *used |= 1u << (t - 1);
    return t - 1;
}

/* Pairs and Max's sum (Max 1999) into n; mag is the sum of the terms' squared lengths. Returns
 * whether every slot paired: then every neighbour appears an even number of times, so none lies
 * on a boundary. */
static int second_walk(const double *P, uint32_t count, uint32_t v, const fan_local *F, uint8_t *pair, double n[4])
{
    const double *p = P + 3 * (size_t)v;
    double nx = 0, ny = 0, nz = 0, mag = 0;
    uint32_t used = 0;
    int all = 1;
    for (uint32_t a = 0; a < count; a++) {
        uint32_t b = find_partner(F, F->prev[a], &used);
        double bx, by, bz, bl;
        pair[a] = (uint8_t)b;
        if (b != MESH_UNPAIRED) {
            bx = F->ex[b], by = F->ey[b], bz = F->ez[b], bl = F->el[b];
        } else {
            const double *q = P + 3 * (size_t)F->prev[a];
            bx = q[0] - p[0], by = q[1] - p[1], bz = q[2] - p[2], bl = bx * bx + by * by + bz * bz, all = 0;
        }
        double w = F->el[a] * bl;
        if (!(w > 0)) continue;
        double x = F->ey[a] * bz - F->ez[a] * by, y = F->ez[a] * bx - F->ex[a] * bz, z = F->ex[a] * by - F->ey[a] * bx;
        double iw = 1 / w;
        nx += x * iw, ny += y * iw, nz += z * iw, mag += (x * x + y * y + z * z) * iw * iw;
    }
    n[0] = nx, n[1] = ny, n[2] = nz, n[3] = mag;
    return all;
}

/* The unit normal from Max's sum, or from the largest face where the sum cancels. */
static void store_normal(const lucent_mesh *m, const uint32_t *slot, uint32_t count, uint32_t v, double *n, float *dest)
{
    v3 u = v3_load(n);
    if (!(v3_dot(u, u) > 1e-12 * n[3])) largest_face_normal(m, slot, count, v, n), u = v3_load(n);
    u = v3_normalize(u);
    dest[0] = (float)u.x, dest[1] = (float)u.y, dest[2] = (float)u.z;
}

/* The same for a fan of any size, without pairs (high valence, rare). */
static void max_normal_any(const lucent_mesh *m, const uint32_t *slot, uint32_t count, uint32_t v, float *dest)
{
    const double *P = m->positions;
    v3 p = v3_load(P + 3 * v), sum = {0, 0, 0};
    double mag = 0;
    for (uint32_t a = 0; a < count; a++) {
        uint32_t j, k;
        mesh_slot_others(m->faces, slot[a], &j, &k);
        v3 e1 = v3_sub(v3_load(P + 3 * j), p), e2 = v3_sub(v3_load(P + 3 * k), p);
        double w = v3_dot(e1, e1) * v3_dot(e2, e2);
        if (!(w > 0)) continue;
        v3 x = v3_cross(e1, e2);
        double iw = 1 / w;
        sum = v3_madd(sum, x, iw);
        mag += v3_dot(x, x) * iw * iw;
    }
    double n[4] = {sum.x, sum.y, sum.z, mag};
    store_normal(m, slot, count, v, n, dest);
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
    uint32_t count = adj->start[v + 1] - adj->start[v];
    uint8_t local[MESH_FAN_MAX], *pair = j->out->pair ? j->out->pair + adj->start[v] : local;
    float *normal = j->out->normals + 3 * (size_t)v;
    if (count > MESH_FAN_MAX) {
        max_normal_any(j->mesh, slot, count, v, normal);
        j->out->flags[v] = any_single_slow(j->mesh->faces, slot, count) ? LUCENT_CURVATURE_BOUNDARY : 0;
        for (uint32_t a = 0; j->out->pair && a < count; a++) pair[a] = MESH_UNPAIRED;
        return;
    }
    fan_local F;
    double n[4];
    first_walk(j->mesh, adj, v, &F);
    int closed = second_walk(j->mesh->positions, count, v, &F, pair, n);
    store_normal(j->mesh, slot, count, v, n, normal);
    j->out->flags[v] = !closed && any_single(F.next, F.prev, count) ? LUCENT_CURVATURE_BOUNDARY : 0;
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
