/* The surface and compose passes shared by the mesh methods (surface.h). */
#include <string.h>

#include "gl/methods/surface.h"

lucent_status gl_surface_program(lucent_renderer *r, const char *frag, const char *defines, GLuint *dest)
{
    char all[256];
    snprintf(all, sizeof all, "%s#define AOV %d\n", defines ? defines : "", r->aov ? 1 : 0);
    return gl_programs_get(&r->programs, "scene.vert.glsl", frag, all, dest);
}

void gl_surface_material_uniforms(const lucent_renderer *r, int i, GLuint p)
{
    const lucent_scene_object *o = &r->scene->objects[i];
    double a[3];
    gl_renderer_object_albedo(r, i, a);
    glUniform3f(glGetUniformLocation(p, "u_albedo"), (float)a[0], (float)a[1], (float)a[2]);
    glUniform1f(glGetUniformLocation(p, "u_roughness"), (float)o->roughness);
    glUniform1f(glGetUniformLocation(p, "u_eta"), (float)o->material.eta);
    const double *sa = o->material.sigma_a, *ss = o->material.sigma_s;
    glUniform3f(glGetUniformLocation(p, "u_sigma_t"), (float)(sa[0] + ss[0]), (float)(sa[1] + ss[1]),
                (float)(sa[2] + ss[2]));
    glUniform1f(glGetUniformLocation(p, "u_material"), (float)r->tables.object_material[i]);
    glUniform1f(glGetUniformLocation(p, "u_object"), (float)i);
    glUniform1f(glGetUniformLocation(p, "u_shadow_offset"), 1.5f);
}

/* The material's uniforms and the albedo map (unit 0) of object i. */
static void common_uniforms(const lucent_renderer *r, int i, GLuint p)
{
    const gl_mesh *g = &r->meshes.mesh[i];
    gl_surface_material_uniforms(r, i, p);
    glUniform1i(glGetUniformLocation(p, "u_use_map"), g->albedo_map != 0);
    glBindTextureUnit(0, g->albedo_map ? g->albedo_map : r->dummy_tex);
}

static void clear_scene(const gl_targets *t)
{
    for (int i = 0; i < gl_targets_scene_outputs(t); i++)
        glClearNamedFramebufferfv(t->fbo_scene, GL_COLOR, i, (const float[4]){0});
    glClearNamedFramebufferfv(t->fbo_scene, GL_DEPTH, 0, (const float[1]){1});
}

void gl_surface_draw(lucent_renderer *r, GLuint program, GLuint lut, const lucent_render_settings *s,
                     gl_surface_object_fn fn, const void *state)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, r->targets.fbo_scene);
    glViewport(0, 0, r->targets.width, r->targets.height);
    clear_scene(&r->targets);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glUseProgram(program);
    gl_shadows_bind(&r->shadows);
    glBindTextureUnit(3, lut ? lut : r->dummy_tex);
    glBindTextureUnit(4, r->tables.transmit_tex ? r->tables.transmit_tex : r->dummy_tex);
    if (r->tables.spheres_tex) glBindTextureUnit(GL_SPHERES_UNIT, r->tables.spheres_tex);
    if (r->tables.sheet_tex) glBindTextureUnit(GL_SHEET_UNIT, r->tables.sheet_tex);
    glVertexAttrib1f(GL_ATTR_CURVATURE, 0.0f); /* curvature and texture coordinates where a mesh has none */
    glVertexAttrib2f(GL_ATTR_UV, 0.0f, 0.0f);
    for (int i = 0; i < r->scene->object_count; i++) {
        if (!r->scene->objects[i].visible) continue;
        common_uniforms(r, i, program);
        if (fn) fn(r, state, s, i, program);
        gl_meshes_draw(&r->meshes, i);
    }
    gl_shadows_unbind();
    glDisable(GL_DEPTH_TEST);
    gl_timer_mark(&r->timer, "geometry");
}

void gl_compose(lucent_renderer *r, const lucent_render_settings *s, GLuint blurred)
{
    GLuint p = r->compose_program;
    const double *bg = s->view.background, *amb = r->shadows.ambient;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, r->targets.fbo_final);
    glViewport(0, 0, r->targets.width, r->targets.height);
    glUseProgram(p);
    glBindVertexArray(r->empty_vao);
    glBindTextureUnit(0, r->targets.diffuse);
    glBindTextureUnit(1, blurred ? blurred : r->dummy_tex);
    glBindTextureUnit(2, r->targets.specular);
    glBindTextureUnit(3, r->targets.depth);
    glUniform1i(glGetUniformLocation(p, "u_blurred_valid"), blurred != 0);
    glUniform3f(glGetUniformLocation(p, "u_background"), (float)(bg[0] + amb[0]), (float)(bg[1] + amb[1]),
                (float)(bg[2] + amb[2]));
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    gl_timer_mark(&r->timer, "compose");
}
