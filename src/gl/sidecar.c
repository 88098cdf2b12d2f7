/* The JSON sidecar of a render: what made the image (the scene after overrides, the settings, the
 * GL device), what it cost (per-pass GPU times, CPU setup) and the values it used (albedo, sigma0,
 * curvature ranges, every kernel's taps). Format: docs/render.md. */
#include <string.h>
#include "base/settings_table.h"
#include "gl/methods/method.h"


static void add_gl(cJSON *root, const lucent_gl_context *ctx)
{
    cJSON *g = cJSON_AddObjectToObject(root, "gl");
    if (!g) return;
    cJSON_AddStringToObject(g, "platform", ctx->info.platform);
    cJSON_AddStringToObject(g, "device", ctx->info.device);
    cJSON_AddStringToObject(g, "renderer", ctx->info.renderer);
    cJSON_AddStringToObject(g, "vendor", ctx->info.vendor);
    cJSON_AddStringToObject(g, "version", ctx->info.version);
    cJSON_AddStringToObject(g, "glsl", ctx->info.glsl);
    cJSON_AddBoolToObject(g, "software", ctx->info.software);
}

static void add_settings(cJSON *root, const lucent_render_settings *s)
{
    cJSON *o = cJSON_AddObjectToObject(root, "settings");
    if (o) lucent_settings_write_json(s, o);
}

static void add_timings(cJSON *root, const lucent_render_result *res)
{
    cJSON *t = cJSON_AddObjectToObject(root, "timings");
    if (!t) return;
    cJSON_AddNumberToObject(t, "gpu_frame_ms", res->times.gpu_ms);
    cJSON_AddNumberToObject(t, "cpu_frame_ms", res->times.cpu_ms);
    cJSON_AddNumberToObject(t, "blur_ms", res->times.blur_ms);
    cJSON_AddNumberToObject(t, "setup_ms", res->times.setup_ms);
    cJSON_AddNumberToObject(t, "readback_ms", res->readback_ms);
    cJSON *passes = cJSON_AddArrayToObject(t, "passes");
    for (int i = 0; passes && i < res->times.pass_count; i++) {
        cJSON *p = cJSON_CreateObject();
        if (!p) return;
        cJSON_AddStringToObject(p, "name", res->times.pass_name[i]);
        cJSON_AddNumberToObject(p, "gpu_ms", res->times.pass_ms[i]);
        cJSON_AddItemToArray(passes, p);
    }
}

static void add_objects(cJSON *root, const lucent_renderer *r)
{
    cJSON *list = cJSON_AddArrayToObject(root, "objects");
    for (int i = 0; list && i < r->scene->object_count; i++) {
        lucent_render_object_info info;
        cJSON *o = cJSON_CreateObject();
        if (!o || lucent_renderer_object_info(r, i, &info) != LUCENT_OK) return cJSON_Delete(o);
        cJSON_AddStringToObject(o, "name", r->scene->objects[i].name);
        cJSON_AddStringToObject(o, "material", r->scene->objects[i].material.name);
        lucent_json_add_numbers(o, "albedo", info.albedo, 3);
        lucent_json_add_numbers(o, "sigma0_mm", info.sigma0, 3);
        cJSON_AddStringToObject(o, "sigma0_from", info.sigma0_from);
        lucent_json_add_numbers(o, "curvature_p5_p95", info.curvature_range, 2);
        cJSON_AddNumberToObject(o, "kernel_range_mm", info.kernel_range);
        cJSON_AddNumberToObject(o, "transmit_range_mm", info.transmit_range);
        cJSON_AddItemToArray(list, o);
    }
}

lucent_status lucent_render_sidecar(const lucent_renderer *r, const lucent_render_settings *settings,
                                    const lucent_render_result *res, char **dest)
{
    const lucent_render_settings *s = settings ? settings : &r->scene->render;
    cJSON *root = cJSON_CreateObject(), *scene = r->scene->json ? cJSON_Parse(r->scene->json) : NULL;
    if (!root) return cJSON_Delete(scene), lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    cJSON_AddStringToObject(root, "lucent", LUCENT_VERSION_STRING);
    cJSON_AddStringToObject(root, "scene_file", r->scene->path);
    add_gl(root, r->ctx);
    add_settings(root, s);
    add_timings(root, res);
    add_objects(root, r);
    const gl_method *m = gl_methods[s->view.method];
    void *state = r->state[s->view.method];
    if (m->sidecar && state) m->sidecar(r, state, s, root);
    if (scene) cJSON_AddItemToObject(root, "scene", scene);
    char *text = cJSON_Print(root);
    cJSON_Delete(root);
    if (!text) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    *dest = text;
    return LUCENT_OK;
}
