/* Per-vertex curvature: dispatch to the estimators, optional smoothing, units, and the
 * guarantee that no NaN or Inf leaves (such vertices get 0 and LUCENT_CURVATURE_INVALID). */
#include <stdlib.h>
#include <string.h>

#include "mesh/internal.h"

static const char *const k_names[] = {"rusinkiewicz", "meyer", "garimella"};

const char *lucent_curvature_method_name(lucent_curvature_method method)
{
    return (unsigned)method < 3 ? k_names[method] : "unknown";
}

lucent_status lucent_curvature_method_parse(const char *name, lucent_curvature_method *dest)
{
    for (int i = 0; i < 3; i++)
        if (name && strcmp(name, k_names[i]) == 0) {
            *dest = (lucent_curvature_method)i;
            return LUCENT_OK;
        }
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "unknown curvature method '%s' "
                        "(rusinkiewicz, meyer, garimella)", name ? name : "");
}

void lucent_curvature_free(lucent_curvature *c)
{
    if (!c) return;
    free(c->k1), free(c->k2), free(c->mean), free(c->gauss), free(c->dir1), free(c->dir2), free(c->flags);
    memset(c, 0, sizeof *c);
}

static lucent_status alloc_curvature(size_t n, lucent_curvature *c)
{
    memset(c, 0, sizeof *c);
    c->count = n;
    c->k1 = calloc(n + 1, sizeof *c->k1), c->k2 = calloc(n + 1, sizeof *c->k2);
    c->mean = calloc(n + 1, sizeof *c->mean), c->gauss = calloc(n + 1, sizeof *c->gauss);
    c->dir1 = calloc(3 * n + 1, sizeof *c->dir1), c->dir2 = calloc(3 * n + 1, sizeof *c->dir2);
    c->flags = calloc(n + 1, 1);
    if (c->k1 && c->k2 && c->mean && c->gauss && c->dir1 && c->dir2 && c->flags) return LUCENT_OK;
    lucent_curvature_free(c);
    return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory for curvature of %zu vertices", n);
}

/* Scales to mm^-1 and replaces anything non-finite by 0 (flagged INVALID). */
static void finish(lucent_curvature *c, double mm_per_unit)
{
    double s = 1 / mm_per_unit;
    c->invalid_count = 0;
    for (size_t v = 0; v < c->count; v++) {
        c->k1[v] *= s, c->k2[v] *= s, c->mean[v] *= s, c->gauss[v] *= s * s;
        int bad = !isfinite(c->k1[v]) || !isfinite(c->k2[v]) || !isfinite(c->mean[v]) || !isfinite(c->gauss[v]);
        for (int k = 0; k < 3; k++) bad |= !isfinite(c->dir1[3 * v + k]) || !isfinite(c->dir2[3 * v + k]);
        if (bad || (c->flags[v] & LUCENT_CURVATURE_INVALID)) {
            c->k1[v] = c->k2[v] = c->mean[v] = c->gauss[v] = 0;
            memset(c->dir1 + 3 * v, 0, 3 * sizeof *c->dir1), memset(c->dir2 + 3 * v, 0, 3 * sizeof *c->dir2);
            c->flags[v] |= LUCENT_CURVATURE_INVALID;
            c->invalid_count++;
        }
    }
}

typedef struct per_vertex_job {
    mesh_vertex_job job;
    mesh_vertex_fn fn;
} per_vertex_job;

static lucent_status per_vertex_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)thread;
    const per_vertex_job *j = ctx;
    for (uint64_t v = begin; v < end; v++) j->fn(&j->job, (uint32_t)v);
    return LUCENT_OK;
}

lucent_status mesh_curvature_per_vertex(const lucent_mesh *mesh, const mesh_adjacency *adj,
                                        lucent_pool *pool, mesh_vertex_fn fn, lucent_curvature *dest)
{
    double *normals = malloc((3 * mesh->vertex_count + 1) * sizeof *normals);
    if (!normals) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "curvature: out of memory");
    per_vertex_job j = {{mesh, adj, normals, dest}, fn};
    lucent_status s = mesh_max_normals(mesh, adj, pool, normals);
    if (s == LUCENT_OK) s = lucent_parallel_for(pool, mesh->vertex_count, 4096, per_vertex_chunk, &j);
    free(normals);
    return s;
}

typedef struct boundary_job {
    const lucent_mesh *mesh;
    const mesh_adjacency *adj;
    uint8_t *flags;
} boundary_job;

static lucent_status boundary_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)thread;
    boundary_job *j = ctx;
    for (uint64_t v = begin; v < end; v++)
        if (mesh_vertex_on_boundary(j->mesh, j->adj, (uint32_t)v)) j->flags[v] |= LUCENT_CURVATURE_BOUNDARY;
    return LUCENT_OK;
}

/* Sets LUCENT_CURVATURE_BOUNDARY once, before the estimators (which read it). */
static lucent_status mark_boundaries(const lucent_mesh *mesh, const mesh_adjacency *adj, lucent_pool *pool,
                                     lucent_curvature *c)
{
    boundary_job job = {mesh, adj, c->flags};
    return lucent_parallel_for(pool, mesh->vertex_count, 4096, boundary_chunk, &job);
}

lucent_status lucent_mesh_curvature(const lucent_mesh *mesh, const lucent_curvature_desc *desc,
                                    lucent_curvature *dest)
{
    lucent_curvature_desc d = desc ? *desc : (lucent_curvature_desc){0};
    if (!(d.mm_per_unit > 0)) d.mm_per_unit = 1;
    if (!isfinite(d.mm_per_unit) || d.smooth_rings < 0 || d.smooth_rings > 1000 || (unsigned)d.method > 2)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "curvature: method 0..2, smooth_rings 0..1000, "
                            "finite mm_per_unit");
    lucent_status s = alloc_curvature(mesh->vertex_count, dest);
    if (s != LUCENT_OK) return s;
    mesh_adjacency adj;
    s = mesh_adjacency_build(mesh, &adj);
    if (s == LUCENT_OK) s = mark_boundaries(mesh, &adj, d.pool, dest);
    if (s == LUCENT_OK) {
        if (d.method == LUCENT_CURVATURE_RUSINKIEWICZ) s = mesh_curvature_rusinkiewicz(mesh, &adj, d.pool, d.fast, dest);
        else if (d.method == LUCENT_CURVATURE_MEYER)
            s = mesh_curvature_per_vertex(mesh, &adj, d.pool, mesh_meyer_vertex, dest);
        else s = mesh_curvature_per_vertex(mesh, &adj, d.pool, mesh_garimella_vertex, dest);
        if (s == LUCENT_OK && d.smooth_rings > 0) s = mesh_smooth(mesh, &adj, d.smooth_rings, dest);
        mesh_adjacency_free(&adj);
    }
    if (s == LUCENT_OK) finish(dest, d.mm_per_unit);
    else lucent_curvature_free(dest);
    return s;
}
