/* The scene's distinct materials (with the roughness of their boundary: an entry per material and
 * roughness), what the bake room made of each (lucent/bake.h: profile, taps, transmittance, sigma0,
 * the boundary's tables), and the GPU tables built from them: the transmittance T(s), a row per
 * material (a float texture, linear in s), and the boundary's entry and exit factors, a layer per
 * material. */
#ifndef LUCENT_SRC_GL_TABLES_H
#define LUCENT_SRC_GL_TABLES_H

#include "gl/core/gpu.h"
#include "lucent/bake.h"
#include "lucent/scene.h"

enum { GLR_MAX_MATERIALS = 8 }; /* distinct materials in one scene (kernel rows, transmittance rows) */
enum { GL_BOUNDARY_UNIT = 9 };  /* the texture unit of the boundary's tables in every pass (lights.glsl) */
enum { GL_SPHERES_UNIT = 10 };  /* the curved parts' tables (cdrf with cdrf_spheres) */
enum { GL_SHEET_UNIT = 11 };    /* the thin parts' sheet tables (surface.glsl) */

typedef struct gl_tables {
    int count;
    lucent_material material[GLR_MAX_MATERIALS];
    double roughness[GLR_MAX_MATERIALS]; /* the boundary's GGX alpha (the objects' roughness) */
    lucent_baked baked[GLR_MAX_MATERIALS];
    int *object_material; /* per scene object: its index into material */
    GLuint transmit_tex;  /* RGB32F, LUCENT_BAKE_TRANSMIT_SIZE x count */
    char transmit_key[GLR_MAX_MATERIALS * LUCENT_BAKE_KEY_SIZE];
    GLuint boundary_tex; /* RGB32F array: LUCENT_BOUNDARY_BINS x (BINS + 1), a layer per material (bake.h) */
    GLuint spheres_tex;  /* RGB32F array: SPHERE_BINS x 2 (SPHERE_RADII + 1), a layer per material */
    char spheres_key[GLR_MAX_MATERIALS * LUCENT_BAKE_KEY_SIZE];
    char boundary_key[GLR_MAX_MATERIALS * LUCENT_BAKE_KEY_SIZE];
    GLuint sheet_tex; /* RGB32F array: LUCENT_SHEET_BINS x 2 SHEET_ROWS, a layer per material (bake.h) */
    char sheet_key[GLR_MAX_MATERIALS * LUCENT_BAKE_KEY_SIZE];
} gl_tables;

/* Finds the scene's distinct materials and roughnesses (at most GLR_MAX_MATERIALS). */
lucent_status gl_tables_collect(gl_tables *t, const lucent_scene *scene);

/* Finds the scene's materials again (after they changed): the bakes of materials still there are
 * kept, the others freed; the transmittance texture is uploaded again by the next frame. */
lucent_status gl_tables_recollect(gl_tables *t, const lucent_scene *scene);

/* Copies baked into the bake of material m (every entry of m, whatever its roughness; a boundary part
 * baked at another roughness is baked again by the next frame); LUCENT_ERR_NOT_FOUND when m is not in
 * the table. */
lucent_status gl_tables_adopt(gl_tables *t, const lucent_material *m, const lucent_baked *baked);

/* Bakes what desc asks for for every material, the boundary at the entry's roughness (only what
 * changed is rebuilt). */
lucent_status gl_tables_bake(gl_tables *t, const lucent_bake_desc *desc, lucent_cache *cache);

/* Uploads the baked transmittance rows (after a bake with LUCENT_BAKE_TRANSMITTANCE) unless they are
 * on the GPU already. */
lucent_status gl_tables_upload_transmittance(gl_tables *t);

/* Uploads the boundary's tables (after a bake with LUCENT_BAKE_BOUNDARY) unless they are on the GPU
 * already. */
lucent_status gl_tables_upload_boundary(gl_tables *t);

/* Uploads the curved parts' tables (after a bake with LUCENT_BAKE_SPHERES) unless they are on the GPU
 * already. */
lucent_status gl_tables_upload_spheres(gl_tables *t);

/* Uploads the thin parts' sheet tables (after a bake with LUCENT_BAKE_SHEET) unless they are on the
 * GPU already. */
lucent_status gl_tables_upload_sheet(gl_tables *t);

/* The baked parts of object i's material. */
const lucent_baked *gl_tables_of(const gl_tables *t, int object);

void gl_tables_free(gl_tables *t);

#endif
