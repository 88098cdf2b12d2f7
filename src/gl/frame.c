/* One frame: shadow maps, the scene pass into diffuse / specular / depth targets, the separable
 * blur (ssss), and the composition (Freude 4.2, passes 1-4), each between two timestamp queries. */
#include <math.h>
#include <string.h>

#include "base/mat4.h"
#include "gl/renderer_internal.h"

/* ---- targets ---- */

static void free_targets(lucent_renderer *r)
{
    GLuint tex[8] = {r->tex_diffuse, r->tex_specular, r->tex_depth, r->tex_zbuffer, r->tex_final,
                     r->tex_aov[0], r->tex_aov[1], r->tex_aov[2]};
    glDeleteTextures(8, tex);
    GLuint fbo[2] = {r->fbo_scene, r->fbo_final};
    glDeleteFramebuffers(2, fbo);
    r->tex_diffuse = r->tex_specular = r->tex_depth = r->tex_zbuffer = r->tex_final = 0;
    r->tex_aov[0] = r->tex_aov[1] = r->tex_aov[2] = r->fbo_scene = r->fbo_final = 0;
}

lucent_status gl_targets_resize(lucent_renderer *r, int width, int height)
{
    bool has_aov = r->tex_aov[0] != 0;
    if (r->fbo_scene && r->width == width && r->height == height && has_aov == r->aov) return LUCENT_OK;
    free_targets(r);
    r->width = width, r->height = height;
    r->tex_diffuse = gl_texture(GL_RGBA32F, width, height, GL_NEAREST);
    r->tex_specular = gl_texture(GL_RGBA32F, width, height, GL_NEAREST);
    r->tex_depth = gl_texture(GL_RG32F, width, height, GL_NEAREST);
    r->tex_zbuffer = gl_texture(GL_DEPTH_COMPONENT32F, width, height, GL_NEAREST);
    r->tex_final = gl_texture(GL_RGBA32F, width, height, GL_LINEAR);
    for (int i = 0; r->aov && i < 3; i++) r->tex_aov[i] = gl_texture(GL_RGBA32F, width, height, GL_NEAREST);
    GLuint colors[6] = {r->tex_diffuse, r->tex_specular, r->tex_depth, r->tex_aov[0], r->tex_aov[1], r->tex_aov[2]};
    lucent_status s = gl_framebuffer(r->aov ? 6 : 3, colors, r->tex_zbuffer, "the scene targets", &r->fbo_scene);
    if (s == LUCENT_OK) s = gl_framebuffer(1, &r->tex_final, 0, "the final target", &r->fbo_final);
    if (s == LUCENT_OK) s = gl_blur_resize(&r->blur, width, height);
    return s;
}

/* ---- the scene programs, one per method variant ---- */

static void scene_locations(GLuint p, gl_scene_uniforms *u)
{
    u->albedo = glGetUniformLocation(p, "u_albedo");
    u->sigma0 = glGetUniformLocation(p, "u_sigma0");
    u->use_map = glGetUniformLocation(p, "u_use_map");
    u->sigma0_from_map = glGetUniformLocation(p, "u_sigma0_from_map");
    u->roughness = glGetUniformLocation(p, "u_roughness");
    u->f0 = glGetUniformLocation(p, "u_f0");
    u->strength = glGetUniformLocation(p, "u_strength");
    u->material = glGetUniformLocation(p, "u_material");
    u->object = glGetUniformLocation(p, "u_object");
    u->translucency = glGetUniformLocation(p, "u_translucency");
    u->transmit_range = glGetUniformLocation(p, "u_transmit_range");
    u->transmit_v = glGetUniformLocation(p, "u_transmit_v");
    u->transmit_albedo = glGetUniformLocation(p, "u_transmit_albedo");
    u->curvature_gain = glGetUniformLocation(p, "u_curvature_gain");
    u->cdrf_reach = glGetUniformLocation(p, "u_cdrf_reach");
    u->shadow_offset = glGetUniformLocation(p, "u_shadow_offset");
    u->lut_sigma_max = glGetUniformLocation(p, "u_lut_sigma_max");
}

static lucent_status scene_program(lucent_renderer *r, const lucent_render_settings *s, gl_program_entry **dest)
{
    char key[64], defines[160];
    int lut = s->cdrf_lut ? 1 : 0, variant = (int)s->cdrf_variant, aov = r->aov ? 1 : 0;
    snprintf(key, sizeof key, "scene m%d l%d v%d a%d", (int)s->method, lut, variant, aov);
    for (int i = 0; i < r->program_count; i++)
        if (!strcmp(r->programs[i].key, key)) {
            *dest = &r->programs[i];
            return LUCENT_OK;
        }
    if (r->program_count == GLR_MAX_PROGRAMS) return lucent_error(LUCENT_ERR_INTERNAL, "too many shader variants");
    snprintf(defines, sizeof defines, "#define METHOD %d\n#define CDRF_LUT %d\n#define CDRF_VARIANT %d\n#define AOV %d\n",
             (int)s->method, lut, variant, aov);
    gl_program_entry *e = &r->programs[r->program_count];
    lucent_status st = gl_program_build(gl_embedded_source, NULL, "scene.vert.glsl", "scene.frag.glsl", defines,
                                        &e->program);
    if (st != LUCENT_OK) return st;
    snprintf(e->key, sizeof e->key, "%s", key);
    scene_locations(e->program, &e->u);
    r->program_count++;
    *dest = e;
    return LUCENT_OK;
}

/* ---- the per-frame uniform block ---- */

static void light_block(const lucent_renderer *r, int i, gl_frame_block *b)
{
    const gl_light *g = &r->lights[i];
    const lucent_light *l = &r->scene->lights[g->scene_index];
    bool directional = l->type == LUCENT_LIGHT_DIRECTIONAL;
    for (int c = 0; c < 3; c++) {
        b->light_vec[i][c] = (float)(directional ? l->direction[c] : l->position[c]);
        b->light_rgb[i][c] = (float)(l->color[c] * l->intensity);
    }
    b->light_vec[i][3] = directional ? 0.0f : 1.0f;
    b->light_shadow[i][0] = (float)g->layer;
    b->light_shadow[i][1] = (float)g->near_plane, b->light_shadow[i][2] = (float)g->far_plane;
    b->light_shadow[i][3] = g->ortho ? 1.0f : 0.0f;
    b->light_texel[i][0] = (float)(g->texel / r->shadow_size);
    lucent_mat4_to_float(g->matrix, b->light_matrix[i]);
}

static void frame_block(const lucent_renderer *r, gl_frame_block *b)
{
    const lucent_camera *cam = &r->scene->camera;
    double view[16], proj[16], vp[16], f[3], len = 0;
    memset(b, 0, sizeof *b);
    lucent_camera_view(cam, view);
    lucent_camera_projection(cam, (double)r->width / r->height, proj);
    lucent_mat4_mul(proj, view, vp);
    lucent_mat4_to_float(vp, b->view_proj);
    for (int i = 0; i < 3; i++) f[i] = cam->target[i] - cam->position[i], len += f[i] * f[i];
    for (int i = 0; i < 3; i++) {
        b->eye[i] = (float)cam->position[i];
        b->forward[i] = (float)(f[i] / sqrt(len));
        b->ambient[i] = (float)r->ambient[i];
    }
    b->counts[0] = r->light_count;
    for (int i = 0; i < r->light_count; i++) light_block(r, i, b);
}

/* ---- passes ---- */

static void object_uniforms(const lucent_renderer *r, const lucent_render_settings *s, int i, const gl_scene_uniforms *u)
{
    const lucent_scene_object *o = &r->scene->objects[i];
    const gl_mesh *g = &r->meshes[i];
    const gl_material *m = &r->materials[g->material];
    bool map = g->albedo_map != 0, map_sigma0 = map && !o->sigma0_set && s->sigma0_source == LUCENT_SIGMA0_DIFFUSE;
    double reach = map_sigma0 ? 1 : fmax(g->sigma0[0], fmax(g->sigma0[1], g->sigma0[2]));
    glUniform3f(u->albedo, (float)o->albedo[0], (float)o->albedo[1], (float)o->albedo[2]);
    glUniform3f(u->sigma0, (float)g->sigma0[0], (float)g->sigma0[1], (float)g->sigma0[2]);
    glUniform1i(u->use_map, map);
    glUniform1i(u->sigma0_from_map, map_sigma0);
    glUniform1f(u->roughness, (float)o->roughness);
    glUniform1f(u->f0, (float)o->specular_f0);
    glUniform1f(u->strength, (float)(o->sss_strength * s->strength));
    glUniform1f(u->material, (float)g->material);
    glUniform1f(u->object, (float)i);
    glUniform1i(u->translucency, s->translucency);
    glUniform1f(u->transmit_range, (float)fmax(m->transmit_range, 1e-6));
    glUniform1f(u->transmit_v, (float)((g->material + 0.5) / r->material_count));
    glUniform1i(u->transmit_albedo, s->transmittance == LUCENT_TRANSMIT_PROFILE);
    glUniform1f(u->curvature_gain, (float)s->translucency_curvature);
    glUniform1f(u->cdrf_reach, (float)(2 * reach)); /* two standard deviations of the CDRF's spread, mm */
    glUniform1f(u->shadow_offset, 1.5f);
    glUniform1f(u->lut_sigma_max, (float)r->lut_sigma_max);
    glBindTextureUnit(0, map ? g->albedo_map : r->dummy_tex);
}

static void bind_tables(const lucent_renderer *r)
{
    glBindTextureUnit(1, r->shadow_tex);
    glBindSampler(1, r->sampler_compare);
    glBindTextureUnit(2, r->shadow_tex);
    glBindSampler(2, r->sampler_raw);
    glBindTextureUnit(3, r->lut_tex ? r->lut_tex : r->dummy_tex);
    glBindTextureUnit(4, r->transmit_tex ? r->transmit_tex : r->dummy_tex);
}

static void draw_scene(lucent_renderer *r, const lucent_render_settings *s, const gl_program_entry *e)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, r->fbo_scene);
    glViewport(0, 0, r->width, r->height);
    for (int i = 0; i < (r->aov ? 6 : 3); i++) glClearNamedFramebufferfv(r->fbo_scene, GL_COLOR, i, (const float[4]){0});
    glClearNamedFramebufferfv(r->fbo_scene, GL_DEPTH, 0, (const float[1]){1});
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glUseProgram(e->program);
    bind_tables(r);
    glVertexAttrib1f(2, 0.0f); /* curvature and texture coordinates where a mesh has none */
    glVertexAttrib2f(3, 0.0f, 0.0f);
    for (int i = 0; i < r->scene->object_count; i++) {
        if (!r->scene->objects[i].visible) continue;
        object_uniforms(r, s, i, &e->u);
        glBindVertexArray(r->meshes[i].vao);
        glDrawElements(GL_TRIANGLES, r->meshes[i].index_count, GL_UNSIGNED_INT, NULL);
    }
    glBindSampler(1, 0);
    glBindSampler(2, 0);
    glDisable(GL_DEPTH_TEST);
}

static void draw_compose(lucent_renderer *r, const lucent_render_settings *s, bool blurred)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, r->fbo_final);
    glViewport(0, 0, r->width, r->height);
    glUseProgram(r->compose_program);
    glBindVertexArray(r->empty_vao);
    glBindTextureUnit(0, r->tex_diffuse);
    glBindTextureUnit(1, blurred ? r->blur.sum_tex : r->dummy_tex);
    glBindTextureUnit(2, r->tex_specular);
    glBindTextureUnit(3, r->tex_depth);
    glUniform1i(glGetUniformLocation(r->compose_program, "u_blurred_valid"), blurred);
    glUniform3f(glGetUniformLocation(r->compose_program, "u_background"), (float)(s->background[0] + r->ambient[0]),
                (float)(s->background[1] + r->ambient[1]), (float)(s->background[2] + r->ambient[2]));
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
}

lucent_status gl_frame_draw(lucent_renderer *r, const lucent_render_settings *s, lucent_frame_times *times)
{
    gl_program_entry *e = NULL;
    lucent_status st = scene_program(r, s, &e);
    if (st != LUCENT_OK) return st;
    gl_frame_block b;
    frame_block(r, &b);
    glNamedBufferSubData(r->frame_ubo, 0, sizeof b, &b);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, r->frame_ubo);
    gl_timer_begin(&r->timer);
    if (r->shadow_layers > 0) gl_shadows_draw(r);
    gl_timer_mark(&r->timer, "shadow");
    draw_scene(r, s, e);
    gl_timer_mark(&r->timer, "geometry");
    bool ssss = s->method == LUCENT_METHOD_SSSS;
    if (ssss) {
        double scale = r->height / (2 * tan(0.5 * r->scene->camera.fov_y * M_PI / 180)) * s->width_scale;
        gl_blur_run(&r->blur, r->tex_diffuse, r->tex_depth, scale, s->depth_filter, &r->timer);
    }
    draw_compose(r, s, ssss);
    gl_timer_mark(&r->timer, "compose");
    gl_timer_end(&r->timer, times);
    return gl_check("drawing the frame");
}

void gl_frame_free(lucent_renderer *r)
{
    free_targets(r);
    for (int i = 0; i < r->program_count; i++) glDeleteProgram(r->programs[i].program);
    r->program_count = 0;
}
