/* The area-weighted normal-curvature estimate (Garimella & Swartz 2003, as used by the CDRF
 * blog): H_i = sum_j A_ij k_ij / sum_j A_ij with k_ij = 2 (x_i - x_j) . n_i / |x_i - x_j|^2,
 * the normal curvature of the circle through x_j tangent to the surface at x_i, A_ij the area
 * of the faces sharing edge ij. Gaussian curvature from the angle deficit (Meyer 2003, eq. 9);
 * k1, k2 = H +- sqrt(max(0, H^2 - K)). Normals: Max 1999 weights (exact on a sphere). */
#include <stdlib.h>

#include "mesh/internal.h"

void mesh_garimella_vertex(const mesh_vertex_job *j, uint32_t v)
{
    const double *P = j->mesh->positions, *p = P + 3 * (size_t)v;
    const float *nf = j->normals + 3 * (size_t)v;
    lucent_curvature *o = j->out;
    double sum = 0, wsum = 0;
    for (uint32_t a = j->adj->start[v]; a < j->adj->start[v + 1]; a++) {
        uint32_t i = j->adj->corner[a], other[2];
        const mesh_face_geometry *f = j->geometry + i / 3;
        double area = (double)f->corner[0] + f->corner[1] + f->corner[2]; /* the face's */
        mesh_slot_others(j->mesh->faces, i, other, other + 1);
        for (int k = 0; k < 2; k++) {
            const double *q = P + 3 * (size_t)other[k];
            v3 d = v3_sub(v3_load(p), v3_load(q));
            double dd = v3_dot(d, d);
            if (!(area > 0) || !(dd > 0)) continue;
            sum += area * 2 * (d.x * nf[0] + d.y * nf[1] + d.z * nf[2]) / dd, wsum += area;
        }
    }
    int boundary = o->flags[v] & LUCENT_CURVATURE_BOUNDARY;
    double mixed;
    double K = mesh_angle_deficit_gauss(j, v, boundary, &mixed);
    if (!(wsum > 0) || !(mixed > 0) || (nf[0] == 0 && nf[1] == 0 && nf[2] == 0)) {
        o->flags[v] |= LUCENT_CURVATURE_INVALID;
        return;
    }
    double H = sum / wsum, disc = sqrt(fmax(0, H * H - K));
    o->mean[v] = H, o->gauss[v] = K, o->k1[v] = H + disc, o->k2[v] = H - disc;
}
