/* GL tests (label gl) of texture-space diffusion (src/gl/methods/tsd.c): a sharp shadow edge on a
 * flat plane (at two texture scales, and cut into two charts turned and scaled against each other,
 * the edge crossing the seam) and on a UV sphere with its analytic coordinates, diffused by TSD,
 * against the CPU convolution in object space of the same irradiance with the same sum of
 * Gaussians (d'Eon's skin table). The irradiance is Lambert's image of the same scene (the same
 * shadow map and filter); positions come from the renderer's auxiliary outputs. The objects have roughness 0,
 * so the boundary's GGX lobe shows no highlight (Lambert's image is then irradiance only, times the
 * slowly varying F_t(w_o) that both methods apply after the diffusion). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "gl/renderer.h"
#include "lucent/profile.h"
#include "lucent/render.h"
#include "test.h"

static lucent_gl_context *g_ctx;

/* The boundary's tables with few photons (about 5% per entry): the tests compare tsd with other
 * methods and references that read the same tables. */
static const lucent_renderer_desc k_desc = {.boundary_photons = 400, .sphere_photons = 2000};

/* ---- meshes written for the scenes ---- */

/* The plane y = 0, x, z in [-20, 20] mm, n x n quads facing +y, texture coordinates
 * (1 - scale) / 2 + scale (x + 20) / 40 (and z alike): scale 1 fills the texture, 0.5 its middle. */
static void write_plane(const char *path, int n, double scale)
{
    FILE *f = fopen(path, "w");
    if (!f) return;
    double a = 0.5 * (1 - scale);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            double x = -20 + 40.0 * i / n, z = -20 + 40.0 * j / n;
            fprintf(f, "v %.9g 0 %.9g\nvt %.9g %.9g\n", x, z, a + scale * i / n, a + scale * j / n);
        }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int v00 = j * (n + 1) + i + 1, v10 = v00 + 1, v01 = v00 + n + 1, v11 = v01 + 1;
            fprintf(f, "f %d/%d %d/%d %d/%d\nf %d/%d %d/%d %d/%d\n", v00, v00, v01, v01, v10, v10, v10, v10, v01, v01,
                    v11, v11);
        }
    fclose(f);
}

/* The same plane cut along its diagonal x + z = 0 into two charts: x + z < 0 at
 * (u, v) = 0.02 + 0.015 (x + 20, z + 20), the rest turned by 90 degrees and at half the scale,
 * (u, v) = (0.66 + 0.0075 (20 - z), 0.02 + 0.0075 (x + 20)); 82 texels of empty texture between the two
 * charts at 2048^2. Each vertex has two coordinates (vt 2 v + 1 and 2 v + 2); a face takes its chart's. */
static void write_two_chart_plane(const char *path, int n)
{
    FILE *f = fopen(path, "w");
    if (!f) return;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            double x = -20 + 40.0 * i / n, z = -20 + 40.0 * j / n;
            fprintf(f, "v %.9g 0 %.9g\nvt %.9g %.9g\nvt %.9g %.9g\n", x, z, 0.02 + 0.015 * (x + 20),
                    0.02 + 0.015 * (z + 20), 0.66 + 0.0075 * (20 - z), 0.02 + 0.0075 * (x + 20));
        }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int v00 = j * (n + 1) + i + 1, v10 = v00 + 1, v01 = v00 + n + 1, v11 = v01 + 1;
            int tri[2][3] = {{v00, v01, v10}, {v10, v01, v11}};
            for (int t = 0; t < 2; t++) {
                int b = i + j + 1 < n || (i + j + 1 == n && t == 0) ? 0 : 1; /* 0: chart A, x + z < 0 */
                fprintf(f, "f %d/%d %d/%d %d/%d\n", tri[t][0], 2 * tri[t][0] - 1 + b, tri[t][1], 2 * tri[t][1] - 1 + b,
                        tri[t][2], 2 * tri[t][2] - 1 + b);
            }
        }
    fclose(f);
}

/* A horizontal occluder at height y: x in [x0, x1], z in [-80, 80]. */
static void write_roof(const char *path, double y, double x0, double x1)
{
    FILE *f = fopen(path, "w");
    if (!f) return;
    fprintf(f, "v %g %g -80\nv %g %g 80\nv %g %g 80\nv %g %g -80\nf 1 2 3\nf 1 3 4\n", x0, y, x0, y, x1, y, x1, y);
    fclose(f);
}

/* ---- samples along the coordinate across the edge ---- */

enum { BIN_MAX = 4096 };

typedef struct profile1d {
    double lo, step; /* bin b covers lo + b step .. + step */
    int count;
    double sum[BIN_MAX][3];
    int n[BIN_MAX];
} profile1d;

/* Bins the image's pixels of object 0 whose position passes keep(), by coord(position). */
static void bin_image(lucent_renderer *r, const lucent_render_settings *s, profile1d *p, bool (*keep)(const float *pos),
                      double (*coord)(const float *pos))
{
    lucent_render_result res;
    lucent_image *pos = NULL;
    memset(p->sum, 0, sizeof p->sum), memset(p->n, 0, sizeof p->n);
    CHECK_OK(lucent_render(r, s, &res));
    CHECK_OK(gl_renderer_read_aov(r, 1, &pos));
    for (size_t i = 0; res.image && pos && i < (size_t)s->view.width * (size_t)s->view.height; i++) {
        const float *q = pos->data + 4 * i;
        if (res.mask->data[i] < 0.5f || q[3] != 0 || !keep(q)) continue;
        int b = (int)floor((coord(q) - p->lo) / p->step);
        if (b < 0 || b >= p->count) continue;
        for (int c = 0; c < 3; c++) p->sum[b][c] += res.image->data[3 * i + c];
        p->n[b]++;
    }
    for (int b = 0; b < p->count; b++)
        for (int c = 0; c < 3 && p->n[b]; c++) p->sum[b][c] /= p->n[b];
    lucent_image_destroy(pos);
    lucent_render_result_free(&res);
}

/* Empty bins linearly between their neighbours (ends: the nearest). */
static void fill_gaps(profile1d *p)
{
    for (int b = 0; b < p->count; b++) {
        if (p->n[b]) continue;
        int l = b - 1, h = b + 1;
        while (l >= 0 && !p->n[l]) l--;
        while (h < p->count && !p->n[h]) h++;
        for (int c = 0; c < 3; c++) {
            double vl = l >= 0 ? p->sum[l][c] : p->sum[h][c], vh = h < p->count ? p->sum[h][c] : vl;
            double t = l >= 0 && h < p->count ? (double)(b - l) / (h - l) : 0;
            p->sum[b][c] = vl + t * (vh - vl);
        }
    }
}

/* The CPU reference: sum_i w_i (E * N(v_i))(x), the 1-D marginal of d'Eon's G(v, r) across a straight
 * edge (GPU Gems 3 Eq. 14-1: per axis variance v), E the binned Lambert image linear between bin
 * centres, integrated on a grid of a fifth of a bin (Riemann sum of the Gaussian). */
static double cpu_diffused(const profile1d *e, const lucent_sog *g, int c, double x)
{
    double sum = 0;
    for (int k = 0; k < g->count; k++) {
        double v = g->variance[c][k], sd = sqrt(v), h = e->step / 5, acc = 0, wsum = 0;
        for (double t = -5 * sd; t <= 5 * sd; t += fmin(h, sd / 4)) {
            double xs = (x + t - e->lo) / e->step - 0.5;
            int b = (int)floor(xs);
            double f = xs - b;
            b = b < 0 ? 0 : b >= e->count - 1 ? e->count - 2 : b;
            f = fmin(fmax(f, 0), 1);
            double w = exp(-0.5 * t * t / v), val = (1 - f) * e->sum[b][c] + f * e->sum[b + 1][c];
            acc += w * val, wsum += w;
        }
        sum += g->weight[c][k] * acc / wsum;
    }
    return sum;
}

static void normalised_deon(lucent_sog *g)
{
    lucent_sog_deon_skin(g);
    for (int c = 0; c < 3; c++) {
        double t = 0;
        for (int k = 0; k < g->count; k++) t += g->weight[c][k];
        for (int k = 0; k < g->count; k++) g->weight[c][k] /= t;
    }
}

/* The worst |TSD - CPU| over bins in [from, to], relative to the step (lit minus shadowed Lambert);
 * also how far TSD moved from Lambert there (that diffusion happened). */
static void compare_edge(const profile1d *lam, const profile1d *tsd, double from, double to, const double step[3],
                         double worst[3], double moved[3])
{
    lucent_sog g;
    normalised_deon(&g);
    for (int c = 0; c < 3; c++) worst[c] = moved[c] = 0;
    for (int b = 0; b < tsd->count; b++) {
        double x = tsd->lo + (b + 0.5) * tsd->step;
        if (x < from || x > to || !tsd->n[b]) continue;
        for (int c = 0; c < 3; c++) {
            double e = fabs(tsd->sum[b][c] - cpu_diffused(lam, &g, c, x)) / step[c];
            worst[c] = fmax(worst[c], e);
            moved[c] = fmax(moved[c], fabs(tsd->sum[b][c] - lam->sum[b][c]) / step[c]);
        }
    }
}

/* ---- the plane ---- */

static bool on_plane(const float *p) { return fabsf(p[1]) < 0.01f && fabsf(p[2]) < 5; }
static double plane_x(const float *p) { return p[0]; }

static const char k_plane_scene[] =
    "{\"camera\": {\"position\": [8, 40, 10], \"target\": [0, 0, 0], \"fov_y\": 40},"
    " \"lights\": [{\"type\": \"directional\", \"direction\": [1, -1, 0], \"intensity\": 3}],"
    " \"objects\": [{\"mesh\": \"%s\", \"material\": \"skin1\", \"roughness\": 0},"
    "              {\"mesh\": \"%s\", \"material\": \"skin1\", \"roughness\": 0}],"
    " \"render\": {\"width\": 512, \"height\": 512, \"method\": \"tsd\", \"tsd_size\": 2048, \"tsd_sog\": \"deon\", "
    "\"translucency\": false}}";

/* The roof at y = 10 over x < -10 lit along (1, -1, 0): the plane's shadow ends at x = 0. */
static void plane_edge(double scale, double worst[3], profile1d *out, double step[3])
{
    char dir[] = "/tmp/lucent-tsd-XXXXXX", plane[256], roof[256], json[2048];
    if (!mkdtemp(dir)) return;
    snprintf(plane, sizeof plane, "%s/plane.obj", dir), snprintf(roof, sizeof roof, "%s/roof.obj", dir);
    write_plane(plane, 80, scale);
    write_roof(roof, 10, -60, -10);
    snprintf(json, sizeof json, k_plane_scene, plane, roof);
    lucent_scene *sc = NULL;
    lucent_renderer *r = NULL;
    CHECK_OK(lucent_scene_parse(json, "plane.json", NULL, NULL, &sc));
    if (sc) CHECK_OK(lucent_renderer_create(g_ctx, sc, &k_desc, &r));
    static profile1d lam, tsd;
    memset(out, 0, sizeof *out), step[0] = step[1] = step[2] = 1;
    if (r) {
        gl_renderer_set_aov(r, true);
        lucent_render_settings s = sc->render;
        lam.lo = tsd.lo = -19, lam.step = tsd.step = 0.05, lam.count = tsd.count = 760;
        bin_image(r, &s, &tsd, on_plane, plane_x);
        s.view.method = LUCENT_METHOD_LAMBERT;
        bin_image(r, &s, &lam, on_plane, plane_x);
        fill_gaps(&lam);
        double moved[3];
        for (int c = 0; c < 3; c++) step[c] = lam.sum[lam.count - 60][c] - lam.sum[60][c]; /* x = 16 and -16 */
        memcpy(out, &tsd, sizeof tsd);
        compare_edge(&lam, &tsd, -8, 8, step, worst, moved);
        printf("  plane, texture scale %.2f: |TSD - CPU| / step at most %.4f %.4f %.4f (r g b) over x in [-8, 8] mm; "
               "TSD differs from Lambert by up to %.3f %.3f %.3f\n",
               scale, worst[0], worst[1], worst[2], moved[0], moved[1], moved[2]);
        CHECK(moved[0] > 0.1); /* red diffuses visibly (d'Eon's widest red Gaussian: 2.7 mm) */
        for (int c = 0; c < 3; c++) CHECK_MSG(worst[c] < 0.02, "channel %d: %.4f of the step", c, worst[c]);
    }
    lucent_renderer_destroy(r);
    lucent_scene_destroy(sc);
    unlink(plane), unlink(roof), rmdir(dir);
}

/* Stretch correction: the plane over the whole texture and over its middle quarter give the same
 * diffusion (the Gaussians are in mm, the taps in texels scaled by the stretch map). */
TEST(plane_edge_matches_object_space_convolution)
{
    if (!g_ctx) CHECK_OK(lucent_gl_create(NULL, &g_ctx));
    if (!g_ctx) return;
    static profile1d full, half;
    double worst[3], step[3], apart[3] = {0};
    plane_edge(1, worst, &full, step);
    plane_edge(0.5, worst, &half, step);
    for (int b = 0; b < full.count; b++) {
        double x = full.lo + (b + 0.5) * full.step;
        for (int c = 0; c < 3 && fabs(x) < 8 && full.n[b] && half.n[b]; c++)
            apart[c] = fmax(apart[c], fabs(full.sum[b][c] - half.sum[b][c]) / step[c]);
    }
    printf("  the two texture scales differ by at most %.4f %.4f %.4f of the step\n", apart[0], apart[1], apart[2]);
    for (int c = 0; c < 3; c++) CHECK_MSG(apart[c] < 0.01, "channel %d: %.4f of the step apart", c, apart[c]);
}

/* ---- a seam ---- */

static bool near_seam(const float *p) { return fabsf(p[1]) < 0.01f && fabsf(p[0] + p[2]) < 0.5f; }

/* The plane of two charts (write_two_chart_plane) under the same roof: the shadow edge x = 0 crosses
 * the seam x + z = 0 at the origin, at 45 degrees to both charts' axes. Pixels within 0.5 mm of the seam
 * (both charts), binned by x, against the CPU convolution across the edge of Lambert's image of the
 * same pixels (the irradiance depends on x alone); the seam must not show. With seams off (each chart
 * blurred alone, d'Eon's normalised convolution) the same comparison is printed and must fail: the
 * test sees what it tests. */
static void seam_edge(bool seams, double worst[3])
{
    char dir[] = "/tmp/lucent-tsd-XXXXXX", plane[256], roof[256], json[2048];
    worst[0] = worst[1] = worst[2] = 1;
    if (!mkdtemp(dir)) return;
    snprintf(plane, sizeof plane, "%s/plane.obj", dir), snprintf(roof, sizeof roof, "%s/roof.obj", dir);
    write_two_chart_plane(plane, 80);
    write_roof(roof, 10, -60, -10);
    snprintf(json, sizeof json, k_plane_scene, plane, roof);
    lucent_scene *sc = NULL;
    lucent_renderer *r = NULL;
    CHECK_OK(lucent_scene_parse(json, "seam.json", NULL, NULL, &sc));
    if (sc) CHECK_OK(lucent_renderer_create(g_ctx, sc, &k_desc, &r));
    static profile1d lam, tsd;
    if (r) {
        gl_renderer_set_aov(r, true);
        lucent_render_settings s = sc->render;
        s.tsd.seams = seams;
        lam.lo = tsd.lo = -19, lam.step = tsd.step = 0.05, lam.count = tsd.count = 760;
        bin_image(r, &s, &tsd, near_seam, plane_x);
        s.view.method = LUCENT_METHOD_LAMBERT;
        bin_image(r, &s, &lam, near_seam, plane_x); /* the same pixels: the same view-dependent F_t(w_o) */
        int first = 0, last = lam.count - 1;        /* the band's ends in view, 8 mm and more from the edge */
        while (first < last && !lam.n[first]) first++;
        while (last > first && !lam.n[last]) last--;
        CHECK(lam.lo + first * lam.step < -8 && lam.lo + last * lam.step > 8);
        fill_gaps(&lam);
        double moved[3], step[3];
        for (int c = 0; c < 3; c++) step[c] = lam.sum[last][c] - lam.sum[first][c];
        compare_edge(&lam, &tsd, -8, 8, step, worst, moved);
        printf(
            "  two charts (the second turned 90 degrees, half the scale), seams %s: |TSD - CPU| / step at the seam "
            "at most %.4f %.4f %.4f (r g b) over x in [-8, 8] mm; TSD differs from Lambert by up to %.3f %.3f %.3f\n",
            seams ? "followed" : "off", worst[0], worst[1], worst[2], moved[0], moved[1], moved[2]);
        CHECK(moved[0] > 0.1);
    }
    lucent_renderer_destroy(r);
    lucent_scene_destroy(sc);
    unlink(plane), unlink(roof), rmdir(dir);
}

TEST(seam_invisible_in_the_diffusion)
{
    if (!g_ctx) CHECK_OK(lucent_gl_create(NULL, &g_ctx));
    if (!g_ctx) return;
    double with[3], without[3];
    seam_edge(true, with);
    seam_edge(false, without);
    for (int c = 0; c < 3; c++) CHECK_MSG(with[c] < 0.02, "channel %d: %.4f of the step", c, with[c]);
    CHECK_MSG(without[0] > 0.02, "without the seams the red error is only %.4f of the step", without[0]);
}

/* ---- the sphere ---- */

static bool on_equator(const float *p) { return fabsf(p[2]) < 0.6f && p[1] > 0; }
static double equator_arc(const float *p) { return hypot(hypot(p[0], p[1]), p[2]) * atan2(p[0], p[1]); }

/* A UV sphere of radius 20 (poles on z, its analytic coordinates), lit from +y, under a roof at
 * y = 50 over x < 0: the shadow edge is the meridian x = 0, crossing the equator at the top, where
 * the equator runs along u. Arc length s = R atan2(x, y) along the equator. */
TEST(sphere_edge_matches_object_space_convolution)
{
    if (!g_ctx) CHECK_OK(lucent_gl_create(NULL, &g_ctx));
    if (!g_ctx) return;
    char dir[] = "/tmp/lucent-tsd-XXXXXX", roof[256], json[2048];
    if (!mkdtemp(dir)) return;
    snprintf(roof, sizeof roof, "%s/roof.obj", dir);
    write_roof(roof, 50, -80, 0);
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [0, 45, 25], \"target\": [0, 20, 0], \"fov_y\": 50},"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [0, -1, 0], \"intensity\": 3}],"
             " \"objects\": [{\"mesh\": {\"primitive\": \"uv_sphere\", \"radius\": 20, \"u_count\": 256, \"v_count\":"
             " 128}, \"material\": \"skin1\", \"roughness\": 0},"
             "              {\"mesh\": \"%s\", \"material\": \"skin1\", \"roughness\": 0}],"
             " \"render\": {\"width\": 1024, \"height\": 1024, \"method\": \"tsd\", \"tsd_size\": 2048, \"tsd_sog\": "
             "\"deon\", \"translucency\": false}}",
             roof);
    lucent_scene *sc = NULL;
    lucent_renderer *r = NULL;
    CHECK_OK(lucent_scene_parse(json, "sphere.json", NULL, NULL, &sc));
    if (sc) CHECK_OK(lucent_renderer_create(g_ctx, sc, &k_desc, &r));
    static profile1d lam, tsd;
    if (r) {
        gl_renderer_set_aov(r, true);
        lucent_render_settings s = sc->render;
        lam.lo = tsd.lo = -18, lam.step = tsd.step = 0.05, lam.count = tsd.count = 720;
        bin_image(r, &s, &tsd, on_equator, equator_arc);
        s.view.method = LUCENT_METHOD_LAMBERT;
        bin_image(r, &s, &lam, on_equator, equator_arc);
        fill_gaps(&lam);
        double step[3], worst[3], moved[3];
        for (int c = 0; c < 3; c++) step[c] = lam.sum[370][c] - lam.sum[120][c]; /* s = 0.5 and -12 mm */
        compare_edge(&lam, &tsd, -6, 6, step, worst, moved);
        printf("  sphere R 20: |TSD - CPU| / step at most %.4f %.4f %.4f (r g b) over s in [-6, 6] mm; TSD differs "
               "from Lambert by up to %.3f %.3f %.3f\n",
               worst[0], worst[1], worst[2], moved[0], moved[1], moved[2]);
        CHECK(moved[0] > 0.1);
        for (int c = 0; c < 3; c++) CHECK_MSG(worst[c] < 0.02, "channel %d: %.4f of the step", c, worst[c]);
    }
    lucent_renderer_destroy(r);
    lucent_scene_destroy(sc);
    unlink(roof), rmdir(dir);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {TEST_ENTRY(plane_edge_matches_object_space_convolution),
                                      TEST_ENTRY(seam_invisible_in_the_diffusion),
                                      TEST_ENTRY(sphere_edge_matches_object_space_convolution)};
    int rc = test_run(cases, (int)(sizeof cases / sizeof cases[0]), argc, argv);
    lucent_gl_destroy(g_ctx);
    return rc;
}
