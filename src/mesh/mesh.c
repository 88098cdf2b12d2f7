/* Triangle meshes: allocation, area-weighted normals, welding, statistics. */
#include <stdlib.h>
#include <string.h>

#include "base/radix_sort.h"
#include "mesh/internal.h"

lucent_status lucent_mesh_create(size_t vertex_count, size_t face_count, lucent_mesh **dest)
{
    *dest = NULL;
    if (vertex_count > UINT32_MAX || face_count > UINT32_MAX / 3)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "mesh too large (%zu vertices, %zu faces)", vertex_count,
                            face_count);
    lucent_mesh *m = calloc(1, sizeof *m);
    if (!m) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory for a mesh");
    m->vertex_count = vertex_count, m->face_count = face_count;
    m->positions = calloc(vertex_count * 3 + 1, sizeof *m->positions);
    m->normals = calloc(vertex_count * 3 + 1, sizeof *m->normals);
    m->faces = calloc(face_count * 3 + 1, sizeof *m->faces);
    mesh_advise_large(m->positions, vertex_count * 3 * sizeof *m->positions);
    mesh_advise_large(m->normals, vertex_count * 3 * sizeof *m->normals);
    mesh_advise_large(m->faces, face_count * 3 * sizeof *m->faces);
    if (!m->positions || !m->normals || !m->faces) {
        lucent_mesh_destroy(m);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory for a mesh of %zu vertices", vertex_count);
    }
    *dest = m;
    return LUCENT_OK;
}

void lucent_mesh_destroy(lucent_mesh *mesh)
{
    if (!mesh) return;
    free(mesh->positions), free(mesh->normals), free(mesh->faces), free(mesh->uvs);
    free(mesh);
}

void lucent_mesh_compute_normals(lucent_mesh *mesh)
{
    double *n = mesh->normals;
    memset(n, 0, mesh->vertex_count * 3 * sizeof *n);
    for (size_t f = 0; f < mesh->face_count; f++) {
        const uint32_t *t = mesh->faces + 3 * f;
        v3 p0 = v3_load(mesh->positions + 3 * t[0]);
        v3 e1 = v3_sub(v3_load(mesh->positions + 3 * t[1]), p0), e2 = v3_sub(v3_load(mesh->positions + 3 * t[2]), p0);
        v3 c = v3_cross(e1, e2); /* twice the area times the unit normal */
        for (int j = 0; j < 3; j++) v3_store(v3_add(v3_load(n + 3 * t[j]), c), n + 3 * t[j]);
    }
    for (size_t v = 0; v < mesh->vertex_count; v++) v3_store(v3_normalize(v3_load(n + 3 * v)), n + 3 * v);
}

/* ---- welding: an open-addressing hash of exact positions ---- */

static uint64_t hash_position(const double *p)
{
    uint64_t h = 1469598103934665603ull, bits;
    for (int k = 0; k < 3; k++) {
        double x = p[k] == 0 ? 0 : p[k]; /* -0 and +0 weld */
        memcpy(&bits, &x, sizeof bits);
        h = (h ^ bits) * 1099511628211ull;
        h ^= h >> 29;
    }
    return h;
}

/* remap[v] = index of the first vertex at v's position. */
static lucent_status weld_map(const lucent_mesh *m, uint32_t *remap)
{
    size_t cap = 16;
    while (cap < 2 * m->vertex_count) cap *= 2;
    uint32_t *slot = mesh_alloc_large(cap * sizeof *slot);
    if (!slot) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory welding a mesh");
    memset(slot, 0xff, cap * sizeof *slot);
    for (size_t v = 0; v < m->vertex_count; v++) {
        const double *p = m->positions + 3 * v;
        size_t h = (size_t)hash_position(p) & (cap - 1);
        while (slot[h] != UINT32_MAX) {
            const double *q = m->positions + 3 * slot[h];
            if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) break;
            h = (h + 1) & (cap - 1);
        }
        if (slot[h] == UINT32_MAX) slot[h] = (uint32_t)v;
        remap[v] = slot[h];
    }
    free(slot);
    return LUCENT_OK;
}

/* Rewrites faces through remap, drops faces with a repeated index, then compacts vertices in
 * order of first use (remap is reused as the new index table). */
static void weld_apply(lucent_mesh *m, uint32_t *remap, uint32_t *newidx)
{
    size_t nf = 0, nv = 0;
    for (size_t f = 0; f < m->face_count; f++) {
        uint32_t a = remap[m->faces[3 * f]], b = remap[m->faces[3 * f + 1]], c = remap[m->faces[3 * f + 2]];
        if (a == b || b == c || a == c) continue;
        if (m->uvs) memmove(m->uvs + 6 * nf, m->uvs + 6 * f, 6 * sizeof *m->uvs); /* corners follow faces */
        m->faces[3 * nf] = a, m->faces[3 * nf + 1] = b, m->faces[3 * nf + 2] = c;
        nf++;
    }
    memset(newidx, 0xff, m->vertex_count * sizeof *newidx);
    for (size_t i = 0; i < 3 * nf; i++) {
        uint32_t v = m->faces[i];
        if (newidx[v] == UINT32_MAX) {
            newidx[v] = (uint32_t)nv++;
        }
        m->faces[i] = newidx[v];
    }
    /* Gather positions through the inverse table (built in remap, no longer needed). */
    for (size_t v = 0; v < m->vertex_count; v++)
        if (newidx[v] != UINT32_MAX) remap[newidx[v]] = (uint32_t)v;
    double *pos = m->normals; /* scratch, normals are recomputed */
    for (size_t n = 0; n < nv; n++) memcpy(pos + 3 * n, m->positions + 3 * remap[n], 3 * sizeof *pos);
    double *old = m->positions;
    m->positions = pos, m->normals = old;
    m->vertex_count = nv, m->face_count = nf;
}

lucent_status lucent_mesh_weld(lucent_mesh *mesh)
{
    uint32_t *remap = mesh_alloc_large((mesh->vertex_count + 1) * sizeof *remap);
    uint32_t *newidx = mesh_alloc_large((mesh->vertex_count + 1) * sizeof *newidx);
    lucent_status s = remap && newidx ? weld_map(mesh, remap)
                                      : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory welding a mesh");
    if (s == LUCENT_OK) weld_apply(mesh, remap, newidx);
    free(remap), free(newidx);
    if (s == LUCENT_OK) lucent_mesh_compute_normals(mesh);
    return s;
}

/* ---- adjacency ---- */

/* The counting sort runs in `parts` vertex ranges, one per thread: each part scans every face
 * slot but counts and places only its own vertices, so no two threads write the same counter
 * and the result (slots of a vertex in face order) does not depend on the number of parts. */
typedef struct adjacency_job {
    const uint32_t *faces;
    size_t slots, parts, vertices;
    uint32_t *start, *corner;
    int place; /* 0: count degrees into start[v + 2]; 1: place slots */
} adjacency_job;

static lucent_status adjacency_chunk(void *ctx, uint64_t part, uint64_t begin, uint64_t end, int thread)
{
    (void)begin, (void)end, (void)thread;
    const adjacency_job *j = ctx;
    uint32_t lo = (uint32_t)(j->vertices * part / j->parts);
    uint32_t span = (uint32_t)(j->vertices * (part + 1) / j->parts) - lo;
    uint32_t *start = j->start, *corner = j->corner;
    const uint32_t *faces = j->faces;
    if (!j->place) {
        for (size_t i = 0; i < j->slots; i++)
            if (faces[i] - lo < span) start[faces[i] + 2]++;
        return LUCENT_OK;
    }
    for (size_t i = 0; i < j->slots; i++)
        if (faces[i] - lo < span) corner[start[faces[i] + 1]++] = (uint32_t)i;
    return LUCENT_OK;
}

lucent_status mesh_adjacency_build(const lucent_mesh *mesh, lucent_pool *pool, mesh_adjacency *dest)
{
    size_t nv = mesh->vertex_count, nc = 3 * mesh->face_count;
    dest->start = mesh_alloc_large((nv + 2) * sizeof *dest->start);
    dest->corner = mesh_alloc_large((nc + MESH_SLOT_PAD) * sizeof *dest->corner);
    if (!dest->start || !dest->corner) {
        mesh_adjacency_free(dest);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory for mesh adjacency");
    }
    memset(dest->start, 0, (nv + 2) * sizeof *dest->start);
    memset(dest->corner + nc, 0, MESH_SLOT_PAD * sizeof *dest->corner);
    adjacency_job job = {mesh->faces, nc, (size_t)lucent_pool_threads(pool), nv, dest->start, dest->corner, 0};
    lucent_status s = lucent_parallel_for(pool, job.parts, 1, adjacency_chunk, &job);
    for (size_t v = 0; v < nv; v++) dest->start[v + 2] += dest->start[v + 1];
    job.place = 1;
    if (s == LUCENT_OK) s = lucent_parallel_for(pool, job.parts, 1, adjacency_chunk, &job);
    if (s != LUCENT_OK) mesh_adjacency_free(dest);
    return s;
}

void mesh_adjacency_free(mesh_adjacency *adj)
{
    free(adj->start), free(adj->corner);
    adj->start = adj->corner = NULL;
}

/* ---- corner areas ---- */

void mesh_corner_areas_edges(const double e[3][3], double dest[3])
{
    v3 e0 = v3_load(e[0]), e1 = v3_load(e[1]), e2 = v3_load(e[2]);
    double l[3] = {v3_dot(e0, e0), v3_dot(e1, e1), v3_dot(e2, e2)};
    double xl = v3_length(v3_cross(e0, e1));
    dest[0] = dest[1] = dest[2] = 0;
    if (!(xl > 0) || !isfinite(xl)) return;
    mesh_mixed_areas(l, xl, 1 / xl, dest);
}

void mesh_corner_areas(const lucent_mesh *mesh, size_t f, double dest[3])
{
    const uint32_t *t = mesh->faces + 3 * f;
    v3 p[3] = {v3_load(mesh->positions + 3 * t[0]), v3_load(mesh->positions + 3 * t[1]),
               v3_load(mesh->positions + 3 * t[2])};
    double e[3][3];
    for (int j = 0; j < 3; j++) v3_store(v3_sub(p[(j + 2) % 3], p[(j + 1) % 3]), e[j]); /* e[j] opposite j */
    mesh_corner_areas_edges(e, dest);
}

/* ---- statistics ---- */

/* Each face edge as one key, lower vertex * vertex_count + higher (below 2^64 for any
 * vertex_count <= UINT32_MAX, and only as many bits as the mesh needs: fewer radix passes);
 * sorted, an edge's faces are a run of equal keys. */
static void count_edges(const lucent_mesh *m, uint64_t *keys, uint64_t *scratch, lucent_mesh_stats *dest)
{
    size_t n = 3 * m->face_count;
    uint64_t nv = m->vertex_count;
    for (size_t i = 0; i < n; i++) {
        uint64_t a = m->faces[i], b = m->faces[i - i % 3 + (i + 1) % 3];
        keys[i] = a < b ? a * nv + b : b * nv + a;
    }
    lucent_radix_sort_u64(keys, scratch, n);
    for (size_t i = 0; i < n;) {
        size_t j = i;
        while (j < n && keys[j] == keys[i]) j++;
        dest->boundary_edges += j - i == 1;
        dest->nonmanifold_edges += j - i >= 3;
        i = j;
    }
}

lucent_status lucent_mesh_stats_compute(const lucent_mesh *mesh, lucent_mesh_stats *dest)
{
    *dest = (lucent_mesh_stats){0};
    uint64_t *keys = mesh_alloc_large((6 * mesh->face_count + 1) * sizeof *keys); /* keys, the sort's scratch */
    uint8_t *used = calloc(mesh->vertex_count + 1, 1);
    if (!keys || !used) {
        free(keys), free(used);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory for mesh statistics");
    }
    count_edges(mesh, keys, keys + 3 * mesh->face_count, dest);
    for (size_t f = 0; f < mesh->face_count; f++) {
        double a[3];
        mesh_corner_areas(mesh, f, a);
        dest->degenerate_faces += a[0] + a[1] + a[2] == 0;
        for (int j = 0; j < 3; j++) used[mesh->faces[3 * f + j]] = 1;
    }
    for (int k = 0; k < 3; k++) dest->bbox_min[k] = mesh->vertex_count ? INFINITY : 0;
    for (int k = 0; k < 3; k++) dest->bbox_max[k] = mesh->vertex_count ? -INFINITY : 0;
    for (size_t v = 0; v < mesh->vertex_count; v++) {
        dest->unused_vertices += !used[v];
        for (int k = 0; k < 3; k++) {
            dest->bbox_min[k] = fmin(dest->bbox_min[k], mesh->positions[3 * v + k]);
            dest->bbox_max[k] = fmax(dest->bbox_max[k], mesh->positions[3 * v + k]);
        }
    }
    free(keys), free(used);
    return LUCENT_OK;
}
