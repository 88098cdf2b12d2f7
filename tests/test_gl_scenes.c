/* GL tests on the default scenes (label gl only: the real meshes, every method, minutes under the
 * sanitizers). No method leaves a black or non-finite pixel inside the object (issue 31). */
#include <math.h>
#include <stdlib.h>

#include "lucent/lucent.h"
#include "test.h"

static lucent_gl_context *g_ctx;

static lucent_gl_context *context(void)
{
    if (!g_ctx) CHECK_OK(lucent_gl_create(NULL, &g_ctx));
    return g_ctx;
}

/* The scene at the given size, tsd's textures at 256 texels (their size changes no normal; 1024, the
 * default, costs 27 s of CPU on llvmpipe for the five spheres); the bakes with few photons (their noise
 * changes no pixel's sign). */
static lucent_scene *load_scene(const char *name, int width, int height)
{
    char path[1024], w[64], h[64];
    snprintf(path, sizeof path, "%s/data/scenes/%s.json", LUCENT_SOURCE_DIR, name);
    snprintf(w, sizeof w, "render.width=%d", width), snprintf(h, sizeof h, "render.height=%d", height);
    const char *sets[3] = {w, h, "render.tsd_size=256"};
    lucent_scene *sc = NULL;
    CHECK_OK(lucent_scene_load(path, &(lucent_scene_load_desc){.overrides = sets, .override_count = 3}, &sc));
    return sc;
}

static const lucent_renderer_desc k_quick = {
    .sigma0_photons = 1000, .transmit_photons = 1000, .boundary_photons = 200, .sphere_photons = 1000};

/* Inside the object: covered, with the eight neighbours covered (compare's mask). */
static bool interior(const lucent_image *mask, int x, int y)
{
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= mask->width || yy >= mask->height ||
                mask->data[(size_t)yy * mask->width + xx] < 0.999f)
                return false;
        }
    return true;
}

/* Every default scene has an environment light, so every visible point of its objects receives light
 * (the albedo times the environment, at least) and leaves some toward the viewer: no pixel inside the
 * object can be black. Before issue 31 the shading normal, interpolated across a silhouette or on faces
 * wound the other way round, could face away from the viewer (n.v down to -0.9 on the dragon), where
 * the smooth boundary's transmittance toward the viewer, 1 - F(max(n.v, 0)), is 0 and the specular
 * lobe too: 42 black pixels of the dragon at 512^2 with every method (11 at 256^2). */
TEST(no_black_or_nonfinite_pixel_inside_the_object)
{
    static const struct {
        const char *scene;
        int w, h;
    } scenes[] = {
        {"dragon-marble", 256, 256}, {"bunny-skin", 192, 192}, {"spheres-skin", 288, 96}, {"bunny-jade", 192, 192}};
    if (!context()) return;
    for (size_t k = 0; k < sizeof scenes / sizeof scenes[0]; k++) {
        lucent_scene *sc = load_scene(scenes[k].scene, scenes[k].w, scenes[k].h);
        lucent_renderer *r = NULL;
        if (sc) CHECK_OK(lucent_renderer_create(g_ctx, sc, &k_quick, &r));
        for (int m = 0; r && m < LUCENT_METHOD_COUNT; m++) { /* every method, with the scene's settings */
            lucent_render_settings s = sc->render;
            s.view.method = (lucent_render_method)m;
            lucent_render_result res = {0};
            CHECK_OK(lucent_render(r, &s, &res));
            int black = 0, nonfinite = 0, inside = 0;
            for (int y = 0; res.image && y < res.image->height; y++)
                for (int x = 0; x < res.image->width; x++) {
                    if (!interior(res.mask, x, y)) continue;
                    const float *p = lucent_image_pixel(res.image, x, y);
                    inside++;
                    nonfinite += !isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]);
                    black += p[0] <= 0 && p[1] <= 0 && p[2] <= 0;
                }
            printf("     %s %s: %d pixels inside, %d black, %d not finite (CPU %.1f s)\n", scenes[k].scene,
                   lucent_render_method_name(s.view.method), inside, black, nonfinite, lucent_cpu_seconds());
            CHECK_MSG(inside > 1000 && black == 0 && nonfinite == 0, "%s %s: %d black, %d not finite of %d",
                      scenes[k].scene, lucent_render_method_name(s.view.method), black, nonfinite, inside);
            lucent_render_result_free(&res);
        }
        lucent_renderer_destroy(r);
        lucent_scene_destroy(sc);
    }
}

static void teardown(void)
{
    lucent_gl_destroy(g_ctx);
    g_ctx = NULL;
}

TEST_MAIN(TEST_ENTRY(no_black_or_nonfinite_pixel_inside_the_object), TEST_ENTRY(teardown))
