/* What the Rusinkiewicz estimator's files share: the per-face record and the per-face fit. */
#ifndef LUCENT_MESH_RUSINKIEWICZ_H
#define LUCENT_MESH_RUSINKIEWICZ_H

#include <stdint.h>

/* One face: its unit tangent t (along edge 0) and normal n, b = n x t completing the frame;
 * the tensor [[e, f], [f, g]] in (t, b) kept as mean = (e + g)/2, diff = (e - g)/2 and off = f,
 * because turning the frame by an angle phi keeps the mean and turns (diff, off) by 2 phi;
 * the three corner areas; edges 0 and 1 in (t, b) in units of edge 0's length L, (1, 0) and
 * (u1, w1) (edge 2 closes the triangle), and 1/L: all the second fit needs of the geometry.
 * Floats, one 64-byte line: the per-vertex gather reads them at random. */
typedef struct face_rec {
    float t[3], n[3];
    float mean, diff, off;
    float corner[3];
    float u1, w1, inv_len, unused;
} face_rec;

/* Fits the tensors of faces begin .. end - 1 to the vertex normals (3 floats per vertex, read
 * four at a time: the array holds one float more) and writes face f's (mean, diff, off) to
 * dest + stride f; zeros for a degenerate face (no corner area, or a singular fit). */
void mesh_rus_fit_faces(const uint32_t *faces, const float *normals, const face_rec *recs, uint64_t begin, uint64_t end,
                        float *dest, uint64_t stride);

#endif
