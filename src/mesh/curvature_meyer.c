/* Meyer, Desbrun, Schroder & Barr 2003, "Discrete differential-geometry operators for
 * triangulated 2-manifolds": mean curvature from the cotangent Laplacian over the mixed
 * Voronoi area (eq. 8 with Fig. 4's areas), Gaussian curvature from the angle deficit (eq. 9),
 * principal curvatures k = H +- sqrt(max(0, H^2 - K)) (eq. 10, the root clamped at 0). */
#include <stdlib.h>

#include "mesh/internal.h"

static const uint8_t k_next[3] = {1, 2, 0}, k_prev[3] = {2, 0, 1};

/* The exact sum, one atan2 per corner (fans of more than 44 faces). */
static double angle_sum_exact(const mesh_face_geometry *g, const uint32_t *slot, uint32_t count)
{
    double sum = 0;
    for (uint32_t a = 0; a < count; a++) {
        const mesh_face_geometry *f = g + slot[a] / 3;
        if (f->corner[slot[a] % 3] > 0) sum += atan2(1, f->cot[slot[a] % 3]);
    }
    return sum;
}

/* The angle sum as the argument of the product of the corners' (cot, 1) = |.| (cos, sin): one
 * atan2 a vertex instead of one a corner. The argument is known modulo 2 pi; the number of turns
 * comes from an estimate of each angle, pi/2 (1 - cot/(1 + |cot|)), within 0.071 of it, so it is
 * exact for fans of up to 44 faces. Each factor is divided by 1 + |cot| >= |(cot, 1)|, which
 * keeps the product's size between 2^(-n/2) and 1. */
double mesh_angle_sum(const mesh_face_geometry *g, const uint32_t *slot, uint32_t count)
{
    if (count > 44) return angle_sum_exact(g, slot, count);
    double re = 1, im = 0, estimate = 0;
    for (uint32_t a = 0; a < count; a++) {
        const mesh_face_geometry *f = g + slot[a] / 3;
        double c = f->cot[slot[a] % 3], q = 1 / (1 + fabs(c)), valid = f->corner[slot[a] % 3] > 0;
        double zr = valid ? c * q : 1, zi = valid * q, r = re * zr - im * zi; /* zero area: angle 0 */
        im = re * zi + im * zr, re = r, estimate += valid * (0.5 * M_PI) * (1 - c * q);
    }
    double d = (atan2(im, re) - estimate) * (0.5 / M_PI), turns = (double)(long)(d + 128.5) - 128;
    return estimate + (d - turns) * (2 * M_PI);
}

double mesh_angle_deficit_gauss(const mesh_vertex_job *j, uint32_t v, int boundary, double *area)
{
    const uint32_t *slot = j->adj->corner + j->adj->start[v];
    uint32_t count = j->adj->start[v + 1] - j->adj->start[v];
    *area = 0;
    for (uint32_t a = 0; a < count; a++) *area += j->geometry[slot[a] / 3].corner[slot[a] % 3];
    return *area > 0 ? ((boundary ? M_PI : 2 * M_PI) - mesh_angle_sum(j->geometry, slot, count)) / *area : 0;
}

/* Accumulates the cotangent Laplacian of v over its faces (eq. 8's sum of (cot alpha + cot
 * beta)(x_i - x_j), face by face: each face gives the edge to its next vertex the cotangent at its
 * previous one, and the other way round). */
static void cot_laplacian(const mesh_vertex_job *j, uint32_t v, double *lap)
{
    const double *P = j->mesh->positions, *pi = P + 3 * (size_t)v;
    lap[0] = lap[1] = lap[2] = 0;
    for (uint32_t a = j->adj->start[v]; a < j->adj->start[v + 1]; a++) {
        uint32_t i = j->adj->corner[a], vj, vk;
        const mesh_face_geometry *f = j->geometry + i / 3;
        double cot_j = f->cot[k_next[i % 3]], cot_k = f->cot[k_prev[i % 3]];
        mesh_slot_others(j->mesh->faces, i, &vj, &vk);
        const double *pj = P + 3 * (size_t)vj, *pk = P + 3 * (size_t)vk;
        for (int c = 0; c < 3; c++) lap[c] += cot_k * (pi[c] - pj[c]) + cot_j * (pi[c] - pk[c]);
    }
}

void mesh_meyer_vertex(const mesh_vertex_job *j, uint32_t v)
{
    lucent_curvature *o = j->out;
    int boundary = o->flags[v] & LUCENT_CURVATURE_BOUNDARY;
    double area, lap[3];
    double K = mesh_angle_deficit_gauss(j, v, boundary, &area);
    if (!(area > 0)) {
        o->flags[v] |= LUCENT_CURVATURE_INVALID;
        return;
    }
    cot_laplacian(j, v, lap);
    /* K(x) = lap / (2 A) = 2 H n: H = |lap| / (4 A), signed by the side of the normal. */
    double H = v3_length(v3_load(lap)) / (4 * area);
    const float *n = j->normals + 3 * (size_t)v;
    if (lap[0] * n[0] + lap[1] * n[1] + lap[2] * n[2] < 0) H = -H;
    double disc = sqrt(fmax(0, H * H - K));
    o->mean[v] = H, o->gauss[v] = K, o->k1[v] = H + disc, o->k2[v] = H - disc;
}
