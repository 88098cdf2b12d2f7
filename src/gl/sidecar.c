/* The JSON sidecar of a render: what made the image (the scene after overrides, the settings, the
 * GL device), what it cost (per-pass GPU times, CPU setup) and the values it used (albedo, sigma0,
 * curvature ranges, every kernel's taps). Format: docs/render.md. */
#include <string.h>

#include "base/json.h"
#include "gl/renderer_internal.h"


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
    if (!o) return;
    cJSON_AddNumberToObject(o, "width", s->width);
    cJSON_AddNumberToObject(o, "height", s->height);
    cJSON_AddStringToObject(o, "method", lucent_render_method_name(s->method));
    cJSON_AddStringToObject(o, "kernel", lucent_kernel_model_name(s->kernel_model));
    cJSON_AddNumberToObject(o, "rank", s->kernel_rank);
    cJSON_AddNumberToObject(o, "taps", s->taps);
    cJSON_AddStringToObject(o, "profile", s->profile);
    cJSON_AddNumberToObject(o, "strength", s->strength);
    cJSON_AddNumberToObject(o, "width_scale", s->width_scale);
    cJSON_AddStringToObject(o, "depth_filter", lucent_depth_filter_name(s->depth_filter));
    cJSON_AddBoolToObject(o, "translucency", s->translucency);
    cJSON_AddStringToObject(o, "transmittance", lucent_transmittance_name(s->transmittance));
    cJSON_AddNumberToObject(o, "translucency_curvature", s->translucency_curvature);
    cJSON_AddStringToObject(o, "cdrf_variant", lucent_cdrf_variant_name(s->cdrf_variant));
    cJSON_AddBoolToObject(o, "cdrf_lut", s->cdrf_lut);
    cJSON_AddStringToObject(o, "sigma0", lucent_sigma0_source_name(s->sigma0_source));
    cJSON_AddNumberToObject(o, "curvature_smooth", s->curvature_smooth);
    cJSON_AddNumberToObject(o, "shadow_map_size", s->shadow_map_size);
    lucent_json_add_numbers(o, "background", s->background, 3);
    cJSON_AddStringToObject(o, "tonemap", lucent_tonemap_op_name(s->tonemap));
    cJSON_AddNumberToObject(o, "exposure", s->exposure);
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

static cJSON *taps_json(const gl_material *m)
{
    const lucent_taps *t = m->taps;
    cJSON *k = cJSON_CreateObject();
    if (!k) return NULL;
    cJSON_AddStringToObject(k, "material", m->m.name);
    cJSON_AddStringToObject(k, "key", m->taps_key);
    cJSON_AddNumberToObject(k, "taps", t->count);
    cJSON_AddNumberToObject(k, "rank", t->rank);
    lucent_json_add_numbers(k, "offsets_mm", t->offset, t->count);
    static const char *const names[3] = {"weights_r", "weights_g", "weights_b"};
    static const char *const signs[3] = {"sign_r", "sign_g", "sign_b"};
    for (int c = 0; c < 3; c++) {
        lucent_json_add_numbers(k, names[c], t->weight[c], t->rank * t->count);
        lucent_json_add_numbers(k, signs[c], t->sign[c], t->rank);
    }
    return k;
}

static void add_kernels(cJSON *root, const lucent_renderer *r, const lucent_render_settings *s)
{
    if (s->method != LUCENT_METHOD_SSSS) return;
    cJSON *list = cJSON_AddArrayToObject(root, "kernels");
    for (int i = 0; list && i < r->material_count; i++) {
        cJSON *k = r->materials[i].taps ? taps_json(&r->materials[i]) : NULL;
        if (k) cJSON_AddItemToArray(list, k);
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
    add_kernels(root, r, s);
    if (scene) cJSON_AddItemToObject(root, "scene", scene);
    char *text = cJSON_Print(root);
    cJSON_Delete(root);
    if (!text) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    *dest = text;
    return LUCENT_OK;
}
