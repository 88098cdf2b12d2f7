/* Light between surfaces (render.bounce, src/gl/bounce.c): a wall standing on a floor, the light straight
 * down, a little past the wall's face (n.l = -0.1: every method's direct term is zero there, and the curved
 * parts' table, read between its bins at n.l = 0, is not), so the face gets no light of its own and shows only what the lit floor sends it. The
 * real-time methods' wall against the path tracer's (subsurface only, every light path between the
 * surfaces), per band of height. Expected values: the tracer (src/trace, an independent renderer of the
 * same physics), never the GL code; its noise is measured per band (the per-pixel variance) and printed
 * with every ratio. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/render.h"
#include "lucent/trace.h"
#include "test.h"

#if defined(__SANITIZE_ADDRESS__)
#define SLOW 4 /* sanitizer builds run about ten times slower: a quarter of the work */
#else
#define SLOW 1
#endif

enum { BW = 24, BH = 24, BANDS = 3 };
static const double k_band[BANDS + 1] = {25, 45, 65, 85}; /* mm above the floor */

/* The floor, a box 300 x 20 x 300 mm with its top at y = 0, and the wall on it, 20 x 120 x 300 mm with
 * its face at x = 0 looking along +x, as OBJs in the test's folder. Each face is a 3 x 3 grid of quads
 * whose outer ring is 1 mm wide: the loader welds the faces' shared edges and smooths the normals there,
 * so the rest of each face keeps its own normal (a plain box's normals lean over the whole face). */
static const char *box_obj(const char *name, const double lo[3], const double hi[3])
{
    const char *path = test_path(name);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return path;
    int base = 1;
    for (int a = 0; a < 3; a++)
        for (int side = 0; side < 2; side++) {
            int u = (a + 1) % 3, w = (a + 2) % 3;
            double cu[4] = {lo[u], lo[u] + 1, hi[u] - 1, hi[u]}, cw[4] = {lo[w], lo[w] + 1, hi[w] - 1, hi[w]};
            for (int j = 0; j < 4; j++)
                for (int i = 0; i < 4; i++) {
                    double p[3];
                    p[a] = side ? hi[a] : lo[a], p[u] = cu[i], p[w] = cw[j];
                    fprintf(f, "v %.17g %.17g %.17g\n", p[0], p[1], p[2]);
                }
            /* (u, w, a) is right-handed: counter-clockwise in (u, w) faces +a */
            for (int j = 0; j < 3; j++)
                for (int i = 0; i < 3; i++) {
                    int v0 = base + 4 * j + i, v1 = v0 + 1, v2 = v0 + 5, v3 = v0 + 4;
                    if (side)
                        fprintf(f, "f %d %d %d\nf %d %d %d\n", v0, v1, v2, v0, v2, v3);
                    else
                        fprintf(f, "f %d %d %d\nf %d %d %d\n", v0, v2, v1, v0, v3, v2);
                }
            base += 16;
        }
    fclose(f);
    return path;
}

/* The camera 150 mm in front of the wall, level with its middle: the face seen head-on from 10 to 90 mm
 * above the floor (the floor itself out of view). Marble floor (bright), Skin1 wall (darker: the light
 * that crosses back from the wall to the floor and returns, which the one bounce leaves out, is a few %). */
static lucent_scene *wall_scene(void)
{
    char json[2048];
    const double flo[3] = {-150, -20, -150}, fhi[3] = {150, 0, 150}, wlo[3] = {-20, 0, -150}, whi[3] = {0, 120, 150};
    char floor_path[512];
    snprintf(floor_path, sizeof floor_path, "%s", box_obj("bounce-floor.obj", flo, fhi));
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [150, 50, 0], \"target\": [0, 50, 0], \"fov_y\": 30},"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [0.1, -1, 0], \"intensity\": 1}],"
             " \"objects\": [{\"mesh\": \"%s\", \"material\": \"marble\", \"roughness\": 0.3},"
             " {\"mesh\": \"%s\", \"material\": \"skin1\", \"roughness\": 0.3}],"
             " \"render\": {\"width\": %d, \"height\": %d, \"shadow_map_size\": 512}}",
             floor_path, box_obj("bounce-wall.obj", wlo, whi), BW, BH);
    lucent_scene *sc = NULL;
    CHECK_OK(lucent_scene_parse(json, "wall.json", NULL, NULL, &sc));
    return sc;
}

/* The band of pixel (x, y) on the wall's face, or -1. */
static int band_of(const lucent_scene *sc, int x, int y)
{
    double org[3], dir[3];
    lucent_camera_ray(&sc->camera, BW, BH, x + 0.5, y + 0.5, org, dir);
    double t = -org[0] / dir[0], h = org[1] + t * dir[1], z = org[2] + t * dir[2];
    if (fabs(z) > 100) return -1;
    for (int k = 0; k < BANDS; k++)
        if (h >= k_band[k] && h < k_band[k + 1]) return k;
    return -1;
}

typedef struct bands {
    double tracer[BANDS][3], var[BANDS][3];
    int pixels[BANDS];
} bands;

static void sum_bands(const lucent_scene *sc, const lucent_image *im, const lucent_image *var, double sum[][3],
                      double vsum[][3], int *pixels)
{
    for (int y = 0; im && y < BH; y++)
        for (int x = 0; x < BW; x++) {
            int k = band_of(sc, x, y);
            if (k < 0) continue;
            size_t i = (size_t)y * BW + (size_t)x;
            for (int c = 0; c < 3; c++) {
                sum[k][c] += im->data[3 * i + c];
                if (vsum) vsum[k][c] += var->data[3 * i + c];
            }
            if (pixels) pixels[k]++;
        }
}

/* A method's wall per band with render.bounce at `bounce` surfels per side. */
static void render_bands(lucent_gl_context *ctx, const lucent_scene *sc, lucent_pool *pool, lucent_render_method method,
                         int bounce, double out[][3])
{
    lucent_renderer *gr = NULL;
    memset(out, 0, sizeof(double) * 3 * BANDS);
    CHECK_OK(lucent_renderer_create(
        ctx, sc,
        &(lucent_renderer_desc){
            .pool = pool, .cache_dir = test_path("cache"), .boundary_photons = 2000, .sheet_photons = 2000},
        &gr));
    if (!gr) return;
    lucent_render_settings s = sc->render;
    s.view.method = method;
    s.view.bounce = bounce;
    lucent_render_result res = {0};
    CHECK_OK(lucent_render(gr, &s, &res));
    sum_bands(sc, res.image, NULL, out, NULL, NULL);
    lucent_render_result_free(&res);
    lucent_renderer_destroy(gr);
}

/* The wall's light, all of it from the floor: lambert and ssss with the default bounce (32 surfels per
 * side) against the tracer per band of height and channel, within 10% + 2.5 standard errors of the
 * tracer's band. The 10%: the one bounce leaves out the light that goes back from the wall to the floor
 * and returns (the wall's albedo x the floor's x the two view factors, about 2-5% here) and draws the
 * floor's light as diffuse (the tracer's leaves a rough boundary, with its own exit curve), and the
 * surfels are 14 mm apart. Without the bounce the wall gets nothing: under 2% of the tracer's. */
TEST(wall_shows_the_light_its_floor_sends_it)
{
    lucent_pool *pool = lucent_pool_create(2);
    lucent_scene *sc = wall_scene();
    lucent_gl_context *ctx = NULL;
    CHECK_OK(lucent_gl_create(NULL, &ctx));
    if (sc && ctx) {
        bands b = {0};
        lucent_tracer *tr = NULL;
        lucent_trace_result r = {0};
        CHECK_OK(lucent_tracer_create(sc, &(lucent_tracer_desc){.subsurface_only = true}, &tr));
        if (tr)
            CHECK_OK(lucent_tracer_render(tr, &(lucent_trace_desc){.spp = 512 / SLOW, .seed = 3, .pool = pool}, &r));
        sum_bands(sc, r.image, r.variance, b.tracer, b.var, b.pixels);
        static const lucent_render_method methods[2] = {LUCENT_METHOD_LAMBERT, LUCENT_METHOD_SSSS};
        static const char *const names[2] = {"lambert", "ssss"};
        double gl[2][BANDS][3], off[BANDS][3];
        for (int m = 0; m < 2; m++) render_bands(ctx, sc, pool, methods[m], 32, gl[m]);
        render_bands(ctx, sc, pool, LUCENT_METHOD_SSSS, 0, off);
        for (int k = 0; k < BANDS; k++) {
            printf("     %2.0f-%2.0f mm (%d px): tracer", k_band[k], k_band[k + 1], b.pixels[k]);
            for (int c = 0; c < 3; c++)
                printf(" %.4g+-%.1f%%", b.tracer[k][c] / b.pixels[k], 100 * sqrt(b.var[k][c]) / b.tracer[k][c]);
            for (int m = 0; m < 2; m++) {
                printf(" | %s", names[m]);
                for (int c = 0; c < 3; c++) printf(" %.3f", gl[m][k][c] / b.tracer[k][c]);
            }
            printf(" | ssss, no bounce");
            for (int c = 0; c < 3; c++) printf(" %.3f", off[k][c] / b.tracer[k][c]);
            printf("\n");
            for (int c = 0; c < 3; c++) {
                double se = sqrt(b.var[k][c]) / b.tracer[k][c];
                for (int m = 0; m < 2; m++) {
                    double q = gl[m][k][c] / b.tracer[k][c];
                    CHECK_MSG(b.pixels[k] > 0 && fabs(q - 1) <= 0.10 + 2.5 * se,
                              "%s, %.0f-%.0f mm, channel %d: GL / tracer %.3f (se %.3f)", names[m], k_band[k],
                              k_band[k + 1], c, q, se);
                }
                CHECK_MSG(off[k][c] <= 0.02 * b.tracer[k][c],
                          "ssss without the bounce, %.0f-%.0f mm, channel %d: %.3f of the tracer", k_band[k],
                          k_band[k + 1], c, off[k][c] / b.tracer[k][c]);
            }
        }
        lucent_trace_result_free(&r);
        lucent_tracer_destroy(tr);
    }
    lucent_gl_destroy(ctx);
    lucent_scene_destroy(sc);
    lucent_pool_destroy(pool);
}

TEST_MAIN(TEST_ENTRY(wall_shows_the_light_its_floor_sends_it))
