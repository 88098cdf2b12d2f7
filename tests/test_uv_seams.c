/* Texture seams (src/mesh/uv_seams.c): a flat plane cut along a diagonal into two charts, the second
 * turned by 90 degrees and scaled by 0.5 in texture space (then also sheared and scaled unevenly, as a
 * planar projection of a slanted face would be). Each texel near the seam is mapped to the
 * chart across it; the expected point is the same surface point, found here from the two charts'
 * analytic texture maps (inverted by hand), not from the library's edge frames. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/mesh.h"
#include "test.h"

enum { N = 40, SIZE = 512 };
static const double K = 0.015; /* chart A: texture units per mm; chart B: half of it */
static bool g_sheared;         /* chart B's v: K/4 (x + 20) + K/10 (20 - z) instead of K/2 (x + 20) */

/* The plane y = 0, x, z in [-20, 20] mm, N x N quads cut along their anti-diagonals; faces with
 * x + z < 0 in chart A (u, v) = 0.02 + K (x + 20, z + 20), the others in chart B, turned by 90
 * degrees: (u, v) = (0.66 + K/2 (20 - z), 0.02 + K/2 (x + 20)). */
static void chart_a(double x, double z, double *uv) { uv[0] = 0.02 + K * (x + 20), uv[1] = 0.02 + K * (z + 20); }
static void chart_b(double x, double z, double *uv)
{
    uv[0] = 0.66 + 0.5 * K * (20 - z);
    uv[1] = g_sheared ? 0.02 + 0.25 * K * (x + 20) + 0.1 * K * (20 - z) : 0.02 + 0.5 * K * (x + 20);
}
/* The inverses, from texel coordinates to (x, z) mm. */
static void from_a(double tx, double ty, double *p)
{
    p[0] = (tx / SIZE - 0.02) / K - 20, p[1] = (ty / SIZE - 0.02) / K - 20;
}
static void from_b(double tx, double ty, double *p)
{
    p[1] = 20 - (tx / SIZE - 0.66) / (0.5 * K);
    p[0] =
        g_sheared ? (ty / SIZE - 0.02 - 0.1 * K * (20 - p[1])) / (0.25 * K) - 20 : (ty / SIZE - 0.02) / (0.5 * K) - 20;
}
static bool in_a_half(double tx) { return tx / SIZE < 0.64; } /* A's box lies left of u = 0.64, B's right */

static lucent_mesh *two_chart_plane(void)
{
    lucent_mesh *m = NULL;
    CHECK_OK(lucent_mesh_create((N + 1) * (N + 1), 2 * N * N, &m));
    if (!m) return NULL;
    m->uvs = malloc(12 * N * N * sizeof *m->uvs);
    for (int j = 0; j <= N; j++)
        for (int i = 0; i <= N; i++) {
            double *p = m->positions + 3 * (j * (N + 1) + i);
            p[0] = -20 + 40.0 * i / N, p[1] = 0, p[2] = -20 + 40.0 * j / N;
        }
    size_t f = 0;
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            uint32_t v00 = (uint32_t)(j * (N + 1) + i), v10 = v00 + 1, v01 = v00 + N + 1, v11 = v01 + 1;
            uint32_t tri[2][3] = {{v00, v01, v10}, {v10, v01, v11}};
            for (int t = 0; t < 2; t++, f++) {
                double cx = 0, cz = 0;
                for (int k = 0; k < 3; k++)
                    cx += m->positions[3 * tri[t][k]] / 3, cz += m->positions[3 * tri[t][k] + 2] / 3;
                for (int k = 0; k < 3; k++) {
                    m->faces[3 * f + k] = tri[t][k];
                    const double *p = m->positions + 3 * tri[t][k];
                    (cx + cz < 0 ? chart_a : chart_b)(p[0], p[2], m->uvs + 6 * f + 2 * k);
                }
            }
        }
    return m;
}

static void check_seam_map(bool sheared)
{
    g_sheared = sheared;
    lucent_mesh *m = two_chart_plane();
    if (!m) return;
    lucent_uv_seams s = {0};
    size_t charts = 0;
    uint32_t chart[2 * N * N];
    CHECK_OK(lucent_mesh_uv_charts(m, chart, &charts));
    CHECK(charts == 2);
    CHECK_OK(lucent_mesh_uv_seams(m, SIZE, 2, &s));
    double worst = 0, worst_j = 0;
    for (size_t i = 0; i < s.count; i++) {
        const lucent_uv_seam_texel *t = &s.texels[i];
        double cx = t->x + 0.5, cy = t->y + 0.5, here[2], there[2], step_here[2], step_there[2];
        bool a = in_a_half(cx);
        CHECK(t->chart != t->across);
        (a ? from_a : from_b)(cx, cy, here);
        (a ? from_b : from_a)(t->target[0], t->target[1], there);
        worst = fmax(worst, hypot(here[0] - there[0], here[1] - there[1]));
        for (int d = 0; d < 2; d++) { /* one texel along x, then y, here and J of it there */
            double dx = d == 0, dy = d == 1;
            (a ? from_a : from_b)(cx + dx, cy + dy, step_here);
            (a ? from_b : from_a)(t->target[0] + t->jacobian[0] * dx + t->jacobian[1] * dy,
                                  t->target[1] + t->jacobian[2] * dx + t->jacobian[3] * dy, step_there);
            for (int c = 0; c < 2; c++)
                worst_j = fmax(worst_j, fabs((step_here[c] - here[c]) - (step_there[c] - there[c])));
        }
    }
    /* every texel whose centre lies 0.2 .. 1.5 texels outside a chart along the seam (away from the
     * plane's corners) is mapped: the seam x + z = 0 at x = -18 .. 18 mm, stepped outward */
    size_t missing = 0, probes = 0;
    for (int side = 0; side < 2; side++)
        for (double x = -18; x <= 18; x += 0.05)
            for (double out = 0.2; out <= 1.5; out += 0.1, probes++) {
                /* d mm along x and z, (1, 1) out of A or back out of B: `out` texels in that chart */
                double uv[2], o0[2], o1[2];
                (side ? chart_b : chart_a)(0, 0, o0), (side ? chart_b : chart_a)(side ? -1 : 1, side ? -1 : 1, o1);
                double d = out / (SIZE * hypot(o1[0] - o0[0], o1[1] - o0[1]));
                if (side == 0)
                    chart_a(x + d, -x + d, uv); /* A's side: outward is x + z > 0 */
                else
                    chart_b(x - d, -x - d, uv);
                uint32_t tx = (uint32_t)(uv[0] * SIZE), ty = (uint32_t)(uv[1] * SIZE);
                bool found = false;
                for (size_t i = 0; i < s.count && !found; i++)
                    found = s.texels[i].x == tx && s.texels[i].y == ty && in_a_half(tx + 0.5) == (side == 0);
                missing += !found;
            }
    printf("  %s: %zu seam texels at %d^2: the mapped point off the same surface point by at most %.2g mm, a texel's "
           "step by %.2g mm; %zu of %zu probes outside the seam unmapped\n",
           sheared ? "B sheared" : "B turned and scaled", s.count, SIZE, worst, worst_j, missing, probes);
    CHECK(s.count > 0);
    CHECK_MSG(worst < 1e-3, "%.3g mm", worst); /* float texel coordinates: about 1e-5 mm */
    CHECK_MSG(worst_j < 1e-4, "%.3g mm", worst_j);
    CHECK(missing == 0);
    lucent_uv_seams_free(&s);
    lucent_mesh_destroy(m);
}

TEST(seam_texels_map_to_the_same_surface_point)
{
    check_seam_map(false);
    check_seam_map(true);
    g_sheared = false;
    lucent_mesh *m = two_chart_plane();
    if (!m) return;
    lucent_uv_seams s = {0};
    CHECK_ERR(lucent_mesh_uv_seams(m, SIZE, 0, &s), LUCENT_ERR_INVALID_ARGUMENT, "reach");
    free(m->uvs), m->uvs = NULL;
    CHECK_ERR(lucent_mesh_uv_seams(m, SIZE, 2, &s), LUCENT_ERR_INVALID_ARGUMENT, "no texture coordinates");
    lucent_mesh_destroy(m);
}

/* One chart without seams maps nothing (boundary edges have no face across). */
TEST(no_seams_no_texels)
{
    lucent_mesh *m = two_chart_plane();
    if (!m) return;
    for (size_t f = 0; f < m->face_count; f++)
        for (int k = 0; k < 3; k++) {
            const double *p = m->positions + 3 * m->faces[3 * f + k];
            chart_a(p[0], p[2], m->uvs + 6 * f + 2 * k);
        }
    lucent_uv_seams s = {0};
    CHECK_OK(lucent_mesh_uv_seams(m, SIZE, 2, &s));
    CHECK(s.count == 0);
    lucent_uv_seams_free(&s);
    lucent_mesh_destroy(m);
}

TEST_MAIN(TEST_ENTRY(seam_texels_map_to_the_same_surface_point), TEST_ENTRY(no_seams_no_texels))
