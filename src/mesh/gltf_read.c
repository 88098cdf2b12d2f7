/* glTF 2.0 reading (src/mesh/gltf.h), written for hostile input: the GLB container, buffers (the BIN
 * chunk, base64 data URIs, files in the document's folder), and accessors into triangle meshes. Every
 * index, offset, stride and count is checked against what the buffer holds before it is used, with
 * sizes in 64 bits; an error names the file and the JSON path ("a.glb: accessors[3].count: 900
 * elements of 12 bytes at stride 12 from byte 0 need 10800 bytes, bufferViews[1] has 96"). The
 * glTF 2.0 specification, sections 3.6 (buffers, views, accessors) and 4.4 (GLB). */
#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/gltf.h"
#include "mesh/internal.h"

enum { GLB_MAGIC = 0x46546C67, GLB_JSON = 0x4E4F534A, GLB_BIN = 0x004E4942 };
enum { GLTF_MAX_BUFFERS = 4096 };

typedef struct gltf_buffer {
    unsigned char *data; /* owned unless it points into the GLB */
    size_t size;
    bool loaded, owned;
} gltf_buffer;

struct gltf_doc {
    cJSON *json;
    char *name, *base_dir; /* base_dir NULL: external buffers refused */
    unsigned char *bytes;  /* the whole input (the GLB's BIN chunk lies inside) */
    const unsigned char *bin;
    size_t bin_size;
    bool has_bin;
    int buffer_count;
    gltf_buffer *buffers;
};

static uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* GLB (spec 4.4): a 12-byte header, a JSON chunk, then an optional BIN chunk. */
static lucent_status read_glb(gltf_doc *d, size_t size, char **json_text)
{
    const unsigned char *b = d->bytes;
    if (size < 20) return lucent_error(LUCENT_ERR_PARSE, "%s: GLB: %zu bytes, shorter than its header", d->name, size);
    if (le32(b + 4) != 2)
        return lucent_error(LUCENT_ERR_UNSUPPORTED, "%s: GLB version %u (only 2 is read)", d->name, le32(b + 4));
    if (le32(b + 8) > size)
        return lucent_error(LUCENT_ERR_PARSE, "%s: GLB: the header says %u bytes, the file has %zu", d->name,
                            le32(b + 8), size);
    size = le32(b + 8);
    size_t at = 12;
    for (int chunk = 0; at + 8 <= size; chunk++) {
        uint64_t len = le32(b + at), type = le32(b + at + 4);
        if (len > size - at - 8)
            return lucent_error(LUCENT_ERR_PARSE, "%s: GLB chunk %d at byte %zu: %llu bytes, past the end (%zu)",
                                d->name, chunk, at, (unsigned long long)len, size);
        if (chunk == 0 && type != GLB_JSON)
            return lucent_error(LUCENT_ERR_PARSE, "%s: GLB: the first chunk is not JSON", d->name);
        if (chunk == 0) {
            if (!(*json_text = malloc(len + 1)))
                return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", d->name);
            memcpy(*json_text, b + at + 8, len);
            (*json_text)[len] = '\0';
        } else if (chunk == 1 && type == GLB_BIN) {
            d->bin = b + at + 8, d->bin_size = len, d->has_bin = true;
        }
        at += 8 + len;
    }
    if (!*json_text) return lucent_error(LUCENT_ERR_PARSE, "%s: GLB without a JSON chunk", d->name);
    if (strlen(*json_text) == 0) return lucent_error(LUCENT_ERR_PARSE, "%s: GLB: empty JSON chunk", d->name);
    return LUCENT_OK;
}

static lucent_status parse(gltf_doc *d, size_t size)
{
    char *text = NULL;
    lucent_status s = LUCENT_OK;
    if (size >= 4 && le32(d->bytes) == GLB_MAGIC)
        s = read_glb(d, size, &text);
    else if (memchr(d->bytes, '\0', size))
        s = lucent_error(LUCENT_ERR_PARSE, "%s: neither glTF JSON text nor a GLB (\"glTF\" magic)", d->name);
    if (s == LUCENT_OK) s = lucent_json_parse_text(text ? text : (const char *)d->bytes, d->name, &d->json);
    free(text);
    lucent_json_node root = gltf_root(d);
    if (s == LUCENT_OK && !cJSON_IsObject(d->json))
        s = lucent_json_fail(&root, NULL, LUCENT_ERR_PARSE, "expected a glTF object {\"asset\": ...}");
    lucent_json_node asset, list;
    const char *version;
    if (s == LUCENT_OK) s = lucent_json_object(&root, "asset", true, &asset);
    if (s == LUCENT_OK) s = lucent_json_string(&asset, "version", &version);
    if (s == LUCENT_OK && strncmp(version, "2.", 2) != 0)
        s = lucent_json_fail(&asset, "version", LUCENT_ERR_UNSUPPORTED, "glTF %s (only 2.x is read)", version);
    if (s == LUCENT_OK) s = lucent_json_array(&root, "buffers", false, &list, &d->buffer_count);
    if (s == LUCENT_OK && d->buffer_count > GLTF_MAX_BUFFERS)
        s = lucent_json_fail(&list, NULL, LUCENT_ERR_UNSUPPORTED, "%d buffers (at most %d)", d->buffer_count,
                             GLTF_MAX_BUFFERS);
    if (s == LUCENT_OK && d->buffer_count > 0 && !(d->buffers = calloc((size_t)d->buffer_count, sizeof *d->buffers)))
        s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", d->name);
    return s;
}

static lucent_status open_bytes(unsigned char *bytes, size_t size, const char *name, const char *base_dir,
                                gltf_doc **dest)
{
    *dest = NULL;
    gltf_doc *d = calloc(1, sizeof *d);
    lucent_status s = d ? LUCENT_OK : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", name);
    if (s == LUCENT_OK) {
        d->bytes = bytes, bytes = NULL;
        d->name = strdup(name), d->base_dir = base_dir ? strdup(base_dir) : NULL;
        if (!d->name || (base_dir && !d->base_dir))
            s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", name);
    }
    if (s == LUCENT_OK) s = parse(d, size);
    free(bytes);
    if (s != LUCENT_OK) return gltf_close(d), s;
    *dest = d;
    return LUCENT_OK;
}

lucent_status gltf_open(const char *path, gltf_doc **dest)
{
    *dest = NULL;
    char *bytes;
    size_t size;
    lucent_status s = lucent_read_file(path, &bytes, &size);
    if (s != LUCENT_OK) return s;
    char *dir = strdup(path);
    if (!dir) return free(bytes), lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    char *slash = strrchr(dir, '/');
    if (slash)
        slash[slash == dir] = '\0'; /* "/x.gltf": "/" */
    else
        strcpy(dir, ".");
    s = open_bytes((unsigned char *)bytes, size, path, dir, dest);
    free(dir);
    return s;
}

lucent_status gltf_open_memory(const void *data, size_t size, const char *name, const char *base_dir, gltf_doc **dest)
{
    *dest = NULL;
    unsigned char *copy = malloc(size + 1);
    if (!copy) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", name);
    if (size) memcpy(copy, data, size);
    copy[size] = '\0';
    return open_bytes(copy, size, name, base_dir, dest);
}

void gltf_close(gltf_doc *d)
{
    if (!d) return;
    for (int i = 0; i < d->buffer_count; i++)
        if (d->buffers[i].owned) free(d->buffers[i].data);
    free(d->buffers);
    cJSON_Delete(d->json);
    free(d->bytes);
    free(d->name);
    free(d->base_dir);
    free(d);
}

lucent_json_node gltf_root(const gltf_doc *d) { return lucent_json_root(d->json, d->name, ""); }

const char *gltf_path(const gltf_doc *d) { return d->name; }

bool gltf_mode_is_surface(int mode) { return mode >= 4 && mode <= 6; }

/* ---- buffers ---- */

static int b64_value(unsigned char c)
{
    return c >= 'A' && c <= 'Z'   ? c - 'A'
           : c >= 'a' && c <= 'z' ? c - 'a' + 26
           : c >= '0' && c <= '9' ? c - '0' + 52
           : c == '+'             ? 62
           : c == '/'             ? 63
                                  : -1;
}

/* Decodes base64 text (padding optional) into a new block. */
static lucent_status decode_base64(const lucent_json_node *n, const char *text, unsigned char **dest, size_t *size)
{
    size_t len = strlen(text);
    while (len > 0 && text[len - 1] == '=') len--;
    unsigned char *out = malloc(len / 4 * 3 + 3);
    if (!out) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", n->file);
    size_t o = 0;
    uint32_t acc = 0;
    for (size_t i = 0; i < len; i++) {
        int v = b64_value((unsigned char)text[i]);
        if (v < 0) {
            free(out);
            return lucent_json_fail(n, NULL, LUCENT_ERR_PARSE, "not base64 at character %zu of the data", i);
        }
        acc = acc << 6 | (uint32_t)v;
        if (i % 4 == 3)
            out[o++] = (unsigned char)(acc >> 16), out[o++] = (unsigned char)(acc >> 8), out[o++] = (unsigned char)acc;
    }
    if (len % 4 == 1) {
        free(out);
        return lucent_json_fail(n, NULL, LUCENT_ERR_PARSE, "truncated base64 data");
    }
    if (len % 4 == 2) out[o++] = (unsigned char)(acc >> 4);
    if (len % 4 == 3) out[o++] = (unsigned char)(acc >> 10), out[o++] = (unsigned char)(acc >> 2);
    *dest = out, *size = o;
    return LUCENT_OK;
}

/* A relative URI's file name, %-decoded; refuses schemes, absolute paths and "..". */
static lucent_status uri_path(const lucent_json_node *n, const char *uri, const char *base_dir, char *dest, size_t size)
{
    char file[1024];
    size_t o = 0;
    for (const char *p = uri; *p; p++) {
        char c = *p;
        if (c == '%' && isxdigit((unsigned char)p[1]) && isxdigit((unsigned char)p[2])) {
            char hex[3] = {p[1], p[2], 0};
            c = (char)strtol(hex, NULL, 16);
            p += 2;
        }
        if (c == '\0' || o + 1 >= sizeof file)
            return lucent_json_fail(n, NULL, LUCENT_ERR_PARSE, "\"%.80s\": not a file name Lucent reads", uri);
        file[o++] = c;
    }
    file[o] = '\0';
    bool parent = !strcmp(file, "..") || !strncmp(file, "../", 3) || strstr(file, "/../") ||
                  (o >= 3 && !strcmp(file + o - 3, "/.."));
    if (strchr(file, ':') || file[0] == '/' || parent || o == 0)
        return lucent_json_fail(n, NULL, LUCENT_ERR_UNSUPPORTED,
                                "\"%.80s\": only files in the asset's folder or below are read (no scheme, absolute "
                                "path or \"..\")",
                                uri);
    if (!base_dir)
        return lucent_json_fail(n, NULL, LUCENT_ERR_UNSUPPORTED,
                                "\"%.80s\": an external file, but the asset was "
                                "given from memory",
                                uri);
    if ((size_t)snprintf(dest, size, "%s/%s", base_dir, file) >= size)
        return lucent_json_fail(n, NULL, LUCENT_ERR_PARSE, "\"%.80s\": path too long", uri);
    return LUCENT_OK;
}

static lucent_status load_uri(gltf_doc *d, const lucent_json_node *b, gltf_buffer *buf)
{
    lucent_json_node u;
    const char *uri;
    lucent_status s = lucent_json_member(b, "uri", true, &u);
    if (s == LUCENT_OK) s = lucent_json_string(b, "uri", &uri);
    if (s != LUCENT_OK) return s;
    if (!strncmp(uri, "data:", 5)) {
        const char *comma = strchr(uri, ',');
        if (!comma || comma - uri < 12 || strncmp(comma - 7, ";base64", 7) != 0)
            return lucent_json_fail(&u, NULL, LUCENT_ERR_UNSUPPORTED, "a data URI that is not base64");
        s = decode_base64(&u, comma + 1, &buf->data, &buf->size);
    } else {
        char path[4096];
        char *bytes;
        s = uri_path(&u, uri, d->base_dir, path, sizeof path);
        if (s == LUCENT_OK && (s = lucent_read_file(path, &bytes, &buf->size)) != LUCENT_OK)
            s = lucent_json_fail(&u, NULL, s, "%s", lucent_last_error());
        if (s == LUCENT_OK) buf->data = (unsigned char *)bytes;
    }
    if (s == LUCENT_OK) buf->owned = true;
    return s;
}

/* Buffer i, read on first use; its bytes hold at least byteLength. */
static lucent_status get_buffer(gltf_doc *d, const lucent_json_node *ref, int i, const gltf_buffer **dest)
{
    lucent_json_node root = gltf_root(d), list, b;
    int count;
    lucent_status s = lucent_json_array(&root, "buffers", false, &list, &count);
    if (s == LUCENT_OK && (i < 0 || i >= d->buffer_count))
        s = lucent_json_fail(ref, "buffer", LUCENT_ERR_PARSE, "%d: no such buffer (%d in the file)", i,
                             d->buffer_count);
    if (s == LUCENT_OK) s = lucent_json_element(&list, i, &b);
    gltf_buffer *buf = s == LUCENT_OK ? &d->buffers[i] : NULL;
    if (s != LUCENT_OK || buf->loaded) return *dest = buf, s;
    double length;
    if (s == LUCENT_OK) s = lucent_json_number(&b, "byteLength", &length);
    if (s == LUCENT_OK && !(length >= 1 && length <= 9.007199254740992e15 && length == (double)(uint64_t)length))
        s = lucent_json_fail(&b, "byteLength", LUCENT_ERR_PARSE, "must be a whole number >= 1, got %g", length);
    if (s == LUCENT_OK && !lucent_json_has(&b, "uri")) {
        if (i != 0 || !d->has_bin)
            s = lucent_json_fail(&b, NULL, LUCENT_ERR_PARSE, "no uri, and not the GLB's BIN chunk");
        else
            buf->data = (unsigned char *)d->bin, buf->size = d->bin_size;
    } else if (s == LUCENT_OK) {
        s = load_uri(d, &b, buf);
    }
    if (s == LUCENT_OK && (uint64_t)length > buf->size)
        s = lucent_json_fail(&b, "byteLength", LUCENT_ERR_PARSE, "%.0f bytes, the data holds %zu", length, buf->size);
    if (s == LUCENT_OK) buf->size = (size_t)length, buf->loaded = true;
    *dest = buf;
    return s;
}

/* ---- accessors ---- */

/* A whole number in [lo, hi] (absent: def; NAN: required). */
static lucent_status whole(const lucent_json_node *n, const char *key, double def, double lo, double hi, uint64_t *dest)
{
    double v;
    if (isnan(def) && !lucent_json_has(n, key)) return lucent_json_fail(n, key, LUCENT_ERR_PARSE, "missing field");
    lucent_status s = lucent_json_number_or(n, key, def, &v);
    if (s == LUCENT_OK && !(v >= lo && v <= hi && v == (double)(int64_t)v))
        s = lucent_json_fail(n, key, LUCENT_ERR_PARSE, "must be a whole number in [%.0f, %.0f], got %g", lo, hi, v);
    if (s == LUCENT_OK) *dest = (uint64_t)v;
    return s;
}

/* The elements of an accessor: where they lie and how they are laid out. */
typedef struct span {
    const unsigned char *at;
    uint64_t count, stride;
    int component, components;
} span;

static int type_components(const char *type)
{
    static const char *const names[] = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
    static const int n[] = {1, 2, 3, 4, 4, 9, 16};
    for (int i = 0; i < 7; i++)
        if (!strcmp(type, names[i])) return n[i];
    return 0;
}

static int component_size(int type)
{
    return type == 5120 || type == 5121 ? 1 : type == 5122 || type == 5123 ? 2 : type == 5125 || type == 5126 ? 4 : 0;
}

static lucent_status view_span(gltf_doc *d, const lucent_json_node *a, uint64_t view, uint64_t offset, span *sp)
{
    lucent_json_node views, v;
    int count;
    lucent_json_node root = gltf_root(d);
    lucent_status s = lucent_json_array(&root, "bufferViews", false, &views, &count);
    if (s == LUCENT_OK && view >= (uint64_t)count)
        s = lucent_json_fail(a, "bufferView", LUCENT_ERR_PARSE, "%llu: no such buffer view (%d in the file)",
                             (unsigned long long)view, count);
    if (s == LUCENT_OK) s = lucent_json_element(&views, (int)view, &v);
    uint64_t buffer, voff, vlen, stride, elem = (uint64_t)component_size(sp->component) * (uint64_t)sp->components;
    if (s == LUCENT_OK) s = whole(&v, "buffer", NAN, 0, GLTF_MAX_BUFFERS - 1, &buffer);
    if (s == LUCENT_OK) s = whole(&v, "byteOffset", 0, 0, 9.0e15, &voff);
    if (s == LUCENT_OK) s = whole(&v, "byteLength", NAN, 1, 9.0e15, &vlen);
    stride = elem; /* tightly packed unless said */
    if (s == LUCENT_OK && lucent_json_has(&v, "byteStride")) s = whole(&v, "byteStride", NAN, 4, 252, &stride);
    if (s == LUCENT_OK && stride < elem)
        s = lucent_json_fail(&v, "byteStride", LUCENT_ERR_PARSE, "%llu, less than an element's %llu bytes",
                             (unsigned long long)stride, (unsigned long long)elem);
    const gltf_buffer *buf = NULL;
    if (s == LUCENT_OK) s = get_buffer(d, &v, (int)buffer, &buf);
    if (s == LUCENT_OK && voff + vlen > buf->size)
        s = lucent_json_fail(&v, NULL, LUCENT_ERR_PARSE,
                             "bytes %llu to %llu, past the end of buffers[%llu] (%zu bytes)", (unsigned long long)voff,
                             (unsigned long long)(voff + vlen), (unsigned long long)buffer, buf->size);
    /* count elements, the last one ends at offset + (count - 1) stride + elem: within the view */
    if (s == LUCENT_OK && sp->count > 0 && (offset + elem > vlen || (sp->count - 1) > (vlen - offset - elem) / stride))
        s = lucent_json_fail(a, "count", LUCENT_ERR_PARSE,
                             "%llu elements of %llu bytes at stride %llu from byte %llu need more "
                             "than the %llu bytes of bufferViews[%llu]",
                             (unsigned long long)sp->count, (unsigned long long)elem, (unsigned long long)stride,
                             (unsigned long long)offset, (unsigned long long)vlen, (unsigned long long)view);
    if (s == LUCENT_OK) sp->at = buf->data + voff + offset, sp->stride = stride;
    return s;
}

/* Accessor i with the given component types and components; *a names it in messages. */
static lucent_status accessor(gltf_doc *d, const lucent_json_node *ref, const char *key, int want_components,
                              const int *types, int type_count, lucent_json_node *a, span *sp)
{
    lucent_json_node root = gltf_root(d), list;
    int count;
    uint64_t i;
    lucent_status s = whole(ref, key, NAN, 0, 2147483647.0, &i);
    if (s == LUCENT_OK) s = lucent_json_array(&root, "accessors", false, &list, &count);
    if (s == LUCENT_OK && i >= (uint64_t)count)
        s = lucent_json_fail(ref, key, LUCENT_ERR_PARSE, "%llu: no such accessor (%d in the file)",
                             (unsigned long long)i, count);
    if (s == LUCENT_OK) s = lucent_json_element(&list, (int)i, a);
    uint64_t type, n, offset, view;
    const char *kind;
    bool normalized = false;
    if (s == LUCENT_OK) s = whole(a, "componentType", NAN, 5120, 5126, &type);
    if (s == LUCENT_OK) s = whole(a, "count", NAN, 1, 4294967295.0, &n);
    if (s == LUCENT_OK) s = lucent_json_string(a, "type", &kind);
    if (s == LUCENT_OK) s = lucent_json_bool_or(a, "normalized", false, &normalized);
    if (s == LUCENT_OK) s = whole(a, "byteOffset", 0, 0, 9.0e15, &offset);
    bool type_ok = false;
    for (int t = 0; t < type_count; t++) type_ok |= (int)type == types[t];
    if (s == LUCENT_OK && (!type_ok || normalized))
        s = lucent_json_fail(a, "componentType", LUCENT_ERR_UNSUPPORTED, "%llu%s: not what %s takes here",
                             (unsigned long long)type, normalized ? " (normalized)" : "", key);
    if (s == LUCENT_OK && type_components(kind) != want_components)
        s = lucent_json_fail(a, "type", LUCENT_ERR_PARSE, "\"%s\": %s takes %s", kind, key,
                             want_components == 1 ? "SCALAR" : "VEC3");
    if (s == LUCENT_OK && lucent_json_has(a, "sparse"))
        s = lucent_json_fail(a, "sparse", LUCENT_ERR_UNSUPPORTED, "sparse accessors are not read");
    if (s == LUCENT_OK && offset % (uint64_t)component_size((int)type) != 0)
        s = lucent_json_fail(a, "byteOffset", LUCENT_ERR_PARSE, "%llu: not a multiple of the component size",
                             (unsigned long long)offset);
    *sp = (span){.count = n, .component = (int)type, .components = want_components};
    /* an accessor without a view is all zeros (spec 3.6.2.3): nothing a mesh can use, and its count
       would be bounded by nothing in the file */
    if (s == LUCENT_OK && !lucent_json_has(a, "bufferView"))
        s = lucent_json_fail(a, "bufferView", LUCENT_ERR_UNSUPPORTED, "missing: every element would be zero");
    if (s == LUCENT_OK) s = whole(a, "bufferView", NAN, 0, 2147483647.0, &view);
    if (s == LUCENT_OK) s = view_span(d, a, view, offset, sp);
    return s;
}

static uint32_t index_at(const span *sp, uint64_t k)
{
    const unsigned char *p = sp->at + k * sp->stride;
    return sp->component == 5121 ? p[0] : sp->component == 5123 ? (uint32_t)p[0] | (uint32_t)p[1] << 8 : le32(p);
}

static lucent_status read_positions(gltf_doc *d, const lucent_json_node *attrs, lucent_mesh *m)
{
    static const int floats[] = {5126};
    lucent_json_node a;
    span sp;
    lucent_status s = accessor(d, attrs, "POSITION", 3, floats, 1, &a, &sp);
    if (s != LUCENT_OK) return s;
    if (!(m->positions = malloc(3 * sp.count * sizeof *m->positions)))
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", d->name);
    m->vertex_count = sp.count;
    for (uint64_t v = 0; v < sp.count; v++)
        for (int k = 0; k < 3; k++) {
            float f;
            memcpy(&f, sp.at + v * sp.stride + 4 * k, 4); /* glTF is little-endian, as is every host here */
            if (!isfinite(f))
                return lucent_json_fail(&a, NULL, LUCENT_ERR_PARSE, "vertex %llu is not finite", (unsigned long long)v);
            m->positions[3 * v + k] = f;
        }
    return LUCENT_OK;
}

/* The indices, or 0 .. n - 1 without them; *count receives how many. */
static lucent_status read_indices(gltf_doc *d, const lucent_json_node *p, uint64_t vertices, uint32_t **dest,
                                  uint64_t *count)
{
    static const int uints[] = {5121, 5123, 5125};
    lucent_json_node a = *p;
    span sp = {.count = vertices};
    lucent_status s = lucent_json_has(p, "indices") ? accessor(d, p, "indices", 1, uints, 3, &a, &sp) : LUCENT_OK;
    bool given = lucent_json_has(p, "indices");
    if (s == LUCENT_OK && !(*dest = malloc(sp.count * sizeof **dest)))
        s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", d->name);
    for (uint64_t k = 0; s == LUCENT_OK && k < sp.count; k++) {
        (*dest)[k] = given ? index_at(&sp, k) : (uint32_t)k;
        if ((*dest)[k] >= vertices)
            s = lucent_json_fail(&a, NULL, LUCENT_ERR_PARSE, "index %llu is %u, past the %llu vertices",
                                 (unsigned long long)k, (*dest)[k], (unsigned long long)vertices);
    }
    *count = sp.count;
    return s;
}

/* Triangles from a list, a strip or a fan (spec 3.7.2.1); collapsed ones are dropped by the weld. */
static lucent_status triangles(const lucent_json_node *p, int mode, const uint32_t *idx, uint64_t n, lucent_mesh *m)
{
    uint64_t tris = mode == 4 ? n / 3 : n >= 3 ? n - 2 : 0;
    if (tris == 0)
        return lucent_json_fail(p, NULL, LUCENT_ERR_PARSE, "no triangles (%llu indices)", (unsigned long long)n);
    if (!(m->faces = malloc(3 * tris * sizeof *m->faces)))
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", p->file);
    for (uint64_t t = 0; t < tris; t++) {
        uint32_t *f = m->faces + 3 * t;
        if (mode == 4)
            f[0] = idx[3 * t], f[1] = idx[3 * t + 1], f[2] = idx[3 * t + 2];
        else if (mode == 5) /* strip: every other triangle reversed to keep the winding */
            f[0] = idx[t + (t & 1)], f[1] = idx[t + 1 - (t & 1)], f[2] = idx[t + 2];
        else
            f[0] = idx[0], f[1] = idx[t + 1], f[2] = idx[t + 2];
    }
    m->face_count = tris;
    return LUCENT_OK;
}

lucent_status gltf_read_primitive(gltf_doc *d, int mesh, int primitive, lucent_mesh **dest)
{
    *dest = NULL;
    lucent_json_node root = gltf_root(d), meshes, me, prims, p, attrs;
    int count, pcount;
    uint64_t mode;
    lucent_status s = lucent_json_array(&root, "meshes", true, &meshes, &count);
    if (s == LUCENT_OK && (mesh < 0 || mesh >= count))
        s = lucent_json_fail(&meshes, NULL, LUCENT_ERR_PARSE, "%d: no such mesh (%d in the file)", mesh, count);
    if (s == LUCENT_OK) s = lucent_json_element(&meshes, mesh, &me);
    if (s == LUCENT_OK) s = lucent_json_array(&me, "primitives", true, &prims, &pcount);
    if (s == LUCENT_OK && (primitive < 0 || primitive >= pcount))
        s = lucent_json_fail(&prims, NULL, LUCENT_ERR_PARSE, "%d: no such primitive (%d)", primitive, pcount);
    if (s == LUCENT_OK) s = lucent_json_element(&prims, primitive, &p);
    if (s == LUCENT_OK) s = whole(&p, "mode", 4, 0, 6, &mode);
    if (s == LUCENT_OK && !gltf_mode_is_surface((int)mode))
        s = lucent_json_fail(&p, "mode", LUCENT_ERR_UNSUPPORTED, "%llu: points or lines, not a surface",
                             (unsigned long long)mode);
    if (s == LUCENT_OK) s = lucent_json_object(&p, "attributes", true, &attrs);
    lucent_mesh *m = NULL;
    if (s == LUCENT_OK && (m = calloc(1, sizeof *m)) == NULL)
        s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", d->name);
    if (s == LUCENT_OK) s = read_positions(d, &attrs, m);
    uint32_t *idx = NULL;
    uint64_t n = 0;
    if (s == LUCENT_OK) s = read_indices(d, &p, m->vertex_count, &idx, &n);
    if (s == LUCENT_OK) s = triangles(&p, (int)mode, idx, n, m);
    free(idx);
    if (s == LUCENT_OK && !(m->normals = calloc(3 * m->vertex_count + 1, sizeof *m->normals)))
        s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", d->name);
    if (s == LUCENT_OK) s = lucent_mesh_weld(m);
    if (s == LUCENT_OK && m->face_count == 0)
        s = lucent_json_fail(&p, NULL, LUCENT_ERR_PARSE, "every triangle is degenerate");
    if (s != LUCENT_OK) return lucent_mesh_destroy(m), s;
    *dest = m;
    return LUCENT_OK;
}
