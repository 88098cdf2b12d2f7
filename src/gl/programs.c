/* The renderer's shader programs (programs.h). */
#include <string.h>

#include "gl/programs.h"

lucent_status gl_programs_get(gl_programs *p, const char *vert, const char *frag, const char *defines, GLuint *dest)
{
    char key[sizeof p->entry[0].key];
    snprintf(key, sizeof key, "%s %s %s", vert, frag, defines ? defines : "");
    for (int i = 0; i < p->count; i++)
        if (!strcmp(p->entry[i].key, key)) return *dest = p->entry[i].program, LUCENT_OK;
    if (p->count == GLR_MAX_PROGRAMS) return lucent_error(LUCENT_ERR_INTERNAL, "too many shader variants");
    GLuint program = 0;
    lucent_status s = gl_program_build(gl_embedded_source, NULL, vert, frag, defines, &program);
    if (s != LUCENT_OK) return s;
    snprintf(p->entry[p->count].key, sizeof key, "%s", key);
    p->entry[p->count++].program = program;
    *dest = program;
    return LUCENT_OK;
}

void gl_programs_free(gl_programs *p)
{
    for (int i = 0; i < p->count; i++) glDeleteProgram(p->entry[i].program);
    p->count = 0;
}
