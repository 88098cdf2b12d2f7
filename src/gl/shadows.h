/* Lights and their shadow maps: one layer of a depth-texture array per shadow-casting light, an
 * orthographic projection around the scene's bounding sphere for directional lights and a
 * perspective one toward it for point and sphere lights (a sphere light shadows as a point). The
 * same maps give the thickness the translucency reads (Jimenez 2010). Environment lights add up to
 * the ambient radiance. */
#ifndef LUCENT_SRC_GL_SHADOWS_H
#define LUCENT_SRC_GL_SHADOWS_H

#include "gl/core/gpu.h"
#include "lucent/scene.h"

enum { GLR_MAX_LIGHTS = 8 }; /* lights other than environment lights (common.glsl MAX_LIGHTS) */

/* A light's projection. */
typedef struct gl_light {
    int scene_index;
    int layer;         /* shadow layer, -1: none */
    double matrix[16]; /* world -> light clip space, column-major */
    double near_plane, far_plane, texel;
    bool ortho;
} gl_light;

typedef struct gl_shadows {
    gl_light lights[GLR_MAX_LIGHTS];
    int light_count, layers, size;
    double ambient[3]; /* environment lights' radiance, summed */
    double bound_centre[3], bound_radius;
    GLuint tex, fbo, sampler_compare, sampler_raw, program;
} gl_shadows;

/* Sets up the lights of scene (its meshes give the bounds) and the shadow program. */
lucent_status gl_shadows_setup(gl_shadows *sh, const lucent_scene *scene);

/* Re-reads the lights' directions, positions, colours and intensities from scene (same lights as at
 * setup): their projections and the ambient radiance. */
void gl_shadows_update(gl_shadows *sh, const lucent_scene *scene);

/* (Re)creates the maps at size x size texels; no-op when unchanged. */
lucent_status gl_shadows_resize(gl_shadows *sh, int size);

/* Starts drawing light i's layer (binds, clears, sets the light's matrix); false when light i casts
 * no shadow. Draw the casters, then call gl_shadows_end once after the last light. */
bool gl_shadows_begin(gl_shadows *sh, int i);
void gl_shadows_end(void);

/* Binds the maps for the scene shaders: compare sampler on unit 1, raw depths on unit 2. */
void gl_shadows_bind(const gl_shadows *sh);
void gl_shadows_unbind(void);

void gl_shadows_free(gl_shadows *sh);

#endif
