/* n-ring smoothing: `rings` passes of a 1-ring average weighted by the neighbours' mixed
 * Voronoi areas (a vertex's own value included). Mean and Gaussian curvature are averaged;
 * k1, k2 are recomputed from them (H +- sqrt(max(0, H^2 - K))); directions are kept. Invalid
 * vertices neither give nor take. */
#include <stdlib.h>
#include <string.h>

#include "mesh/internal.h"

static void vertex_areas(const lucent_mesh *m, double *area)
{
    double ca[3];
    memset(area, 0, m->vertex_count * sizeof *area);
    for (size_t f = 0; f < m->face_count; f++) {
        mesh_corner_areas(m, f, ca);
        for (int j = 0; j < 3; j++) area[m->faces[3 * f + j]] += ca[j];
    }
}

/* One pass over values src -> dst. Neighbours are counted once per incident face. */
static void smooth_pass(const lucent_mesh *m, const mesh_adjacency *adj, const double *area, const uint8_t *flags,
                        const double *src, double *dst)
{
    for (size_t v = 0; v < m->vertex_count; v++) {
        if (flags[v] & LUCENT_CURVATURE_INVALID) {
            dst[v] = src[v];
            continue;
        }
        double s = area[v] * src[v], w = area[v];
        for (uint32_t a = adj->start[v]; a < adj->start[v + 1]; a++) {
            uint32_t u, unused;
            mesh_slot_others(m->faces, adj->corner[a], &u, &unused);
            if (flags[u] & LUCENT_CURVATURE_INVALID) continue;
            s += area[u] * src[u], w += area[u];
        }
        dst[v] = w > 0 ? s / w : src[v];
    }
}

lucent_status mesh_smooth(const lucent_mesh *mesh, const mesh_adjacency *adj, int rings, lucent_curvature *curv)
{
    size_t n = mesh->vertex_count;
    double *area = malloc((n + 1) * sizeof *area), *tmp = malloc((n + 1) * sizeof *tmp);
    if (!area || !tmp) {
        free(area), free(tmp);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "curvature smoothing: out of memory");
    }
    vertex_areas(mesh, area);
    double *fields[2] = {curv->mean, curv->gauss};
    for (int r = 0; r < rings; r++)
        for (int f = 0; f < 2; f++) {
            smooth_pass(mesh, adj, area, curv->flags, fields[f], tmp);
            memcpy(fields[f], tmp, n * sizeof *tmp);
        }
    for (size_t v = 0; v < n; v++) {
        double disc = sqrt(fmax(0, curv->mean[v] * curv->mean[v] - curv->gauss[v]));
        curv->k1[v] = curv->mean[v] + disc, curv->k2[v] = curv->mean[v] - disc;
    }
    free(area), free(tmp);
    return LUCENT_OK;
}
