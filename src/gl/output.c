/* What a frame gives out: the images read back, the window's picture (the final target tonemapped
 * with the settings' operator and exposure, sRGB-encoded), and the JSON sidecar (what made the image:
 * the scene after overrides, the settings, the GL device; what it cost: per-pass GPU times, CPU setup;
 * the values it used: albedo, sigma0, curvature ranges, the method's own such as every kernel's
 * taps; format: docs/render.md). */
#include <math.h>
#include <string.h>

#include "base/settings_table.h"
#include "gl/methods/method.h"

/* ---- read-back ---- */

lucent_status gl_renderer_read_back(lucent_renderer *r, lucent_render_result *res, int k, int n)
{
    const gl_targets *t = &r->targets;
    lucent_image *rgba = NULL;
    lucent_status s = gl_read_image(t->fbo_final, 0, t->width, t->height, 4, true, &rgba);
    if (s == LUCENT_OK && k == 0) s = lucent_image_create(t->width, t->height, 3, &res->image);
    if (s == LUCENT_OK && k == 0) s = lucent_image_create(t->width, t->height, 1, &res->mask);
    size_t count = (size_t)t->width * (size_t)t->height;
    float w = 1.0f / (float)n;
    for (size_t i = 0; s == LUCENT_OK && i < count; i++) {
        for (int c = 0; c < 3; c++) res->image->data[3 * i + c] += w * rgba->data[4 * i + c];
        res->mask->data[i] += w * rgba->data[4 * i + 3];
    }
    for (size_t i = 0; s == LUCENT_OK && k == n - 1 && i < count; i++)
        res->mask->data[i] = res->mask->data[i] > 0.5f ? 1.0f : 0.0f;
    lucent_image_destroy(rgba);
    return s;
}

/* ---- the window ---- */

lucent_status lucent_render_present_region(lucent_renderer *r, const lucent_present_desc *d)
{
    if (!r->ctx->window || !r->have_frame) return LUCENT_OK;
    lucent_status s = lucent_gl_make_current(r->ctx);
    if (s == LUCENT_OK && !r->present_program)
        s = gl_program_build(gl_embedded_source, NULL, "fullscreen.vert.glsl", "present.frag.glsl", NULL,
                             &r->present_program);
    if (s != LUCENT_OK) return s;
    int w, h;
    gl_window_size(r->ctx, &w, &h);
    int rx = d->x, rw = d->width > 0 ? d->width : w, rh = d->width > 0 ? d->height : h;
    int ry = d->width > 0 ? h - d->y - rh : 0; /* GL counts rows from the bottom */
    if (d->width <= 0) rx = 0;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glDisable(GL_SCISSOR_TEST);
    if (d->clear) {
        glViewport(0, 0, w, h);
        glClearColor(0.12f, 0.12f, 0.13f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
    }
    if (d->clip[2] > 0) {
        glEnable(GL_SCISSOR_TEST);
        glScissor(d->clip[0], h - d->clip[1] - d->clip[3], d->clip[2], d->clip[3]);
    }
    glViewport(rx, ry, rw, rh);
    glUseProgram(r->present_program);
    glBindVertexArray(r->empty_vao);
    glBindTextureUnit(0, r->targets.final);
    glUniform1i(glGetUniformLocation(r->present_program, "u_tonemap"), (int)r->last.view.tonemap);
    glUniform1f(glGetUniformLocation(r->present_program, "u_exposure"), (float)exp2(r->last.view.exposure));
    glUniform2f(glGetUniformLocation(r->present_program, "u_scale"), (float)r->targets.width / (float)(rw > 0 ? rw : 1),
                (float)r->targets.height / (float)(rh > 0 ? rh : 1));
    glUniform2f(glGetUniformLocation(r->present_program, "u_origin"), (float)rx, (float)ry);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_SCISSOR_TEST);
    if (d->swap) gl_window_swap(r->ctx);
    return gl_check("presenting the frame");
}

lucent_status lucent_render_present(lucent_renderer *r)
{
    return lucent_render_present_region(r, &(lucent_present_desc){.swap = true});
}

/* ---- the sidecar ---- */

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
