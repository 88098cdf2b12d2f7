/* GL tests (label gl): the renderer on llvmpipe. The CDRF and Lambert passes against the CPU shading
 * reference (src/gl/reference.c) at every covered pixel; symmetry of a sphere lit along the view
 * axis; translucency through a thin disc lit from behind (brighter, and red for skin); timings,
 * masks, rebuilds; a scene changed under a renderer and bakes adopted from elsewhere; context and
 * shader errors that name their cause. */
#include <math.h>
#include <stdlib.h>

#include "base/optics.h"
#include "gl/core/gpu.h"
#include "gl/reference/reference.h"
#include "gl/renderer.h"
#include "lucent/mc.h"
#include "lucent/render.h"
#include "test.h"

static lucent_gl_context *g_ctx;

static lucent_gl_context *context(void)
{
    if (!g_ctx) CHECK_OK(lucent_gl_create(NULL, &g_ctx));
    return g_ctx;
}

static lucent_scene *scene_from(const char *json)
{
    lucent_scene *sc = NULL;
    CHECK_OK(lucent_scene_parse(json, "test.json", NULL, NULL, &sc));
    return sc;
}

static lucent_renderer *renderer_with(const lucent_scene *sc, const lucent_renderer_desc *desc)
{
    lucent_renderer *r = NULL;
    if (sc && context()) CHECK_OK(lucent_renderer_create(g_ctx, sc, desc, &r));
    return r;
}

/* The boundary's tables with few photons (about 5% per entry): no test here measures them (the
 * reference comparisons read the table the renderer used; test_gl_boundary holds the tables to the
 * path tracer), and every renderer of a test bakes its own. */
enum { TEST_BOUNDARY_PHOTONS = 400, TEST_SPHERE_PHOTONS = 2000 };

static lucent_renderer *renderer_of(const lucent_scene *sc)
{
    return renderer_with(
        sc, &(lucent_renderer_desc){.boundary_photons = TEST_BOUNDARY_PHOTONS, .sphere_photons = TEST_SPHERE_PHOTONS});
}

/* ---- the CDRF and Lambert passes against the CPU reference ---- */

/* A torus (positive and near-zero mean curvature), skin with an explicit sigma0 large enough that
 * sigma = sigma0 kappa spans [0, 3]; one directional light without shadows plus an environment. */
static const char k_torus[] =
    "{\"camera\": {\"position\": [0, 14, 22], \"target\": [0, 0, 0], \"fov_y\": 40},"
    " \"lights\": [{\"type\": \"directional\", \"direction\": [0.8, -0.5, -0.3], \"intensity\": 3, \"shadows\": false},"
    "              {\"type\": \"environment\", \"intensity\": 0.05}],"
    " \"objects\": [{\"mesh\": {\"primitive\": \"torus\", \"major_radius\": 6, \"radius\": 2.5, \"u_count\": 96,"
    "               \"v_count\": 48}, \"material\": \"skin1\", \"sigma0\": [9, 5, 2.5], \"roughness\": 0.35}],"
    " \"render\": {\"width\": 96, \"height\": 96, \"method\": \"cdrf\", \"shadow_map_size\": 256}}";

/* Max |GPU - CPU| over the covered pixels; the CPU gets the GPU's own normal, curvature, position. */
static double shading_error(lucent_renderer *r, const lucent_scene *sc, const lucent_render_settings *s,
                            const lucent_image *lut, double *max_sigma)
{
    lucent_render_result res;
    lucent_image *nk = NULL, *pos = NULL;
    double worst = -1;
    CHECK_OK(lucent_render(r, s, &res));
    CHECK_OK(gl_renderer_read_aov(r, 0, &nk));
    CHECK_OK(gl_renderer_read_aov(r, 1, &pos));
    const lucent_scene_object *o = &sc->objects[0];
    const lucent_baked *b = gl_tables_of(&r->tables, 0); /* the tables it used */
    bool curved = s->view.method == LUCENT_METHOD_CDRF && s->cdrf.curved_parts;
    gl_ref_material m = {.roughness = o->roughness,
                         .eta = o->material.eta,
                         .boundary = b->boundary,
                         .spheres = curved ? b->spheres : NULL,
                         .sphere_r0 = b->sphere_r0};
    lucent_render_object_info info;
    CHECK_OK(lucent_renderer_object_info(r, 0, &info)); /* the albedo it shaded with: the boundary's */
    for (int c = 0; c < 3; c++) m.albedo[c] = info.albedo[c], m.sigma0[c] = o->sigma0[c];
    for (size_t i = 0; res.image && nk && pos && i < (size_t)s->view.width * (size_t)s->view.height; i++) {
        if (res.mask->data[i] < 0.5f) continue;
        gl_ref_point p = {.curvature = nk->data[4 * i + 3]};
        for (int c = 0; c < 3; c++) p.position[c] = pos->data[4 * i + c], p.normal[c] = nk->data[4 * i + c];
        double d[3], sp[3];
        gl_ref_shade(sc, s->view.method, s->cdrf.variant, s->cdrf.lut ? lut : NULL, 3.0, &m, &p, d, sp);
        for (int c = 0; c < 3; c++) worst = fmax(worst, fabs(res.image->data[3 * i + c] - (d[c] + sp[c])));
        *max_sigma = fmax(*max_sigma, m.sigma0[0] * p.curvature);
    }
    lucent_image_destroy(nk);
    lucent_image_destroy(pos);
    lucent_render_result_free(&res);
    return worst;
}

/* Expected: the CPU reference gl_ref_shade (double precision, written apart from scene.frag.glsl)
 * with the LUT read bilinearly from a table built on the CPU, or the exact function
 * (lucent_cdrf_kubo, lucent_cdrf_collomb) for the closed form. */
TEST(cdrf_and_lambert_equal_cpu_reference)
{
    lucent_scene *sc = scene_from(k_torus);
    lucent_renderer *r = renderer_of(sc);
    if (!r) return lucent_scene_destroy(sc);
    gl_renderer_set_aov(r, true);
    static const struct {
        lucent_render_method m;
        lucent_cdrf_variant v;
        bool lut, curved;
    } cases[] = {{LUCENT_METHOD_CDRF, LUCENT_CDRF_KUBO, true, false},
                 {LUCENT_METHOD_CDRF, LUCENT_CDRF_COLLOMB, true, false},
                 {LUCENT_METHOD_CDRF, LUCENT_CDRF_KUBO, false, false},
                 {LUCENT_METHOD_CDRF, LUCENT_CDRF_COLLOMB, false, false},
                 {LUCENT_METHOD_LAMBERT, LUCENT_CDRF_KUBO, false, false},
                 {LUCENT_METHOD_CDRF, LUCENT_CDRF_KUBO, true, true}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        lucent_render_settings s = sc->render;
        s.view.method = cases[k].m, s.cdrf.variant = cases[k].v, s.cdrf.lut = cases[k].lut;
        s.cdrf.curved_parts = cases[k].curved;
        lucent_cdrf_lut_desc ld = lucent_cdrf_lut_defaults();
        ld.variant = cases[k].v;
        lucent_image *lut = NULL;
        CHECK_OK(lucent_cdrf_lut_build(&ld, &lut));
        double max_sigma = 0, err = shading_error(r, sc, &s, lut, &max_sigma);
        const char *how = s.cdrf.curved_parts ? "curved parts" : s.cdrf.lut ? "LUT" : "closed form";
        CHECK_MSG(err >= 0 && err <= 1e-3, "%s %s %s: max |GPU - CPU| = %.3g", lucent_render_method_name(s.view.method),
                  lucent_cdrf_variant_name(s.cdrf.variant), how, err);
        printf("     %s %s %s: max |GPU - CPU| = %.3g (sigma up to %.2f)\n", lucent_render_method_name(s.view.method),
               lucent_cdrf_variant_name(s.cdrf.variant), how, err, max_sigma);
        if (k == 0) CHECK_MSG(max_sigma > 1.5, "the torus exercises sigma up to %.2f only", max_sigma);
        lucent_image_destroy(lut);
    }
    lucent_renderer_destroy(r);
    lucent_scene_destroy(sc);
}

/* ---- symmetry ---- */

/* An icosphere (mirror-symmetric about the coordinate planes) seen and lit along the z axis. */
static const char k_sphere[] =
    "{\"camera\": {\"position\": [0, 0, 60], \"target\": [0, 0, 0], \"fov_y\": 30},"
    " \"lights\": [{\"type\": \"directional\", \"direction\": [0, 0, -1], \"intensity\": 3},"
    "              {\"type\": \"environment\", \"intensity\": 0.05}],"
    " \"objects\": [{\"mesh\": {\"primitive\": \"icosphere\", \"radius\": 10, \"subdivisions\": 4},"
    "               \"material\": \"skin1\", \"sigma0\": [3, 2, 1]}],"
    " \"render\": {\"width\": 64, \"height\": 64, \"shadow_map_size\": 256, \"taps\": 17}}";

/* Largest |I(x, y) - I(mirror)| over both mirrors, relative to the image's largest value. */
static double asymmetry(const lucent_image *img)
{
    double worst = 0, peak = 1e-30;
    for (int y = 0; y < img->height; y++)
        for (int x = 0; x < img->width; x++)
            for (int c = 0; c < 3; c++) {
                double v = lucent_image_get(img, x, y, c);
                peak = fmax(peak, v);
                worst = fmax(worst, fabs(v - lucent_image_get(img, img->width - 1 - x, y, c)));
                worst = fmax(worst, fabs(v - lucent_image_get(img, x, img->height - 1 - y, c)));
            }
    return worst / peak;
}

/* Expected: a scene symmetric about the x = 0 and y = 0 planes renders symmetric (analytic fact);
 * the tolerance (1e-3 of the peak) allows float rounding in the rasteriser. */
TEST(sphere_lit_along_view_axis_is_symmetric)
{
    lucent_scene *sc = scene_from(k_sphere);
    lucent_renderer *r = renderer_of(sc);
    for (int m = 0; r && m < LUCENT_METHOD_COUNT; m++) {
        lucent_render_settings s = sc->render;
        s.view.method = (lucent_render_method)m;
        lucent_render_result res;
        CHECK_OK(lucent_render(r, &s, &res));
        double a = res.image ? asymmetry(res.image) : 1;
        /* tsd diffuses in the icosphere's atlas, whose charts are not mirror-symmetric (its accuracy is
         * tested against the object-space convolution in test_gl_tsd.c); burley's disk of samples turns per
         * pixel (noise, as HDRP's before its temporal filter; its accuracy is tested against Burley's edge
         * response in test_gl_burley.c): printed, not checked */
        if (m != LUCENT_METHOD_TSD && m != LUCENT_METHOD_BURLEY)
            CHECK_MSG(a <= 1e-3, "%s: asymmetry %.3g of the peak", lucent_render_method_name(s.view.method), a);
        printf("     %s: asymmetry %.2g of the peak\n", lucent_render_method_name(s.view.method), a);
        CHECK(res.mask && lucent_image_get(res.mask, 0, 0, 0) == 0 && lucent_image_get(res.mask, 32, 32, 0) == 1);
        lucent_render_result_free(&res);
    }
    lucent_renderer_destroy(r);
    lucent_scene_destroy(sc);
}

/* ---- translucency ---- */

/* A thin disc (an ellipsoid 50 x 50 x 4 mm) of skin, seen from the front, lit from straight behind. */
static const char k_slab[] =
    "{\"camera\": {\"position\": [0, 0, 80], \"target\": [0, 0, 0], \"fov_y\": 40},"
    " \"lights\": [{\"type\": \"directional\", \"direction\": [0, 0, 1], \"intensity\": 3},"
    "              {\"type\": \"environment\", \"intensity\": 0.02}],"
    " \"objects\": [{\"mesh\": {\"primitive\": \"ellipsoid\", \"axes\": [25, 25, 2], \"u_count\": 64, \"v_count\": 32},"
    "               \"material\": \"skin1\", \"sigma0\": [3.5, 2.3, 1.5]}],"
    " \"render\": {\"width\": 64, \"height\": 64, \"shadow_map_size\": 512, \"taps\": 17}}";

/* Mean radiance over the square [lo, hi) x [lo, hi) of pixels. */
static void square_mean(lucent_renderer *r, const lucent_render_settings *s, int lo, int hi, double dest[3])
{
    lucent_render_result res;
    dest[0] = dest[1] = dest[2] = 0;
    CHECK_OK(lucent_render(r, s, &res));
    int n = 0;
    for (int y = lo; res.image && y < hi; y++)
        for (int x = lo; x < hi; x++, n++)
            for (int c = 0; c < 3; c++) dest[c] += lucent_image_get(res.image, x, y, c);
    for (int c = 0; c < 3 && n; c++) dest[c] /= n;
    lucent_render_result_free(&res);
}

/* The disc's central pixels (within 12 mm of the axis). */
static void centre_mean(lucent_renderer *r, const lucent_render_settings *s, double dest[3])
{
    square_mean(r, s, 20, 44, dest);
}

/* Expected: light through a thin part adds to what the visible side shows (physics: the disc is lit
 * only from behind), and skin passes red far better than blue (Skin1's absorption rises from red to
 * blue, so its diffusion length 1 / sigma_tr is longest in red: 3.7, 1.4, 0.7 mm). Seen along the
 * light, through the thin parts' forward lobe (render.thin_sheet), red over green is what the path
 * tracer's Skin1 sheets show on their axis (test_gl_sheet: 1.7 at 2 mm, 4.4 at 5 mm): more than 2 at
 * the disc's 4 mm. */
TEST(translucency_brightens_a_backlit_disc_in_red)
{
    lucent_scene *sc = scene_from(k_slab);
    lucent_renderer *r = renderer_of(sc);
    if (r) {
        lucent_render_settings s = sc->render;
        s.translucency.sheet = true; /* the term this expectation is for (off by default) */
        double on[3], off[3], cdrf[3], cdrft[3];
        s.view.method = LUCENT_METHOD_SSSS;
        s.translucency.enabled = true;
        centre_mean(r, &s, on);
        s.translucency.enabled = false;
        centre_mean(r, &s, off);
        s.view.method = LUCENT_METHOD_CDRF;
        centre_mean(r, &s, cdrf);
        s.view.method = LUCENT_METHOD_CDRF_TRANSLUCENCY;
        centre_mean(r, &s, cdrft);
        double t[3] = {on[0] - off[0], on[1] - off[1], on[2] - off[2]};
        printf("     ssss: translucency on %.4f %.4f %.4f, off %.4f %.4f %.4f; transmitted R/G/B %.4f %.4f %.4f\n",
               on[0], on[1], on[2], off[0], off[1], off[2], t[0], t[1], t[2]);
        printf("     cdrf %.4f %.4f %.4f, cdrf+translucency %.4f %.4f %.4f\n", cdrf[0], cdrf[1], cdrf[2], cdrft[0],
               cdrft[1], cdrft[2]);
        CHECK_MSG(on[0] + on[1] + on[2] > 1.5 * (off[0] + off[1] + off[2]), "translucency on is not brighter");
        CHECK_MSG(t[0] > 2 * t[1] && t[1] > t[2] && t[2] >= 0, "transmitted light is not red: %g %g %g", t[0], t[1],
                  t[2]);
        CHECK_MSG(cdrft[0] > cdrf[0] + 0.5 * t[0], "cdrf+translucency adds no red through the disc");
    }
    lucent_renderer_destroy(r);
    lucent_scene_destroy(sc);
}

/* Expected: with render.transmittance "slab" and thin_sheet off, a point of a flat part lit from straight
 * behind with irradiance E shows E (T(s) - T_0(s)) E_x(mu_o) / pi of diffuse transmitted radiance, T(s) the
 * total transmittance of a slab of the material s mm thick (docs/render.md), T_0(s) = (1 - F0)^2
 * e^(-sigma_t s) its unscattered part (Beer-Lambert through two smooth faces of normal-incidence Fresnel
 * F0 = ((eta - 1) / (eta + 1))^2; the faces' repeated reflections, R^2 e^(-2 sigma_t s) of it, are below
 * 1e-6 here), which leaves as a lobe along the light's direction (test_gl_sheet): the camera looks at the
 * disc 45 degrees off its axis, outside that lobe. E_x is the boundary's exit curve (the diffuse light's
 * way out toward the viewer, the same for every method, checked against the path tracer by
 * test_gl_boundary; read here from the renderer's table at mu_o = cos 45). T comes here from an independent Monte Carlo run
 * (lucent_mc_run, 400000 photons per channel, another seed) at s = 4 mm, the disc's thickness on its
 * axis; the Monte Carlo itself is checked against van de Hulst's and Giovanelli's tables in test_mc,
 * so what is tested here is the renderer's path from table to pixel: sampling and interpolating the
 * table, the shadow-map thickness, the shader's E T / pi. The renderer's table is given TABLE_PHOTONS
 * per channel and thickness, so the tolerance is 3 of its standard errors,
 * sqrt(T (1 - T) / TABLE_PHOTONS), plus the shadow lookup's inward offset
 * (1.5 texels of a 4096 map over the 50 mm disc and margin: under 0.025 mm, a factor
 * exp(sigma_tr 0.025) on T), plus 1% for the table's interpolation. The transmitted light is the
 * difference between cdrf+translucency (curvature modulation off) and cdrf. */
TEST(slab_translucency_matches_monte_carlo_transmittance)
{
    enum { TABLE_PHOTONS = 20000 };
    char json[sizeof k_slab + 64] = "";
    const char *cam = strstr(k_slab, "[0, 0, 80]"); /* 80 mm away, 45 degrees off the axis */
    if (cam) snprintf(json, sizeof json, "%.*s[0, 56.5685, 56.5685]%s", (int)(cam - k_slab), k_slab, cam + 10);
    lucent_scene *sc = scene_from(json);
    lucent_renderer *r = renderer_with(sc, &(lucent_renderer_desc){.transmit_photons = TABLE_PHOTONS,
                                                                   .boundary_photons = TEST_BOUNDARY_PHOTONS,
                                                                   .sphere_photons = TEST_SPHERE_PHOTONS});
    if (r) {
        lucent_render_settings s = sc->render;
        s.view.shadow_map_size = 4096;
        s.translucency.curvature = 0;
        s.translucency.transmittance = LUCENT_TRANSMIT_SLAB;
        s.translucency.sheet = false; /* the slab's T(s) / pi (the sheet tables: test_gl_sheet) */
        double with[3], without[3];
        s.view.method = LUCENT_METHOD_CDRF_TRANSLUCENCY;
        square_mean(r, &s, 31, 33, with); /* the 2 x 2 pixels on the axis: 4 mm to 0.1% */
        s.view.method = LUCENT_METHOD_CDRF;
        square_mean(r, &s, 31, 33, without);
        const lucent_material *m = &sc->objects[0].material;
        lucent_material_derived d;
        lucent_material_derive(m, &d);
        for (int c = 0; c < 3; c++) {
            /* the light leaves the disc's front toward the camera, 45 degrees off its normal */
            double ft_axis = gl_ref_boundary(gl_tables_of(&r->tables, 0)->boundary, c, 0, sqrt(0.5), true);
            lucent_mc_layer layer = {
                .n = m->eta, .sigma_a = m->sigma_a[c], .sigma_s = m->sigma_s[c], .g = m->g[c], .thickness = 4};
            lucent_mc_desc md = {.layers = &layer,
                                 .layer_count = 1,
                                 .photons = 400000,
                                 .seed = 12345,
                                 .grid = {.dr = 1, .nr = 1, .nz = 1, .na = 1}};
            lucent_mc_result mc = {0};
            CHECK_OK(lucent_mc_run(&md, &mc));
            double r0 = (m->eta - 1) / (m->eta + 1), t0 = (1 - r0 * r0) * (1 - r0 * r0) * exp(-d.sigma_t[c] * 4);
            double t = mc.tt, expected = 3 * (t - t0) * ft_axis / M_PI, got = with[c] - without[c];
            double tol = 3 * sqrt(t * (1 - t) / TABLE_PHOTONS) / t + (exp(d.sigma_tr[c] * 0.025) - 1) + 0.01;
            printf("     channel %d: transmitted %.5f, 3 (T(4 mm) - T_0) E_x(cos 45) / pi %.5f (T %.4f +- %.4f), rel. "
                   "diff "
                   "%.2f%%, tol "
                   "%.2f%%\n",
                   c, got, expected, t, mc.tt_se, 100 * (got / expected - 1), 100 * tol);
            CHECK_MSG(fabs(got / expected - 1) <= tol, "channel %d: %g vs %g", c, got, expected);
            lucent_mc_result_free(&mc);
        }
    }
    lucent_renderer_destroy(r);
    lucent_scene_destroy(sc);
}

/* ---- timings, rebuilds, settings ---- */

/* render.samples: lucent_render's image is the mean of frames jittered over the pixel, as the path
 * tracer's pixels average their area. A sphere that gives no light (a light of intensity 0) before a white
 * background: every pixel is 1 minus the share of its area the sphere covers, here computed apart from the
 * GL, 32 x 32 rays per pixel (lucent_camera_ray) against the exact sphere (the mesh: 256 x 128 quads, its
 * silhouette within 0.01 pixel of the sphere's). With one sample a pixel is its centre's, 0 or 1; with 64
 * the Halton points' share of a nearly straight edge is within about 1/16 of the area's. */
TEST(pixel_samples_average_the_pixel)
{
    enum { W = 40, H = 32, SUB = 32 };
    const double R = 10;
    lucent_scene *sc = scene_from(
        "{\"camera\": {\"position\": [0, 0, 60], \"target\": [0.3, 0.2, 0], \"fov_y\": 30},"
        " \"lights\": [{\"type\": \"directional\", \"direction\": [0, 0, -1], \"intensity\": 0}],"
        " \"objects\": [{\"mesh\": {\"primitive\": \"uv_sphere\", \"radius\": 10, \"u_count\": 256, \"v_count\": 128},"
        " \"material\": \"skin1\", \"albedo\": [0, 0, 0]}],"
        " \"render\": {\"width\": 40, \"height\": 32, \"method\": \"lambert\", \"background\": [1, 1, 1]}}");
    lucent_renderer *r = renderer_of(sc);
    double worst[2] = {0, 0};
    int edge = 0;
    for (int k = 0; r && k < 2; k++) {
        lucent_render_settings s = sc->render;
        s.view.samples = k ? 64 : 1;
        lucent_render_result res = {0};
        CHECK_OK(lucent_render(r, &s, &res));
        for (int y = 0; res.image && y < H; y++)
            for (int x = 0; x < W; x++) {
                int hit = 0;
                for (int j = 0; j < SUB; j++)
                    for (int i = 0; i < SUB; i++) {
                        double o[3], d[3];
                        lucent_camera_ray(&sc->camera, W, H, x + (i + 0.5) / SUB, y + (j + 0.5) / SUB, o, d);
                        double b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
                        double c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - R * R;
                        hit += b * b - c >= 0 && b < 0;
                    }
                double want = 1 - (double)hit / (SUB * SUB), got = res.image->data[3 * ((size_t)y * W + x)];
                if (hit > 0 && hit < SUB * SUB) edge += k == 0;
                worst[k] = fmax(worst[k], fabs(got - want));
            }
        lucent_render_result_free(&res);
    }
    printf("     %d silhouette pixels; largest |pixel - uncovered share|: 1 sample %.3f, 64 samples %.3f\n", edge,
           worst[0], worst[1]);
    CHECK(edge > 20);
    CHECK_MSG(worst[1] <= 1.0 / 16, "64 samples: a pixel %.3f from its uncovered share", worst[1]);
    CHECK_MSG(worst[0] >= 0.25, "1 sample: the pixels should be their centres' (0 or 1), largest difference %.3f",
              worst[0]);
    lucent_renderer_destroy(r);
    lucent_scene_destroy(sc);
}

TEST(timings_name_every_pass)
{
    lucent_scene *sc = scene_from(k_sphere);
    lucent_renderer *r = renderer_of(sc);
    if (r) {
        lucent_render_settings s = sc->render;
        s.ssss.kernel = LUCENT_KERNEL_SVD, s.ssss.rank = 2;
        lucent_render_result res;
        CHECK_OK(lucent_render(r, &s, &res));
        static const char *const names[] = {"shadow",  "bounce",  "geometry", "blur h1",
                                            "blur v1", "blur h2", "blur v2",  "compose"};
        CHECK(res.times.pass_count == 8);
        double sum = 0;
        for (int i = 0; i < res.times.pass_count && i < 8; i++) {
            CHECK_MSG(!strcmp(res.times.pass_name[i], names[i]), "pass %d is \"%s\"", i, res.times.pass_name[i]);
            CHECK(res.times.pass_ms[i] >= 0 && isfinite(res.times.pass_ms[i]));
            sum += res.times.pass_ms[i];
        }
        CHECK_NEAR(sum, res.times.gpu_ms, 1e-6 * fmax(1, sum)); /* consecutive timestamps add up */
        CHECK(res.times.blur_ms > 0 || res.times.gpu_ms == 0);
        lucent_render_result_free(&res);
    }
    lucent_renderer_destroy(r);
    lucent_scene_destroy(sc);
}

/* Settings change from call to call; only what they touch is rebuilt (the kernel's taps survive a
 * Lambert frame), and the same settings give the same image again (a deterministic pipeline). */
TEST(settings_change_between_frames)
{
    lucent_scene *sc = scene_from(k_sphere);
    lucent_renderer *r = renderer_of(sc);
    if (r) {
        lucent_render_settings s = sc->render, lam = s, small = s;
        lam.view.method = LUCENT_METHOD_LAMBERT;
        small.view.width = 40, small.view.height = 24;
        lucent_render_result a, b, c, d;
        CHECK_OK(lucent_render(r, &s, &a));
        const lucent_taps *taps = r->tables.baked[0].taps;
        CHECK_OK(lucent_render(r, &lam, &b));
        CHECK_OK(lucent_render(r, &small, &d));
        CHECK(d.image && d.image->width == 40 && d.image->height == 24);
        CHECK_OK(lucent_render(r, &s, &c));
        CHECK(r->tables.baked[0].taps == taps);
        CHECK(c.times.setup_ms >= 0);
        CHECK(a.image && c.image && !memcmp(a.image->data, c.image->data, lucent_image_value_count(a.image) * 4));
        CHECK(b.image && a.image && memcmp(a.image->data, b.image->data, lucent_image_value_count(a.image) * 4));
        lucent_render_result_free(&a), lucent_render_result_free(&b), lucent_render_result_free(&c);
        lucent_render_result_free(&d);
        lucent_render_settings bad = s;
        bad.ssss.taps = 16;
        CHECK_ERR(lucent_render(r, &bad, &a), LUCENT_ERR_INVALID_ARGUMENT, "taps must be odd");
        bad = s, bad.view.width = 0;
        CHECK_ERR(lucent_render(r, &bad, &a), LUCENT_ERR_INVALID_ARGUMENT, "width must be in [1, 16384]");
        s.cdrf.sigma0 = LUCENT_SIGMA0_DIFFUSE, s.view.method = LUCENT_METHOD_CDRF;
        sc->objects[0].sigma0_set = false;
        CHECK_OK(lucent_render(r, &s, &a));
        lucent_render_object_info info;
        CHECK_OK(lucent_renderer_object_info(r, 0, &info));
        CHECK_NEAR(info.sigma0[0], info.albedo[0] * info.albedo[0], 1e-12); /* Kubo Eq. 6 */
        CHECK(!strcmp(info.sigma0_from, "diffuse"));
        lucent_render_result_free(&a);
    }
    lucent_renderer_destroy(r);
    lucent_scene_destroy(sc);
}

/* ---- the scene changed under a renderer (the viewer): the same pixels as a renderer made for the
 * changed scene, which is the independent computation here ---- */

static lucent_scene *sphere_of(const char *material, const char *direction)
{
    char json[1024];
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [0, 0, 60], \"target\": [0, 0, 0], \"fov_y\": 30},"
             " \"lights\": [{\"type\": \"directional\", \"direction\": %s, \"intensity\": 3},"
             "              {\"type\": \"environment\", \"intensity\": 0.05}],"
             " \"objects\": [{\"mesh\": {\"primitive\": \"icosphere\", \"radius\": 10, \"subdivisions\": 3},"
             "               \"material\": \"%s\", \"sigma0\": [3, 2, 1]}],"
             " \"render\": {\"width\": 48, \"height\": 40, \"shadow_map_size\": 256, \"taps\": 11}}",
             direction, material);
    return scene_from(json);
}

/* Renders sc with a renderer of its own (ssss). */
static lucent_image *fresh_render(lucent_scene *sc)
{
    lucent_renderer *r = renderer_of(sc);
    lucent_render_result res = {0};
    if (r) CHECK_OK(lucent_render(r, NULL, &res));
    lucent_renderer_destroy(r);
    lucent_image_destroy(res.mask);
    return res.image;
}

static bool same_image(const lucent_image *a, const lucent_image *b)
{
    return a && b && a->width == b->width && a->height == b->height &&
           !memcmp(a->data, b->data, lucent_image_value_count(a) * sizeof *a->data);
}

TEST(scene_changes_and_adopted_bakes_give_a_fresh_renderers_pixels)
{
    lucent_scene *sc = sphere_of("skin1", "[0, 0, -1]"), *other = sphere_of("chicken1", "[0, 0, -1]");
    lucent_scene *turned = sphere_of("chicken1", "[0.5, -0.3, -0.8]");
    lucent_renderer *r = renderer_of(sc);
    lucent_image *want_other = fresh_render(other), *want_turned = fresh_render(turned);
    if (r && want_other && want_turned) {
        lucent_render_result a = {0}, b = {0}, c = {0};
        CHECK_OK(lucent_render(r, NULL, &a)); /* skin1 baked and uploaded */
        /* the material changed in the scene (with its albedo, the dipole Rd, as the loader sets it) */
        sc->objects[0].material = other->objects[0].material;
        memcpy(sc->objects[0].albedo, other->objects[0].albedo, sizeof sc->objects[0].albedo);
        CHECK_OK(lucent_renderer_scene_changed(r, LUCENT_RENDERER_MATERIALS));
        CHECK_OK(lucent_render(r, NULL, &b));
        CHECK(same_image(b.image, want_other) && !same_image(a.image, b.image));
        /* a light turned */
        memcpy(sc->lights[0].direction, turned->lights[0].direction, sizeof sc->lights[0].direction);
        CHECK_OK(lucent_renderer_scene_changed(r, LUCENT_RENDERER_LIGHTS));
        CHECK_OK(lucent_render(r, NULL, &c));
        CHECK(same_image(c.image, want_turned));
        lucent_render_result_free(&a), lucent_render_result_free(&b), lucent_render_result_free(&c);
    }
    lucent_renderer_destroy(r);
    /* parts baked elsewhere (a copy of them) are adopted: the frame bakes nothing and draws the same */
    lucent_renderer *m = renderer_of(other);
    if (m) {
        lucent_renderer_desc rd = lucent_renderer_defaults();
        lucent_baked b = {0}, copy = {0};
        unsigned what = lucent_renderer_bakes(m, &other->render);
        /* the boundary's tables (the albedo and the entry and exit factors) with every method; ssss's
         * curved parts (on by default) */
        unsigned ssss = LUCENT_BAKE_TAPS | LUCENT_BAKE_SPHERES | LUCENT_BAKE_BOUNDARY;
        /* and the slab's transmittance where translucency is on, the sheet tables where thin_sheet is too */
        const lucent_render_settings *os = &other->render;
        unsigned thin = os->translucency.enabled
                            ? LUCENT_BAKE_TRANSMITTANCE |
                                  (os->translucency.sheet && os->translucency.transmittance == LUCENT_TRANSMIT_SLAB
                                       ? LUCENT_BAKE_SHEET
                                       : 0u)
                            : 0u;
        CHECK_MSG(what == (ssss | thin), "bakes %#x, expected %#x", what, ssss | thin);
        CHECK_OK(lucent_material_bake(&other->objects[0].material,
                                      &(lucent_bake_desc){.what = what,
                                                          .settings = &other->render,
                                                          .profile_photons = rd.profile_photons,
                                                          .transmit_photons = rd.transmit_photons,
                                                          .sigma0_photons = rd.sigma0_photons,
                                                          .roughness = other->objects[0].roughness,
                                                          .boundary_photons = TEST_BOUNDARY_PHOTONS,
                                                          .sphere_photons = TEST_SPHERE_PHOTONS},
                                      NULL, &b));
        CHECK_OK(lucent_baked_copy(&b, &copy));
        lucent_baked_free(&b); /* the copy stands alone */
        CHECK_OK(lucent_renderer_adopt_baked(m, &other->objects[0].material, &copy));
        const lucent_taps *adopted = m->tables.baked[0].taps;
        lucent_render_result res = {0};
        CHECK_OK(lucent_render(m, NULL, &res));
        CHECK(m->tables.baked[0].taps == adopted); /* not baked again */
        CHECK(same_image(res.image, want_other));
        lucent_render_result_free(&res);
        lucent_material ketchup;
        lucent_material_preset_find("ketchup", &ketchup);
        CHECK_ERR(lucent_renderer_adopt_baked(m, &ketchup, &copy), LUCENT_ERR_NOT_FOUND, "Ketchup");
        /* what each method bakes: lambert only the boundary's tables; cdrf no sigma0 fit where the
         * scene gives sigma0, the spheres with curved parts (the default); the boundary's tables also
         * where the scene gives its colour (the entry and exit factors) */
        lucent_render_settings s = other->render;
        unsigned curved = LUCENT_BAKE_SPHERES | LUCENT_BAKE_BOUNDARY;
        s.view.method = LUCENT_METHOD_LAMBERT;
        CHECK(lucent_renderer_bakes(m, &s) == LUCENT_BAKE_BOUNDARY);
        s.view.method = LUCENT_METHOD_CDRF, s.cdrf.sigma0 = LUCENT_SIGMA0_FIT;
        CHECK(lucent_renderer_bakes(m, &s) == curved);
        s.cdrf.curved_parts = false;
        CHECK(lucent_renderer_bakes(m, &s) == LUCENT_BAKE_BOUNDARY);
        s.cdrf.curved_parts = true;
        other->objects[0].sigma0_set = false;
        CHECK(lucent_renderer_bakes(m, &s) == (LUCENT_BAKE_SIGMA0 | curved));
        other->objects[0].albedo_source = LUCENT_ALBEDO_COLOR;
        CHECK(lucent_renderer_bakes(m, &s) == (LUCENT_BAKE_SIGMA0 | curved));
        lucent_baked_free(&copy);
    }
    lucent_renderer_destroy(m);
    lucent_image_destroy(want_other), lucent_image_destroy(want_turned);
    lucent_scene_destroy(sc), lucent_scene_destroy(other), lucent_scene_destroy(turned);
}

/* ---- errors ---- */

TEST(context_errors_name_their_cause)
{
    lucent_gl_context *c = NULL;
    setenv("LUCENT_GL_PLATFORM", "teapot", 1);
    CHECK_ERR(lucent_gl_create(NULL, &c), LUCENT_ERR_GL, "LUCENT_GL_PLATFORM", "unknown GL platform 'teapot'");
    CHECK(c == NULL);
    CHECK_OK(lucent_gl_create(&(lucent_gl_desc){.ignore_env = true}, &c));
    lucent_gl_destroy(c), c = NULL;
    unsetenv("LUCENT_GL_PLATFORM");
    CHECK_ERR(lucent_gl_create(&(lucent_gl_desc){.platform = LUCENT_GL_DEVICE, .device = 99}, &c), LUCENT_ERR_GL,
              "EGL device 99 not found");
    setenv("LUCENT_GL_DEVICE", "0", 1);
    CHECK_ERR(lucent_gl_create(NULL, &c), LUCENT_ERR_GL, "LUCENT_GL_DEVICE");
    unsetenv("LUCENT_GL_DEVICE");
    const char *display = getenv("DISPLAY"), *wayland = getenv("WAYLAND_DISPLAY");
    if (!display && !wayland)
        CHECK_ERR(lucent_gl_create(&(lucent_gl_desc){.platform = LUCENT_GL_WINDOW}, &c), LUCENT_ERR_GL,
                  "no OpenGL window");
    if (context()) { /* contexts share EGL's display: ending one must not end another */
        CHECK_OK(lucent_gl_create(&(lucent_gl_desc){.platform = LUCENT_GL_SURFACELESS}, &c));
        lucent_gl_destroy(c);
        CHECK_OK(lucent_gl_make_current(g_ctx));
        lucent_gl_info info;
        lucent_gl_get_info(g_ctx, &info);
        CHECK(info.renderer[0] && info.vendor[0] && strstr(info.version, "4.") && info.platform[0]);
        printf("     GL: %s | %s | %s (%s)\n", info.renderer, info.vendor, info.version, info.platform);
    }
}

static const char *broken_sources(const char *name, void *user)
{
    (void)user;
    if (!strcmp(name, "main.frag.glsl"))
        return "// line 1\n#include \"part.glsl\"\nout vec4 o;\nvoid main()\n{\n    o = vec4(undefined_thing);\n}\n";
    if (!strcmp(name, "part.glsl")) return "// part, line 1\nfloat part_ok(float x) { return x; }\n";
    if (!strcmp(name, "bad_part.frag.glsl"))
        return "#include \"bad.glsl\"\nout vec4 o;\nvoid main() { o = vec4(1); }\n";
    if (!strcmp(name, "bad.glsl")) return "// bad, line 1\n// line 2\nfloat f() { return nonsense; }\n";
    return gl_embedded_source(name, NULL);
}

/* Expected: the error's file and line as written in the (made-up) sources above. */
TEST(shader_errors_name_file_and_line)
{
    if (!context()) return;
    CHECK_OK(lucent_gl_make_current(g_ctx)); /* another test destroyed its own context */
    GLuint p = 0;
    CHECK_ERR(gl_program_build(broken_sources, NULL, "fullscreen.vert.glsl", "main.frag.glsl", "#define X 1\n", &p),
              LUCENT_ERR_GL, "main.frag.glsl does not compile", "main.frag.glsl:6");
    printf("     %s\n", lucent_last_error());
    CHECK_ERR(gl_program_build(broken_sources, NULL, "fullscreen.vert.glsl", "bad_part.frag.glsl", NULL, &p),
              LUCENT_ERR_GL, "bad.glsl:3");
    CHECK_ERR(gl_program_build(broken_sources, NULL, "fullscreen.vert.glsl", "missing.frag.glsl", NULL, &p),
              LUCENT_ERR_GL, "missing.frag.glsl", "no such file");
    CHECK(p == 0);
}

/* Issue 32: a framebuffer the driver cannot make is named with the driver's limits (it said "framebuffer
 * incomplete (status 0x8cd6)"); a target one texel wider than GL_MAX_TEXTURE_SIZE fails cheaply, as a
 * 16384 x 16384 float target fails for memory on llvmpipe (3 GB; checked by hand). */
TEST(framebuffer_errors_name_the_drivers_limits)
{
    if (!context() || lucent_gl_make_current(g_ctx) != LUCENT_OK) return;
    GLint max = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max);
    GLuint t = gl_texture(GL_R8, max + 1, 1, GL_NEAREST), f = 0;
    char limit[64];
    snprintf(limit, sizeof limit, "its limits: textures of %d texels a side", max);
    CHECK_ERR(gl_framebuffer(1, &t, 0, "the test target", &f), LUCENT_ERR_GL,
              "the test target: the GL driver cannot make the framebuffer", limit, "lower render.width");
    CHECK(f == 0);
    glDeleteTextures(1, &t);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {TEST_ENTRY(framebuffer_errors_name_the_drivers_limits),
                                      TEST_ENTRY(cdrf_and_lambert_equal_cpu_reference),
                                      TEST_ENTRY(sphere_lit_along_view_axis_is_symmetric),
                                      TEST_ENTRY(translucency_brightens_a_backlit_disc_in_red),
                                      TEST_ENTRY(slab_translucency_matches_monte_carlo_transmittance),
                                      TEST_ENTRY(pixel_samples_average_the_pixel),
                                      TEST_ENTRY(timings_name_every_pass),
                                      TEST_ENTRY(settings_change_between_frames),
                                      TEST_ENTRY(scene_changes_and_adopted_bakes_give_a_fresh_renderers_pixels),
                                      TEST_ENTRY(context_errors_name_their_cause),
                                      TEST_ENTRY(shader_errors_name_file_and_line)};
    int rc = test_run(cases, (int)(sizeof cases / sizeof cases[0]), argc, argv);
    lucent_gl_destroy(g_ctx);
    return rc;
}
