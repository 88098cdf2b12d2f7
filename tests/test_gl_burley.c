/* GL test (label gl) of the burley method (src/gl/methods/burley.c): the disk-sampled blur against
 * Burley's edge response computed here. A plane facing the camera, evenly lit along the view axis, is two
 * squares of one material (Skin1), the left white and the right black (their "albedo" colours) and without
 * specular: the radiance across the edge is c P(x), P(x) the share of the profile over the white half-plane
 * for a point x mm from the edge, here by numerical integration of Burley's profile (Christensen & Burley
 * 2015, eq. 2) in polar coordinates, independent of the shader. With the hand mapping d = 1 / sigma_tr
 * (lucent_material_derive), known without a fit. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "lucent/material.h"
#include "lucent/render.h"
#include "lucent/scene.h"
#include "test.h"

/* The share of the unit Burley profile of d over the half-plane u < -x, the point at the origin:
 * integral over rho of pdf(rho) frac(rho), pdf(rho) = (e^{-rho/d} + e^{-rho/(3 d)}) / (4 d), frac the
 * share of the circle of radius rho beyond the edge. Simpson's rule to 60 d. */
static double edge_share(double d, double x)
{
    const int n = 20000;
    double h = 60.0 * d / n, sum = 0.0;
    for (int i = 0; i <= n; i++) {
        double rho = i * h, frac;
        if (rho == 0.0)
            frac = x > 0 ? 0.0 : x < 0 ? 1.0 : 0.5;
        else if (rho <= fabs(x))
            frac = x > 0 ? 0.0 : 1.0;
        else
            frac = x >= 0 ? acos(x / rho) / M_PI : 1.0 - acos(-x / rho) / M_PI;
        double f = (exp(-rho / d) + exp(-rho / (3.0 * d))) / (4.0 * d) * frac;
        sum += f * (i == 0 || i == n ? 1 : i % 2 ? 4 : 2);
    }
    return sum * h / 3.0;
}

TEST(edge_share_is_a_cdf)
{
    /* the share is 1/2 on the edge (symmetry), tends to 1 deep in the white, 0 deep in the black */
    CHECK_NEAR(edge_share(2.0, 0.0), 0.5, 1e-6);
    CHECK_NEAR(edge_share(2.0, -200.0), 1.0, 1e-6);
    CHECK_NEAR(edge_share(2.0, 200.0), 0.0, 1e-6);
    CHECK_NEAR(edge_share(2.0, 3.0) + edge_share(2.0, -3.0), 1.0, 1e-6);
}

/* A square of the plane z = 0, x in [x0, x1], y in [-40, 40] mm, facing +z. */
static void write_square(const char *path, double x0, double x1)
{
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return;
    fprintf(f, "v %g -40 0\nv %g -40 0\nv %g 40 0\nv %g 40 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1//1 3//1 4//1\n", x0, x1,
            x1, x0);
    fclose(f);
}

/* The scene: the white and black squares (white_left: the left one's albedo 1, else 0). */
static lucent_scene *halves(double white_left)
{
    char left[1100], right[1100], json[4096];
    snprintf(left, sizeof left, "%s", test_path("left.obj"));
    snprintf(right, sizeof right, "%s", test_path("right.obj"));
    write_square(left, -70, 0);
    write_square(right, 0, 70);
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [0, 0, 400], \"target\": [0, 0, 0], \"fov_y\": 6},"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [0, 0, -1], \"intensity\": 1}],"
             " \"objects\": [{\"name\": \"left\", \"mesh\": \"%s\", \"material\": \"skin1\", \"albedo\": %g},"
             " {\"name\": \"right\", \"mesh\": \"%s\", \"material\": \"skin1\", \"albedo\": 0}],"
             " \"render\": {\"width\": 160, \"height\": 64, \"method\": \"burley:hand\", \"burley_samples\": 128,"
             " \"shadow_map_size\": 256}}",
             left, white_left, right);
    lucent_scene *sc = NULL;
    CHECK_OK(lucent_scene_parse(json, "edge.json", NULL, NULL, &sc));
    return sc;
}

/* The mean of rows 20 .. 43 of each column. */
static void row_means(const lucent_image *img, double dest[][3])
{
    for (int x = 0; x < img->width; x++)
        for (int c = 0; c < 3; c++) {
            dest[x][c] = 0.0;
            for (int y = 20; y < 44; y++) dest[x][c] += lucent_image_get(img, x, y, c) / 24.0;
        }
}

/* Expected: the blurred edge follows P(x) per channel within 0.03 of the white plateau (the disk's sampling
 * noise left after averaging 24 rows, about 0.01, and the 0.6 mm pixel across the steepest part). The
 * specular, the same on both halves, is taken out by a render with both black. */
TEST(burley_edge_follows_the_profile)
{
    lucent_scene *sc = halves(1.0), *dark = halves(0.0);
    lucent_gl_context *ctx = NULL;
    lucent_renderer *r = NULL, *rd = NULL;
    lucent_render_result res = {0}, spec = {0};
    if (sc && dark) CHECK_OK(lucent_gl_create(NULL, &ctx));
    lucent_renderer_desc desc = {.cache_dir = test_tmpdir(), .profile_photons = 20000}; /* the hand's d needs none */
    if (ctx) CHECK_OK(lucent_renderer_create(ctx, sc, &desc, &r));
    if (ctx) CHECK_OK(lucent_renderer_create(ctx, dark, &desc, &rd));
    if (r && rd) CHECK_OK(lucent_render(r, &sc->render, &res));
    if (r && rd) CHECK_OK(lucent_render(rd, &dark->render, &spec));
    if (res.image && spec.image) {
        lucent_material_derived d;
        lucent_material_derive(&sc->objects[0].material, &d);
        static double lit[160][3], sp[160][3];
        double x_mm[160];
        row_means(res.image, lit);
        row_means(spec.image, sp);
        for (int x = 0; x < res.image->width; x++) {
            double o[3], dir[3];
            lucent_camera_ray(&sc->camera, res.image->width, res.image->height, x + 0.5, 32.0, o, dir);
            x_mm[x] = o[0] - o[2] / dir[2] * dir[0]; /* where the ray meets z = 0 */
        }
        for (int c = 0; c < 3; c++) {
            double dc = d.mfp_diffuse[c];                                      /* the hand mapping's d = 1 / sigma_tr */
            double plateau = (lit[2][c] - sp[2][c]) / edge_share(dc, x_mm[2]); /* the far left, its own share */
            for (int x = 4; x < res.image->width - 4; x += 4) {
                double want = edge_share(dc, x_mm[x]), got = (lit[x][c] - sp[x][c]) / plateau;
                CHECK_MSG(fabs(got - want) <= 0.03, "channel %d, x = %.2f mm: %.4f, Burley %.4f", c, x_mm[x], got,
                          want);
            }
        }
    }
    lucent_render_result_free(&res);
    lucent_render_result_free(&spec);
    lucent_renderer_destroy(r);
    lucent_renderer_destroy(rd);
    lucent_gl_destroy(ctx);
    lucent_scene_destroy(sc);
    lucent_scene_destroy(dark);
}

TEST_MAIN(TEST_ENTRY(edge_share_is_a_cdf), TEST_ENTRY(burley_edge_follows_the_profile))
