/* Issue 31's thin parts: a sheet of the material lit from behind along its normal and seen from the
 * front, the real-time methods' light through it against the path tracer's (subsurface only), per bin
 * of view angle, for several thicknesses and two phase functions. Expected values: the tracer
 * (src/trace, an independent renderer of the same physics), never the GL code; its noise is measured
 * per bin (the per-pixel variance) and printed with every ratio. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/bake.h"
#include "lucent/profile.h"
#include "lucent/render.h"
#include "lucent/trace.h"
#include "test.h"

#if defined(__SANITIZE_ADDRESS__)
#define SLOW 4 /* sanitizer builds run about ten times slower: a quarter of the work */
#else
#define SLOW 1
#endif

enum { SH_W = 16, SH_H = 48, SH_BINS = 4 };
static const double k_edges[SH_BINS + 1] = {0, 10, 20, 40, 60}; /* degrees of the view from the normal */

/* Skin1 (Jensen et al. 2001, g 0 as the preset) and the same reduced scattering with g 0.9 (sigma_s =
 * sigma_s' / (1 - g)): the forward lobe of a real skin's phase function. */
static const char *const k_materials[2] = {
    "\"skin1\"", "{\"name\": \"skin1-g0.9\", \"units\": \"mm^-1\", \"sigma_a\": [0.032, 0.17, 0.48], "
                 "\"sigma_s_prime\": [0.74, 0.88, 1.01], \"g\": 0.9, \"eta\": 1.3}"};

/* A sheet 800 x 800 mm, thickness s, its front face at z = 0, as an OBJ in the test's folder. */
static const char *sheet_obj(double s)
{
    char name[64];
    snprintf(name, sizeof name, "sheet-%g.obj", s);
    const char *path = test_path(name);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return path;
    fprintf(f,
            "v -400 -400 %.17g\nv 400 -400 %.17g\nv 400 400 %.17g\nv -400 400 %.17g\n"
            "v -400 -400 0\nv 400 -400 0\nv 400 400 0\nv -400 400 0\n"
            "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\n"
            "f 4 1 5\nf 4 5 8\n",
            -s, -s, -s, -s);
    fclose(f);
    return path;
}

/* The scene: the camera 40 mm in front of the sheet looking 32 degrees off its normal (views from 0 to
 * about 65 degrees), a directional light of irradiance 1 travelling along +z (from behind). */
static lucent_scene *sheet_scene(const char *material, double s, const double travel[3])
{
    char json[2048];
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [0, 0, 40], \"target\": [0, 25, 0], \"fov_y\": 70},"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [%.17g, %.17g, %.17g], \"intensity\": 1}],"
             " \"objects\": [{\"mesh\": \"%s\", \"material\": %s, \"roughness\": 0.3}],"
             " \"render\": {\"width\": %d, \"height\": %d, \"light_paths\": \"off\"}}",
             travel[0], travel[1], travel[2], sheet_obj(s), material, SH_W, SH_H);
    lucent_scene *sc = NULL;
    CHECK_OK(lucent_scene_parse(json, "sheet.json", NULL, NULL, &sc));
    return sc;
}

/* The view bin of pixel (x, y), or -1; *theta the angle between the view (toward the camera) and the
 * light's direction of travel (radians): for the light along the normal, the view angle from the normal. */
static int view_bin(const lucent_scene *sc, int x, int y, const double travel[3], double *theta)
{
    double org[3], dir[3];
    lucent_camera_ray(&sc->camera, SH_W, SH_H, x + 0.5, y + 0.5, org, dir);
    *theta = acos(fmin(1.0, -(dir[0] * travel[0] + dir[1] * travel[1] + dir[2] * travel[2])));
    double deg = *theta * 180 / M_PI;
    int k = 0;
    while (k < SH_BINS && deg >= k_edges[k + 1]) k++;
    return k == SH_BINS ? -1 : k;
}

/* The methods rendered: ssss, cdrf+translucency and tsd with the sheet tables (SH_SHEET of them), and
 * ssss without them (the slab's T(s) / pi, as before issue 31's thin parts). tsd at its default
 * tsd_size (at 256 its texture-space sampling undershot the g 0.9 0.5 mm sheet's forward peak by 10-16%:
 * that medium's light of orders >= 2 is forward-peaked too); not under the sanitizers (its 2048^2
 * texture passes). */
enum { SH_METHODS = 4, SH_SHEET = 3, SH_SLAB = 3 /* the method without the sheet tables */ };
static const double k_normal[3] = {0, 0, 1};
static const char *const k_method_names[SH_METHODS] = {"ssss", "cdrf+tr", "tsd", "ssss T(s)/pi"};
static const lucent_render_method k_methods[SH_METHODS] = {LUCENT_METHOD_SSSS, LUCENT_METHOD_CDRF_TRANSLUCENCY,
                                                           LUCENT_METHOD_TSD, LUCENT_METHOD_SSSS};

typedef struct sheet_bins {
    double tracer[SH_BINS][3], var[SH_BINS][3], gl[SH_METHODS][SH_BINS][3];
    int pixels[SH_BINS];
} sheet_bins;

static lucent_gl_context *g_ctx;

/* The real-time methods' images of the sheet, summed per view bin. */
static void render_case(const lucent_scene *sc, const double travel[3], uint64_t photons, lucent_pool *pool,
                        sheet_bins *out)
{
    if (!g_ctx) CHECK_OK(lucent_gl_create(NULL, &g_ctx));
    lucent_renderer *gr = NULL;
    if (g_ctx)
        CHECK_OK(lucent_renderer_create(
            g_ctx, sc,
            &(lucent_renderer_desc){
                .pool = pool, .cache_dir = test_path("cache"), .sheet_photons = photons, .boundary_photons = 2000},
            &gr));
    for (int mi = 0; gr && mi < SH_METHODS; mi++) {
        if (SLOW > 1 && k_methods[mi] == LUCENT_METHOD_TSD) continue;
        lucent_render_settings s = sc->render;
        s.view.method = k_methods[mi];
        s.translucency.sheet = mi < SH_SHEET;
        lucent_render_result res = {0};
        CHECK_OK(lucent_render(gr, &s, &res));
        for (int y = 0; res.image && y < SH_H; y++)
            for (int x = 0; x < SH_W; x++) {
                double theta;
                int k = view_bin(sc, x, y, travel, &theta);
                if (k < 0) continue;
                size_t i = (size_t)y * SH_W + (size_t)x;
                for (int c = 0; c < 3; c++) out->gl[mi][k][c] += res.image->data[3 * i + c];
            }
        lucent_render_result_free(&res);
    }
    lucent_renderer_destroy(gr);
}

static void sheet_case(int material, double s, const double travel[3], int spp, uint64_t photons, lucent_pool *pool,
                       sheet_bins *out)
{
    memset(out, 0, sizeof *out);
    lucent_scene *sc = sheet_scene(k_materials[material], s, travel);
    if (!sc) return;
    lucent_tracer *tr = NULL;
    lucent_trace_result r = {0};
    CHECK_OK(lucent_tracer_create(sc, &(lucent_tracer_desc){.subsurface_only = true}, &tr));
    if (tr) CHECK_OK(lucent_tracer_render(tr, &(lucent_trace_desc){.spp = spp, .seed = 5, .pool = pool}, &r));
    for (int y = 0; r.image && y < SH_H; y++)
        for (int x = 0; x < SH_W; x++) {
            double theta;
            int k = view_bin(sc, x, y, travel, &theta);
            if (k < 0) continue;
            size_t i = (size_t)y * SH_W + (size_t)x;
            for (int c = 0; c < 3; c++) {
                out->tracer[k][c] += r.image->data[3 * i + c];
                out->var[k][c] += r.variance->data[3 * i + c];
            }
            out->pixels[k]++;
        }
    render_case(sc, travel, photons, pool, out);
    lucent_trace_result_free(&r);
    lucent_tracer_destroy(tr);
    lucent_scene_destroy(sc);
}

/* Issue 31's thin parts: ssss, cdrf+translucency and tsd (the thin-part term with the sheet
 * tables, baked by the renderer: 4000 photons per channel and thickness) against the tracer's sheets of
 * 0.5, 2 and 5 mm, Skin1 (g 0) and g 0.9, per view bin and channel. The bound: a model error of 5% (2%
 * for the baked table's own noise, about 1-3% per bin at 4000 photons, scaled by the square root of the
 * sanitizers' cut in photons; 3% for its interpolation between thickness rows and angle bins) plus 2.5
 * standard errors of the tracer's bin (printed; Skin1 at 16 spp 1.5-4%, the
 * g 0.9 medium at 48 spp 5-30%: the tracer's walks through a forward-peaked medium are noisy). Printed
 * beside: the slab's T(s) / pi (thin_sheet off, the term before), which the same bound fails. */
TEST(sheet_agrees_with_the_tracer)
{
    static const double thick[3] = {0.5, 2, 5};
    static const int spp[2] = {16, 48};
    lucent_pool *pool = lucent_pool_create(2);
    double worst = 0, model = 0.03 + 0.02 * sqrt((double)SLOW);
    /* a bin whose tracer standard error is over 10% bounds nothing (2.5 se alone would pass a GL / tracer of
     * 0.75: the g 0.9 medium at 5 mm, 7-39%); such bins are printed and counted, not checked */
    enum { MAX_SE_PERCENT = 10 };
    const double MAX_SE = MAX_SE_PERCENT / 100.0;
    int checked = 0, skipped = 0;
    /* under the sanitizers (a quarter of the samples) Skin1 alone: at 12 spp the g 0.9 medium's fireflies
     * make the tracer's per-pixel variance a poor measure of its error (blue 0.56-2.1 of GL, the
     * variance's standard error 4-34%) */
    for (int m = 0; m < (SLOW > 1 ? 1 : 2); m++)
        for (int j = 0; j < 3; j++) {
            sheet_bins h;
            sheet_case(m, thick[j], k_normal, spp[m] / SLOW, 4000 / SLOW, pool, &h);
            printf("     %s %.1f mm: tracer radiance (R G B) +- se | GL / tracer per view bin\n", m ? "g 0.9" : "Skin1",
                   thick[j]);
            for (int k = 0; k < SH_BINS; k++) {
                printf("       %2.0f-%2.0f (%3d px):", k_edges[k], k_edges[k + 1], h.pixels[k]);
                for (int c = 0; c < 3; c++)
                    printf(" %.4g+-%.1f%%", h.tracer[k][c] / h.pixels[k], 100 * sqrt(h.var[k][c]) / h.tracer[k][c]);
                for (int mi = 0; mi < SH_METHODS; mi++) {
                    printf(" | %s", k_method_names[mi]);
                    for (int c = 0; c < 3; c++) printf(" %.3f", h.gl[mi][k][c] / h.tracer[k][c]);
                }
                printf("\n");
                for (int mi = 0; mi < SH_SHEET; mi++)
                    for (int c = 0; c < 3 && !(SLOW > 1 && k_methods[mi] == LUCENT_METHOD_TSD); c++) {
                        double ratio = h.gl[mi][k][c] / h.tracer[k][c], se = sqrt(h.var[k][c]) / h.tracer[k][c];
                        if (!(se <= MAX_SE)) { /* the tracer cannot see the model here: printed, not checked */
                            skipped++;
                            continue;
                        }
                        checked++;
                        worst = fmax(worst, fabs(ratio - 1) / (model + 2.5 * se));
                        CHECK_MSG(h.pixels[k] > 0 && fabs(ratio - 1) <= model + 2.5 * se,
                                  "%s %.1f mm, %.0f-%.0f deg, %s, channel %d: GL / tracer %.3f (se %.3f)",
                                  m ? "g 0.9" : "Skin1", thick[j], k_edges[k], k_edges[k + 1], k_method_names[mi], c,
                                  ratio, se);
                    }
            }
        }
    printf("     largest |GL / tracer - 1| over its bound: %.2f; %d bins checked, %d with the tracer's se over %.0f%% "
           "printed only\n",
           worst, checked, skipped, 100 * MAX_SE);
    CHECK_MSG(checked >= 3 * skipped, "only %d bins checked against %d too noisy to check", checked, skipped);
    lucent_pool_destroy(pool);
}

/* Thin parts lit obliquely: Skin1 sheets of 0.5 and 1 mm lit from behind 40 degrees off their normal,
 * whose unscattered light leaves along the light's own direction (parallel faces) through two rough
 * faces, against the tracer, per bin of the angle between the view and the light's direction of
 * travel. The method: ssss with render.thin_sheet off (the default), the slab's T(s) less its
 * unscattered part, which leaves as the lobe of lights.glsl's thin_ballistic. Checked: (1) the path the
 * light takes through the sheet, by the lobe's colour: the peak bin's GL / tracer is the same in R, G and
 * B within 3% when the chord is right (e^(-sigma_t x) differs by channel: Skin1's sigma_t 0.77, 1.05,
 * 1.49 /mm; each 0.1 mm of path wrong tilts blue against red by 7%; before the shadow pass's slope offset
 * was taken off the chord and the normal offset's share of it was offset / |n.l|, blue / red was 1.51,
 * 1.35 with the slope offset alone taken off); (2) the lobe's bins (0-40 degrees) within 10% + 2.5
 * tracer standard errors (the lobe is the two faces' single path, without the light the faces reflect
 * back into the sheet, and the diffuse rest shares the 20-40 bin: measured 0.89-1.07; with the two faces'
 * roughness as one GGX of alpha sqrt 2 the shoulders were 0.65-0.83). The 40-60 bin, the diffuse rest's
 * (the normal-incidence slab's, read at the chord: 0.84-1.62), is printed, not checked. */
TEST(sheet_lit_obliquely_passes_its_unscattered_light_along_the_light)
{
    static const double thick[2] = {0.5, 1};
    const double a = 40 * M_PI / 180, travel[3] = {0, -sin(a), cos(a)};
    lucent_pool *pool = lucent_pool_create(2);
    for (int j = 0; j < 2; j++) {
        sheet_bins h;
        sheet_case(0, thick[j], travel, 32 / SLOW, 4000 / SLOW, pool, &h);
        printf("     Skin1 %.1f mm, light 40 deg off the normal: tracer radiance +- se | ssss / tracer per bin of the "
               "view's angle from the light's direction\n",
               thick[j]);
        for (int k = 0; k < SH_BINS; k++) {
            printf("       %2.0f-%2.0f (%3d px):", k_edges[k], k_edges[k + 1], h.pixels[k]);
            for (int c = 0; c < 3; c++)
                printf(" %.4g+-%.1f%%", h.tracer[k][c] / h.pixels[k], 100 * sqrt(h.var[k][c]) / h.tracer[k][c]);
            printf(" |");
            for (int c = 0; c < 3; c++) printf(" %.3f", h.gl[SH_SLAB][k][c] / h.tracer[k][c]);
            printf("\n");
        }
        for (int k = 0; k < 3; k++) { /* 0-10, 10-20, 20-40 */
            double q[3], se[3];
            for (int c = 0; c < 3; c++)
                q[c] = h.gl[SH_SLAB][k][c] / h.tracer[k][c], se[c] = sqrt(h.var[k][c]) / h.tracer[k][c];
            if (k == 0)
                CHECK_MSG(h.pixels[0] > 0 && fabs(q[2] / q[0] - 1) <= 0.03 + 2.5 * hypot(se[0], se[2]),
                          "Skin1 %.1f mm: the peak's GL / tracer blue %.3f against red %.3f (se %.3f, %.3f)", thick[j],
                          q[2], q[0], se[2], se[0]);
            for (int c = 0; c < 3; c++)
                CHECK_MSG(h.pixels[k] > 0 && fabs(q[c] - 1) <= 0.10 + 2.5 * se[c],
                          "Skin1 %.1f mm, %.0f-%.0f deg, channel %d: %.3f (se %.3f)", thick[j], k_edges[k],
                          k_edges[k + 1], c, q[c], se[c]);
        }
    }
    lucent_pool_destroy(pool);
    lucent_gl_destroy(g_ctx);
}

TEST_MAIN(TEST_ENTRY(sheet_agrees_with_the_tracer),
          TEST_ENTRY(sheet_lit_obliquely_passes_its_unscattered_light_along_the_light))
