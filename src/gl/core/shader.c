/* GLSL programs: embedded sources, #include, and info logs mapped back to file and line. */
#include <ctype.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "base/embedded.h"
#include "base/strbuf.h"
#include "gl/core/shader.h"

enum { MAX_DEPTH = 8 };

const char *gl_embedded_source(const char *name, void *user)
{
    (void)user;
    char path[256];
    snprintf(path, sizeof path, "src/gl/shaders/%s", name);
    const lucent_embedded_file *f = lucent_embedded(path);
    return f ? (const char *)f->data : NULL;
}

/* ---- assembling ---- */

static void put(gl_source *s, const char *text, size_t n)
{
    if (s->failed) return;
    if (s->len + n + 1 > s->cap) {
        size_t cap = (s->cap ? s->cap * 2 : 4096) + n;
        char *t = realloc(s->text, cap);
        if (!t) {
            s->failed = true;
            return;
        }
        s->text = t, s->cap = cap;
    }
    memcpy(s->text + s->len, text, n);
    s->len += n;
    s->text[s->len] = '\0';
}

static void putf(gl_source *s, const char *fmt, ...) LUCENT_PRINTF(2, 3);
static void putf(gl_source *s, const char *fmt, ...)
{
    char buf[256];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    put(s, buf, (size_t)(n < (int)sizeof buf ? n : (int)sizeof buf - 1));
}

/* If line is `#include "name"`, copies name into dest and returns true. */
static bool include_name(const char *line, size_t len, char *dest, size_t size)
{
    const char *p = line, *end = line + len;
    while (p < end && isspace((unsigned char)*p)) p++;
    if (end - p < 8 || strncmp(p, "#include", 8) != 0) return false;
    p += 8;
    while (p < end && isspace((unsigned char)*p)) p++;
    const char *q = p < end && *p == '"' ? memchr(p + 1, '"', (size_t)(end - p - 1)) : NULL;
    if (!q || (size_t)(q - p - 1) >= size) return false;
    memcpy(dest, p + 1, (size_t)(q - p - 1));
    dest[q - p - 1] = '\0';
    return true;
}

static int file_index(const gl_source *s, const char *name)
{
    for (int i = 0; i < s->file_count; i++)
        if (!strcmp(s->files[i], name)) return i;
    return -1;
}

static lucent_status add_file(gl_source_fn fn, void *user, const char *name, gl_source *s, int depth, const char *from,
                              int from_line);

/* Copies text line by line, expanding includes. */
static lucent_status add_lines(gl_source_fn fn, void *user, const char *text, int index, gl_source *s, int depth)
{
    int line = 1;
    for (const char *p = text; *p; line++) {
        const char *nl = strchr(p, '\n');
        size_t len = nl ? (size_t)(nl - p) : strlen(p);
        char inc[96];
        if (include_name(p, len, inc, sizeof inc)) {
            if (file_index(s, inc) < 0) {
                lucent_status st = add_file(fn, user, inc, s, depth + 1, s->files[index], line);
                if (st != LUCENT_OK) return st;
                putf(s, "#line %d %d\n", line + 1, index);
            } else {
                put(s, "\n", 1); /* included before: keep the line count */
            }
        } else {
            put(s, p, len);
            put(s, "\n", 1);
        }
        p += len + (nl ? 1 : 0);
    }
    return LUCENT_OK;
}

static lucent_status add_file(gl_source_fn fn, void *user, const char *name, gl_source *s, int depth, const char *from,
                              int from_line)
{
    const char *text = fn(name, user);
    if (!text && from) return lucent_error(LUCENT_ERR_GL, "%s:%d: cannot include \"%s\"", from, from_line, name);
    if (!text) return lucent_error(LUCENT_ERR_GL, "shader \"%s\": no such file", name);
    if (depth > MAX_DEPTH || s->file_count == GLR_SHADER_MAX_FILES)
        return lucent_error(LUCENT_ERR_GL, "%s:%d: includes nest too deep", from ? from : name, from_line);
    int index = s->file_count++;
    snprintf(s->files[index], sizeof s->files[index], "%s", name);
    putf(s, "#line 1 %d\n", index);
    return add_lines(fn, user, text, index, s, depth);
}

lucent_status gl_source_assemble(gl_source_fn fn, void *user, const char *name, const char *defines, gl_source *dest)
{
    memset(dest, 0, sizeof *dest);
    put(dest, "#version 450 core\n", 18);
    if (defines) put(dest, defines, strlen(defines));
    lucent_status s = add_file(fn, user, name, dest, 0, NULL, 0);
    if (s == LUCENT_OK && dest->failed) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    if (s != LUCENT_OK) gl_source_free(dest);
    return s;
}

void gl_source_free(gl_source *s)
{
    free(s->text);
    memset(s, 0, sizeof *s);
}

/* ---- info logs ---- */

/* Reads "S:L" or "S(L)" at p; returns the length consumed (0: no match). */
static size_t parse_location(const char *p, int *file, int *line)
{
    char *end;
    long f = strtol(p, &end, 10);
    if (end == p || f < 0) return 0;
    const char *q = end;
    if (*q != ':' && *q != '(') return 0;
    long l = strtol(q + 1, &end, 10);
    if (end == q + 1 || l < 0) return 0;
    if (*q == '(' && *end++ != ')') return 0;
    *file = (int)f, *line = (int)l;
    return (size_t)(end - p);
}

static void map_line(const gl_source *src, const char *p, size_t len, lucent_strbuf *b)
{
    size_t skip = !strncmp(p, "ERROR: ", 7) ? 7 : !strncmp(p, "WARNING: ", 9) ? 9 : 0;
    int file, line;
    size_t n = skip < len ? parse_location(p + skip, &file, &line) : 0;
    if (n && file < src->file_count) {
        lucent_strbuf_printf(b, "src/gl/shaders/%s:%d%.*s", src->files[file], line, (int)(len - skip - n),
                             p + skip + n);
        return;
    }
    lucent_strbuf_printf(b, "%.*s", (int)len, p);
}

lucent_status gl_source_map_log(const gl_source *src, const char *log, char **dest)
{
    lucent_strbuf b = {0};
    for (const char *p = log; *p;) {
        const char *nl = strchr(p, '\n');
        size_t len = nl ? (size_t)(nl - p) : strlen(p);
        if (len) {
            map_line(src, p, len, &b);
            lucent_strbuf_printf(&b, "\n");
        }
        p += len + (nl ? 1 : 0);
    }
    lucent_strbuf_printf(&b, "%s", "");
    return lucent_strbuf_finish(&b, dest);
}

/* ---- compiling and linking ---- */

static char *info_log(GLuint object, bool program)
{
    GLint n = 0;
    if (program)
        glGetProgramiv(object, GL_INFO_LOG_LENGTH, &n);
    else
        glGetShaderiv(object, GL_INFO_LOG_LENGTH, &n);
    char *log = calloc((size_t)(n > 0 ? n : 0) + 1, 1);
    if (log && n > 0 && program)
        glGetProgramInfoLog(object, n, NULL, log);
    else if (log && n > 0)
        glGetShaderInfoLog(object, n, NULL, log);
    return log;
}

/* Trims trailing newlines so that the message ends cleanly. */
static void trim(char *s)
{
    for (size_t n = strlen(s); n && (s[n - 1] == '\n' || s[n - 1] == ' '); n--) s[n - 1] = '\0';
}

static lucent_status compile(gl_source_fn fn, void *user, GLenum stage, const char *name, const char *defines,
                             GLuint *dest)
{
    gl_source src;
    lucent_status s = gl_source_assemble(fn, user, name, defines, &src);
    if (s != LUCENT_OK) return s;
    GLuint sh = glCreateShader(stage);
    if (!sh) {
        gl_source_free(&src);
        return lucent_error(LUCENT_ERR_GL, "%s: cannot create a shader (no current GL context?)", name);
    }
    const GLchar *text = src.text;
    glShaderSource(sh, 1, &text, NULL);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char *log = info_log(sh, false), *mapped = NULL;
        if (log) gl_source_map_log(&src, log, &mapped);
        if (mapped) trim(mapped);
        s = lucent_error(LUCENT_ERR_GL, "%s does not compile:\n%s", name, mapped ? mapped : "(no log)");
        free(log), free(mapped);
        glDeleteShader(sh);
        sh = 0;
    }
    gl_source_free(&src);
    *dest = sh;
    return s;
}

static lucent_status link(GLuint vs, GLuint fs, const char *vert, const char *frag, GLuint *dest)
{
    GLuint p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    glLinkProgram(p);
    glDetachShader(p, vs);
    glDetachShader(p, fs);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (ok) return *dest = p, LUCENT_OK;
    char *log = info_log(p, true);
    if (log) trim(log);
    lucent_status s = lucent_error(LUCENT_ERR_GL, "%s + %s do not link:\n%s", vert, frag, log ? log : "(no log)");
    free(log);
    glDeleteProgram(p);
    return s;
}

lucent_status gl_program_build(gl_source_fn fn, void *user, const char *vert, const char *frag, const char *defines,
                               GLuint *dest)
{
    GLuint vs = 0, fs = 0;
    *dest = 0;
    lucent_status s = compile(fn, user, GL_VERTEX_SHADER, vert, defines, &vs);
    if (s == LUCENT_OK) s = compile(fn, user, GL_FRAGMENT_SHADER, frag, defines, &fs);
    if (s == LUCENT_OK) s = link(vs, fs, vert, frag, dest);
    if (vs) glDeleteShader(vs);
    if (fs) glDeleteShader(fs);
    return s;
}
