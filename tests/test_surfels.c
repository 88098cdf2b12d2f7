/* Tests of the surfels (lucent/surfels.h). Expected values from the geometry of the inputs:
 *   a square grid of spacing s: every interior point has 4 neighbours at s and 4 at s sqrt(2), so the
 *   radius from the 8 nearest is s sqrt(2) and from the 4 nearest s;
 *   coverage: a point of the surface is covered when it lies within some surfel's radius of its
 *   centre (the disks of a surface without holes cover every point of it);
 *   levels: on a plane, cells of twice the spacing hold four grid points, so each level has about a
 *   quarter of the surfels of the one below and twice its spacing. */
#include "lucent/surfels.h"
#include "test.h"

static float *grid_points(int n, double s, float **normals)
{
    float *p = malloc(3 * (size_t)n * n * sizeof *p);
    *normals = malloc(3 * (size_t)n * n * sizeof **normals);
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
            size_t i = (size_t)y * n + x;
            p[3 * i] = (float)(x * s), p[3 * i + 1] = (float)(y * s), p[3 * i + 2] = 0;
            (*normals)[3 * i] = 0, (*normals)[3 * i + 1] = 0, (*normals)[3 * i + 2] = 1;
        }
    return p;
}

TEST(grid_radii)
{
    const int n = 40;
    const double s = 0.25;
    float *nrm, *pos = grid_points(n, s, &nrm);
    int ks[2] = {8, 4};
    double expect[2] = {s * sqrt(2.0), s};
    for (int t = 0; t < 2; t++) {
        lucent_surfels *sf = NULL;
        lucent_surfels_desc d = {.neighbours = ks[t], .max_levels = 1};
        CHECK_OK(lucent_surfels_from_points((size_t)n * n, pos, nrm, NULL, NULL, &d, &sf));
        if (!sf) continue;
        CHECK(sf->count == (size_t)n * n && sf->level_count == 1);
        int bad = 0;
        for (int y = 1; y < n - 1; y++)
            for (int x = 1; x < n - 1; x++) bad += fabs(sf->radii[y * n + x] - expect[t]) > 1e-5;
        CHECK_MSG(bad == 0, "k %d: %d interior radii differ from %g", ks[t], bad, expect[t]);
        CHECK_NEAR(sf->levels[0].spacing, expect[t] / sqrt(2.0), 1e-5);
        lucent_surfels_destroy(sf);
    }
    free(pos), free(nrm);
}

/* The fraction of test points of the square [lo, hi]^2 (z = 0) covered by no surfel of level l. */
static double uncovered(const lucent_surfels *sf, int l, double lo, double hi, int samples)
{
    const lucent_surfel_level *lv = &sf->levels[l];
    int holes = 0;
    for (int t = 0; t < samples; t++) {
        double u = lo + (hi - lo) * ((t * 0.618033988749895) - floor(t * 0.618033988749895));
        double v = lo + (hi - lo) * ((t * 0.754877666246693) - floor(t * 0.754877666246693));
        bool in = false;
        for (size_t i = lv->first; i < lv->first + lv->count && !in; i++) {
            double dx = sf->positions[3 * i] - u, dy = sf->positions[3 * i + 1] - v;
            in = dx * dx + dy * dy <= (double)sf->radii[i] * sf->radii[i];
        }
        holes += !in;
    }
    return (double)holes / samples;
}

/* A jittered grid with 30% of the points removed at random: every level covers the plane. */
TEST(coverage_with_holes)
{
    const int n = 60;
    float *nrm, *pos = grid_points(n, 1.0, &nrm);
    size_t kept = 0;
    uint64_t h = 12345;
    for (size_t i = 0; i < (size_t)n * n; i++) {
        h = h * 6364136223846793005ull + 1442695040888963407ull;
        double r1 = (double)(h >> 11) / 9007199254740992.0;
        h = h * 6364136223846793005ull + 1442695040888963407ull;
        double r2 = (double)(h >> 11) / 9007199254740992.0;
        if (r1 < 0.3) continue;
        pos[3 * kept] = pos[3 * i] + (float)(0.3 * (r2 - 0.5)),
                pos[3 * kept + 1] = pos[3 * i + 1] + (float)(0.3 * (r1 - 0.65));
        pos[3 * kept + 2] = 0;
        kept++;
    }
    lucent_surfels *sf = NULL;
    CHECK_OK(lucent_surfels_from_points(kept, pos, nrm, NULL, NULL, NULL, &sf));
    if (sf) {
        CHECK(sf->level_count >= 3);
        for (int l = 0; l < sf->level_count && l < 4; l++) {
            double frac = uncovered(sf, l, 5, n - 6, 4000);
            CHECK_MSG(frac == 0, "level %d (%zu surfels): %.4f of the plane uncovered", l, sf->levels[l].count, frac);
        }
    }
    lucent_surfels_destroy(sf);
    free(pos), free(nrm);
}

TEST(levels_and_children)
{
    const int n = 64;
    float *nrm, *pos = grid_points(n, 0.5, &nrm);
    lucent_surfels *sf = NULL;
    lucent_surfels_desc d = {.decimation = 2, .min_count = 16};
    CHECK_OK(lucent_surfels_from_points((size_t)n * n, pos, nrm, NULL, NULL, &d, &sf));
    if (!sf) return;
    CHECK(sf->level_count >= 4);
    for (int l = 1; l < sf->level_count && l < 4; l++) {
        const lucent_surfel_level *a = &sf->levels[l - 1], *b = &sf->levels[l];
        double ratio = (double)a->count / (double)b->count;
        CHECK_MSG(ratio > 3 && ratio < 5, "level %d: %zu -> %zu surfels (a quarter expected)", l, a->count, b->count);
        CHECK_MSG(b->spacing / a->spacing > 1.5 && b->spacing / a->spacing < 2.6, "level %d: spacing %g -> %g", l,
                  a->spacing, b->spacing);
    }
    /* every surfel of level l >= 1 lists children whose parent it is; every child appears once */
    size_t listed = 0;
    int bad = 0;
    for (int l = 1; l < sf->level_count; l++)
        for (size_t c = sf->levels[l].first; c < sf->levels[l].first + sf->levels[l].count; c++) {
            bad += sf->child_start[c + 1] <= sf->child_start[c];
            for (uint32_t k = sf->child_start[c]; k < sf->child_start[c + 1]; k++, listed++) {
                uint32_t ch = sf->children[k];
                bad += sf->parent[ch] != c || ch < sf->levels[l - 1].first ||
                       ch >= sf->levels[l - 1].first + sf->levels[l - 1].count;
            }
        }
    CHECK_MSG(bad == 0, "%d bad parent/children links", bad);
    CHECK(listed == sf->count - sf->levels[sf->level_count - 1].count);
    for (size_t i = 0; i < sf->count; i++) bad += fabs(sf->normals[3 * i + 2] - 1) > 1e-6 || !(sf->radii[i] > 0);
    CHECK_MSG(bad == 0, "normals of a plane stay (0, 0, 1), radii > 0");
    lucent_surfels_destroy(sf);
    free(pos), free(nrm);
}

TEST(threads_give_the_same_surfels)
{
    lucent_primitive_desc pd = {.kind = LUCENT_PRIMITIVE_ICOSPHERE, .radius = 10, .subdivisions = 4};
    lucent_mesh *m = NULL;
    CHECK_OK(lucent_mesh_primitive(&pd, &m));
    if (!m) return;
    lucent_surfels *a = NULL, *b = NULL;
    lucent_pool *one = lucent_pool_create(1), *two = lucent_pool_create(2);
    CHECK_OK(lucent_surfels_from_mesh(m, &(lucent_surfels_desc){.pool = one}, &a));
    CHECK_OK(lucent_surfels_from_mesh(m, &(lucent_surfels_desc){.pool = two}, &b));
    if (a && b) {
        CHECK(a->levels[0].count == m->vertex_count);
        CHECK(a->count == b->count && a->level_count == b->level_count);
        CHECK(!memcmp(a->positions, b->positions, 3 * a->count * sizeof(float)));
        CHECK(!memcmp(a->radii, b->radii, a->count * sizeof(float)));
        CHECK(!memcmp(a->normals, b->normals, 3 * a->count * sizeof(float)));
        /* coverage of the sphere: points on it lie within a radius of some surfel of each level */
        for (int l = 0; l < a->level_count && l < 3; l++) {
            int holes = 0;
            for (int t = 0; t < 500; t++) {
                double z = 1 - 2 * (t + 0.5) / 500, phi = t * 2.399963229728653, rr = sqrt(1 - z * z);
                double p[3] = {10 * rr * cos(phi), 10 * rr * sin(phi), 10 * z};
                bool in = false;
                for (size_t i = a->levels[l].first; i < a->levels[l].first + a->levels[l].count && !in; i++) {
                    double d2 = 0;
                    for (int k = 0; k < 3; k++)
                        d2 += (a->positions[3 * i + k] - p[k]) * (a->positions[3 * i + k] - p[k]);
                    in = d2 <= (double)a->radii[i] * a->radii[i];
                }
                holes += !in;
            }
            CHECK_MSG(holes == 0, "level %d: %d of 500 sphere points uncovered", l, holes);
        }
    }
    lucent_surfels_destroy(a), lucent_surfels_destroy(b);
    lucent_pool_destroy(one), lucent_pool_destroy(two);
    lucent_mesh_destroy(m);
}

TEST(bad_points)
{
    float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, nrm[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1}, r[3] = {1, 1, 1};
    lucent_surfels *sf = NULL;
    CHECK_ERR(lucent_surfels_from_points(1, pos, nrm, NULL, NULL, NULL, &sf), LUCENT_ERR_INVALID_ARGUMENT,
              "two points");
    CHECK_ERR(lucent_surfels_from_points(0, pos, nrm, NULL, NULL, NULL, &sf), LUCENT_ERR_INVALID_ARGUMENT,
              "two points");
    pos[4] = NAN;
    CHECK_ERR(lucent_surfels_from_points(3, pos, nrm, NULL, NULL, NULL, &sf), LUCENT_ERR_INVALID_ARGUMENT, "point 1",
              "not finite");
    pos[4] = 0, nrm[8] = 0;
    CHECK_ERR(lucent_surfels_from_points(3, pos, nrm, NULL, NULL, NULL, &sf), LUCENT_ERR_INVALID_ARGUMENT, "point 2",
              "normal is zero");
    nrm[8] = 1, r[1] = 0;
    CHECK_ERR(lucent_surfels_from_points(3, pos, nrm, r, NULL, NULL, &sf), LUCENT_ERR_INVALID_ARGUMENT, "point 1",
              "radius");
    CHECK(sf == NULL);
    r[1] = 1;
    CHECK_OK(lucent_surfels_from_points(3, pos, nrm, r, NULL, NULL, &sf));
    if (sf) CHECK(sf->radii[1] == 1);
    lucent_surfels_destroy(sf);
}

TEST_MAIN(TEST_ENTRY(grid_radii), TEST_ENTRY(coverage_with_holes), TEST_ENTRY(levels_and_children),
          TEST_ENTRY(threads_give_the_same_surfels), TEST_ENTRY(bad_points))
