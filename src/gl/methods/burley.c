/* burley: Burley's normalized diffusion (Christensen & Burley 2015) on the screen, sampled as Unity HDRP
 * samples its Diffusion Profiles (Golubev 2018, "Efficient Screen-Space Subsurface Scattering Using
 * Burley's Normalized Diffusion in Real-Time", SIGGRAPH course): one pass, a disk of `samples` points per
 * pixel at radii drawn from the profile of the widest channel (its CDF inverted) and golden-angle
 * azimuths rotated per pixel, each weighted per channel by the profile at the 3-D distance over the
 * sampling density, the sums normalised per channel. Each material's albedo A and d = 1 / s are those
 * `lucent fit` gives HDRP (lucent/engine.h), or the hand mapping (d = 1 / sigma_tr, colour T), so that
 * the renderer shows what an engine shows with those parameters. The surface pass is ssss's (Lambert
 * irradiance times the albedo, and with render.translucency the light through thin parts, as ssss: the
 * engines carry their own transmission); the compose pass adds the specular. */
#include <math.h>
#include <string.h>

#include "base/json.h"
#include "base/settings_table.h"
#include "gl/methods/surface.h"
#include "lucent/engine.h"

/* ---- the settings group ---- */

SETTINGS_NAMES(params_names, "fit", "hand")

static const lucent_setting k_burley[] = {
    SETTING_CHOICE("burley_params", burley.params, "fit", params_names,
                   "each material's (A, d): lucent fit's HDRP parameters, or the hand mapping d = 1/sigma_tr"),
    SETTING_INT("burley_samples", burley.samples, 40, 4, 256, 0, "disk samples per pixel (HDRP's sample budget)"),
};

const lucent_settings_group gl_burley_settings =
    SETTINGS_GROUP("burley", "Burley's profile sampled on a disk, as Unity HDRP", k_burley);

/* ---- the method ---- */

typedef struct burley_state {
    GLuint surface, blur, tex, fbo;
    int width, height;
    double albedo[GLR_MAX_MATERIALS][3], d[GLR_MAX_MATERIALS][3];
    char key[GLR_MAX_MATERIALS * 48 + 16]; /* what (A, d) were made from */
} burley_state;

static lucent_status variant(const char *text, lucent_render_settings *s)
{
    if (!strcmp(text, "fit"))
        s->burley.params = LUCENT_BURLEY_PARAMS_FIT;
    else if (!strcmp(text, "hand"))
        s->burley.params = LUCENT_BURLEY_PARAMS_HAND;
    else
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "burley:%s: the variant is fit or hand", text);
    return LUCENT_OK;
}

/* (A, d) of every material: its truth (the renderer's profile_photons when given, T then from twice as many;
 * else the defaults, T disk-cached) and HDRP's fit or hand mapping. */
static lucent_status prepare_params(lucent_renderer *r, burley_state *st, const lucent_render_settings *s)
{
    char key[sizeof st->key];
    snprintf(key, sizeof key, "%d", (int)s->burley.params);
    for (int m = 0; m < r->tables.count; m++)
        snprintf(key + strlen(key), sizeof key - strlen(key), " %.40s", r->tables.material[m].name);
    if (!strcmp(key, st->key)) return LUCENT_OK;
    st->key[0] = '\0';
    for (int m = 0; m < r->tables.count; m++) {
        lucent_engine_target t;
        lucent_engine_fit_result fit;
        lucent_status e =
            lucent_engine_target_build(&(lucent_engine_target_desc){.material = &r->tables.material[m],
                                                                    .photons = r->desc.profile_photons,
                                                                    .total_photons = 2 * r->desc.profile_photons,
                                                                    .pool = r->desc.pool,
                                                                    .cache = r->cache},
                                       &t);
        if (e == LUCENT_OK)
            e = s->burley.params == LUCENT_BURLEY_PARAMS_HAND
                    ? lucent_engine_hand(&t, LUCENT_ENGINE_UNITY_HDRP, NULL, &fit)
                    : lucent_engine_fit(&t, LUCENT_ENGINE_UNITY_HDRP, NULL, &fit);
        lucent_engine_target_free(&t);
        if (e != LUCENT_OK) return lucent_error_context(e, "burley");
        memcpy(st->albedo[m], fit.burley.albedo, sizeof st->albedo[m]);
        memcpy(st->d[m], fit.burley.d, sizeof st->d[m]);
        lucent_engine_fit_result_free(&fit);
    }
    snprintf(st->key, sizeof st->key, "%s", key);
    return LUCENT_OK;
}

static lucent_status prepare_target(lucent_renderer *r, burley_state *st)
{
    if (st->fbo && st->width == r->targets.width && st->height == r->targets.height) return LUCENT_OK;
    if (st->fbo) glDeleteFramebuffers(1, &st->fbo), glDeleteTextures(1, &st->tex);
    st->width = r->targets.width, st->height = r->targets.height;
    st->tex = gl_texture(GL_RGBA32F, st->width, st->height, GL_NEAREST);
    return gl_framebuffer(1, &st->tex, 0, "the burley blur's target", &st->fbo);
}

static lucent_status prepare(lucent_renderer *r, void *state, const lucent_render_settings *s)
{
    burley_state *st = state;
    lucent_status e = prepare_params(r, st, s);
    if (e == LUCENT_OK && s->translucency.enabled) e = gl_translucency_prepare(r, s);
    if (e == LUCENT_OK) e = prepare_target(r, st);
    if (e == LUCENT_OK) e = gl_surface_program(r, "ssss.frag.glsl", NULL, &st->surface);
    if (e == LUCENT_OK && !st->blur)
        e = gl_program_build(gl_embedded_source, NULL, "fullscreen.vert.glsl", "burley_blur.frag.glsl", NULL,
                             &st->blur);
    return e;
}

static void object_uniforms(const lucent_renderer *r, const void *state, const lucent_render_settings *s, int i,
                            GLuint p)
{
    const burley_state *st = state;
    const double *a = st->albedo[r->tables.object_material[i]];
    if (r->scene->objects[i].albedo_source == LUCENT_ALBEDO_FROM_MATERIAL)
        glUniform3f(glGetUniformLocation(p, "u_albedo"), (float)a[0], (float)a[1], (float)a[2]);
    glUniform1f(glGetUniformLocation(p, "u_strength"), (float)r->scene->objects[i].sss_strength);
    gl_translucency_uniforms(r, s, i, p, s->translucency.enabled);
}

static void blur(lucent_renderer *r, burley_state *st, const lucent_render_settings *s)
{
    GLuint p = st->blur;
    float d[GLR_MAX_MATERIALS * 3];
    for (int m = 0; m < GLR_MAX_MATERIALS; m++)
        for (int c = 0; c < 3; c++) d[3 * m + c] = m < r->tables.count ? (float)st->d[m][c] : 1.0f;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, st->fbo);
    glViewport(0, 0, st->width, st->height);
    glUseProgram(p);
    glBindVertexArray(r->empty_vao);
    glBindTextureUnit(0, r->targets.diffuse);
    glBindTextureUnit(1, r->targets.depth);
    glUniform3fv(glGetUniformLocation(p, "u_d"), GLR_MAX_MATERIALS, d);
    glUniform1i(glGetUniformLocation(p, "u_samples"), s->burley.samples);
    glUniform1f(glGetUniformLocation(p, "u_scale"),
                (float)lucent_screen_pixels_per_mm(r->targets.height, r->scene->camera.fov_y, 1));
    glDisable(GL_DEPTH_TEST);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    gl_timer_mark(&r->timer, "burley blur");
}

static lucent_status draw(lucent_renderer *r, void *state, const lucent_render_settings *s)
{
    burley_state *st = state;
    gl_surface_draw(r, st->surface, 0, s, object_uniforms, st);
    blur(r, st, s);
    gl_compose(r, s, st->tex);
    return LUCENT_OK;
}

/* Each material's (A, d): what an engine needs to reproduce the frame. */
static void sidecar(const lucent_renderer *r, const void *state, const lucent_render_settings *s, cJSON *root)
{
    const burley_state *st = state;
    (void)s;
    cJSON *list = cJSON_AddArrayToObject(root, "burley");
    for (int m = 0; list && m < r->tables.count; m++) {
        cJSON *j = cJSON_CreateObject();
        if (!j) break;
        cJSON_AddItemToArray(list, j);
        cJSON_AddStringToObject(j, "material", r->tables.material[m].name);
        cJSON_AddItemToObject(j, "albedo", cJSON_CreateDoubleArray(st->albedo[m], 3));
        cJSON_AddItemToObject(j, "d_mm", cJSON_CreateDoubleArray(st->d[m], 3));
    }
}

static void release(void *state)
{
    burley_state *st = state;
    if (st->fbo) glDeleteFramebuffers(1, &st->fbo), glDeleteTextures(1, &st->tex);
    if (st->blur) glDeleteProgram(st->blur);
    memset(st, 0, sizeof *st);
}

static unsigned bakes(const lucent_renderer *r, const lucent_render_settings *s)
{
    (void)r;
    return gl_translucency_bakes(s, s->translucency.enabled);
}

const gl_method gl_method_burley = {
    .name = "burley",
    .settings = (const char *const[]){"burley_params", "burley_samples", "translucency", "transmittance", NULL},
    .variant = variant,
    .variant_doc = "fit|hand",
    .bakes = bakes,
    .state_size = sizeof(burley_state),
    .prepare = prepare,
    .draw = draw,
    .sidecar = sidecar,
    .release = release,
};
