/* Loop subdivision (C. Loop, "Smooth Subdivision Surfaces Based on Triangles", MS thesis, University
 * of Utah, 1987): every triangle becomes four; new edge vertices and moved old vertices take the
 * masks below. Boundary edges and vertices follow the boundary curve's cubic B-spline masks (Hoppe
 * et al. 1994); vertices on non-manifold edges or on more than one boundary stay where they are. */
#include <stdlib.h>
#include <string.h>

#include "mesh/internal.h"

/* A half-edge: the edge (lo, hi) of face he / 3, corner he % 3 (from corner k to k + 1). */
typedef struct half_edge {
    uint64_t key; /* lo << 32 | hi */
    uint32_t he;
} half_edge;

typedef struct edge_table {
    half_edge *h;    /* 3F half-edges sorted by key */
    uint32_t *edge;  /* 3F: the edge id of each half-edge (indexed by he) */
    uint32_t *first; /* E + 1: the edge's half-edges are h[first[e] .. first[e + 1]) */
    size_t count;    /* E */
} edge_table;

static int cmp_half_edge(const void *a, const void *b)
{
    const half_edge *x = a, *y = b;
    if (x->key != y->key) return x->key < y->key ? -1 : 1;
    return x->he < y->he ? -1 : x->he > y->he;
}

static void edge_table_free(edge_table *t)
{
    free(t->h), free(t->edge), free(t->first);
    memset(t, 0, sizeof *t);
}

static lucent_status edge_table_build(const lucent_mesh *m, edge_table *t)
{
    size_t n = 3 * m->face_count;
    t->h = malloc((n + 1) * sizeof *t->h);
    t->edge = malloc((n + 1) * sizeof *t->edge);
    t->first = malloc((n + 2) * sizeof *t->first);
    if (!t->h || !t->edge || !t->first)
        return edge_table_free(t), lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (size_t i = 0; i < n; i++) {
        uint64_t a = m->faces[i], b = m->faces[i - i % 3 + (i % 3 + 1) % 3];
        t->h[i] = (half_edge){a < b ? a << 32 | b : b << 32 | a, (uint32_t)i};
    }
    qsort(t->h, n, sizeof *t->h, cmp_half_edge);
    t->count = 0;
    for (size_t i = 0; i < n; i++) {
        if (i == 0 || t->h[i].key != t->h[i - 1].key) t->first[t->count++] = (uint32_t)i;
        t->edge[t->h[i].he] = (uint32_t)(t->count - 1);
    }
    t->first[t->count] = (uint32_t)n;
    return LUCENT_OK;
}

/* The vertex of face f opposite its corner-k edge. */
static uint32_t opposite(const lucent_mesh *m, uint32_t he) { return m->faces[he - he % 3 + (he % 3 + 2) % 3]; }

/* Odd (edge) vertices: 3/8 (a + b) + 1/8 (c + d) inside, the midpoint on boundaries and
 * non-manifold edges. */
static void edge_points(const lucent_mesh *m, const edge_table *t, double *dest)
{
    for (size_t e = 0; e < t->count; e++) {
        uint32_t lo = (uint32_t)(t->h[t->first[e]].key >> 32), hi = (uint32_t)t->h[t->first[e]].key;
        const double *a = m->positions + 3 * (size_t)lo, *b = m->positions + 3 * (size_t)hi;
        double *p = dest + 3 * e;
        bool interior = t->first[e + 1] - t->first[e] == 2;
        for (int i = 0; i < 3; i++) p[i] = interior ? 0.375 * (a[i] + b[i]) : 0.5 * (a[i] + b[i]);
        for (uint32_t k = t->first[e]; interior && k < t->first[e + 1]; k++) {
            const double *c = m->positions + 3 * (size_t)opposite(m, t->h[k].he);
            for (int i = 0; i < 3; i++) p[i] += 0.125 * c[i];
        }
    }
}

/* Per vertex: the sum and number of all neighbours, of boundary neighbours, and whether it touches a
 * non-manifold edge. */
typedef struct vertex_ring {
    double sum[3], boundary_sum[3];
    uint32_t valence, boundary_count;
    bool pinned;
} vertex_ring;

static void gather_rings(const edge_table *t, const lucent_mesh *m, vertex_ring *ring)
{
    for (size_t e = 0; e < t->count; e++) {
        uint32_t v[2] = {(uint32_t)(t->h[t->first[e]].key >> 32), (uint32_t)t->h[t->first[e]].key};
        uint32_t faces = t->first[e + 1] - t->first[e];
        for (int s = 0; s < 2; s++) {
            vertex_ring *r = &ring[v[s]];
            const double *q = m->positions + 3 * (size_t)v[1 - s];
            r->valence++;
            for (int i = 0; i < 3; i++) r->sum[i] += q[i];
            if (faces > 2) r->pinned = true;
            if (faces != 1) continue;
            r->boundary_count++;
            for (int i = 0; i < 3; i++) r->boundary_sum[i] += q[i];
        }
    }
}

/* Even (old) vertices: (1 - n beta) v + beta sum, beta = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n
 * inside (Loop 1987); 3/4 v + 1/8 (b1 + b2) on a boundary; unchanged when pinned, on two or more
 * boundaries, or unused. */
static void vertex_points(const lucent_mesh *m, const vertex_ring *ring, double *dest)
{
    for (size_t v = 0; v < m->vertex_count; v++) {
        const vertex_ring *r = &ring[v];
        const double *p = m->positions + 3 * v;
        double *q = dest + 3 * v;
        memcpy(q, p, 3 * sizeof *q);
        if (r->pinned || r->valence == 0 || (r->boundary_count != 0 && r->boundary_count != 2)) continue;
        if (r->boundary_count == 2) {
            for (int i = 0; i < 3; i++) q[i] = 0.75 * p[i] + 0.125 * r->boundary_sum[i];
            continue;
        }
        double n = r->valence, c = 0.375 + 0.25 * cos(2 * M_PI / n), beta = (0.625 - c * c) / n;
        for (int i = 0; i < 3; i++) q[i] = (1 - n * beta) * p[i] + beta * r->sum[i];
    }
}

/* Each face (a, b, c) with edge vertices ab, bc, ca becomes (a, ab, ca), (b, bc, ab), (c, ca, bc),
 * (ab, bc, ca): the orientation is kept. */
static void split_faces(const lucent_mesh *m, const edge_table *t, uint32_t *dest)
{
    uint32_t base = (uint32_t)m->vertex_count;
    for (size_t f = 0; f < m->face_count; f++) {
        const uint32_t *v = m->faces + 3 * f;
        uint32_t e[3]; /* e[k]: the vertex on edge (v[k], v[k + 1]) */
        for (int k = 0; k < 3; k++) e[k] = base + t->edge[3 * f + (size_t)k];
        uint32_t *o = dest + 12 * f;
        uint32_t quad[12] = {v[0], e[0], e[2], v[1], e[1], e[0], v[2], e[2], e[1], e[0], e[1], e[2]};
        memcpy(o, quad, sizeof quad);
    }
}

/* The children's corner coordinates, the parent's linearly interpolated (edge midpoints). */
static lucent_status split_uvs(const lucent_mesh *m, lucent_mesh *dest)
{
    if (!m->uvs) return LUCENT_OK;
    dest->uvs = malloc(24 * m->face_count * sizeof *dest->uvs + 1);
    if (!dest->uvs) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (size_t f = 0; f < m->face_count; f++) {
        const double *c = m->uvs + 6 * f;
        double e[3][2]; /* the midpoint of edge (k, k + 1) */
        for (int k = 0; k < 3; k++)
            for (int i = 0; i < 2; i++) e[k][i] = 0.5 * (c[2 * k + i] + c[2 * ((k + 1) % 3) + i]);
        const double *corner[12] = {c, e[0], e[2], c + 2, e[1], e[0], c + 4, e[2], e[1], e[0], e[1], e[2]};
        for (int j = 0; j < 12; j++) memcpy(dest->uvs + 24 * f + 2 * j, corner[j], 2 * sizeof *dest->uvs);
    }
    return LUCENT_OK;
}

static lucent_status subdivide_once(const lucent_mesh *m, lucent_mesh **dest)
{
    edge_table t = {0};
    lucent_status s = edge_table_build(m, &t);
    if (s != LUCENT_OK) return s;
    if (m->vertex_count + t.count > UINT32_MAX)
        s = lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "subdivision: the mesh would exceed 2^32 vertices");
    vertex_ring *ring = s == LUCENT_OK ? calloc(m->vertex_count + 1, sizeof *ring) : NULL;
    if (s == LUCENT_OK && !ring) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    if (s == LUCENT_OK) s = lucent_mesh_create(m->vertex_count + t.count, 4 * m->face_count, dest);
    if (s == LUCENT_OK) {
        gather_rings(&t, m, ring);
        vertex_points(m, ring, (*dest)->positions);
        edge_points(m, &t, (*dest)->positions + 3 * m->vertex_count);
        split_faces(m, &t, (*dest)->faces);
        lucent_mesh_compute_normals(*dest);
        s = split_uvs(m, *dest);
        if (s != LUCENT_OK) lucent_mesh_destroy(*dest), *dest = NULL;
    }
    free(ring);
    edge_table_free(&t);
    return s;
}

lucent_status lucent_mesh_subdivide(lucent_mesh *mesh, int levels)
{
    if (levels < 0 || levels > 6)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "subdivision levels must be in [0, 6], got %d", levels);
    for (int l = 0; l < levels; l++) {
        lucent_mesh *next;
        lucent_status s = subdivide_once(mesh, &next);
        if (s != LUCENT_OK) return s;
        /* swap the contents so that the caller's handle now holds the finer mesh */
        lucent_mesh tmp = *mesh;
        *mesh = *next;
        *next = tmp;
        lucent_mesh_destroy(next);
    }
    return LUCENT_OK;
}
