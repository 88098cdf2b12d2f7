/* Tests of point clouds read as surfels (lucent_surfels_load) and of "points" scene objects, on PLY
 * fixtures written here. Expected values from the file formats and geometry, computed independently:
 *   colours: the sRGB transfer function (IEC 61966-2-1: c <= 0.04045 ? c / 12.92 :
 *   ((c + 0.055) / 1.055)^2.4) of the stored value over the type's largest (uchar: 255);
 *   3D Gaussian splats (Kerbl et al. 2023): the quaternion (w, x, y, z) = (cos t/2, sin t/2, 0, 0)
 *   turns about x by t, so the axis e_z goes to (0, -sin t, cos t); scales are stored as logs; the
 *   colour is 0.5 + Y00 f_dc with Y00 = 1 / (2 sqrt(pi));
 *   a square grid of spacing s: the 8th nearest neighbour of an interior point is a diagonal one, s sqrt(2);
 *   normals move by the inverse transpose of the linear map. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/scene.h"
#include "lucent/surfels.h"
#include "test.h"

static double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4); }

/* An ASCII PLY: header properties (e.g. "float x\nfloat y\n...") and the rows as text. */
static const char *write_ascii(const char *name, int count, const char *props, const char *rows)
{
    const char *path = test_path(name);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return path;
    fprintf(f, "ply\nformat ascii 1.0\nelement vertex %d\n", count);
    for (const char *p = props; *p;) {
        const char *e = strchr(p, '\n');
        fprintf(f, "property %.*s\n", (int)(e ? e - p : (long)strlen(p)), p);
        p = e ? e + 1 : p + strlen(p);
    }
    fprintf(f, "end_header\n%s", rows);
    fclose(f);
    return path;
}

/* A little-endian binary 3D Gaussian splatting file of count splats, 18 floats each: x y z nx ny nz
 * f_dc_0..2 f_rest_0 opacity scale_0..2 rot_0..3; truncate_bytes cut off the end. */
static const char *write_splats(const char *name, int count, const float *values, int truncate_bytes)
{
    static const char *const names[] = {"x",       "y",       "z",      "nx",       "ny",      "nz",
                                        "f_dc_0",  "f_dc_1",  "f_dc_2", "f_rest_0", "opacity", "scale_0",
                                        "scale_1", "scale_2", "rot_0",  "rot_1",    "rot_2",   "rot_3"};
    const char *path = test_path(name);
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL);
    if (!f) return path;
    fprintf(f, "ply\nformat binary_little_endian 1.0\nelement vertex %d\n", count);
    for (int i = 0; i < 18; i++) fprintf(f, "property float %s\n", names[i]);
    fprintf(f, "end_header\n");
    fwrite(values, 1, (size_t)count * 18 * sizeof(float) - (size_t)truncate_bytes, f);
    fclose(f);
    return path;
}

TEST(plain_cloud_with_colour_and_radius)
{
    const char *path = write_ascii("plain.ply", 3,
                                   "float x\nfloat y\nfloat z\nfloat nx\nfloat ny\nfloat nz\nuchar red\nuchar "
                                   "green\nuchar blue\nfloat radius",
                                   "0 0 0 0 0 2 255 128 0 0.5\n1 0 0 3 0 4 10 20 30 0.25\n0 1 0 0 -1 0 0 0 0 1\n");
    lucent_surfels *sf = NULL;
    CHECK_OK(lucent_surfels_load(path, &(lucent_surfels_desc){.max_levels = 1}, &sf));
    if (!sf) return;
    CHECK(sf->count == 3 && sf->level_count == 1 && sf->radii_given && sf->colors);
    CHECK_NEAR(sf->positions[3], 1, 0);
    CHECK_NEAR(sf->normals[2], 1, 1e-7); /* (0, 0, 2) made unit */
    CHECK_NEAR(sf->normals[3], 0.6, 1e-7);
    CHECK_NEAR(sf->normals[5], 0.8, 1e-7);
    CHECK_NEAR(sf->radii[0], 0.5, 0);
    CHECK_NEAR(sf->radii[1], 0.25, 0);
    CHECK_NEAR(sf->colors[0], 1, 1e-6);
    CHECK_NEAR(sf->colors[1], srgb_to_linear(128 / 255.0), 1e-4);
    CHECK_NEAR(sf->colors[2], 0, 1e-7);
    CHECK_NEAR(sf->colors[5], srgb_to_linear(30 / 255.0), 1e-4);
    lucent_surfels_destroy(sf);
}

TEST(plain_cloud_radii_from_neighbours)
{
    /* 5 x 5 grid of spacing 0.5 without radii: the centre's 8th neighbour at 0.5 sqrt(2) */
    char rows[2048] = "";
    for (int y = 0; y < 5; y++)
        for (int x = 0; x < 5; x++) {
            char line[64];
            snprintf(line, sizeof line, "%g %g 0 0 0 1\n", 0.5 * x, 0.5 * y);
            strcat(rows, line);
        }
    const char *path = write_ascii("grid.ply", 25, "float x\nfloat y\nfloat z\nfloat nx\nfloat ny\nfloat nz", rows);
    lucent_surfels *sf = NULL;
    CHECK_OK(lucent_surfels_load(path, &(lucent_surfels_desc){.max_levels = 1}, &sf));
    if (!sf) return;
    CHECK(!sf->radii_given && !sf->colors);
    CHECK_NEAR(sf->radii[12], 0.5 * sqrt(2.0), 1e-6);
    lucent_surfels_destroy(sf);
}

/* Two splats: A at (0, 0, 2), unnormalised identity rotation (3, 0, 0, 0), scales 2, 3, 0.5 (the
 * normal: e_z; radius 2 sqrt(2 x 3)); B at (0, -2, 0), turned by -90 degrees about x, scales 1, 4,
 * 0.25 (e_z goes to (0, 1, 0), which faces the centroid (0, -1, 1), so it is turned to (0, -1, 0);
 * radius 2 sqrt(1 x 4) = 4). */
static void two_splats(float v[2][18])
{
    double h = sqrt(0.5);
    float a[18] = {0, 0, 2, 0, 0, 0, 0, 1, -2, 0.3f, 0.9f, (float)log(2), (float)log(3), (float)log(0.5), 3, 0, 0, 0};
    float b[18] = {0,        -2,        0, 0, 0, 0, 0.5f, 0.5f, 0.5f, 0, 0, 0, (float)log(4), (float)log(0.25),
                   (float)h, (float)-h, 0, 0};
    memcpy(v[0], a, sizeof a), memcpy(v[1], b, sizeof b);
}

TEST(gaussian_splatting_file)
{
    float v[2][18];
    two_splats(v);
    const char *path = write_splats("splats.ply", 2, v[0], 0);
    lucent_surfels *sf = NULL;
    CHECK_OK(lucent_surfels_load(path, &(lucent_surfels_desc){.max_levels = 1}, &sf));
    if (!sf) return;
    CHECK(sf->count == 2 && sf->radii_given && sf->colors);
    double want_n[2][3] = {{0, 0, 1}, {0, -1, 0}}, want_r[2] = {2 * sqrt(6.0), 4};
    for (int i = 0; i < 2; i++) {
        for (int a = 0; a < 3; a++) CHECK_NEAR(sf->normals[3 * i + a], want_n[i][a], 1e-6);
        CHECK_NEAR(sf->radii[i], want_r[i], 1e-5);
    }
    double y00 = 1 / (2 * sqrt(M_PI));
    CHECK_NEAR(sf->colors[0], srgb_to_linear(0.5), 1e-6);
    CHECK_NEAR(sf->colors[1], srgb_to_linear(0.5 + y00), 1e-6);
    CHECK_NEAR(sf->colors[2], 0, 0); /* 0.5 - 2 Y00 < 0: clamped */
    CHECK_NEAR(sf->colors[3], srgb_to_linear(0.5 + 0.5 * y00), 1e-6);
    lucent_surfels_destroy(sf);
}

#define XYZN "float x\nfloat y\nfloat z\nfloat nx\nfloat ny\nfloat nz"

TEST(bad_clouds_name_the_file_and_the_field)
{
    lucent_surfels *sf = NULL;
    const char *p = write_ascii("no-normals.ply", 2, "float x\nfloat y\nfloat z", "0 0 0\n1 0 0\n");
    CHECK_ERR(lucent_surfels_load(p, NULL, &sf), LUCENT_ERR_PARSE, p, "no vertex normals", "nx");
    p = write_ascii("nan.ply", 2, XYZN, "0 0 0 0 0 1\n1 0 0 0 nan 1\n");
    CHECK_ERR(lucent_surfels_load(p, NULL, &sf), LUCENT_ERR_PARSE, p, "vertex 1", "ny", "not finite");
    p = write_ascii("inf.ply", 2, XYZN, "0 0 inf 0 0 1\n1 0 0 0 0 1\n");
    CHECK_ERR(lucent_surfels_load(p, NULL, &sf), LUCENT_ERR_PARSE, p, "vertex 0", "z", "not finite");
    p = write_ascii("zero-radius.ply", 2, XYZN "\nfloat radius", "0 0 0 0 0 1 1\n1 0 0 0 0 1 0\n");
    CHECK_ERR(lucent_surfels_load(p, NULL, &sf), LUCENT_ERR_PARSE, p, "vertex 1", "radius must be > 0");
    p = write_ascii("zero-normal.ply", 2, XYZN, "0 0 0 0 0 1\n1 0 0 0 0 0\n");
    CHECK_ERR(lucent_surfels_load(p, NULL, &sf), LUCENT_ERR_PARSE, p, "vertex 1", "normal", "zero");
    p = write_ascii("empty.ply", 0, XYZN, "");
    CHECK_ERR(lucent_surfels_load(p, NULL, &sf), LUCENT_ERR_PARSE, p, "holds 0 points");
    p = write_ascii("one.ply", 1, XYZN, "0 0 0 0 0 1\n");
    CHECK_ERR(lucent_surfels_load(p, NULL, &sf), LUCENT_ERR_PARSE, p, "holds 1 point");
    p = write_ascii("short.ply", 3, XYZN, "0 0 0 0 0 1\n1 0 0 0 0 1\n");
    CHECK_ERR(lucent_surfels_load(p, NULL, &sf), LUCENT_ERR_PARSE, p);
    float v[2][18];
    two_splats(v);
    p = write_splats("truncated-splats.ply", 2, v[0], 6);
    CHECK_ERR(lucent_surfels_load(p, NULL, &sf), LUCENT_ERR_PARSE, p);
    v[1][15] = v[1][14] = 0;
    p = write_splats("zero-rotation.ply", 2, v[0], 0);
    CHECK_ERR(lucent_surfels_load(p, NULL, &sf), LUCENT_ERR_PARSE, p, "vertex 1", "rot_0..3", "zero");
    two_splats(v);
    v[0][12] = 1000; /* exp(1000): the radius overflows */
    p = write_splats("huge-scale.ply", 2, v[0], 0);
    CHECK_ERR(lucent_surfels_load(p, NULL, &sf), LUCENT_ERR_PARSE, p, "vertex 0", "scale_0..2");
    p = write_ascii("half-splat.ply", 2, XYZN "\nfloat scale_0", "0 0 0 0 0 0 1\n1 0 0 0 0 0 1\n");
    CHECK_ERR(lucent_surfels_load(p, NULL, &sf), LUCENT_ERR_PARSE, p, "f_dc_0");
    CHECK_ERR(lucent_surfels_load(test_path("absent.ply"), NULL, &sf), LUCENT_ERR_IO, "absent.ply", "cannot open");
    CHECK(sf == NULL);
}

TEST(transform_moves_normals_by_the_inverse_transpose)
{
    const char *p = write_ascii("tilted.ply", 2, XYZN "\nfloat radius", "1 2 3 1 0 1 0.5\n0 0 0 1 0 0 0.5\n");
    lucent_surfels *sf = NULL;
    CHECK_OK(lucent_surfels_load(p, &(lucent_surfels_desc){.max_levels = 1}, &sf));
    if (!sf) return;
    /* x scaled by 2, then mirrored in y, then moved by (10, 0, 0): (x, y, z) -> (2x + 10, -y, z) */
    double m[16] = {2, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1, 0, 10, 0, 0, 1};
    lucent_surfels_transform(sf, m);
    CHECK_NEAR(sf->positions[0], 12, 1e-6);
    CHECK_NEAR(sf->positions[1], -2, 1e-6);
    CHECK_NEAR(sf->positions[2], 3, 1e-6);
    /* M^-T (1, 0, 1) = (1/2, 0, 1), made unit */
    CHECK_NEAR(sf->normals[0], 0.5 / sqrt(1.25), 1e-6);
    CHECK_NEAR(sf->normals[1], 0, 1e-6);
    CHECK_NEAR(sf->normals[2], 1 / sqrt(1.25), 1e-6);
    CHECK_NEAR(sf->radii[0], 0.5 * cbrt(2.0), 1e-6); /* |det| = 2 */
    lucent_surfels_destroy(sf);
}

static lucent_status parse_object(const char *object, lucent_scene **sc)
{
    char text[4096];
    snprintf(text, sizeof text,
             "{\"camera\": {\"position\": [0, 0, 50], \"target\": [0, 0, 0]}, \"lights\": [{\"type\": "
             "\"directional\", \"direction\": [0, 0, -1]}], \"objects\": [%s]}",
             object);
    return lucent_scene_parse(text, "t.json", test_tmpdir(), NULL, sc);
}

TEST(points_objects_in_scenes)
{
    write_ascii("scene-cloud.ply", 3, XYZN "\nfloat radius", "0 0 0 0 0 1 0.5\n1 0 0 0 0 1 0.5\n0 1 0 0 0 1 0.5\n");
    lucent_scene *sc = NULL;
    CHECK_OK(parse_object("{\"points\": \"scene-cloud.ply\", \"material\": \"skin1\", \"mm_per_unit\": 2}", &sc));
    if (sc) {
        const lucent_scene_object *o = &sc->objects[0];
        CHECK(o->points && o->as_points && o->mesh && o->mesh->face_count == 0 && o->mesh->vertex_count == 3);
        CHECK_NEAR(o->points->positions[3], 2, 1e-6); /* mm_per_unit 2 */
        CHECK_NEAR(o->mesh->positions[3], 2, 1e-12);
        CHECK_NEAR(o->mesh->normals[2], 1, 1e-7);
        CHECK_NEAR(o->points->radii[0], 1, 1e-6);
    }
    lucent_scene_destroy(sc);
    sc = NULL;
    CHECK_ERR(parse_object("{\"points\": \"scene-cloud.ply\", \"mesh\": \"x.ply\", \"material\": \"skin1\"}", &sc),
              LUCENT_ERR_PARSE, "t.json", "objects[0].points", "not both");
    CHECK_ERR(parse_object("{\"points\": \"nowhere.ply\", \"material\": \"skin1\"}", &sc), LUCENT_ERR_NOT_FOUND,
              "t.json", "objects[0].points", "nowhere.ply");
    CHECK_ERR(parse_object("{\"points\": \"scene-cloud.ply\", \"material\": \"skin1\", \"subdivide\": 1}", &sc),
              LUCENT_ERR_PARSE, "objects[0].subdivide", "point cloud");
    write_ascii("scene-nan.ply", 2, XYZN, "0 0 0 0 0 1\n1 0 nan 0 0 1\n");
    CHECK_ERR(parse_object("{\"points\": \"scene-nan.ply\", \"material\": \"skin1\"}", &sc), LUCENT_ERR_PARSE, "t.json",
              "objects[0].points", "scene-nan.ply", "vertex 1", "z");
    CHECK(sc == NULL);
}

/* Issue 32 items 6 and 10: each point is checked as it is read, so a bad point is named before the rest of the
 * body is read (here lines that are not rows after it: the old whole-body check reported those); rows past
 * the header's count, a property declared twice and radii that no Gaussian can draw are refused. */
TEST(clouds_checked_point_by_point)
{
    lucent_surfels *sf = NULL;
    char rows[16384] = "0 0 0 0 0 1\n1 0 0 0 0 0\n"; /* then 7000 lines that are not rows */
    for (size_t at = strlen(rows); at + 3 < sizeof rows; at += 2) memcpy(rows + at, "x\n", 3);
    const char *p = write_ascii("early.ply", 1000, XYZN, rows);
    CHECK_ERR(lucent_surfels_load(p, NULL, &sf), LUCENT_ERR_PARSE, p, "vertex 1: the normal (nx, ny, nz) is zero");
    p = write_ascii("extra.ply", 2, XYZN, "0 0 0 0 0 1\n1 0 0 0 0 1\n2 0 0 0 0 1\n");
    CHECK_ERR(lucent_surfels_load(p, NULL, &sf), LUCENT_ERR_PARSE, p, "more rows than the header declares");
    p = write_ascii("blank-tail.ply", 2, XYZN, "0 0 0 0 0 1\n1 0 0 0 0 1\n \n\n");
    CHECK_OK(lucent_surfels_load(p, NULL, &sf)); /* blank lines after the rows are no rows */
    lucent_surfels_destroy(sf), sf = NULL;
    p = write_ascii("twice.ply", 2, XYZN "\nfloat nz", "0 0 0 0 0 1 1\n1 0 0 0 0 1 1\n");
    CHECK_ERR(lucent_surfels_load(p, NULL, &sf), LUCENT_ERR_PARSE, p, "declares the property nz twice");
    p = write_ascii("tiny-radius.ply", 2, XYZN "\nfloat radius", "0 0 0 0 0 1 1\n1 0 0 0 0 1 1e-30\n");
    CHECK_ERR(lucent_surfels_load(p, NULL, &sf), LUCENT_ERR_PARSE, p, "vertex 1: radius must be > 0, from 1e-18");
    p = write_ascii("big.ply", 2, "double x\nfloat y\nfloat z\nfloat nx\nfloat ny\nfloat nz",
                    "0 0 0 0 0 1\n1e39 0 0 0 0 1\n");
    CHECK_ERR(lucent_surfels_load(p, NULL, &sf), LUCENT_ERR_PARSE, p, "vertex 1: x = 1e+39 does not fit a float");
    CHECK(sf == NULL);
}

TEST_MAIN(TEST_ENTRY(clouds_checked_point_by_point), TEST_ENTRY(plain_cloud_with_colour_and_radius),
          TEST_ENTRY(plain_cloud_radii_from_neighbours), TEST_ENTRY(gaussian_splatting_file),
          TEST_ENTRY(bad_clouds_name_the_file_and_the_field),
          TEST_ENTRY(transform_moves_normals_by_the_inverse_transpose), TEST_ENTRY(points_objects_in_scenes))
