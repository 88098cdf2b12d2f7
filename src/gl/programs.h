/* The renderer's shader programs, compiled the first time a method asks for a variant and kept
 * until the renderer goes (or the auxiliary outputs are switched). */
#ifndef LUCENT_SRC_GL_PROGRAMS_H
#define LUCENT_SRC_GL_PROGRAMS_H

#include "gl/core/gpu.h"

enum { GLR_MAX_PROGRAMS = 32 };

typedef struct gl_programs {
    int count;
    struct {
        char key[256];
        GLuint program;
    } entry[GLR_MAX_PROGRAMS];
} gl_programs;

/* The program of the embedded vert + frag files with defines ("#define X 1\n" lines; may be NULL). */
lucent_status gl_programs_get(gl_programs *p, const char *vert, const char *frag, const char *defines, GLuint *dest);

/* Deletes every program (they are rebuilt on demand). */
void gl_programs_free(gl_programs *p);

#endif
