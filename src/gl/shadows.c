/* Lights and shadow maps (shadows.h). */
#include <math.h>
#include <string.h>

#include "base/mat4.h"
#include "gl/shadows.h"

static void free_maps(gl_shadows *r);

static void scene_sphere(gl_shadows *r, const lucent_scene *scene)
{
    double lo[3], hi[3], rr = 0;
    lucent_scene_bounds(scene, lo, hi);
    for (int i = 0; i < 3; i++) {
        r->bound_centre[i] = lo[i] <= hi[i] ? 0.5 * (lo[i] + hi[i]) : 0;
        rr += lo[i] <= hi[i] ? 0.25 * (hi[i] - lo[i]) * (hi[i] - lo[i]) : 0;
    }
    r->bound_radius = fmax(sqrt(rr), 1e-3);
}

/* The light looks at the bounding sphere's centre from eye; up is any axis not along the view. */
static void light_view(const double eye[3], const double centre[3], double dest[16])
{
    lucent_camera cam = {.fov_y = 30};
    double d[3], len = 0;
    for (int i = 0; i < 3; i++) cam.position[i] = eye[i], cam.target[i] = centre[i], d[i] = centre[i] - eye[i];
    for (int i = 0; i < 3; i++) len += d[i] * d[i];
    bool vertical = fabs(d[1]) > 0.99 * sqrt(len);
    cam.up[0] = vertical ? 1 : 0, cam.up[1] = vertical ? 0 : 1, cam.up[2] = 0;
    lucent_camera_view(&cam, dest);
}

static void directional(const gl_shadows *r, const lucent_light *l, gl_light *g)
{
    double R = r->bound_radius, eye[3], proj[16] = {0}, view[16];
    for (int i = 0; i < 3; i++) eye[i] = r->bound_centre[i] - l->direction[i] * 2 * R;
    light_view(eye, r->bound_centre, view);
    g->near_plane = R, g->far_plane = 3 * R, g->ortho = true, g->texel = 2 * R;
    proj[0] = proj[5] = 1 / R;
    proj[10] = -2 / (g->far_plane - g->near_plane);
    proj[14] = -(g->far_plane + g->near_plane) / (g->far_plane - g->near_plane);
    proj[15] = 1;
    lucent_mat4_mul(proj, view, g->matrix);
}

/* Returns false when the light stands inside the scene's bounding sphere (no single map covers). */
static bool point(const gl_shadows *r, const lucent_light *l, gl_light *g)
{
    double R = r->bound_radius, dist = 0, view[16], proj[16];
    for (int i = 0; i < 3; i++) dist += (r->bound_centre[i] - l->position[i]) * (r->bound_centre[i] - l->position[i]);
    dist = sqrt(dist);
    if (dist < 1.05 * R) return false;
    lucent_camera cam = {.fov_y = 2 * asin(R / dist) * 180 / M_PI * 1.02};
    g->near_plane = cam.near_plane = fmax(dist - R, dist * 1e-3);
    g->far_plane = cam.far_plane = dist + R;
    g->ortho = false;
    g->texel = 2 * dist * tan(0.5 * cam.fov_y * M_PI / 180);
    light_view(l->position, r->bound_centre, view);
    lucent_camera_projection(&cam, 1, proj);
    lucent_mat4_mul(proj, view, g->matrix);
    return true;
}

lucent_status gl_shadows_setup(gl_shadows *r, const lucent_scene *scene)
{
    scene_sphere(r, scene);
    lucent_status s =
        gl_program_build(gl_embedded_source, NULL, "shadow.vert.glsl", "shadow.frag.glsl", NULL, &r->program);
    for (int i = 0; i < scene->light_count && s == LUCENT_OK; i++) {
        const lucent_light *l = &scene->lights[i];
        if (l->type == LUCENT_LIGHT_ENVIRONMENT) {
            for (int c = 0; c < 3; c++) r->ambient[c] += l->color[c] * l->intensity;
            continue;
        }
        if (r->light_count == GLR_MAX_LIGHTS)
            return lucent_error(LUCENT_ERR_UNSUPPORTED, "%s: lights[%d]: at most %d lights besides environment lights",
                                scene->name, i, GLR_MAX_LIGHTS);
        gl_light *g = &r->lights[r->light_count++];
        memset(g, 0, sizeof *g);
        g->scene_index = i, g->layer = -1;
        if (!l->shadows) continue;
        if (l->type == LUCENT_LIGHT_DIRECTIONAL)
            directional(r, l, g);
        else if (!point(r, l, g)) {
            lucent_log(LUCENT_LOG_WARN, "%s: lights[%d] stands inside the scene's bounds: drawn without shadows",
                       scene->name, i);
            continue;
        }
        g->layer = r->layers++;
    }
    return s;
}

void gl_shadows_update(gl_shadows *r, const lucent_scene *scene)
{
    r->ambient[0] = r->ambient[1] = r->ambient[2] = 0;
    for (int i = 0; i < scene->light_count; i++) {
        const lucent_light *l = &scene->lights[i];
        if (l->type == LUCENT_LIGHT_ENVIRONMENT)
            for (int c = 0; c < 3; c++) r->ambient[c] += l->color[c] * l->intensity;
    }
    for (int i = 0; i < r->light_count; i++) {
        gl_light *g = &r->lights[i];
        const lucent_light *l = &scene->lights[g->scene_index];
        if (g->layer < 0) continue;
        if (l->type == LUCENT_LIGHT_DIRECTIONAL)
            directional(r, l, g);
        else
            point(r, l, g); /* inside the bounds now: the last projection stays */
    }
}

lucent_status gl_shadows_resize(gl_shadows *r, int size)
{
    if (r->tex && r->size == size) return LUCENT_OK;
    free_maps(r);
    int layers = r->layers > 0 ? r->layers : 1, side = r->layers > 0 ? size : 1;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &r->tex);
    glTextureStorage3D(r->tex, 1, GL_DEPTH_COMPONENT32F, side, side, layers);
    glCreateFramebuffers(1, &r->fbo);
    glNamedFramebufferDrawBuffer(r->fbo, GL_NONE);
    glNamedFramebufferReadBuffer(r->fbo, GL_NONE);
    glCreateSamplers(1, &r->sampler_compare);
    glCreateSamplers(1, &r->sampler_raw);
    GLuint samplers[2] = {r->sampler_compare, r->sampler_raw};
    for (int i = 0; i < 2; i++) {
        glSamplerParameteri(samplers[i], GL_TEXTURE_MIN_FILTER, i == 0 ? GL_LINEAR : GL_NEAREST);
        glSamplerParameteri(samplers[i], GL_TEXTURE_MAG_FILTER, i == 0 ? GL_LINEAR : GL_NEAREST);
        glSamplerParameteri(samplers[i], GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glSamplerParameteri(samplers[i], GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    glSamplerParameteri(r->sampler_compare, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glSamplerParameteri(r->sampler_compare, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    r->size = size;
    return gl_check("creating the shadow maps");
}

bool gl_shadows_begin(gl_shadows *r, int i)
{
    const gl_light *g = &r->lights[i];
    if (g->layer < 0) return false;
    glUseProgram(r->program);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, r->fbo);
    glViewport(0, 0, r->size, r->size);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.5f, 2.0f);
    float m[16];
    lucent_mat4_to_float(g->matrix, m);
    glUniformMatrix4fv(glGetUniformLocation(r->program, "u_light_mvp"), 1, GL_FALSE, m);
    glNamedFramebufferTextureLayer(r->fbo, GL_DEPTH_ATTACHMENT, r->tex, 0, g->layer);
    glClearNamedFramebufferfv(r->fbo, GL_DEPTH, 0, (const float[1]){1});
    return true;
}

void gl_shadows_end(void) { glDisable(GL_POLYGON_OFFSET_FILL); }

void gl_shadows_bind(const gl_shadows *r)
{
    glBindTextureUnit(1, r->tex);
    glBindSampler(1, r->sampler_compare);
    glBindTextureUnit(2, r->tex);
    glBindSampler(2, r->sampler_raw);
}

void gl_shadows_unbind(void)
{
    glBindSampler(1, 0);
    glBindSampler(2, 0);
}

static void free_maps(gl_shadows *r)
{
    if (r->tex) glDeleteTextures(1, &r->tex);
    if (r->fbo) glDeleteFramebuffers(1, &r->fbo);
    if (r->sampler_compare) glDeleteSamplers(1, &r->sampler_compare);
    if (r->sampler_raw) glDeleteSamplers(1, &r->sampler_raw);
    r->tex = r->fbo = r->sampler_compare = r->sampler_raw = 0;
}

void gl_shadows_free(gl_shadows *r)
{
    free_maps(r);
    if (r->program) glDeleteProgram(r->program);
    memset(r, 0, sizeof *r);
}
