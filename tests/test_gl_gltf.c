/* GL test (label gl): a glTF scene renders the pixels of the same scene written as Lucent JSON. The glTF
 * is a pack's material.gltf (a sphere, its camera and key light); the JSON scene takes that camera and
 * light as the glTF scene read them (tests/test_gltf.c checks those against the glTF's definitions),
 * the preset material and the same mesh file read through assimp, an independent glTF reader. Both
 * render with Lambert and a given albedo (no Monte Carlo bake) and must agree in every byte. */
#include "lucent/pack.h"
#include "lucent/render.h"
#include "lucent/scene.h"
#include "test.h"

static lucent_status render(lucent_gl_context *ctx, const lucent_scene *sc, lucent_image **dest)
{
    lucent_renderer *r = NULL;
    lucent_render_result res = {0};
    lucent_status s = lucent_renderer_create(ctx, sc, NULL, &r);
    if (s == LUCENT_OK) s = lucent_render(r, &sc->render, &res);
    if (s == LUCENT_OK) *dest = res.image, res.image = NULL;
    lucent_render_result_free(&res);
    lucent_renderer_destroy(r);
    return s;
}

TEST(gltf_sphere_renders_the_pixels_of_the_json_sphere)
{
    lucent_material m;
    CHECK_OK(lucent_material_preset_find("skin1", &m));
    char out[1024], gltf[1100], json[4096];
    snprintf(out, sizeof out, "%s", test_path("pack"));
    lucent_pack_desc d = {.engine = LUCENT_PACK_JSON,
                          .out = out,
                          .object_height_mm = 30,
                          .sigma0_photons = 300,
                          .transmit_photons = 100,
                          .lut_width = 4,
                          .lut_height = 4,
                          .no_fit = true};
    CHECK_OK(lucent_pack(&m, &d, NULL));
    snprintf(gltf, sizeof gltf, "%s/material.gltf", out);
    static const char *const sets[] = {"render.width=48", "render.height=40", "render.method=lambert",
                                       "objects[0].albedo=[0.7, 0.5, 0.4]"};
    lucent_scene *sc = NULL, *js = NULL;
    CHECK_OK(lucent_scene_load(gltf, &(lucent_scene_load_desc){.overrides = sets, .override_count = 4}, &sc));
    if (!sc) return;
    const lucent_camera *c = &sc->camera;
    const double *l = sc->lights[0].direction;
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [%.17g, %.17g, %.17g], \"target\": [%.17g, %.17g, %.17g], \"fov_y\": %.17g, "
             "\"near\": %.17g},\n \"lights\": [{\"type\": \"directional\", \"intensity\": 3, \"direction\": [%.17g, "
             "%.17g, %.17g]}],\n \"objects\": [{\"mesh\": \"material.gltf\", \"mm_per_unit\": 1000, \"material\": "
             "\"skin1\", \"roughness\": 0.3, \"albedo\": [0.7, 0.5, 0.4]}],\n \"render\": {\"width\": 48, \"height\": "
             "40, \"method\": \"lambert\"}}\n",
             c->position[0], c->position[1], c->position[2], c->target[0], c->target[1], c->target[2], c->fov_y,
             c->near_plane, l[0], l[1], l[2]);
    CHECK_OK(lucent_scene_parse(json, "sphere.json", out, NULL, &js));
    lucent_gl_context *ctx = NULL;
    CHECK_OK(lucent_gl_create(NULL, &ctx));
    lucent_image *a = NULL, *b = NULL;
    if (ctx && js) CHECK_OK(render(ctx, sc, &a));
    if (ctx && js) CHECK_OK(render(ctx, js, &b));
    if (a && b) {
        double diff = 0, sum = 0;
        for (int y = 0; y < 40; y++)
            for (int x = 0; x < 48; x++)
                for (int k = 0; k < 3; k++) {
                    diff = fmax(diff, fabs(lucent_image_get(a, x, y, k) - lucent_image_get(b, x, y, k)));
                    sum += lucent_image_get(a, x, y, k);
                }
        CHECK_MSG(diff == 0 && sum > 0, "glTF and JSON spheres differ by %g (sum %g)", diff, sum);
    }
    lucent_image_destroy(a);
    lucent_image_destroy(b);
    lucent_gl_destroy(ctx);
    lucent_scene_destroy(js);
    lucent_scene_destroy(sc);
}

TEST_MAIN(TEST_ENTRY(gltf_sphere_renders_the_pixels_of_the_json_sphere))
