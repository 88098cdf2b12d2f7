/* Tests of the mesh module: import (PLY ASCII/binary/.gz, OBJ, glTF), welding, dirty scans,
 * primitives and curvature against analytic values. The expected curvatures come from
 * closed forms written out here (not from the library):
 *   sphere of radius R:  H = 1/R, K = 1/R^2;
 *   torus R, r at tube angle v (cos v = (rho - R)/r, rho = distance from the axis):
 *     k1 = 1/r, k2 = cos v/(R + r cos v), H = (R + 2 r cos v)/(2 r (R + r cos v)) (do Carmo 3-3);
 *   ellipsoid a, b, c with W = x^2/a^4 + y^2/b^4 + z^2/c^4:
 *     K = 1/(a^2 b^2 c^2 W^2), H = (a^2 + b^2 + c^2 - |p|^2)/(2 a^2 b^2 c^2 W^(3/2)). */
#include <zlib.h>

#include "lucent/image.h"
#include "lucent/mesh.h"
#include "test.h"

static const char *fixture(const char *name)
{
    static char buf[2][1024];
    static int k;
    k ^= 1;
    snprintf(buf[k], sizeof buf[k], "%s/tests/fixtures/mesh/%s", LUCENT_SOURCE_DIR, name);
    return buf[k];
}

static const char *sample(const char *name)
{
    static char buf[1024];
    snprintf(buf, sizeof buf, "%s/data/meshes/%s", LUCENT_SOURCE_DIR, name);
    FILE *f = fopen(buf, "rb");
    if (!f) {
        printf("  note: %s absent (make setup fetches it); skipped\n", buf);
        return NULL;
    }
    fclose(f);
    return buf;
}

/* ---- analytic curvature (see the header comment) ---- */

static double torus_mean(double R, double r, const double *p)
{
    double rho = hypot(p[0], p[1]), cv = (rho - R) / r;
    return (R + 2 * r * cv) / (2 * r * (R + r * cv));
}

static double torus_gauss(double R, double r, const double *p)
{
    double rho = hypot(p[0], p[1]), cv = (rho - R) / r;
    return cv / (r * (R + r * cv));
}

static void ellipsoid_hk(const double *ax, const double *p, double *H, double *K)
{
    double a2 = ax[0] * ax[0], b2 = ax[1] * ax[1], c2 = ax[2] * ax[2];
    double w = p[0] * p[0] / (a2 * a2) + p[1] * p[1] / (b2 * b2) + p[2] * p[2] / (c2 * c2);
    *K = 1 / (a2 * b2 * c2 * w * w);
    *H = (a2 + b2 + c2 - (p[0] * p[0] + p[1] * p[1] + p[2] * p[2])) / (2 * a2 * b2 * c2 * pow(w, 1.5));
}

/* RMS of the relative error of values against truth, over valid vertices. */
static double rel_rms(const lucent_curvature *c, const double *values, const double *truth)
{
    double s = 0;
    size_t n = 0;
    for (size_t v = 0; v < c->count; v++) {
        if (c->flags[v] & LUCENT_CURVATURE_INVALID) continue;
        double e = (values[v] - truth[v]) / truth[v];
        s += e * e, n++;
    }
    return n ? sqrt(s / (double)n) : INFINITY;
}

static double max_rel(const lucent_curvature *c, const double *values, double truth)
{
    double m = 0;
    for (size_t v = 0; v < c->count; v++) m = fmax(m, fabs(values[v] - truth) / truth);
    return m;
}

static int all_finite(const lucent_curvature *c)
{
    for (size_t v = 0; v < c->count; v++)
        if (!isfinite(c->k1[v]) || !isfinite(c->k2[v]) || !isfinite(c->mean[v]) || !isfinite(c->gauss[v]) ||
            !isfinite(c->dir1[3 * v]) || !isfinite(c->dir2[3 * v]))
            return 0;
    return 1;
}

static lucent_curvature curvature_of(const lucent_mesh *m, lucent_curvature_method method)
{
    lucent_curvature c = {0};
    lucent_curvature_desc d = {.method = method};
    CHECK_OK(lucent_mesh_curvature(m, &d, &c));
    return c;
}

/* ---- primitives and curvature ---- */

static double torus_error_desc(double jitter, const lucent_curvature_desc *cd, double *gauss_err);

static double torus_error(double jitter, lucent_curvature_method method, double *gauss_err)
{
    return torus_error_desc(jitter, &(lucent_curvature_desc){.method = method}, gauss_err);
}

static double torus_error_desc(double jitter, const lucent_curvature_desc *cd, double *gauss_err)
{
    lucent_mesh *m;
    lucent_primitive_desc d = {.kind = LUCENT_PRIMITIVE_TORUS,
                               .major_radius = 3,
                               .radius = 1,
                               .u_count = 192,
                               .v_count = 64,
                               .jitter = jitter,
                               .seed = 7};
    CHECK_OK(lucent_mesh_primitive(&d, &m));
    lucent_curvature c = {0};
    CHECK_OK(lucent_mesh_curvature(m, cd, &c));
    double *H = malloc(m->vertex_count * sizeof *H), *K = malloc(m->vertex_count * sizeof *K), gk = 0, gn = 0;
    for (size_t v = 0; v < m->vertex_count; v++) {
        const double *p = m->positions + 3 * v;
        H[v] = torus_mean(3, 1, p), K[v] = torus_gauss(3, 1, p);
        gk += (c.gauss[v] - K[v]) * (c.gauss[v] - K[v]), gn += K[v] * K[v];
    }
    double e = rel_rms(&c, c.mean, H);
    *gauss_err = sqrt(gk / gn); /* K crosses zero: RMS error over RMS value */
    free(H), free(K);
    lucent_curvature_free(&c);
    lucent_mesh_destroy(m);
    return e;
}

/* The acceptance: torus R = 3, r = 1 on a 192 x 64 grid, Rusinkiewicz mean curvature
 * within 0.1% RMS (trimesh2 as shipped: 8.2%); jittered by a quarter cell: within 4%. */
TEST(torus_rusinkiewicz_accuracy)
{
    double gk, e = torus_error(0, LUCENT_CURVATURE_RUSINKIEWICZ, &gk);
    printf("  torus 192x64 rusinkiewicz: H rel RMS %.4f%%, K RMS/RMS %.4f%%\n", 100 * e, 100 * gk);
    CHECK(e <= 0.001);
    e = torus_error(0.25, LUCENT_CURVATURE_RUSINKIEWICZ, &gk);
    printf("  torus jittered 1/4 cell rusinkiewicz: H rel RMS %.3f%%, K %.3f%%\n", 100 * e, 100 * gk);
    CHECK(e <= 0.04);
    /* --fast (no normal-correcting pass): the regular grid is as good, the jittered one worse. */
    e = torus_error_desc(0, &(lucent_curvature_desc){.fast = 1}, &gk);
    printf("  torus rusinkiewicz fast: H rel RMS %.4f%%\n", 100 * e);
    CHECK(e <= 0.001);
    e = torus_error_desc(0.25, &(lucent_curvature_desc){.fast = 1}, &gk);
    printf("  torus jittered rusinkiewicz fast: H rel RMS %.3f%%\n", 100 * e);
    CHECK(e <= 0.06);
}

/* Meyer and Garimella on the same torus. Meyer is accurate on the regular grid (0.05%) but not
 * on the jittered one (about 14%). Garimella's estimate averages the normal curvatures of the
 * edge directions, which on this grid are not spread evenly over angle (the diagonal's angle
 * follows the cell's aspect ratio, 2:1 between the inner and outer equator): about 16% RMS,
 * a bias of the method that the bounds below record, not a tolerance we aim for. */
TEST(torus_meyer_garimella)
{
    double gk, e = torus_error(0, LUCENT_CURVATURE_MEYER, &gk);
    printf("  torus meyer: H rel RMS %.4f%%, K %.4f%%\n", 100 * e, 100 * gk);
    CHECK(e <= 0.001 && gk <= 0.001);
    e = torus_error(0.25, LUCENT_CURVATURE_MEYER, &gk);
    printf("  torus jittered meyer: H rel RMS %.3f%%\n", 100 * e);
    CHECK(e <= 0.2);
    e = torus_error(0, LUCENT_CURVATURE_GARIMELLA, &gk);
    printf("  torus garimella: H rel RMS %.3f%%\n", 100 * e);
    CHECK(e <= 0.2);
}

/* Rusinkiewicz within tol; Meyer and Garimella mean curvature within other_tol (max). */
static void check_sphere(const lucent_primitive_desc *d, double tol, double other_tol, const char *what)
{
    lucent_mesh *m;
    CHECK_OK(lucent_mesh_primitive(d, &m));
    for (int method = 0; method < 3; method++) {
        lucent_curvature c = curvature_of(m, (lucent_curvature_method)method);
        double eh = max_rel(&c, c.mean, 1 / d->radius), ek = max_rel(&c, c.gauss, 1 / (d->radius * d->radius));
        printf("  %s %s: max rel error H %.2g, K %.2g\n", what, lucent_curvature_method_name(method), eh, ek);
        if (method == LUCENT_CURVATURE_RUSINKIEWICZ)
            CHECK(eh <= tol && ek <= 2 * tol);
        else
            CHECK(eh <= other_tol && ek <= fmax(0.01, other_tol) && all_finite(&c));
        for (size_t v = 0; v < c.count; v++) CHECK(c.flags[v] == 0); /* closed: no boundary */
        lucent_curvature_free(&c);
    }
    lucent_mesh_destroy(m);
}

/* Spheres: H = 1/R, K = 1/R^2. Rusinkiewicz with Max-weighted normals is exact to 1e-4 (in
 * fact to rounding), Garimella's H too (each k_ij is exactly 1/R on a sphere); Meyer's
 * cotangent Laplacian is exact only on regular neighbourhoods: on a jittered icosphere its
 * pointwise error reaches 15% (it does not converge pointwise on irregular meshes, Xu 2004). */
TEST(spheres_exact)
{
    check_sphere(
        &(lucent_primitive_desc){.kind = LUCENT_PRIMITIVE_UV_SPHERE, .radius = 2, .u_count = 64, .v_count = 32}, 1e-4,
        2e-3, "uv sphere R=2");
    check_sphere(&(lucent_primitive_desc){.kind = LUCENT_PRIMITIVE_ICOSPHERE, .radius = 0.5, .subdivisions = 4}, 1e-4,
                 1e-4, "icosphere R=0.5");
    check_sphere(
        &(lucent_primitive_desc){
            .kind = LUCENT_PRIMITIVE_ICOSPHERE, .radius = 1, .subdivisions = 4, .jitter = 0.2, .seed = 3},
        1e-4, 0.3, "jittered icosphere");
}

/* Ellipsoid 1 x 1.5 x 2: mean and Gaussian curvature within 1% RMS. */
TEST(ellipsoid_within_one_percent)
{
    lucent_primitive_desc d = {.kind = LUCENT_PRIMITIVE_ELLIPSOID, .axes = {1, 1.5, 2}, .u_count = 128, .v_count = 64};
    lucent_mesh *m;
    CHECK_OK(lucent_mesh_primitive(&d, &m));
    lucent_curvature c = curvature_of(m, LUCENT_CURVATURE_RUSINKIEWICZ);
    double *H = malloc(m->vertex_count * sizeof *H), *K = malloc(m->vertex_count * sizeof *K);
    for (size_t v = 0; v < m->vertex_count; v++) ellipsoid_hk(d.axes, m->positions + 3 * v, &H[v], &K[v]);
    double eh = rel_rms(&c, c.mean, H), ek = rel_rms(&c, c.gauss, K);
    printf("  ellipsoid 1x1.5x2 rusinkiewicz: H rel RMS %.3f%%, K %.3f%%\n", 100 * eh, 100 * ek);
    CHECK(eh <= 0.01 && ek <= 0.01);
    lucent_curvature_value cv;
    CHECK_OK(lucent_primitive_curvature(&d, m->positions + 3 * 100, &cv));
    CHECK_NEAR(cv.mean, H[100], 1e-12);
    CHECK_NEAR(cv.gauss, K[100], 1e-12);
    free(H), free(K);
    lucent_curvature_free(&c);
    lucent_mesh_destroy(m);
}

/* Units: curvature of a sphere of 2 mesh units at 0.5 mm per unit is 1 mm^-1; smoothing
 * keeps a constant field constant; directions are unit and orthogonal to each other. */
TEST(units_smoothing_directions)
{
    lucent_mesh *m;
    CHECK_OK(lucent_mesh_primitive(&(lucent_primitive_desc){.kind = LUCENT_PRIMITIVE_ICOSPHERE, .radius = 2}, &m));
    lucent_curvature c = {0};
    CHECK_OK(lucent_mesh_curvature(m, &(lucent_curvature_desc){.mm_per_unit = 0.5, .smooth_rings = 2}, &c));
    CHECK(max_rel(&c, c.mean, 1.0) < 1e-4);
    CHECK(max_rel(&c, c.gauss, 1.0) < 2e-4);
    lucent_curvature_free(&c);
    for (int method = 0; method < 3; method++) { /* unsmoothed: Rusinkiewicz scales in its last pass */
        CHECK_OK(lucent_mesh_curvature(m, &(lucent_curvature_desc){.method = method, .mm_per_unit = 0.5}, &c));
        CHECK(max_rel(&c, c.mean, 1.0) < 2e-3 && max_rel(&c, c.k1, 1.0) < 0.05 && max_rel(&c, c.gauss, 1.0) < 0.01);
        lucent_curvature_free(&c);
    }
    lucent_mesh_destroy(m);
    CHECK_OK(lucent_mesh_primitive(&(lucent_primitive_desc){.kind = LUCENT_PRIMITIVE_TORUS}, &m));
    c = curvature_of(m, LUCENT_CURVATURE_RUSINKIEWICZ);
    for (size_t v = 0; v < m->vertex_count; v += 97) {
        const double *a = c.dir1 + 3 * v, *b = c.dir2 + 3 * v;
        CHECK_NEAR(a[0] * a[0] + a[1] * a[1] + a[2] * a[2], 1, 1e-9);
        CHECK_NEAR(a[0] * b[0] + a[1] * b[1] + a[2] * b[2], 0, 1e-9);
        CHECK_NEAR(c.k1[v], 1.0, 0.01); /* the tube's curvature 1/r is the larger one */
    }
    lucent_curvature_free(&c);
    lucent_mesh_destroy(m);
}

/* The result does not depend on the thread count (fixed chunks, gather per vertex). */
TEST(thread_count_independent)
{
    lucent_mesh *m;
    CHECK_OK(lucent_mesh_primitive(&(lucent_primitive_desc){.kind = LUCENT_PRIMITIVE_TORUS, .jitter = 0.2}, &m));
    lucent_pool *pool = lucent_pool_create(2);
    for (int method = 0; method < 3; method++) {
        lucent_curvature a = {0}, b = {0};
        CHECK_OK(lucent_mesh_curvature(m, &(lucent_curvature_desc){.method = method}, &a));
        CHECK_OK(lucent_mesh_curvature(m, &(lucent_curvature_desc){.method = method, .pool = pool}, &b));
        CHECK(memcmp(a.mean, b.mean, m->vertex_count * sizeof *a.mean) == 0);
        CHECK(memcmp(a.gauss, b.gauss, m->vertex_count * sizeof *a.gauss) == 0);
        lucent_curvature_free(&a), lucent_curvature_free(&b);
    }
    lucent_pool_destroy(pool);
    lucent_mesh_destroy(m);
}

/* ---- import ---- */

static const char k_quad_ply[] = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\n"
                                 "property float y\nproperty float z\nelement face 2\n"
                                 "property list uchar int vertex_indices\nend_header\n"
                                 "0 0 0\n1 0 0\n1 1 0\n0 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 3 4 5\n";

/* Two triangles stored with six vertices weld into a quad of four; normals are +z. */
TEST(ascii_ply_welds)
{
    lucent_mesh *m;
    CHECK_OK(lucent_mesh_load_memory(k_quad_ply, sizeof k_quad_ply - 1, "quad.ply",
                                     &(lucent_mesh_load_desc){.format = "ply"}, &m));
    if (!m) return;
    CHECK(m->vertex_count == 4 && m->face_count == 2);
    CHECK_NEAR(m->normals[2], 1, 1e-12);
    lucent_mesh_stats st;
    CHECK_OK(lucent_mesh_stats_compute(m, &st));
    CHECK(st.boundary_edges == 4 && st.nonmanifold_edges == 0 && st.degenerate_faces == 0);
    lucent_mesh_destroy(m);
    CHECK_OK(lucent_mesh_load_memory(k_quad_ply, sizeof k_quad_ply - 1, "quad.ply",
                                     &(lucent_mesh_load_desc){.format = "ply", .keep_duplicates = 1}, &m));
    if (m) CHECK(m->vertex_count == 6);
    lucent_mesh_destroy(m);
}

/* The binary tetrahedron fixture, plain and gzipped; an OBJ; a glTF with an embedded buffer. */
TEST(binary_ply_gz_obj_gltf)
{
    lucent_mesh *m;
    CHECK_OK(lucent_mesh_load(fixture("tetra.ply"), NULL, &m));
    if (m) CHECK(m->vertex_count == 4 && m->face_count == 4);
    lucent_mesh_destroy(m);
    char *data;
    size_t size;
    CHECK_OK(lucent_read_file(fixture("tetra.ply"), &data, &size));
    gzFile gz = gzopen(test_path("tetra.ply.gz"), "wb");
    gzwrite(gz, data, (unsigned)size);
    gzclose(gz);
    free(data);
    CHECK_OK(lucent_mesh_load(test_path("tetra.ply.gz"), NULL, &m));
    if (m) CHECK(m->vertex_count == 4 && m->face_count == 4);
    lucent_mesh_destroy(m);
    static const char obj[] = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    CHECK_OK(lucent_mesh_load_memory(obj, sizeof obj - 1, "quad.obj", &(lucent_mesh_load_desc){.format = "obj"}, &m));
    if (m) CHECK(m->vertex_count == 4 && m->face_count == 2); /* the quad is triangulated */
    lucent_mesh_destroy(m);
    /* One triangle: positions (0,0,0) (1,0,0) (0,1,0) as float32, indices 0 1 2 as uint16. */
    static const char gltf[] =
        "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":1},\"indices\":0}]}],"
        "\"buffers\":[{\"uri\":\"data:application/octet-stream;base64,AAABAAIAAAAAAAAAAAAAAAAAAAAAAIA/"
        "AAAAAAAAAAAAAAAAAACAPwAAAAA=\",\"byteLength\":44}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":6,\"target\":34963},"
        "{\"buffer\":0,\"byteOffset\":8,\"byteLength\":36,\"target\":34962}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"},"
        "{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"max\":[1,1,0],\"min\":[0,0,0]}]}";
    CHECK_OK(
        lucent_mesh_load_memory(gltf, sizeof gltf - 1, "tri.gltf", &(lucent_mesh_load_desc){.format = "gltf"}, &m));
    if (m) CHECK(m->vertex_count == 3 && m->face_count == 1);
    lucent_mesh_destroy(m);
}

/* Empty, truncated and garbage files fail with a message naming the file. */
TEST(bad_files_name_the_file)
{
    lucent_mesh *m = NULL;
    const char *names[] = {"empty.ply", "truncated.ply", "garbage.ply"};
    for (int i = 0; i < 3; i++) {
        CHECK_ERR(lucent_mesh_load(fixture(names[i]), NULL, &m), LUCENT_ERR_PARSE, names[i]);
        CHECK(m == NULL);
    }
    CHECK_ERR(lucent_mesh_load(fixture("missing.ply"), NULL, &m), LUCENT_ERR_IO, "missing.ply");
    CHECK_ERR(lucent_mesh_load(fixture("tetra.xyz"), NULL, &m), LUCENT_ERR_UNSUPPORTED, "tetra.xyz");
    FILE *f = fopen(test_path("bad.ply.gz"), "wb");
    fputs("\x1f\x8b\x08\x00garbage", f);
    fclose(f);
    CHECK_ERR(lucent_mesh_load(test_path("bad.ply.gz"), NULL, &m), LUCENT_ERR_PARSE, "bad.ply.gz");
}

/* Zero-area faces, a fan of three faces on one edge, an unused vertex, an isolated
 * degenerate face: no crash, no NaN; vertices without area are flagged invalid. */
TEST(dirty_mesh_no_nan)
{
    lucent_mesh *m;
    CHECK_OK(lucent_mesh_create(8, 5, &m));
    double p[8][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0.5}, {0, 0.5, 1}, {5, 5, 5}, {2, 0, 0}, {3, 0, 0}};
    uint32_t f[5][3] = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}, {0, 1, 6}, {1, 6, 7}};
    memcpy(m->positions, p, sizeof p), memcpy(m->faces, f, sizeof f);
    lucent_mesh_compute_normals(m);
    lucent_mesh_stats st;
    CHECK_OK(lucent_mesh_stats_compute(m, &st));
    CHECK(st.unused_vertices == 1 && st.nonmanifold_edges == 1 && st.degenerate_faces == 2);
    for (int method = 0; method < 3; method++) {
        lucent_curvature c = {0};
        CHECK_OK(lucent_mesh_curvature(m, &(lucent_curvature_desc){.method = method, .smooth_rings = 1}, &c));
        CHECK(all_finite(&c));
        CHECK(c.flags[5] & LUCENT_CURVATURE_INVALID); /* unused */
        CHECK(c.flags[7] & LUCENT_CURVATURE_INVALID); /* only a zero-area face */
        CHECK(c.flags[2] & LUCENT_CURVATURE_BOUNDARY);
        lucent_curvature_free(&c);
    }
    lucent_mesh_destroy(m);
}

/* The PLY writer's output reads back with the same counts. */
TEST(ply_round_trip)
{
    lucent_mesh *m, *back;
    CHECK_OK(
        lucent_mesh_primitive(&(lucent_primitive_desc){.kind = LUCENT_PRIMITIVE_ICOSPHERE, .subdivisions = 2}, &m));
    double *vals = calloc(m->vertex_count, sizeof *vals);
    uint8_t *rgb = calloc(3 * m->vertex_count, 1);
    const char *names[] = {"mean"};
    const double *values[] = {vals};
    CHECK_OK(lucent_mesh_write_ply(test_path("ico.ply"), m, &(lucent_mesh_ply_extra){rgb, 1, names, values}));
    CHECK_OK(lucent_mesh_load(test_path("ico.ply"), NULL, &back));
    if (back) CHECK(back->vertex_count == m->vertex_count && back->face_count == m->face_count);
    free(vals), free(rgb);
    lucent_mesh_destroy(back), lucent_mesh_destroy(m);
}

/* ---- the Stanford meshes ---- */

/* raw: the file's own vertices (keep_duplicates), unused ones included. expect_unused < 0:
 * not checked. Counts checked against the files themselves (a Python count of their edges). */
static void check_scan(const char *name, int raw, int expect_nonmanifold, int expect_unused)
{
    const char *path = sample(name);
    if (!path) return;
    lucent_mesh *m;
    CHECK_OK(lucent_mesh_load(path, &(lucent_mesh_load_desc){.keep_duplicates = raw}, &m));
    if (!m) return;
    lucent_mesh_stats st;
    CHECK_OK(lucent_mesh_stats_compute(m, &st));
    printf("  %s%s: %zu vertices, %zu faces, %zu boundary, %zu non-manifold edges, %zu zero-area faces, "
           "%zu unused\n",
           name, raw ? " (raw)" : "", m->vertex_count, m->face_count, st.boundary_edges, st.nonmanifold_edges,
           st.degenerate_faces, st.unused_vertices);
    if (expect_nonmanifold >= 0) CHECK(st.nonmanifold_edges == (size_t)expect_nonmanifold);
    if (expect_unused >= 0) CHECK(st.unused_vertices == (size_t)expect_unused);
    lucent_pool *pool = lucent_pool_create(0);
    for (int method = 0; method < 3; method++) {
        lucent_curvature c = {0};
        CHECK_OK(lucent_mesh_curvature(
            m, &(lucent_curvature_desc){.method = method, .pool = pool, .smooth_rings = method == 0}, &c));
        CHECK_MSG(all_finite(&c), "%s %s: non-finite curvature", name, lucent_curvature_method_name(method));
        lucent_curvature_free(&c);
    }
    lucent_pool_destroy(pool);
    lucent_mesh_destroy(m);
}

/* The dragon at res2-res4 (closed, but 803-2,534 non-manifold edges; res3 and res4 have unused
 * vertices in the file), raw and welded, and the bunny: every method finite everywhere.
 * res1 (437,645 vertices, 4,270 boundary edges) runs in bench_curvature, raw and welded. */
TEST(stanford_scans_finite)
{
    check_scan("dragon_vrip_res2.ply.gz", 0, 2534, 0);
    check_scan("dragon_vrip_res2.ply.gz", 1, 2534, -1);
    check_scan("dragon_vrip_res3.ply.gz", 1, 2094, 16);
    check_scan("dragon_vrip_res3.ply.gz", 0, 2094, 0);
    check_scan("dragon_vrip_res4.ply.gz", 1, 803, 2);
    check_scan("dragon_vrip_res4.ply.gz", 0, 803, 0);
    check_scan("bunny.ply", 0, 0, 0);
}

/* Boundary flags: none on a closed torus, none when one face is flipped (inconsistent
 * orientation, the exact path), exactly the three corners when one face is removed. */
TEST(boundary_flags)
{
    lucent_primitive_desc d = {
        .kind = LUCENT_PRIMITIVE_TORUS, .major_radius = 3, .radius = 1, .u_count = 24, .v_count = 12};
    lucent_mesh *m, *open, *flip;
    CHECK_OK(lucent_mesh_primitive(&d, &m));
    CHECK_OK(lucent_mesh_create(m->vertex_count, m->face_count - 1, &open));
    CHECK_OK(lucent_mesh_create(m->vertex_count, m->face_count, &flip));
    memcpy(open->positions, m->positions, 3 * m->vertex_count * sizeof *m->positions);
    memcpy(flip->positions, m->positions, 3 * m->vertex_count * sizeof *m->positions);
    memcpy(open->faces, m->faces + 3, 3 * (m->face_count - 1) * sizeof *m->faces); /* face 0 removed */
    memcpy(flip->faces, m->faces, 3 * m->face_count * sizeof *m->faces);
    uint32_t x = flip->faces[0];
    flip->faces[0] = flip->faces[1], flip->faces[1] = x;
    lucent_curvature c = {0};
    size_t count = 0;
    CHECK_OK(lucent_mesh_curvature(m, NULL, &c));
    for (size_t v = 0; v < c.count; v++) count += (c.flags[v] & LUCENT_CURVATURE_BOUNDARY) != 0;
    CHECK(count == 0);
    lucent_curvature_free(&c);
    CHECK_OK(lucent_mesh_curvature(flip, NULL, &c));
    for (size_t v = 0; v < c.count; v++) count += (c.flags[v] & LUCENT_CURVATURE_BOUNDARY) != 0;
    CHECK(count == 0);
    lucent_curvature_free(&c);
    CHECK_OK(lucent_mesh_curvature(open, NULL, &c));
    for (size_t v = 0; v < c.count; v++) {
        int corner = v == m->faces[0] || v == m->faces[1] || v == m->faces[2];
        CHECK(!(c.flags[v] & LUCENT_CURVATURE_BOUNDARY) == !corner);
    }
    lucent_curvature_free(&c);
    lucent_mesh_destroy(m), lucent_mesh_destroy(open), lucent_mesh_destroy(flip);
}

/* ---- lucent_mesh_paint ---- */

/* Paints m in one colour; returns the image (caller frees) and the covered fraction and width. */
static lucent_image *paint_plain(const lucent_mesh *m, double azimuth, double *coverage, double *covered_width)
{
    uint8_t *rgb = malloc(3 * m->vertex_count);
    for (size_t v = 0; v < m->vertex_count; v++) rgb[3 * v] = 255, rgb[3 * v + 1] = rgb[3 * v + 2] = 0;
    lucent_image *img = NULL;
    CHECK_OK(lucent_mesh_paint(
        m, &(lucent_mesh_paint_desc){.width = 200, .height = 200, .azimuth = azimuth, .colors = rgb}, &img));
    free(rgb);
    double covered = 0;
    int x_lo = 200, x_hi = -1;
    for (int y = 0; img && y < 200; y++)
        for (int x = 0; x < 200; x++) {
            covered += fmin(lucent_image_get(img, x, y, 0) / 0.35, 1); /* shading is >= 0.35 */
            if (lucent_image_get(img, x, y, 0) > 0) x_lo = x < x_lo ? x : x_lo, x_hi = x > x_hi ? x : x_hi;
        }
    *coverage = covered / (200.0 * 200.0);
    *covered_width = x_hi - x_lo + 1;
    return img;
}

/* Expected, from the projection the function documents: the bounding sphere's disc has radius 0.46 of
 * the side, so a unit sphere covers pi 0.46^2 = 0.6648 of the image (the icosphere's silhouette is a
 * polygon inscribed in the circle: 0.3% less at 2562 vertices, and edge pixels count by coverage).
 * The centre looks along the normal: red 1, shading 1. An ellipsoid 2 x 1 x 1 is 2 units wide seen
 * along z (azimuth 0) and 1 wide seen along x (azimuth 90): 184 and 92 pixels. Background black. */
TEST(paint_projects_and_colours_the_mesh)
{
    lucent_mesh *sphere = NULL, *ellipsoid = NULL;
    CHECK_OK(lucent_mesh_primitive(
        &(lucent_primitive_desc){.kind = LUCENT_PRIMITIVE_ICOSPHERE, .radius = 1, .subdivisions = 4}, &sphere));
    CHECK_OK(lucent_mesh_primitive(
        &(lucent_primitive_desc){.kind = LUCENT_PRIMITIVE_ELLIPSOID, .axes = {2, 1, 1}, .u_count = 128, .v_count = 64},
        &ellipsoid));
    if (!sphere || !ellipsoid) return;
    double coverage, width;
    lucent_image *img = paint_plain(sphere, 0, &coverage, &width);
    CHECK_NEAR(coverage, M_PI * 0.46 * 0.46, 0.01);
    if (img) {
        CHECK_NEAR(lucent_image_get(img, 100, 100, 0), 1, 0.01);
        CHECK(lucent_image_get(img, 100, 100, 1) == 0 && lucent_image_get(img, 0, 0, 0) == 0);
    }
    lucent_image_destroy(img);
    lucent_image_destroy(paint_plain(ellipsoid, 0, &coverage, &width));
    CHECK_NEAR(width, 184, 2);
    lucent_image_destroy(paint_plain(ellipsoid, 90, &coverage, &width));
    CHECK_NEAR(width, 92, 2);
    lucent_image *none = NULL;
    CHECK_ERR(lucent_mesh_paint(sphere, &(lucent_mesh_paint_desc){0}, &none), LUCENT_ERR_INVALID_ARGUMENT, "colours");
    lucent_mesh_destroy(sphere), lucent_mesh_destroy(ellipsoid);
}

TEST_MAIN(TEST_ENTRY(torus_rusinkiewicz_accuracy), TEST_ENTRY(torus_meyer_garimella), TEST_ENTRY(spheres_exact),
          TEST_ENTRY(ellipsoid_within_one_percent), TEST_ENTRY(units_smoothing_directions),
          TEST_ENTRY(thread_count_independent), TEST_ENTRY(ascii_ply_welds), TEST_ENTRY(binary_ply_gz_obj_gltf),
          TEST_ENTRY(bad_files_name_the_file), TEST_ENTRY(dirty_mesh_no_nan), TEST_ENTRY(ply_round_trip),
          TEST_ENTRY(stanford_scans_finite), TEST_ENTRY(boundary_flags),
          TEST_ENTRY(paint_projects_and_colours_the_mesh))
