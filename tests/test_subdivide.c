/* Tests of Loop subdivision (src/mesh/subdivide.c). Expected values are Loop's masks worked out by
 * hand on shapes where they have a closed form: the regular icosahedron (valence 5), a regular
 * planar grid (linear precision) and a square's boundary (the cubic B-spline masks). */
#include <math.h>
#include <string.h>

#include "lucent/mesh.h"
#include "test.h"

/* The regular icosahedron on the unit sphere: vertices (0, +-1, +-phi) and their cyclic
 * permutations, normalised; faces are the 20 triples of mutually adjacent vertices (edge length
 * 2 before normalising), oriented outward. */
static lucent_mesh *icosahedron(void)
{
    double phi = 0.5 * (1 + sqrt(5.0)), r = sqrt(1 + phi * phi), p[12][3];
    for (int i = 0; i < 4; i++) {
        double a = (i & 1) ? -1 : 1, b = (i & 2) ? -phi : phi;
        double q[3][3] = {{0, a, b}, {a, b, 0}, {b, 0, a}};
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 3; j++) p[4 * k + i][j] = q[k][j] / r;
    }
    lucent_mesh *m;
    if (lucent_mesh_create(12, 20, &m) != LUCENT_OK) return NULL;
    memcpy(m->positions, p, sizeof p);
    double edge2 = 4 / (r * r);
    uint32_t *f = m->faces;
    for (uint32_t a = 0; a < 12; a++)
        for (uint32_t b = a + 1; b < 12; b++)
            for (uint32_t c = b + 1; c < 12; c++) {
                double d[3];
                int adjacent = 1;
                const double *x[3] = {p[a], p[b], p[c]};
                for (int e = 0; e < 3; e++) {
                    for (int j = 0; j < 3; j++) d[j] = x[e][j] - x[(e + 1) % 3][j];
                    adjacent &= fabs(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - edge2) < 1e-9;
                }
                if (!adjacent) continue;
                double u[3], v[3], n[3];
                for (int j = 0; j < 3; j++) u[j] = p[b][j] - p[a][j], v[j] = p[c][j] - p[a][j];
                n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2], n[2] = u[0] * v[1] - u[1] * v[0];
                bool out = n[0] * p[a][0] + n[1] * p[a][1] + n[2] * p[a][2] > 0;
                *f++ = a, *f++ = out ? b : c, *f++ = out ? c : b;
            }
    lucent_mesh_compute_normals(m);
    return m;
}

TEST(counts_and_closedness)
{
    /* V' = V + E, F' = 4 F; an icosahedron (12 vertices, 30 edges, 20 faces) stays closed. */
    lucent_mesh *m = icosahedron();
    if (!m) return;
    CHECK(m->vertex_count == 12 && m->face_count == 20 && m->faces[59] != 0); /* all 20 faces found */
    CHECK_OK(lucent_mesh_subdivide(m, 2));
    CHECK(m->vertex_count == 12 + 30 + 120 && m->face_count == 320); /* 42 vertices, 120 edges after one */
    lucent_mesh_stats st;
    CHECK_OK(lucent_mesh_stats_compute(m, &st));
    CHECK(st.boundary_edges == 0 && st.nonmanifold_edges == 0 && st.degenerate_faces == 0);
    for (size_t v = 0; v < m->vertex_count; v++) {
        const double *p = m->positions + 3 * v, *n = m->normals + 3 * v;
        CHECK(p[0] * n[0] + p[1] * n[1] + p[2] * n[2] > 0); /* orientation kept: normals outward */
    }
    lucent_mesh_destroy(m);
}

TEST(icosahedron_vertex_mask)
{
    /* An old vertex v of the unit icosahedron has 5 neighbours whose sum is sqrt(5) v (each at
     * v.w = 1/sqrt(5)), so Loop's even mask gives |v'| = 1 - 5 beta + sqrt(5) beta with
     * beta = (5/8 - (3/8 + cos(72 deg) / 4)^2) / 5. A new edge vertex between a and b (opposite
     * c and d) is 3/8 (a + b) + 1/8 (c + d); its length follows from the icosahedron's geometry,
     * computed here from the original vertices. */
    lucent_mesh *m = icosahedron(), *orig = icosahedron();
    if (!m || !orig) return;
    CHECK_OK(lucent_mesh_subdivide(m, 1));
    double c = 0.375 + 0.25 * cos(2 * M_PI / 5), beta = (0.625 - c * c) / 5;
    double want = 1 - 5 * beta + sqrt(5.0) * beta;
    for (size_t v = 0; v < 12; v++) {
        const double *p = m->positions + 3 * v;
        CHECK_NEAR(sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), want, 1e-12);
    }
    /* edge vertex of face 0's first edge */
    const uint32_t *f = orig->faces;
    const double *a = orig->positions + 3 * f[0], *b = orig->positions + 3 * f[1], *cc = orig->positions + 3 * f[2];
    double best = 1e300;
    for (size_t g = 1; g < orig->face_count; g++) { /* the other face on edge (a, b): its third vertex */
        const uint32_t *h = orig->faces + 3 * g;
        for (int k = 0; k < 3; k++)
            if (h[k] == f[1] && h[(k + 1) % 3] == f[0]) {
                const double *dd = orig->positions + 3 * h[(k + 2) % 3];
                double e[3];
                for (int i = 0; i < 3; i++) e[i] = 0.375 * (a[i] + b[i]) + 0.125 * (cc[i] + dd[i]);
                for (size_t v = 12; v < m->vertex_count; v++) {
                    const double *p = m->positions + 3 * v;
                    best = fmin(best, fabs(p[0] - e[0]) + fabs(p[1] - e[1]) + fabs(p[2] - e[2]));
                }
            }
    }
    CHECK_NEAR(best, 0, 1e-12);
    lucent_mesh_destroy(m);
    lucent_mesh_destroy(orig);
}

/* A planar regular grid of n x n quads split into triangles along one diagonal: valence 6 inside. */
static lucent_mesh *grid(int n)
{
    lucent_mesh *m;
    if (lucent_mesh_create((size_t)(n + 1) * (n + 1), (size_t)2 * n * n, &m) != LUCENT_OK) return NULL;
    for (int y = 0; y <= n; y++)
        for (int x = 0; x <= n; x++) {
            double *p = m->positions + 3 * (size_t)(y * (n + 1) + x);
            p[0] = x, p[1] = y, p[2] = 0.25 * x - 0.5 * y + 1; /* a tilted plane */
        }
    uint32_t *f = m->faces;
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
            uint32_t a = (uint32_t)(y * (n + 1) + x), b = a + 1, c = a + (uint32_t)n + 1, d = c + 1;
            uint32_t t[6] = {a, b, d, a, d, c};
            for (int k = 0; k < 6; k++) *f++ = t[k];
        }
    lucent_mesh_compute_normals(m);
    return m;
}

TEST(planar_grid_keeps_linear_functions)
{
    /* Loop's masks sum to 1 and are symmetric, so on a regular lattice they reproduce linear
     * functions: every new point of a tilted plane stays on it, interior old vertices stay put,
     * and boundary vertices move along the (straight) boundary only. */
    lucent_mesh *m = grid(4);
    if (!m) return;
    CHECK_OK(lucent_mesh_subdivide(m, 1));
    double worst = 0;
    for (size_t v = 0; v < m->vertex_count; v++) {
        const double *p = m->positions + 3 * v;
        worst = fmax(worst, fabs(p[2] - (0.25 * p[0] - 0.5 * p[1] + 1)));
    }
    CHECK_NEAR(worst, 0, 1e-12);
    const double *centre = m->positions + 3 * (2 * 5 + 2); /* old vertex (2, 2), valence 6 */
    CHECK_NEAR(centre[0], 2, 1e-12);
    CHECK_NEAR(centre[1], 2, 1e-12);
    lucent_mesh_destroy(m);
}

TEST(boundary_masks)
{
    /* A square of two triangles: every vertex is on the boundary. The old corner (0, 0), with
     * boundary neighbours (1, 0) and (0, 1), goes to 3/4 (0, 0) + 1/8 ((1, 0) + (0, 1)) = (1/8, 1/8);
     * the diagonal is interior: its new vertex is 3/8 ((1,0) + (0,1)) + 1/8 ((0,0) + (1,1)). */
    lucent_mesh *m;
    CHECK_OK(lucent_mesh_create(4, 2, &m));
    if (!m) return;
    static const double p[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    static const uint32_t f[6] = {0, 1, 2, 1, 3, 2};
    for (int i = 0; i < 12; i++) m->positions[i] = p[i];
    for (int i = 0; i < 6; i++) m->faces[i] = f[i];
    CHECK_OK(lucent_mesh_subdivide(m, 1));
    CHECK(m->vertex_count == 4 + 5 && m->face_count == 8);
    CHECK_NEAR(m->positions[0], 0.125, 1e-15);
    CHECK_NEAR(m->positions[1], 0.125, 1e-15);
    int found = 0;
    for (size_t v = 4; v < m->vertex_count; v++) /* 3/8 (1 + 0) + 1/8 (0 + 1) = 1/2 in x and y */
        found += fabs(m->positions[3 * v] - 0.5) < 1e-15 && fabs(m->positions[3 * v + 1] - 0.5) < 1e-15;
    CHECK(found == 1);
    lucent_mesh_destroy(m);
}

TEST(levels_are_checked)
{
    lucent_mesh *m = grid(1);
    if (!m) return;
    CHECK_ERR(lucent_mesh_subdivide(m, 7), LUCENT_ERR_INVALID_ARGUMENT, "[0, 6]");
    CHECK(m->vertex_count == 4); /* unchanged */
    CHECK_OK(lucent_mesh_subdivide(m, 0));
    CHECK(m->vertex_count == 4);
    lucent_mesh_destroy(m);
}

TEST_MAIN(TEST_ENTRY(counts_and_closedness), TEST_ENTRY(icosahedron_vertex_mask),
          TEST_ENTRY(planar_grid_keeps_linear_functions), TEST_ENTRY(boundary_masks), TEST_ENTRY(levels_are_checked))
