/* What Meyer's and Garimella's per-vertex estimators need of each face, computed once per face
 * rather than once per corner: the mixed Voronoi corner areas (Meyer et al. 2003, Fig. 4) and
 * the cotangents of the corner angles (the weights of eq. 8; the angle itself, for eq. 9, is
 * arccot). Floats: 24 bytes a face. */
#include "mesh/internal.h"

typedef struct geometry_job {
    const lucent_mesh *mesh;
    mesh_face_geometry *dest;
} geometry_job;

/* Edge k is opposite corner k; the angle at corner k lies between the other two edges, so its
 * cotangent is -(e_k+1 . e_k+2) / |e0 x e1|. */
static void face_geometry(const lucent_mesh *m, size_t f, mesh_face_geometry *g)
{
    const uint32_t *v = m->faces + 3 * f;
    v3 p0 = v3_load(m->positions + 3 * (size_t)v[0]), p1 = v3_load(m->positions + 3 * (size_t)v[1]);
    v3 p2 = v3_load(m->positions + 3 * (size_t)v[2]);
    v3 e0 = v3_sub(p2, p1), e1 = v3_sub(p0, p2), e2 = v3_sub(p1, p0);
    double l[3] = {v3_dot(e0, e0), v3_dot(e1, e1), v3_dot(e2, e2)}, corner[3];
    double xl = v3_length(v3_cross(e0, e1));
    if (!(xl > 0) || !isfinite(xl)) {
        *g = (mesh_face_geometry){{0, 0, 0}, {0, 0, 0}};
        return;
    }
    double in = 1 / xl;
    mesh_mixed_areas(l, xl, in, corner);
    for (int k = 0; k < 3; k++) g->corner[k] = (float)corner[k];
    g->cot[0] = (float)(-v3_dot(e1, e2) * in), g->cot[1] = (float)(-v3_dot(e2, e0) * in);
    g->cot[2] = (float)(-v3_dot(e0, e1) * in);
}

static lucent_status geometry_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)thread;
    const geometry_job *j = ctx;
    for (uint64_t f = begin; f < end; f++) face_geometry(j->mesh, f, j->dest + f);
    return LUCENT_OK;
}

lucent_status mesh_face_geometry_compute(const lucent_mesh *mesh, lucent_pool *pool, mesh_face_geometry *dest)
{
    geometry_job job = {mesh, dest};
    return lucent_parallel_for(pool, mesh->face_count, 8192, geometry_chunk, &job);
}
