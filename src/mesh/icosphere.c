/* Icosphere: an icosahedron subdivided `subdivisions` times, midpoints pushed onto the sphere;
 * optional tangential jitter (a fraction of the edge length), projected back onto the sphere. */
#include <stdlib.h>
#include <string.h>

#include "mesh/internal.h"

static const double k_t = 1.6180339887498948482;
static const double k_ico_v[12][3] = {{-1, k_t, 0}, {1, k_t, 0}, {-1, -k_t, 0}, {1, -k_t, 0},
                                      {0, -1, k_t}, {0, 1, k_t}, {0, -1, -k_t}, {0, 1, -k_t},
                                      {k_t, 0, -1}, {k_t, 0, 1}, {-k_t, 0, -1}, {-k_t, 0, 1}};
static const uint32_t k_ico_f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                        {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                        {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                        {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};

typedef struct edge_map {
    uint64_t *key;
    uint32_t *value;
    size_t mask;
} edge_map;

/* The index of the midpoint of edge (a, b), created on first request. */
static uint32_t midpoint(edge_map *em, lucent_mesh *m, size_t *nv, uint32_t a, uint32_t b)
{
    uint64_t k = a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
    size_t h = (size_t)((k * 0x9E3779B97F4A7C15ull) >> 20) & em->mask;
    while (em->key[h] != UINT64_MAX && em->key[h] != k) h = (h + 1) & em->mask;
    if (em->key[h] == k) return em->value[h];
    double *p = m->positions + 3 * *nv;
    for (int c = 0; c < 3; c++) p[c] = 0.5 * (m->positions[3 * a + c] + m->positions[3 * b + c]);
    v3_store(v3_normalize(v3_load(p)), p);
    em->key[h] = k, em->value[h] = (uint32_t)*nv;
    return (uint32_t)(*nv)++;
}

static void subdivide(lucent_mesh *m, edge_map *em, size_t *nv, size_t nf, uint32_t *out)
{
    memset(em->key, 0xff, (em->mask + 1) * sizeof *em->key);
    for (size_t f = 0; f < nf; f++) {
        uint32_t a = m->faces[3 * f], b = m->faces[3 * f + 1], c = m->faces[3 * f + 2];
        uint32_t ab = midpoint(em, m, nv, a, b), bc = midpoint(em, m, nv, b, c), ca = midpoint(em, m, nv, c, a);
        uint32_t t[12] = {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca};
        memcpy(out + 12 * f, t, sizeof t);
    }
    memcpy(m->faces, out, 12 * nf * sizeof *out);
}

static void jitter_vertices(lucent_mesh *m, double amount, uint64_t seed)
{
    for (size_t v = 0; v < m->vertex_count; v++) {
        lucent_rng rng;
        lucent_rng_init(seed, v, &rng);
        double *p = m->positions + 3 * v;
        for (int c = 0; c < 3; c++) p[c] += amount * (2 * lucent_rng_uniform(&rng) - 1);
        v3_store(v3_normalize(v3_load(p)), p);
    }
}

lucent_status mesh_icosphere(const lucent_primitive_desc *d, lucent_mesh **dest)
{
    size_t nf = 20 << (2 * d->subdivisions), nv_total = nf / 2 + 2, nv = 12;
    lucent_status s = lucent_mesh_create(nv_total, nf, dest);
    if (s != LUCENT_OK) return s;
    lucent_mesh *m = *dest;
    for (int i = 0; i < 12; i++) {
        v3_store(v3_normalize(v3_load(k_ico_v[i])), m->positions + 3 * i);
    }
    memcpy(m->faces, k_ico_f, sizeof k_ico_f);
    size_t cap = 64;
    while (cap < 4 * nf) cap *= 2;
    edge_map em = {malloc(cap * sizeof *em.key), malloc(cap * sizeof *em.value), cap - 1};
    uint32_t *tmp = malloc(3 * nf * sizeof *tmp);
    if (!em.key || !em.value || !tmp) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "icosphere: out of memory");
    for (int level = 0, cur = 20; s == LUCENT_OK && level < d->subdivisions; level++, cur *= 4)
        subdivide(m, &em, &nv, (size_t)cur, tmp);
    free(em.key), free(em.value), free(tmp);
    if (s != LUCENT_OK) {
        lucent_mesh_destroy(m), *dest = NULL;
        return s;
    }
    double edge = 1.1 / (1 << d->subdivisions); /* about the edge length on the unit sphere */
    if (d->jitter > 0) jitter_vertices(m, d->jitter * edge, d->seed);
    for (size_t i = 0; i < 3 * nv; i++) m->positions[i] *= d->radius;
    lucent_mesh_compute_normals(m);
    return LUCENT_OK;
}
