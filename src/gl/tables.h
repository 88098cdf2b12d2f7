/* The scene's distinct materials, what the bake room made of each (lucent/bake.h: profile, taps,
 * transmittance, sigma0), and the GPU table built from them: the transmittance T(s), a row per
 * material (a float texture, linear in s). */
#ifndef LUCENT_SRC_GL_TABLES_H
#define LUCENT_SRC_GL_TABLES_H

#include "gl/core/gpu.h"
#include "lucent/bake.h"
#include "lucent/scene.h"

enum { GLR_MAX_MATERIALS = 8 }; /* distinct materials in one scene (kernel rows, transmittance rows) */

typedef struct gl_tables {
    int count;
    lucent_material material[GLR_MAX_MATERIALS];
    lucent_baked baked[GLR_MAX_MATERIALS];
    int *object_material; /* per scene object: its index into material */
    GLuint transmit_tex;  /* RGB32F, LUCENT_BAKE_TRANSMIT_SIZE x count */
    char transmit_key[GLR_MAX_MATERIALS * LUCENT_BAKE_KEY_SIZE];
} gl_tables;

/* Finds the scene's distinct materials (at most GLR_MAX_MATERIALS). */
lucent_status gl_tables_collect(gl_tables *t, const lucent_scene *scene);

/* Finds the scene's materials again (after they changed): the bakes of materials still there are
 * kept, the others freed; the transmittance texture is uploaded again by the next frame. */
lucent_status gl_tables_recollect(gl_tables *t, const lucent_scene *scene);

/* Copies baked into the bake of material m; LUCENT_ERR_NOT_FOUND when m is not in the table. */
lucent_status gl_tables_adopt(gl_tables *t, const lucent_material *m, const lucent_baked *baked);

/* Bakes what desc asks for for every material (only what changed is rebuilt). */
lucent_status gl_tables_bake(gl_tables *t, const lucent_bake_desc *desc, lucent_cache *cache);

/* Uploads the baked transmittance rows (after a bake with LUCENT_BAKE_TRANSMITTANCE) unless they are
 * on the GPU already. */
lucent_status gl_tables_upload_transmittance(gl_tables *t);

/* The baked parts of object i's material. */
const lucent_baked *gl_tables_of(const gl_tables *t, int object);

void gl_tables_free(gl_tables *t);

#endif
