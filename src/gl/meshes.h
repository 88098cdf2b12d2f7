/* The scene's meshes on the GPU: positions and normals (world mm), texture coordinates and albedo
 * maps, and the per-vertex mean curvature (computed when a method first needs it). */
#ifndef LUCENT_SRC_GL_MESHES_H
#define LUCENT_SRC_GL_MESHES_H

#include "gl/core/gpu.h"
#include "lucent/scene.h"

/* Attribute locations of every mesh program (scene.vert.glsl). */
enum { GL_ATTR_POSITION = 0, GL_ATTR_NORMAL = 1, GL_ATTR_CURVATURE = 2, GL_ATTR_UV = 3 };

/* One scene object on the GPU. */
typedef struct gl_mesh {
    GLuint vao, vertices, indices, curvature, uvs, albedo_map;
    GLsizei index_count;
    int curvature_smooth;      /* the rings the uploaded curvature was smoothed over; -1: none */
    double curvature_range[2]; /* 5th and 95th percentiles of the mean curvature, mm^-1 */
} gl_mesh;

typedef struct gl_meshes {
    int count;
    gl_mesh *mesh; /* one per scene object */
} gl_meshes;

/* Uploads every object's mesh (and albedo map and texture coordinates). */
lucent_status gl_meshes_upload(gl_meshes *m, const lucent_scene *scene);

/* Computes and uploads the visible objects' mean curvature with smooth_rings of smoothing, unless
 * it is there already. */
lucent_status gl_meshes_curvature(gl_meshes *m, const lucent_scene *scene, int smooth_rings, lucent_pool *pool);

/* Draws object i's triangles with the bound program. */
void gl_meshes_draw(const gl_meshes *m, int i);

void gl_meshes_free(gl_meshes *m);

#endif
