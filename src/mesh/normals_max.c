/* Vertex normals with Max's weights (Max 1999, "Weights for computing vertex normals from
 * facet normals"): each corner adds (e1 x e2) / (|e1|^2 |e2|^2), exact for a sphere. The
 * curvature estimators difference normals, so this accuracy matters there. Where the weighted
 * sum cancels (opposite sheets at a non-manifold vertex), the largest incident face's normal. */
#include "mesh/internal.h"

typedef struct normals_job {
    const lucent_mesh *mesh;
    const mesh_adjacency *adj;
    double *dest;
} normals_job;

static lucent_status normals_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)thread;
    const normals_job *j = ctx;
    const double *P = j->mesh->positions;
    for (uint64_t v = begin; v < end; v++) {
        double n[3] = {0, 0, 0}, mag = 0, big = 0, fallback[3] = {0, 0, 0};
        for (uint32_t a = j->adj->start[v]; a < j->adj->start[v + 1]; a++) {
            const uint32_t *t = j->mesh->faces + 3 * j->adj->face[a];
            int c = j->adj->corner[a];
            double e1[3], e2[3], x[3];
            v3_sub(P + 3 * t[(c + 1) % 3], P + 3 * v, e1);
            v3_sub(P + 3 * t[(c + 2) % 3], P + 3 * v, e2);
            double w = v3_dot(e1, e1) * v3_dot(e2, e2);
            if (!(w > 0)) continue;
            v3_cross(e1, e2, x);
            double iw = 1 / w;
            for (int k = 0; k < 3; k++) n[k] += x[k] * iw;
            double l2 = v3_dot(x, x);
            mag += l2 * iw * iw;
            if (l2 > big) big = l2, fallback[0] = x[0], fallback[1] = x[1], fallback[2] = x[2];
        }
        /* Sheets of opposite orientation meeting at v (non-manifold scans) can cancel the sum:
         * then the largest incident face decides. */
        if (!(v3_dot(n, n) > 1e-12 * mag)) n[0] = fallback[0], n[1] = fallback[1], n[2] = fallback[2];
        v3_normalize(n);
        for (int k = 0; k < 3; k++) j->dest[3 * v + k] = n[k];
    }
    return LUCENT_OK;
}

lucent_status mesh_max_normals(const lucent_mesh *mesh, const mesh_adjacency *adj, lucent_pool *pool,
                               double *dest)
{
    normals_job job = {mesh, adj, dest};
    return lucent_parallel_for(pool, mesh->vertex_count, 4096, normals_chunk, &job);
}
