/* Light between surfaces (render.bounce; docs/render.md, "Light between surfaces"): one bounce of each
 * shadow-casting light off the objects' own surfaces, gathered from a reflective shadow map
 * (Dachsbacher & Stamminger 2005): a small map per light, drawn with the light's shadow projection,
 * whose texels are the surfels the light meets first (position, normal, and the power they send back
 * out, albedo x the light's power on the texel). The texels that hold a surface are gathered into one
 * list (a storage buffer, in texel order: the same image every run), and every pixel of the scene pass
 * sums what those surfels give it (bounce.glsl), without occlusion between them. Internal to src/gl. */
#ifndef LUCENT_SRC_GL_BOUNCE_H
#define LUCENT_SRC_GL_BOUNCE_H

#include "gl/core/gpu.h"

enum { GL_BOUNCE_BINDING = 6 }; /* the surfels' storage buffer (bounce.glsl) */

typedef struct gl_bounce {
    int size, layers; /* texels per side (0: off), layers (the shadow maps' count) */
    int count;        /* surfels in the list */
    GLuint position, normal, flux, depth, fbo, program, surfels;
    float *texels, *list; /* read back, size^2 x layers x 12 floats each */
} gl_bounce;

/* (Re)creates the maps at size x size texels, `layers` of them (one per shadow-casting light); size 0
 * frees them. */
lucent_status gl_bounce_resize(gl_bounce *b, int layers, int size);

/* A light's projection as the shadow maps have it (shadows.h). */
typedef struct gl_bounce_light {
    int index, layer;     /* the light's index in the frame block, its layer (< 0: no map) */
    const double *matrix; /* world -> the light's clip space */
    double texel;         /* mm: the map's side where it is centred (the scene's centre) */
    double distance;      /* mm: that centre's distance from a point light; 0 directional */
} gl_bounce_light;

/* Starts drawing a light's surfels (binds, clears, sets its projection); false when the light casts no
 * shadow or the maps are off. Draw each object after gl_bounce_object, then gl_bounce_end. */
bool gl_bounce_begin(gl_bounce *b, const gl_bounce_light *light);

/* The albedo the next object sends the light back with. */
void gl_bounce_object(const gl_bounce *b, const double albedo[3]);

/* After the last light: reads the maps back and lists the texels that hold a surface (b->count). */
lucent_status gl_bounce_end(gl_bounce *b);

/* Binds the list for the scene shaders (nothing when off: the frame block's count is 0 then). */
void gl_bounce_bind(const gl_bounce *b);

void gl_bounce_free(gl_bounce *b);

#endif
