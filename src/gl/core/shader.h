/* GLSL programs from the .glsl files under src/gl/shaders/, embedded at build time. A file may
 * `#include "other.glsl"` (each file once per shader); the prelude (#version, #defines) and every
 * include are bracketed by `#line L S` directives, S numbering the files, so that the driver's info
 * log can be mapped back: errors read "src/gl/shaders/blur.frag.glsl:12: error: ...". */
#ifndef LUCENT_SRC_GL_SHADER_H
#define LUCENT_SRC_GL_SHADER_H

#include <epoxy/gl.h>

#include "lucent/base.h"

enum { GLR_SHADER_MAX_FILES = 16 };

/* Where sources come from: returns the text of the file called name, or NULL. */
typedef const char *(*gl_source_fn)(const char *name, void *user);

/* The embedded files: name "blur.frag.glsl" is "src/gl/shaders/blur.frag.glsl" of the tree. */
const char *gl_embedded_source(const char *name, void *user);

/* One shader's text after the prelude and includes, with its file table. */
typedef struct gl_source {
    char *text;
    size_t len, cap;
    char files[GLR_SHADER_MAX_FILES][96]; /* source-string number -> file name */
    int file_count;
    bool failed; /* out of memory */
} gl_source;

/* Assembles file `name` (with defines, a text of "#define" lines, after #version). */
lucent_status gl_source_assemble(gl_source_fn fn, void *user, const char *name, const char *defines, gl_source *dest);
void gl_source_free(gl_source *s);

/* Rewrites the source-string:line references of a driver info log ("0:12(3): error",
 * "0(12) : error", "ERROR: 0:12: ") as "file:line". Free *dest with free(). */
lucent_status gl_source_map_log(const gl_source *src, const char *log, char **dest);

/* Compiles and links a vertex + fragment program. Errors (LUCENT_ERR_GL) carry the mapped log. */
lucent_status gl_program_build(gl_source_fn fn, void *user, const char *vert, const char *frag, const char *defines,
                               GLuint *dest);

#endif
