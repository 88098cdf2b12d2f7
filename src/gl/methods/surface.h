/* What the mesh methods (lambert, cdrf, ssss) share: the surface pass, every visible object drawn
 * with the method's program (surface.glsl + the method's fragment shader) into the scene targets, and
 * the compose pass (Freude 4.2, pass 4). Also translucency (translucency.c), the light through thin
 * parts that ssss and cdrf+translucency add. */
#ifndef LUCENT_SRC_GL_METHODS_SURFACE_H
#define LUCENT_SRC_GL_METHODS_SURFACE_H

#include "gl/methods/method.h"

/* The method's uniforms of object i (after the common ones: albedo, map, roughness, f0, material). */
typedef void (*gl_surface_object_fn)(const lucent_renderer *r, const void *state, const lucent_render_settings *s,
                                     int i, GLuint program);

/* The program of the method's fragment shader `frag` with defines (the auxiliary outputs added). */
lucent_status gl_surface_program(lucent_renderer *r, const char *frag, const char *defines, GLuint *dest);

/* Object i's material uniforms, shared by every program that shades with surface.glsl's lights: the
 * albedo (gl_renderer_object_albedo), roughness, eta and mean F_t, the material row, object index. */
void gl_surface_material_uniforms(const lucent_renderer *r, int i, GLuint program);

/* The surface pass (timed as "geometry"); table textures: unit 3 lut (0: none), 4 the transmittance. */
void gl_surface_draw(lucent_renderer *r, GLuint program, GLuint lut, const lucent_render_settings *s,
                     gl_surface_object_fn fn, const void *state);

/* The compose pass into the final target (timed as "compose"): the blurred diffuse (0: none) blended
 * with the unblurred one by the per-pixel strength, the specular added, background elsewhere. */
void gl_compose(lucent_renderer *r, const lucent_render_settings *s, GLuint blurred);

/* ---- translucency.c ---- */

/* Bakes and uploads the transmittance tables of every material. */
lucent_status gl_translucency_prepare(lucent_renderer *r, const lucent_render_settings *s);

/* What translucency bakes with settings s when enabled (the transmittance, and the sheet tables for thin
 * parts). */
unsigned gl_translucency_bakes(const lucent_render_settings *s, bool enabled);

/* Object i's translucency uniforms; curvature_gain: cdrf+translucency's modulation (0: none). */
void gl_translucency_uniforms(const lucent_renderer *r, const lucent_render_settings *s, int i, GLuint program,
                              bool enabled);

/* The half-width of the transmittance table of object i's material, mm (0: not built). */
double gl_translucency_range(const lucent_renderer *r, int i);

/* Curved parts (render.curved_parts; surface.glsl, CURVED): the vertex curvature and every material's
 * spheres, baked and uploaded (bound to GL_SPHERES_UNIT by gl_surface_draw). */
lucent_status gl_curved_prepare(lucent_renderer *r, const lucent_render_settings *s);

/* Object i's curved-parts uniforms. */
void gl_curved_uniforms(const lucent_renderer *r, int i, GLuint program);

#endif
