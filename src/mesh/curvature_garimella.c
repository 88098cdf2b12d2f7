/* The area-weighted normal-curvature estimate (Garimella & Swartz 2003, as used by the CDRF
 * blog): H_i = sum_j A_ij k_ij / sum_j A_ij with k_ij = 2 (x_i - x_j) . n_i / |x_i - x_j|^2,
 * the normal curvature of the circle through x_j tangent to the surface at x_i, A_ij the area
 * of the faces sharing edge ij. Gaussian curvature from the angle deficit (Meyer 2003, eq. 9);
 * k1, k2 = H +- sqrt(max(0, H^2 - K)). Normals: Max 1999 weights (exact on a sphere). */
#include <stdlib.h>

#include "mesh/internal.h"

void mesh_garimella_vertex(const mesh_vertex_job *j, uint32_t v)
{
    const double *P = j->mesh->positions, n[3] = {j->normals[3 * v], j->normals[3 * v + 1], j->normals[3 * v + 2]};
    lucent_curvature *o = j->out;
    double sum = 0, wsum = 0, e1[3], e2[3], x[3], d[3];
    for (uint32_t a = j->adj->start[v]; a < j->adj->start[v + 1]; a++) {
        uint32_t other[2];
        mesh_slot_others(j->mesh->faces, j->adj->corner[a], other, other + 1);
        v3_sub(P + 3 * other[0], P + 3 * v, e1), v3_sub(P + 3 * other[1], P + 3 * v, e2);
        v3_cross(e1, e2, x);
        double area = 0.5 * v3_len(x);
        if (!(area > 0)) continue;
        for (int k = 1; k <= 2; k++) {
            v3_sub(P + 3 * v, P + 3 * other[k - 1], d);
            sum += area * 2 * v3_dot(d, n) / v3_dot(d, d), wsum += area;
        }
    }
    int boundary = o->flags[v] & LUCENT_CURVATURE_BOUNDARY;
    double mixed;
    double K = mesh_angle_deficit_gauss(j->mesh, j->adj, v, boundary, &mixed);
    if (!(wsum > 0) || !(mixed > 0) || v3_dot(n, n) == 0) {
        o->flags[v] |= LUCENT_CURVATURE_INVALID;
        return;
    }
    double H = sum / wsum, disc = sqrt(fmax(0, H * H - K));
    o->mean[v] = H, o->gauss[v] = K, o->k1[v] = H + disc, o->k2[v] = H - disc;
}
