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
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                        "unknown curvature method '%s' "
                        "(rusinkiewicz, meyer, garimella)",
                        name ? name : "");
}

void lucent_curvature_free(lucent_curvature *c)
{
    if (!c) return;
    free(c->k1), free(c->k2), free(c->mean), free(c->gauss), free(c->dir1), free(c->dir2), free(c->flags);
    memset(c, 0, sizeof *c);
}

/* Output arrays on huge pages (see alloc.c); every estimator writes every element. */
static lucent_status alloc_curvature(size_t n, lucent_curvature *c)
{
    memset(c, 0, sizeof *c);
    c->count = n;
    c->k1 = mesh_alloc_large((n + 1) * sizeof *c->k1), c->k2 = mesh_alloc_large((n + 1) * sizeof *c->k2);
    c->mean = mesh_alloc_large((n + 1) * sizeof *c->mean), c->gauss = mesh_alloc_large((n + 1) * sizeof *c->gauss);
    c->dir1 = mesh_alloc_large((3 * n + 1) * sizeof *c->dir1);
    c->dir2 = mesh_alloc_large((3 * n + 1) * sizeof *c->dir2);
    c->flags = mesh_alloc_large(n + 1);
    if (c->k1 && c->k2 && c->mean && c->gauss && c->dir1 && c->dir2 && c->flags) return LUCENT_OK;
    lucent_curvature_free(c);
    return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory for curvature of %zu vertices", n);
}

typedef struct finish_job {
    lucent_curvature *c;
    double scale;
} finish_job;

/* Scales to mm^-1 and replaces anything non-finite by 0 (flagged INVALID). */
static lucent_status finish_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)thread;
    const finish_job *j = ctx;
    lucent_curvature *c = j->c;
    double s = j->scale;
    for (uint64_t v = begin; v < end; v++) {
        c->k1[v] *= s, c->k2[v] *= s, c->mean[v] *= s, c->gauss[v] *= s * s;
        double sum = c->k1[v] + c->k2[v] + c->mean[v] + c->gauss[v]; /* non-finite if any is */
        for (int k = 0; k < 3; k++) sum += c->dir1[3 * v + k] + c->dir2[3 * v + k];
        if (isfinite(sum) && !(c->flags[v] & LUCENT_CURVATURE_INVALID)) continue;
        c->k1[v] = c->k2[v] = c->mean[v] = c->gauss[v] = 0;
        memset(c->dir1 + 3 * v, 0, 3 * sizeof *c->dir1), memset(c->dir2 + 3 * v, 0, 3 * sizeof *c->dir2);
        c->flags[v] |= LUCENT_CURVATURE_INVALID;
    }
    return LUCENT_OK;
}

/* scaled: the estimator has already scaled and checked the values. */
static lucent_status finish(lucent_curvature *c, double mm_per_unit, int scaled, lucent_pool *pool)
{
    finish_job job = {c, 1 / mm_per_unit};
    lucent_status s = scaled ? LUCENT_OK : lucent_parallel_for(pool, c->count, 16384, finish_chunk, &job);
    c->invalid_count = 0;
    for (size_t v = 0; v < c->count; v++) c->invalid_count += (c->flags[v] & LUCENT_CURVATURE_INVALID) != 0;
    return s;
}

typedef struct per_vertex_job {
    mesh_vertex_job job;
    mesh_vertex_fn fn;
} per_vertex_job;

static lucent_status per_vertex_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)thread;
    const per_vertex_job *j = ctx;
    lucent_curvature *o = j->job.out;
    size_t n = end - begin; /* no directions; invalid vertices keep these zeros */
    memset(o->k1 + begin, 0, n * sizeof *o->k1), memset(o->k2 + begin, 0, n * sizeof *o->k2);
    memset(o->mean + begin, 0, n * sizeof *o->mean), memset(o->gauss + begin, 0, n * sizeof *o->gauss);
    memset(o->dir1 + 3 * begin, 0, 3 * n * sizeof *o->dir1), memset(o->dir2 + 3 * begin, 0, 3 * n * sizeof *o->dir2);
    for (uint64_t v = begin; v < end; v++) j->fn(&j->job, (uint32_t)v);
    return LUCENT_OK;
}

lucent_status mesh_curvature_per_vertex(const lucent_mesh *mesh, const mesh_adjacency *adj, const mesh_fan *fan,
                                        lucent_pool *pool, mesh_vertex_fn fn, lucent_curvature *dest)
{
    mesh_face_geometry *geometry = mesh_alloc_large((mesh->face_count + 1) * sizeof *geometry);
    if (!geometry) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "curvature: out of memory");
    per_vertex_job j = {{mesh, adj, fan->normals, geometry, dest}, fn};
    lucent_status s = mesh_face_geometry_compute(mesh, pool, geometry);
    if (s == LUCENT_OK) s = lucent_parallel_for(pool, mesh->vertex_count, 4096, per_vertex_chunk, &j);
    free(geometry);
    return s;
}

/* Adjacency and the fan walk (normals, boundary flags, slot pairs), then the estimator. */
static lucent_status estimate(const lucent_mesh *mesh, const lucent_curvature_desc *d, lucent_curvature *dest)
{
    int two_pass = d->method == LUCENT_CURVATURE_RUSINKIEWICZ && !d->fast;
    mesh_adjacency adj;
    lucent_status s = mesh_adjacency_build(mesh, d->pool, &adj);
    if (s != LUCENT_OK) return s;
    mesh_fan fan = {mesh_alloc_large((3 * mesh->vertex_count + 1) * sizeof *fan.normals), dest->flags,
                    two_pass ? mesh_alloc_large(3 * mesh->face_count + 1) : NULL};
    if (!fan.normals || (two_pass && !fan.pair)) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "curvature: out of memory");
    if (s == LUCENT_OK) s = mesh_fan_compute(mesh, &adj, d->pool, &fan);
    if (s == LUCENT_OK) {
        if (d->method == LUCENT_CURVATURE_RUSINKIEWICZ) /* scaled here unless smoothed after */
            s = mesh_curvature_rusinkiewicz(mesh, &adj, &fan, d->pool, d->fast,
                                            d->smooth_rings > 0 ? 1 : 1 / d->mm_per_unit, dest);
        else
            s = mesh_curvature_per_vertex(
                mesh, &adj, &fan, d->pool,
                d->method == LUCENT_CURVATURE_MEYER ? mesh_meyer_vertex : mesh_garimella_vertex, dest);
    }
    if (s == LUCENT_OK && d->smooth_rings > 0) s = mesh_smooth(mesh, &adj, d->smooth_rings, dest);
    free(fan.normals), free(fan.pair);
    mesh_adjacency_free(&adj);
    return s;
}

lucent_status lucent_mesh_curvature(const lucent_mesh *mesh, const lucent_curvature_desc *desc, lucent_curvature *dest)
{
    lucent_curvature_desc d = desc ? *desc : (lucent_curvature_desc){0};
    if (!(d.mm_per_unit > 0)) d.mm_per_unit = 1;
    if (!isfinite(d.mm_per_unit) || d.smooth_rings < 0 || d.smooth_rings > 1000 || (unsigned)d.method > 2)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "curvature: method 0..2, smooth_rings 0..1000, "
                                                         "finite mm_per_unit");
    lucent_status s = alloc_curvature(mesh->vertex_count, dest);
    if (s == LUCENT_OK) s = estimate(mesh, &d, dest);
    int scaled = d.method == LUCENT_CURVATURE_RUSINKIEWICZ && d.smooth_rings == 0;
    if (s == LUCENT_OK) s = finish(dest, d.mm_per_unit, scaled, d.pool);
    if (s != LUCENT_OK) lucent_curvature_free(dest);
    return s;
}
