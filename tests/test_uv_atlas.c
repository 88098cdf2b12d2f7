/* Texture coordinates of meshes: the UV sphere's analytic ones, OBJ and glTF round trips, Loop
 * subdivision, and Lucent's atlas of the Stanford scans (no overlap, gutters, stretch), all checked
 * with a rasteriser written here, apart from the library's. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lucent/mesh.h"
#include "test.h"

static const char *sample(const char *name)
{
    static char buf[1024];
    snprintf(buf, sizeof buf, "%s/data/meshes/%s", LUCENT_SOURCE_DIR, name);
    if (access(buf, R_OK) != 0) {
        printf("  note: %s absent (make setup fetches it); skipped\n", buf);
        return NULL;
    }
    return buf;
}

/* On a UV sphere of radius R every non-pole corner sits at phi = 2 pi u, theta = pi (1 - v). */
TEST(uv_sphere_coordinates_analytic)
{
    lucent_mesh *m;
    CHECK_OK(lucent_mesh_primitive(
        &(lucent_primitive_desc){.kind = LUCENT_PRIMITIVE_UV_SPHERE, .radius = 2, .u_count = 256, .v_count = 128}, &m));
    CHECK(m->uvs != NULL);
    double worst = 0;
    for (size_t i = 0; i < 3 * m->face_count; i++) {
        uint32_t v = m->faces[i];
        if (v == 0 || v == m->vertex_count - 1) continue;
        double u = m->uvs[2 * i], w = m->uvs[2 * i + 1], phi = 2 * M_PI * u, th = M_PI * (1 - w);
        const double *p = m->positions + 3 * v;
        double d = fabs(p[0] - 2 * sin(th) * cos(phi)) + fabs(p[1] - 2 * sin(th) * sin(phi)) + fabs(p[2] - 2 * cos(th));
        worst = fmax(worst, d);
        CHECK(u >= 0 && u <= 1 && w >= 0 && w <= 1);
    }
    CHECK_MSG(worst < 1e-12, "corner off its analytic point by %g", worst);
    /* Sander et al.'s L2 stretch of the latitude-longitude map: |dq/du| = 2 pi R sin(theta),
     * |dq/dv| = pi R, mean of sin^2 over the sphere 2/3, so L2^2 = (4 pi^2 R^2 2/3 + pi^2 R^2) / 2
     * / (4 pi R^2) = 11 pi / 24: L2 = 1.19996 (the mesh's facets differ slightly). */
    lucent_uv_stats st;
    CHECK_OK(lucent_mesh_uv_stats_compute(m, &st));
    printf("  uv sphere 256x128: L2 stretch %.5f (continuous sphere %.5f)\n", st.stretch_l2, sqrt(11 * M_PI / 24));
    CHECK_NEAR(st.stretch_l2, sqrt(11 * M_PI / 24), 0.01);
    CHECK(st.flipped_faces == 0 || st.flipped_faces == m->face_count); /* one orientation */
    lucent_mesh_destroy(m);
}

static void check_same_uvs(const lucent_mesh *a, const lucent_mesh *b, double tol)
{
    CHECK(a->face_count == b->face_count && b->uvs != NULL);
    if (a->face_count != b->face_count || !b->uvs) return;
    double worst = 0;
    for (size_t i = 0; i < 6 * a->face_count; i++) worst = fmax(worst, fabs(a->uvs[i] - b->uvs[i]));
    CHECK_MSG(worst < tol, "corner coordinates differ by %g after the round trip", worst);
}

/* Written as OBJ and glTF, read back through assimp: the same corners (welded again by position). */
TEST(obj_and_gltf_round_trip)
{
    lucent_mesh *m, *back;
    CHECK_OK(lucent_mesh_primitive(
        &(lucent_primitive_desc){.kind = LUCENT_PRIMITIVE_TORUS, .u_count = 24, .v_count = 12}, &m));
    char obj[] = "/tmp/lucent-uv-XXXXXX.obj", gltf[] = "/tmp/lucent-uv-XXXXXX.gltf";
    int fd = mkstemps(obj, 4);
    close(fd);
    fd = mkstemps(gltf, 5);
    close(fd);
    CHECK_OK(lucent_mesh_write_obj(obj, m));
    CHECK_OK(lucent_mesh_load(obj, NULL, &back));
    if (back) {
        check_same_uvs(m, back, 1e-7);
        CHECK(back->vertex_count == m->vertex_count);
    }
    lucent_mesh_destroy(back);
    CHECK_OK(lucent_mesh_write_gltf(gltf, m));
    CHECK_OK(lucent_mesh_load(gltf, NULL, &back));
    if (back) {
        check_same_uvs(m, back, 1e-6);
        CHECK(back->vertex_count == m->vertex_count);
    }
    lucent_mesh_destroy(back);
    unlink(obj), unlink(gltf);
    lucent_mesh_destroy(m);
}

/* Loop subdivision keeps the coordinates (children at the parent's corners and edge midpoints). */
TEST(subdivision_interpolates_coordinates)
{
    lucent_mesh *m;
    CHECK_OK(lucent_mesh_primitive(
        &(lucent_primitive_desc){.kind = LUCENT_PRIMITIVE_UV_SPHERE, .u_count = 16, .v_count = 8}, &m));
    double parent[6];
    memcpy(parent, m->uvs, sizeof parent);
    CHECK_OK(lucent_mesh_subdivide(m, 1));
    CHECK(m->uvs != NULL);
    if (!m->uvs) return lucent_mesh_destroy(m);
    /* face 0's first child is (a, ab, ca) */
    CHECK_NEAR(m->uvs[0], parent[0], 1e-15);
    CHECK_NEAR(m->uvs[2], 0.5 * (parent[0] + parent[2]), 1e-15);
    CHECK_NEAR(m->uvs[5], 0.5 * (parent[5] + parent[1]), 1e-15);
    lucent_mesh_destroy(m);
}

/* ---- an independent rasteriser: texel centres inside a face (by 1e-3 texel) get its chart ---- */

typedef struct raster {
    int size;
    int32_t *chart; /* -1 empty */
    size_t overlaps;
} raster;

static void raster_mesh(const lucent_mesh *m, const uint32_t *chart, raster *r)
{
    int n = r->size;
    for (size_t i = 0; i < (size_t)n * n; i++) r->chart[i] = -1;
    r->overlaps = 0;
    for (size_t f = 0; f < m->face_count; f++) {
        const double *t = m->uvs + 6 * f;
        double x[3], y[3];
        for (int k = 0; k < 3; k++) x[k] = t[2 * k] * n, y[k] = t[2 * k + 1] * n;
        double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
        if (area == 0) continue;
        int x0 = (int)fmax(0, floor(fmin(x[0], fmin(x[1], x[2])))), x1 = (int)fmin(n - 1, fmax(x[0], fmax(x[1], x[2])));
        int y0 = (int)fmax(0, floor(fmin(y[0], fmin(y[1], y[2])))), y1 = (int)fmin(n - 1, fmax(y[0], fmax(y[1], y[2])));
        for (int py = y0; py <= y1; py++)
            for (int px = x0; px <= x1; px++) {
                double cx = px + 0.5, cy = py + 0.5, l[3];
                for (int k = 0; k < 3; k++) {
                    int a = (k + 1) % 3, b = (k + 2) % 3;
                    l[k] = ((x[b] - x[a]) * (cy - y[a]) - (y[b] - y[a]) * (cx - x[a])) / area *
                           hypot(x[b] - x[a], y[b] - y[a]);
                }
                if (l[0] <= 1e-3 || l[1] <= 1e-3 || l[2] <= 1e-3) continue;
                int32_t *c = &r->chart[(size_t)py * n + px];
                if (*c >= 0) r->overlaps++;
                *c = (int32_t)chart[f];
            }
    }
}

/* Texels of two charts closer than reach texels (Chebyshev): gutters not kept. */
static size_t gutter_violations(const raster *r, int reach)
{
    size_t bad = 0;
    int n = r->size;
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
            int32_t c = r->chart[(size_t)y * n + x];
            if (c < 0) continue;
            for (int dy = -reach; dy <= reach; dy++)
                for (int dx = -reach; dx <= reach; dx++) {
                    int qx = x + dx, qy = y + dy;
                    if (qx < 0 || qy < 0 || qx >= n || qy >= n) continue;
                    int32_t d = r->chart[(size_t)qy * n + qx];
                    bad += d >= 0 && d != c;
                }
        }
    return bad;
}

static void check_atlas(const char *name, int subdivide)
{
    const char *path = sample(name);
    if (!path) return;
    lucent_mesh *m;
    CHECK_OK(lucent_mesh_load(path, NULL, &m));
    if (!m) return;
    if (subdivide) CHECK_OK(lucent_mesh_subdivide(m, subdivide));
    lucent_uv_stats st;
    CHECK_OK(lucent_mesh_uv_atlas(m, NULL, &st));
    uint32_t *chart = malloc(m->face_count * sizeof *chart);
    size_t charts = 0;
    CHECK_OK(lucent_mesh_uv_charts(m, chart, &charts));
    raster r = {.size = 4096, .chart = malloc(4096 * 4096 * sizeof(int32_t))};
    raster_mesh(m, chart, &r);
    size_t covered = 0, library_overlaps = 1;
    for (size_t i = 0; i < 4096u * 4096u; i++) covered += r.chart[i] >= 0;
    CHECK_OK(lucent_mesh_uv_overlaps(m, 4096, &library_overlaps, NULL));
    /* the default gutter: two charts at least 4 texels apart at 1024, so texel centres of two charts
     * at least 4 / sqrt 2 > 2 texels apart along one axis */
    raster g = {.size = 1024, .chart = malloc(1024 * 1024 * sizeof(int32_t))};
    raster_mesh(m, chart, &g);
    size_t bad = gutter_violations(&g, 2);
    free(g.chart);
    double lo = 1, hi = 0;
    for (size_t i = 0; i < 6 * m->face_count; i++) lo = fmin(lo, m->uvs[i]), hi = fmax(hi, m->uvs[i]);
    printf("  %s%s: %zu faces, %zu charts (%zu by UV connectivity), L2 stretch %.4f, max %.3f, %zu flipped; at "
           "4096^2: %zu texels covered (%.1f%%), %zu in two faces; at 1024^2 %zu within the gutter of another chart\n",
           name, subdivide ? " subdivided" : "", m->face_count, st.chart_count, charts, st.stretch_l2, st.stretch_max,
           st.flipped_faces, covered, 100.0 * (double)covered / (4096.0 * 4096.0), r.overlaps, bad);
    CHECK(charts == st.chart_count);
    CHECK(r.overlaps == 0 && library_overlaps == 0);
    CHECK(bad == 0);
    CHECK(lo >= 0 && hi <= 1);
    CHECK(covered > 4096u * 4096u / 5); /* packed: at least a fifth of the square used */
    /* planar projection within the cone: each face's stretch at most 1 / cos 40 deg across its slope,
     * so the normalised L2 stays between 1 and that bound */
    CHECK(st.stretch_l2 >= 1 && st.stretch_l2 < 1 / cos(40 * M_PI / 180));
    CHECK(st.flipped_faces == 0);
    free(r.chart), free(chart);
    lucent_mesh_destroy(m);
}

TEST(atlas_bunny_no_overlap) { check_atlas("bunny.ply", 2); }

TEST(atlas_dragon_res2_no_overlap) { check_atlas("dragon_vrip_res2.ply.gz", 0); }

/* The overlap count sees a real overlap, and bad input is refused. */
TEST(overlaps_found_and_bad_input)
{
    lucent_mesh *m;
    CHECK_OK(lucent_mesh_create(4, 2, &m));
    double pos[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    uint32_t faces[6] = {0, 1, 2, 1, 3, 2};
    memcpy(m->positions, pos, sizeof pos), memcpy(m->faces, faces, sizeof faces);
    size_t over;
    CHECK_ERR(lucent_mesh_uv_overlaps(m, 64, &over, NULL), LUCENT_ERR_INVALID_ARGUMENT, "no texture coordinates");
    m->uvs = malloc(12 * sizeof *m->uvs);
    double uvs[12] = {0.1, 0.1, 0.9, 0.1, 0.1, 0.9, 0.1, 0.1, 0.9, 0.1, 0.1, 0.9}; /* both faces on one spot */
    memcpy(m->uvs, uvs, sizeof uvs);
    CHECK_OK(lucent_mesh_uv_overlaps(m, 64, &over, NULL));
    CHECK(over > 1000);                            /* half of 0.8^2 of 64^2 texels: about 1311 */
    CHECK_OK(lucent_mesh_uv_atlas(m, NULL, NULL)); /* the atlas separates them */
    CHECK_OK(lucent_mesh_uv_overlaps(m, 64, &over, NULL));
    CHECK(over == 0);
    CHECK_ERR(lucent_mesh_uv_atlas(m, &(lucent_uv_atlas_desc){.max_angle = 95}, NULL), LUCENT_ERR_INVALID_ARGUMENT,
              "max_angle");
    lucent_mesh_destroy(m);
}

TEST_MAIN(TEST_ENTRY(uv_sphere_coordinates_analytic), TEST_ENTRY(obj_and_gltf_round_trip),
          TEST_ENTRY(subdivision_interpolates_coordinates), TEST_ENTRY(atlas_bunny_no_overlap),
          TEST_ENTRY(atlas_dragon_res2_no_overlap), TEST_ENTRY(overlaps_found_and_bad_input))
