/* Tests of src/scene: the camera (projection and primary rays agree), transforms into world mm,
 * materials and defaults, `--set` overrides, and errors that name the file and the JSON path.
 * Expected values are geometric facts (a rotation by 90 degrees, a sphere's radius after scaling,
 * the pinhole projection) and the material module's own closed forms (dipole Rd). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/kernel.h"
#include "lucent/scene.h"
#include "test.h"

/* A minimal valid scene; %s is spliced into the object (extra members) and the top level. */
static const char *k_scene_fmt =
    "{\"camera\": {\"position\": [0, 0, 50], \"target\": [0, 0, 0], \"fov_y\": 40},\n"
    " \"lights\": [{\"type\": \"directional\", \"direction\": [0, 0, -1]}],\n"
    " \"objects\": [{\"mesh\": {\"primitive\": \"icosphere\", \"radius\": 1, \"subdivisions\": 2},\n"
    "               \"material\": \"skin1\"%s}]%s}";

static lucent_status parse_with(const char *object_extra, const char *top_extra, const lucent_scene_load_desc *d,
                                lucent_scene **sc)
{
    char text[4096];
    snprintf(text, sizeof text, k_scene_fmt, object_extra, top_extra);
    return lucent_scene_parse(text, "t.json", NULL, d, sc);
}

/* Multiplies column-major 4x4 m by (x, y, z, 1). */
static void transform_point(const double m[16], const double p[3], double dest[4])
{
    for (int r = 0; r < 4; r++) dest[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
}

TEST(ray_through_a_pixel_projects_back_onto_it)
{
    /* A point on the primary ray of image point (px, py) must project, through view and
     * projection, to the NDC of that point: x_ndc = 2 px / w - 1, y_ndc = 1 - 2 py / h (top row
     * first). Two independent derivations of one pinhole camera. */
    lucent_camera cam = {
        .position = {3, 4, 20}, .target = {-1, 2, 0}, .up = {0, 1, 0}, .fov_y = 35, .near_plane = 1, .far_plane = 100};
    double view[16], proj[16];
    int w = 320, h = 200;
    lucent_camera_view(&cam, view);
    lucent_camera_projection(&cam, (double)w / h, proj);
    static const double pts[][2] = {{0.5, 0.5}, {160, 100}, {319.5, 0.5}, {10.25, 190.75}, {200, 37}};
    for (int i = 0; i < 5; i++) {
        double o[3], d[3], p[3], e[4], c[4];
        lucent_camera_ray(&cam, w, h, pts[i][0], pts[i][1], o, d);
        CHECK_NEAR(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1, 1e-12);
        for (int k = 0; k < 3; k++) p[k] = o[k] + 17.0 * d[k];
        transform_point(view, p, e);
        double clip[16];
        memcpy(clip, proj, sizeof clip);
        transform_point(clip, e, c);
        CHECK_NEAR(c[0] / c[3], 2 * pts[i][0] / w - 1, 1e-9);
        CHECK_NEAR(c[1] / c[3], 1 - 2 * pts[i][1] / h, 1e-9);
    }
}

TEST(view_matrix_maps_the_target_onto_the_negative_z_axis)
{
    lucent_camera cam = {.position = {1, 2, 3}, .target = {4, -2, 3}, .up = {0, 0, 1}, .fov_y = 30};
    double v[16], e[4];
    lucent_camera_view(&cam, v);
    transform_point(v, cam.target, e);
    CHECK_NEAR(e[0], 0, 1e-12);
    CHECK_NEAR(e[1], 0, 1e-12);
    CHECK_NEAR(e[2], -5, 1e-12); /* |target - position| = 5 */
    transform_point(v, cam.position, e);
    CHECK_NEAR(e[0] * e[0] + e[1] * e[1] + e[2] * e[2], 0, 1e-20);
    /* up = world z projects to eye +y */
    double up_pt[3] = {1, 2, 4};
    transform_point(v, up_pt, e);
    CHECK(e[1] > 0.99);
}

TEST(projection_depth_range)
{
    /* OpenGL clip space: the near plane maps to z_ndc = -1, the far plane to +1. */
    lucent_camera cam = {
        .position = {0, 0, 0}, .target = {0, 0, -1}, .up = {0, 1, 0}, .fov_y = 60, .near_plane = 2, .far_plane = 50};
    double p[16], c[4];
    lucent_camera_projection(&cam, 1.5, p);
    transform_point(p, (double[3]){0, 0, -2}, c);
    CHECK_NEAR(c[2] / c[3], -1, 1e-12);
    transform_point(p, (double[3]){0, 0, -50}, c);
    CHECK_NEAR(c[2] / c[3], 1, 1e-12);
}

TEST(minimal_scene_gets_the_documented_defaults)
{
    lucent_scene *sc = NULL;
    CHECK_OK(parse_with("", "", NULL, &sc));
    if (!sc) return;
    lucent_render_settings d = lucent_render_settings_defaults();
    CHECK(sc->render.view.width == 512 && sc->render.view.height == 512);
    CHECK(sc->render.view.method == LUCENT_METHOD_SSSS && sc->render.ssss.kernel == LUCENT_KERNEL_PREINT);
    CHECK(sc->render.ssss.taps == d.ssss.taps && d.ssss.taps == 17);
    CHECK(sc->render.translucency.curvature == 1 && d.translucency.curvature == 1);
    CHECK(sc->render.translucency.transmittance == LUCENT_TRANSMIT_SLAB &&
          d.translucency.transmittance == LUCENT_TRANSMIT_SLAB);
    CHECK(sc->render.cdrf.tail && d.cdrf.tail);
    CHECK(sc->light_count == 1 && sc->lights[0].shadows && sc->lights[0].intensity == 1);
    CHECK_NEAR(sc->camera.up[1], 1, 0);
    CHECK(!strcmp(sc->name, "t"));
    const lucent_scene_object *o = &sc->objects[0];
    /* albedo defaults to the material's classical-dipole Rd (Jensen 2001; Skin1: 0.4360, 0.2273, 0.1310) */
    CHECK(o->albedo_source == LUCENT_ALBEDO_FROM_MATERIAL);
    CHECK_NEAR(o->albedo[0], 0.4360, 1e-3);
    CHECK_NEAR(o->albedo[2], 0.1310, 1e-3);
    /* F0 = ((eta - 1) / (eta + 1))^2: Skin1's eta 1.3 gives 0.017 */
    CHECK_NEAR(o->specular_f0, pow(0.3 / 2.3, 2), 1e-12);
    CHECK_NEAR(o->roughness, 0.3, 0);
    CHECK(!strcmp(o->name, "Skin1"));
    CHECK(!o->as_points);
    /* near and far enclose the unit sphere 50 mm away */
    CHECK(sc->camera.near_plane > 0 && sc->camera.near_plane < 49);
    CHECK(sc->camera.far_plane > 51);
    CHECK(strstr(sc->json, "\"skin1\"") != NULL);
    lucent_scene_destroy(sc);
}

/* Radius and centre of an object's world mesh. */
static void mesh_sphere(const lucent_mesh *m, double centre[3], double *rmin, double *rmax)
{
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (size_t v = 0; v < m->vertex_count; v++)
        for (int i = 0; i < 3; i++)
            lo[i] = fmin(lo[i], m->positions[3 * v + i]), hi[i] = fmax(hi[i], m->positions[3 * v + i]);
    for (int i = 0; i < 3; i++) centre[i] = 0.5 * (lo[i] + hi[i]);
    *rmin = 1e300, *rmax = 0;
    for (size_t v = 0; v < m->vertex_count; v++) {
        const double *p = m->positions + 3 * v;
        double r = sqrt(pow(p[0] - centre[0], 2) + pow(p[1] - centre[1], 2) + pow(p[2] - centre[2], 2));
        *rmin = fmin(*rmin, r), *rmax = fmax(*rmax, r);
    }
}

TEST(mm_per_unit_and_transform_place_the_mesh_in_world_mm)
{
    lucent_scene *sc = NULL;
    CHECK_OK(
        parse_with(", \"mm_per_unit\": 10, \"transform\": {\"translate\": [5, -2, 1], \"scale\": 2}", "", NULL, &sc));
    if (!sc) return;
    double c[3], rmin, rmax;
    mesh_sphere(sc->objects[0].mesh, c, &rmin, &rmax);
    CHECK_NEAR(rmin, 20, 1e-9); /* icosphere vertices lie on the sphere: 1 unit x 10 mm x 2 */
    CHECK_NEAR(rmax, 20, 1e-9);
    CHECK_NEAR(c[0], 5, 1e-9);
    CHECK_NEAR(c[1], -2, 1e-9);
    CHECK_NEAR(c[2], 1, 1e-9);
    lucent_scene_destroy(sc);
}

/* Each Loop level splits every triangle in four; every new vertex is a convex combination of old
 * ones (Loop's masks have positive weights), so the subdivided icosphere stays inside its sphere. */
TEST(as_points_is_read)
{
    lucent_scene *sc = NULL;
    CHECK_OK(parse_with(", \"as_points\": true", "", NULL, &sc));
    if (sc) CHECK(sc->objects[0].as_points && sc->objects[0].mesh && sc->objects[0].mesh->face_count > 0);
    lucent_scene_destroy(sc);
    CHECK_ERR(parse_with(", \"as_points\": 3", "", NULL, &sc), LUCENT_ERR_PARSE, "t.json", "as_points");
}

TEST(subdivide_refines_the_mesh_after_loading)
{
    lucent_scene *sc = NULL;
    CHECK_OK(parse_with(", \"subdivide\": 1", "", NULL, &sc));
    if (!sc) return;
    CHECK(sc->objects[0].mesh->face_count == 4 * 320); /* icosphere level 2: 20 * 4^2 faces */
    double c[3], rmin, rmax;
    mesh_sphere(sc->objects[0].mesh, c, &rmin, &rmax);
    CHECK(rmax <= 1 + 1e-12 && rmin > 0.9);
    lucent_scene_destroy(sc);
    CHECK_ERR(parse_with(", \"subdivide\": 5", "", NULL, &sc), LUCENT_ERR_PARSE, "objects[0].subdivide");
}

TEST(rotation_follows_the_right_hand_rule)
{
    /* Rotating by 90 degrees about z maps +x to +y; the matrix form must give the same mesh. */
    lucent_scene *a = NULL, *b = NULL;
    CHECK_OK(parse_with(", \"transform\": {\"rotate\": [0, 0, 90], \"translate\": [1, 2, 3]}", "", NULL, &a));
    CHECK_OK(parse_with(", \"transform\": {\"matrix\": [0, -1, 0, 1,  1, 0, 0, 2,  0, 0, 1, 3,  0, 0, 0, 1]}", "", NULL,
                        &b));
    if (!a || !b) goto done;
    const double *x = a->objects[0].to_world;
    CHECK_NEAR(x[0], 0, 1e-15); /* column 0 = image of +x = (0, 1, 0) */
    CHECK_NEAR(x[1], 1, 1e-15);
    CHECK(a->objects[0].mesh->vertex_count == b->objects[0].mesh->vertex_count);
    double worst = 0;
    for (size_t i = 0; i < 3 * a->objects[0].mesh->vertex_count; i++)
        worst = fmax(worst, fabs(a->objects[0].mesh->positions[i] - b->objects[0].mesh->positions[i]));
    CHECK_NEAR(worst, 0, 1e-12);
done:
    lucent_scene_destroy(a);
    lucent_scene_destroy(b);
}

TEST(mirroring_keeps_normals_outward)
{
    lucent_scene *sc = NULL;
    CHECK_OK(parse_with(", \"transform\": {\"scale\": [-1, 1, 1], \"translate\": [4, 0, 0]}", "", NULL, &sc));
    if (!sc) return;
    const lucent_mesh *m = sc->objects[0].mesh;
    int inward = 0;
    for (size_t v = 0; v < m->vertex_count; v++) {
        const double *p = m->positions + 3 * v, *n = m->normals + 3 * v;
        if ((p[0] - 4) * n[0] + p[1] * n[1] + p[2] * n[2] <= 0) inward++;
    }
    CHECK_MSG(inward == 0, "%d normals point inward after a mirror", inward);
    lucent_scene_destroy(sc);
}

TEST(overrides_change_values_and_are_checked_like_the_file)
{
    const char *ov[] = {"render.method=ssss:svd3",
                        "render.taps=33",
                        "objects[0].material=marble",
                        "camera.fov_y=20",
                        "lights[0].intensity=2.5",
                        "render.translucency=false",
                        "objects[0].albedo=[0.5, 0.25, 0.125]",
                        "render.translucency_curvature=0",
                        "render.transmittance=profile"};
    lucent_scene *sc = NULL;
    CHECK_OK(parse_with("", "", &(lucent_scene_load_desc){.overrides = ov, .override_count = 9}, &sc));
    if (!sc) return;
    CHECK(sc->render.view.method == LUCENT_METHOD_SSSS);
    CHECK(sc->render.ssss.kernel == LUCENT_KERNEL_SVD && sc->render.ssss.rank == 3);
    CHECK(sc->render.ssss.taps == 33);
    CHECK(!strcmp(sc->objects[0].material.name, "Marble"));
    CHECK_NEAR(sc->camera.fov_y, 20, 0);
    CHECK_NEAR(sc->lights[0].intensity, 2.5, 0);
    CHECK(!sc->render.translucency.enabled);
    CHECK(sc->render.translucency.curvature == 0);
    CHECK(sc->render.translucency.transmittance == LUCENT_TRANSMIT_PROFILE);
    CHECK(sc->objects[0].albedo_source == LUCENT_ALBEDO_COLOR);
    CHECK_NEAR(sc->objects[0].albedo[2], 0.125, 0);
    CHECK(strstr(sc->json, "svd3") != NULL); /* the record of what made the image */
    lucent_scene_destroy(sc);

    const char *bad1[] = {"render.taps=16"};
    CHECK_ERR(parse_with("", "", &(lucent_scene_load_desc){.overrides = bad1, .override_count = 1}, &sc),
              LUCENT_ERR_PARSE, "t.json", "render.taps", "odd");
    const char *bad2[] = {"objects[3].material=marble"};
    CHECK_ERR(parse_with("", "", &(lucent_scene_load_desc){.overrides = bad2, .override_count = 1}, &sc),
              LUCENT_ERR_INVALID_ARGUMENT, "objects[3].material=marble", "beyond the end");
    const char *bad3[] = {"render.method"};
    CHECK_ERR(parse_with("", "", &(lucent_scene_load_desc){.overrides = bad3, .override_count = 1}, &sc),
              LUCENT_ERR_INVALID_ARGUMENT, "key=value");
    const char *bad4[] = {"camera.wobble=3"};
    CHECK_ERR(parse_with("", "", &(lucent_scene_load_desc){.overrides = bad4, .override_count = 1}, &sc),
              LUCENT_ERR_PARSE, "camera", "wobble");
}

/* The names the sidecar and compare write are the ones a scene file takes back. */
TEST(setting_names_read_back)
{
    char set[3][64];
    snprintf(set[0], sizeof set[0], "render.depth_filter=%s", lucent_depth_filter_name(LUCENT_DEPTH_GAUSSIAN));
    snprintf(set[1], sizeof set[1], "render.transmittance=%s", lucent_transmittance_name(LUCENT_TRANSMIT_PROFILE));
    snprintf(set[2], sizeof set[2], "render.sigma0=%s", lucent_sigma0_source_name(LUCENT_SIGMA0_DIFFUSE));
    const char *ov[] = {set[0], set[1], set[2]};
    lucent_scene *sc = NULL;
    CHECK_OK(parse_with("", "", &(lucent_scene_load_desc){.overrides = ov, .override_count = 3}, &sc));
    if (!sc) return;
    CHECK(sc->render.ssss.depth_filter == LUCENT_DEPTH_GAUSSIAN);
    CHECK(sc->render.translucency.transmittance == LUCENT_TRANSMIT_PROFILE);
    CHECK(sc->render.cdrf.sigma0 == LUCENT_SIGMA0_DIFFUSE);
    CHECK(!strcmp(lucent_depth_filter_name((lucent_depth_filter)9), "unknown"));
    lucent_scene_destroy(sc);
}

TEST(method_names)
{
    lucent_render_method m;
    lucent_render_settings s = lucent_render_settings_defaults();
    s.ssss.rank = 0;
    CHECK_OK(lucent_render_method_parse("cdrf+translucency", &m, &s));
    CHECK(m == LUCENT_METHOD_CDRF_TRANSLUCENCY && s.ssss.rank == 0);
    CHECK_OK(lucent_render_method_parse("ssss:jimenez", &m, &s));
    CHECK(m == LUCENT_METHOD_SSSS && s.ssss.kernel == LUCENT_KERNEL_JIMENEZ && s.ssss.rank == 1);
    CHECK_OK(lucent_render_method_parse("ssss:sog4", &m, &s));
    CHECK(s.ssss.kernel == LUCENT_KERNEL_SOG && s.ssss.rank == 4);
    CHECK_ERR(lucent_render_method_parse("ssss:preint2", &m, &s), LUCENT_ERR_INVALID_ARGUMENT, "rank 1");
    CHECK_ERR(lucent_render_method_parse("cdrf:svd", &m, &s), LUCENT_ERR_INVALID_ARGUMENT, "unknown cdrf variant");
    CHECK_ERR(lucent_render_method_parse("lambert:svd", &m, &s), LUCENT_ERR_INVALID_ARGUMENT, "takes no variant");
    CHECK_OK(lucent_render_method_parse("cdrf:kubo", &m, &s)); /* Kubo's alone: no curved parts */
    CHECK(m == LUCENT_METHOD_CDRF && !s.cdrf.curved_parts);
    CHECK_ERR(lucent_render_method_parse("phong", &m, &s), LUCENT_ERR_INVALID_ARGUMENT, "lambert");
    for (int i = 0; i < LUCENT_METHOD_COUNT; i++) {
        CHECK_OK(lucent_render_method_parse(lucent_render_method_name((lucent_render_method)i), &m, NULL));
        CHECK(m == (lucent_render_method)i);
    }
}

/* Parses the minimal scene with one override. */
static lucent_status parse_set(const char *override, lucent_scene **sc)
{
    const char *ov[] = {override};
    return parse_with("", "", &(lucent_scene_load_desc){.overrides = ov, .override_count = 1}, sc);
}

TEST(bad_fields_are_named)
{
    lucent_scene *sc = NULL;
    CHECK_ERR(parse_set("objects[0].material=marbel", &sc), LUCENT_ERR_PARSE, "t.json", "objects[0].material",
              "marbel");
    CHECK(sc == NULL);
    CHECK_ERR(parse_with(", \"roughness\": 2", "", NULL, &sc), LUCENT_ERR_PARSE, "objects[0].roughness", "[0, 1]");
    CHECK_ERR(
        parse_set("objects[0].material={\"units\": \"mm^-1\", \"sigma_a\": -1, \"sigma_s\": 1, \"eta\": 1.3}", &sc),
        LUCENT_ERR_PARSE, "objects[0].material.sigma_a", ">= 0");
    CHECK_ERR(parse_with("", ", \"render\": {\"method\": \"phong\"}", NULL, &sc), LUCENT_ERR_PARSE, "render.method",
              "phong");
    CHECK_ERR(parse_with("", ", \"render\": {\"wdth\": 3}", NULL, &sc), LUCENT_ERR_PARSE, "render", "wdth");
    CHECK_ERR(parse_with("", ", \"render\": {\"width\": 0}", NULL, &sc), LUCENT_ERR_PARSE, "render.width");
    CHECK_ERR(parse_with("", ", \"render\": {\"transmittance\": \"beer\"}", NULL, &sc), LUCENT_ERR_PARSE,
              "render.transmittance", "beer");
    CHECK_ERR(parse_with("", ", \"render\": {\"profile\": \"tripole\"}", NULL, &sc), LUCENT_ERR_PARSE, "render.profile",
              "tripole");
    CHECK_ERR(parse_set("objects[0].mesh=nowhere/none.ply", &sc), LUCENT_ERR_NOT_FOUND, "objects[0].mesh",
              "nowhere/none.ply", "No such file");
    CHECK_ERR(parse_set("objects[0].mesh={\"primitive\": \"cube\"}", &sc), LUCENT_ERR_PARSE,
              "objects[0].mesh.primitive", "cube");
    /* A primitive with an unknown key (fuzz_scene's first finding: the kind was then read uninitialised). */
    CHECK_ERR(parse_set("objects[0].mesh={\"primitive\": \"icosphere\", \"subdiviseons\": 2}", &sc), LUCENT_ERR_PARSE,
              "objects[0].mesh.subdiviseons", "unknown field");
    CHECK_ERR(parse_set("objects[0].mesh={\"radius\": 1}", &sc), LUCENT_ERR_PARSE, "objects[0].mesh.primitive");
    /* A mesh file name that is not UTF-8 (fuzz_scene's second finding: the name was then NULL, dereferenced). */
    CHECK_ERR(parse_set("objects[0].mesh=\"no-such-mesh.\xf0ly\"", &sc), LUCENT_ERR_PARSE, "objects[0].mesh", "UTF-8");
    CHECK_ERR(parse_with(", \"transform\": {\"scale\": 0}", "", NULL, &sc), LUCENT_ERR_PARSE, "transform.scale");
    CHECK_ERR(parse_with(", \"albedo\": [0.5, 2, 0.1]", "", NULL, &sc), LUCENT_ERR_PARSE, "objects[0].albedo");
    CHECK_ERR(lucent_scene_parse("{\"camera\": {\"position\": [0,0,1], \"target\": [0,0,1]}, \"lights\": [], "
                                 "\"objects\": []}",
                                 "c.json", NULL, NULL, &sc),
              LUCENT_ERR_PARSE, "c.json", "camera.target", "differ");
    CHECK_ERR(lucent_scene_parse("{\"camera\": {\"position\": [0,0,1], \"target\": [0,0,0]}, \"lights\": [], "
                                 "\"objects\": []}",
                                 "l.json", NULL, NULL, &sc),
              LUCENT_ERR_PARSE, "l.json", "lights", "at least one");
    CHECK_ERR(lucent_scene_parse("{\"camera\": {\"position\": [0,0,1], \"target\": [0,0,0]}, \"lights\": "
                                 "[{\"type\": \"sphere\", \"position\": [0,0,0]}], \"objects\": []}",
                                 "s.json", NULL, NULL, &sc),
              LUCENT_ERR_PARSE, "lights[0].radius", "missing");
    CHECK_ERR(lucent_scene_parse("{\"camera\": {\"position\": [0,0,1], \"target\": [0,0,0]}, \"lights\": "
                                 "[{\"type\": \"laser\"}], \"objects\": []}",
                                 "s.json", NULL, NULL, &sc),
              LUCENT_ERR_PARSE, "lights[0].type", "laser");
    CHECK_ERR(lucent_scene_parse("{\"camera\": {\"position\": [0,0,1], ", "trunc.json", NULL, NULL, &sc),
              LUCENT_ERR_PARSE, "trunc.json", "end of file");
    CHECK_ERR(lucent_scene_load("/nonexistent/scene.json", NULL, &sc), LUCENT_ERR_IO, "/nonexistent/scene.json");
    CHECK(sc == NULL);
}

TEST(default_scenes_are_valid)
{
    /* Every scene in data/scenes reads and checks (meshes skipped: they are fetched at set-up). */
    static const char *const names[] = {"dragon-marble", "bunny-skin", "bunny-jade", "spheres-skin",
                                        "bunny-skin-points"};
    for (int i = 0; i < 5; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/data/scenes/%s.json", LUCENT_SOURCE_DIR, names[i]);
        lucent_scene *sc = NULL;
        CHECK_OK(lucent_scene_load(path, &(lucent_scene_load_desc){.skip_meshes = true}, &sc));
        if (sc) CHECK(!strcmp(sc->name, names[i]));
        lucent_scene_destroy(sc);
    }
    char path[1024];
    snprintf(path, sizeof path, "%s/data/scenes/spheres-skin.json", LUCENT_SOURCE_DIR);
    lucent_scene *sc = NULL;
    CHECK_OK(lucent_scene_load(path, NULL, &sc)); /* primitives need no download */
    if (!sc) return;
    CHECK(sc->object_count == 5);
    double c[3], rmin, rmax;
    mesh_sphere(sc->objects[4].mesh, c, &rmin, &rmax);
    CHECK_NEAR(rmax, 16, 1e-9);
    lucent_scene_destroy(sc);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        TEST_ENTRY(ray_through_a_pixel_projects_back_onto_it),
        TEST_ENTRY(view_matrix_maps_the_target_onto_the_negative_z_axis),
        TEST_ENTRY(projection_depth_range),
        TEST_ENTRY(minimal_scene_gets_the_documented_defaults),
        TEST_ENTRY(mm_per_unit_and_transform_place_the_mesh_in_world_mm),
        TEST_ENTRY(as_points_is_read),
        TEST_ENTRY(subdivide_refines_the_mesh_after_loading),
        TEST_ENTRY(rotation_follows_the_right_hand_rule),
        TEST_ENTRY(mirroring_keeps_normals_outward),
        TEST_ENTRY(overrides_change_values_and_are_checked_like_the_file),
        TEST_ENTRY(method_names),
        TEST_ENTRY(setting_names_read_back),
        TEST_ENTRY(bad_fields_are_named),
        TEST_ENTRY(default_scenes_are_valid),
    };
    return test_run(cases, sizeof cases / sizeof cases[0], argc, argv);
}
