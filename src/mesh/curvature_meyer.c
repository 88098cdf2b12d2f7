/* Meyer, Desbrun, Schroder & Barr 2003, "Discrete differential-geometry operators for
 * triangulated 2-manifolds": mean curvature from the cotangent Laplacian over the mixed
 * Voronoi area (eq. 8 with Fig. 4's areas), Gaussian curvature from the angle deficit (eq. 9),
 * principal curvatures k = H +- sqrt(max(0, H^2 - K)) (eq. 10, the root clamped at 0). */
#include <stdlib.h>

#include "mesh/internal.h"

static const double k_pi = 3.14159265358979323846;

/* cot of the corner between edges a and b; 0 when degenerate. */
static int corner_cot(const double *a, const double *b, double *cot)
{
    double x[3];
    v3_cross(a, b, x);
    double s = v3_len(x);
    if (!(s > 0)) return 0;
    *cot = v3_dot(a, b) / s;
    return 1;
}

double mesh_angle_deficit_gauss(const lucent_mesh *mesh, const mesh_adjacency *adj, uint32_t v,
                                int boundary, double *area)
{
    const double *P = mesh->positions;
    double sum = 0, ca[3], e1[3], e2[3], x[3];
    *area = 0;
    for (uint32_t a = adj->start[v]; a < adj->start[v + 1]; a++) {
        uint32_t i = adj->corner[a], j, k;
        mesh_slot_others(mesh->faces, i, &j, &k);
        mesh_corner_areas(mesh, i / 3, ca);
        *area += ca[i % 3];
        v3_sub(P + 3 * j, P + 3 * v, e1);
        v3_sub(P + 3 * k, P + 3 * v, e2);
        v3_cross(e1, e2, x);
        double sn = v3_len(x);
        if (sn > 0) sum += atan2(sn, v3_dot(e1, e2));
    }
    return *area > 0 ? ((boundary ? k_pi : 2 * k_pi) - sum) / *area : 0;
}

/* Accumulates the cotangent Laplacian of v over its faces (sum of cot(x_i - x_j)). */
static void cot_laplacian(const mesh_vertex_job *j, uint32_t v, double *lap)
{
    const double *P = j->mesh->positions;
    lap[0] = lap[1] = lap[2] = 0;
    for (uint32_t a = j->adj->start[v]; a < j->adj->start[v + 1]; a++) {
        uint32_t vj, vk;
        mesh_slot_others(j->mesh->faces, j->adj->corner[a], &vj, &vk);
        const double *pi = P + 3 * v, *pj = P + 3 * vj, *pk = P + 3 * vk;
        double dij[3], dik[3], kj[3], kk[3], jk[3], cot_j, cot_k;
        v3_sub(pi, pj, dij), v3_sub(pi, pk, dik);
        v3_sub(pk, pj, jk), v3_sub(pi, pk, kk);
        for (int i = 0; i < 3; i++) kj[i] = -jk[i];
        /* angle at j: between (pi - pj) and (pk - pj); at k: between (pi - pk) and (pj - pk) */
        if (!corner_cot(dij, jk, &cot_j) || !corner_cot(kk, kj, &cot_k)) continue;
        for (int i = 0; i < 3; i++) lap[i] += cot_k * dij[i] + cot_j * dik[i];
    }
}

void mesh_meyer_vertex(const mesh_vertex_job *j, uint32_t v)
{
    lucent_curvature *o = j->out;
    int boundary = o->flags[v] & LUCENT_CURVATURE_BOUNDARY;
    double area, lap[3];
    double K = mesh_angle_deficit_gauss(j->mesh, j->adj, v, boundary, &area);
    if (!(area > 0)) {
        o->flags[v] |= LUCENT_CURVATURE_INVALID;
        return;
    }
    cot_laplacian(j, v, lap);
    /* K(x) = lap / (2 A) = 2 H n: H = |lap| / (4 A), signed by the side of the normal. */
    double H = v3_len(lap) / (4 * area);
    const float *n = j->normals + 3 * v;
    if (lap[0] * n[0] + lap[1] * n[1] + lap[2] * n[2] < 0) H = -H;
    double disc = sqrt(fmax(0, H * H - K));
    o->mean[v] = H, o->gauss[v] = K, o->k1[v] = H + disc, o->k2[v] = H - disc;
}
