/* Lucent's PLY reader (include/lucent/mesh.h, "PLY reading"): ASCII and binary little/big endian,
 * plain or gzip, streaming through mesh/reader.h, for hostile input. The format is Greg Turk's (PLY,
 * Stanford 1994): a text header of elements and their properties, then the elements' rows in order. */
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/mesh.h"
#include "mesh/internal.h"
#include "mesh/reader.h"

#define MAX_HEADER ((uint64_t)1 << 20)
#define MAX_ELEMENTS 64
#define MAX_PROPERTIES 1024
#define MAX_NAME 128
#define MAX_POLYGON 65536 /* vertices in one face */

typedef enum ptype { T_NONE = 0, T_I8, T_U8, T_I16, T_U16, T_I32, T_U32, T_F32, T_F64 } ptype;

static const int k_size[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};

typedef struct prop {
    char name[MAX_NAME];
    ptype type;       /* scalar type, or the list's item type */
    ptype count_type; /* T_NONE for a scalar */
} prop;

typedef struct element {
    char name[MAX_NAME];
    uint64_t count;
    prop *props;
    int prop_count;
    int fixed_size; /* bytes per row when no property is a list, else 0 */
} element;

enum { FMT_ASCII, FMT_LE, FMT_BE };

struct lucent_ply {
    lucent_reader r;
    int format;
    element elements[MAX_ELEMENTS];
    int element_count;
    int vertex_el, face_el, face_prop; /* -1 when absent */
    int *scalars;                      /* the vertex element's scalar properties (indices into props) */
    int scalar_count;
    int read_done;
};

static ptype type_parse(const char *s)
{
    static const struct {
        const char *name;
        ptype t;
    } k[] = {{"char", T_I8},   {"int8", T_I8},     {"uchar", T_U8},   {"uint8", T_U8},
             {"short", T_I16}, {"int16", T_I16},   {"ushort", T_U16}, {"uint16", T_U16},
             {"int", T_I32},   {"int32", T_I32},   {"uint", T_U32},   {"uint32", T_U32},
             {"float", T_F32}, {"float32", T_F32}, {"double", T_F64}, {"float64", T_F64}};
    for (size_t i = 0; i < sizeof k / sizeof k[0]; i++)
        if (strcmp(s, k[i].name) == 0) return k[i].t;
    return T_NONE;
}

static int is_integer_type(ptype t) { return t >= T_I8 && t <= T_U32; }

/* Splits line into at most max words (in place); returns the count, or max + 1 when there are more. */
static int split(char *line, char **words, int max)
{
    int n = 0;
    for (char *p = line;;) {
        while (*p == ' ' || *p == '\t') p++;
        if (!*p) return n;
        if (n == max) return max + 1;
        words[n++] = p;
        while (*p && *p != ' ' && *p != '\t') p++;
        if (*p) *p++ = '\0';
    }
}

void lucent_ply_close(lucent_ply *ply)
{
    if (!ply) return;
    lucent_reader_close(&ply->r);
    for (int i = 0; i < ply->element_count; i++) free(ply->elements[i].props);
    free(ply->scalars);
    free(ply);
}

static lucent_status header_error(lucent_ply *ply, const char *what)
{
    return lucent_error(LUCENT_ERR_PARSE, "%s: line %llu: %s", ply->r.name, (unsigned long long)ply->r.line, what);
}

static lucent_status read_header(lucent_ply *ply)
{
    lucent_reader *r = &ply->r;
    char *line;
    lucent_status s = lucent_reader_line(r, &line, NULL);
    if (s != LUCENT_OK) return s;
    if (!line || strcmp(line, "ply") != 0)
        return lucent_error(LUCENT_ERR_PARSE, "%s: not a PLY file (the first line is not \"ply\")", r->name);
    int have_format = 0;
    ply->vertex_el = ply->face_el = ply->face_prop = -1;
    for (;;) {
        if (lucent_reader_offset(r) > MAX_HEADER)
            return lucent_error(LUCENT_ERR_PARSE, "%s: the header is longer than %llu bytes (no end_header?)", r->name,
                                (unsigned long long)MAX_HEADER);
        if ((s = lucent_reader_line(r, &line, NULL)) != LUCENT_OK) return s;
        if (!line)
            return lucent_error(LUCENT_ERR_PARSE, "%s: the header ends without end_header (line %llu)", r->name,
                                (unsigned long long)r->line);
        char *w[8];
        int n = split(line, w, 6);
        if (n == 0) continue;
        if (strcmp(w[0], "comment") == 0 || strcmp(w[0], "obj_info") == 0) continue;
        if (strcmp(w[0], "end_header") == 0) break;
        if (strcmp(w[0], "format") == 0) {
            if (n != 3 || have_format) return header_error(ply, "expected one \"format <ascii|binary_*> 1.0\"");
            if (strcmp(w[1], "ascii") == 0)
                ply->format = FMT_ASCII;
            else if (strcmp(w[1], "binary_little_endian") == 0)
                ply->format = FMT_LE;
            else if (strcmp(w[1], "binary_big_endian") == 0)
                ply->format = FMT_BE;
            else
                return header_error(ply, "unknown format (ascii, binary_little_endian or binary_big_endian)");
            if (strcmp(w[2], "1.0") != 0 && strcmp(w[2], "1") != 0) return header_error(ply, "unknown version");
            have_format = 1;
        } else if (strcmp(w[0], "element") == 0) {
            if (n != 3) return header_error(ply, "expected \"element <name> <count>\"");
            if (ply->element_count == MAX_ELEMENTS) return header_error(ply, "more than 64 elements");
            const char *p = w[2];
            int64_t count;
            if (!lucent_parse_int64(&p, w[2] + strlen(w[2]), &count) || count < 0)
                return header_error(ply, "the element count is not a non-negative integer");
            if (strlen(w[1]) >= MAX_NAME) return header_error(ply, "element name too long");
            element *e = &ply->elements[ply->element_count++];
            snprintf(e->name, sizeof e->name, "%s", w[1]);
            e->count = (uint64_t)count;
            if (strcmp(e->name, "vertex") == 0 && ply->vertex_el < 0) ply->vertex_el = ply->element_count - 1;
            if (strcmp(e->name, "face") == 0 && ply->face_el < 0) ply->face_el = ply->element_count - 1;
        } else if (strcmp(w[0], "property") == 0) {
            if (ply->element_count == 0) return header_error(ply, "a property before any element");
            element *e = &ply->elements[ply->element_count - 1];
            if (e->prop_count == MAX_PROPERTIES) return header_error(ply, "more than 1024 properties in an element");
            prop pr = {0};
            const char *name;
            if (n == 5 && strcmp(w[1], "list") == 0) {
                pr.count_type = type_parse(w[2]), pr.type = type_parse(w[3]), name = w[4];
                if (!is_integer_type(pr.count_type) || pr.type == T_NONE)
                    return header_error(ply, "a list needs an integer count type and a known item type");
            } else if (n == 3) {
                pr.type = type_parse(w[1]), name = w[2];
                if (pr.type == T_NONE) return header_error(ply, "unknown property type");
            } else {
                return header_error(ply, "expected \"property <type> <name>\" or \"property list <t> <t> <name>\"");
            }
            if (strlen(name) >= MAX_NAME) return header_error(ply, "property name too long");
            for (int j = 0; j < e->prop_count; j++)
                if (strcmp(e->props[j].name, name) == 0) {
                    char what[MAX_NAME + 96];
                    snprintf(what, sizeof what, "element %s declares the property %s twice", e->name, name);
                    return header_error(ply, what);
                }
            snprintf(pr.name, sizeof pr.name, "%s", name);
            if (e->prop_count % 16 == 0) {
                prop *grown = realloc(e->props, (size_t)(e->prop_count + 16) * sizeof *grown);
                if (!grown) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", r->name);
                e->props = grown;
            }
            e->props[e->prop_count++] = pr;
        } else {
            return header_error(ply, "unknown header keyword");
        }
    }
    if (!have_format) return lucent_error(LUCENT_ERR_PARSE, "%s: the header has no format line", r->name);
    uint64_t rows = 0, limit = lucent_mesh_read_limit();
    for (int i = 0; i < ply->element_count; i++) {
        const element *e = &ply->elements[i];
        rows = rows > UINT64_MAX - e->count ? UINT64_MAX : rows + e->count;
        if (rows > limit)
            return lucent_error(LUCENT_ERR_PARSE,
                                "%s: the header declares %llu %s entries (%llu rows in all so far): above the read "
                                "limit of %llu elements (the environment variable LUCENT_MESH_MAX_ELEMENTS raises it)",
                                r->name, (unsigned long long)e->count, e->name, (unsigned long long)rows,
                                (unsigned long long)limit);
    }
    for (int i = 0; i < ply->element_count; i++) {
        element *e = &ply->elements[i];
        e->fixed_size = 0;
        int fixed = 1;
        for (int j = 0; j < e->prop_count; j++) {
            if (e->props[j].count_type != T_NONE) fixed = 0;
            e->fixed_size += k_size[e->props[j].type];
        }
        if (!fixed) e->fixed_size = 0;
    }
    if (ply->face_el >= 0) {
        element *e = &ply->elements[ply->face_el];
        for (int j = 0; j < e->prop_count && ply->face_prop < 0; j++)
            if (e->props[j].count_type != T_NONE &&
                (strcmp(e->props[j].name, "vertex_indices") == 0 || strcmp(e->props[j].name, "vertex_index") == 0))
                ply->face_prop = j;
    }
    if (ply->vertex_el >= 0) {
        element *e = &ply->elements[ply->vertex_el];
        ply->scalars = malloc((size_t)(e->prop_count + 1) * sizeof *ply->scalars);
        if (!ply->scalars) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", r->name);
        for (int j = 0; j < e->prop_count; j++)
            if (e->props[j].count_type == T_NONE) ply->scalars[ply->scalar_count++] = j;
    }
    return LUCENT_OK;
}

static lucent_status open_common(lucent_ply *ply, lucent_status s, lucent_ply **dest)
{
    if (s == LUCENT_OK) s = read_header(ply);
    if (s != LUCENT_OK) {
        lucent_ply_close(ply);
        return s;
    }
    *dest = ply;
    return LUCENT_OK;
}

lucent_status lucent_ply_open(const char *path, lucent_ply **dest)
{
    *dest = NULL;
    lucent_ply *ply = calloc(1, sizeof *ply);
    if (!ply) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    lucent_status s = lucent_reader_open(&ply->r, path);
    if (s != LUCENT_OK) {
        free(ply);
        return s;
    }
    return open_common(ply, s, dest);
}

lucent_status lucent_ply_open_memory(const void *data, size_t size, const char *name, lucent_ply **dest)
{
    *dest = NULL;
    lucent_ply *ply = calloc(1, sizeof *ply);
    if (!ply) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", name);
    lucent_status s = lucent_reader_open_memory(&ply->r, data, size, name);
    if (s != LUCENT_OK) {
        free(ply);
        return s;
    }
    return open_common(ply, s, dest);
}

size_t lucent_ply_vertex_count(const lucent_ply *ply)
{
    return ply->vertex_el >= 0 ? (size_t)ply->elements[ply->vertex_el].count : 0;
}

size_t lucent_ply_face_count(const lucent_ply *ply)
{
    return ply->face_el >= 0 ? (size_t)ply->elements[ply->face_el].count : 0;
}

int lucent_ply_property_count(const lucent_ply *ply) { return ply->scalar_count; }

const char *lucent_ply_property_name(const lucent_ply *ply, int i)
{
    if (i < 0 || i >= ply->scalar_count) return NULL;
    return ply->elements[ply->vertex_el].props[ply->scalars[i]].name;
}

int lucent_ply_property_index(const lucent_ply *ply, const char *name)
{
    for (int i = 0; i < ply->scalar_count; i++)
        if (strcmp(lucent_ply_property_name(ply, i), name) == 0) return i;
    return -1;
}

bool lucent_ply_property_is_list(const lucent_ply *ply, const char *name)
{
    const element *e = ply->vertex_el >= 0 ? &ply->elements[ply->vertex_el] : NULL;
    for (int j = 0; e && j < e->prop_count; j++)
        if (e->props[j].count_type != T_NONE && strcmp(e->props[j].name, name) == 0) return true;
    return false;
}

double lucent_ply_property_integer_max(const lucent_ply *ply, int i)
{
    if (i < 0 || i >= ply->scalar_count) return 0;
    static const double k_max[] = {[T_I8] = 127,           [T_U8] = 255,           [T_I16] = 32767, [T_U16] = 65535,
                                   [T_I32] = 2147483647.0, [T_U32] = 4294967295.0, [T_F32] = 0,     [T_F64] = 0};
    return k_max[ply->elements[ply->vertex_el].props[ply->scalars[i]].type];
}

void lucent_ply_data_free(lucent_ply_data *data)
{
    if (!data) return;
    free(data->values);
    free(data->values32);
    free(data->triangles);
    memset(data, 0, sizeof *data);
}

/* ---- The body ----------------------------------------------------------------- */

/* One binary value at p. */
static double decode(const unsigned char *p, ptype t, int big)
{
    unsigned char b[8];
    int n = k_size[t];
    for (int i = 0; i < n; i++) b[i] = big ? p[n - 1 - i] : p[i];
    switch (t) {
    case T_I8: return (int8_t)b[0];
    case T_U8: return b[0];
    case T_I16: return (int16_t)(b[0] | b[1] << 8);
    case T_U16: return (uint16_t)(b[0] | b[1] << 8);
    case T_I32: return (int32_t)((uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24);
    case T_U32: return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
    case T_F32: {
        float f;
        memcpy(&f, b, 4);
        return f;
    }
    case T_F64: {
        double d;
        memcpy(&d, b, 8);
        return d;
    }
    default: return 0;
    }
}

typedef struct body {
    lucent_ply *ply;
    const lucent_ply_read_desc *desc;
    int *columns;    /* per output column: the vertex property index, -1 when missing */
    double *row;     /* one vertex row of scalar values, per property index */
    double *checked; /* the row's requested values, for desc->check */
    lucent_ply_data *d;
    size_t vertex_cap, tri_cap;
    int growable;   /* gzip: the counts are only bounds, grow with the data */
    uint32_t *poly; /* one face's indices */
    size_t poly_cap;
} body;

/* Room for a face of n vertices in b->poly (n <= MAX_POLYGON, checked before). */
static int poly_room(body *b, size_t n)
{
    if (n <= b->poly_cap) return 1;
    size_t cap = b->poly_cap ? b->poly_cap : 16;
    while (cap < n) cap *= 2;
    uint32_t *g = realloc(b->poly, cap * sizeof *g);
    if (!g) return 0;
    b->poly = g, b->poly_cap = cap;
    return 1;
}

static lucent_status oom(body *b)
{
    return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", b->ply->r.name);
}

static lucent_status store_vertex(body *b, uint64_t i)
{
    lucent_ply_data *d = b->d;
    int k = b->desc->count;
    if (b->desc->check) {
        for (int c = 0; c < k; c++) b->checked[c] = b->columns[c] >= 0 ? b->row[b->columns[c]] : NAN;
        lucent_status s = b->desc->check(b->desc->user, i, b->checked);
        if (s != LUCENT_OK) return s;
    }
    if (i >= b->vertex_cap) {
        size_t cap = b->vertex_cap ? 2 * b->vertex_cap : 1024;
        size_t total = (size_t)b->ply->elements[b->ply->vertex_el].count;
        if (cap > total) cap = total;
        size_t esz = b->desc->single ? sizeof(float) : sizeof(double);
        void *grown = realloc(b->desc->single ? (void *)d->values32 : (void *)d->values, cap * (size_t)k * esz + 1);
        if (!grown) return oom(b);
        mesh_advise_large(grown, cap * (size_t)k * esz);
        if (b->desc->single)
            d->values32 = grown;
        else
            d->values = grown;
        b->vertex_cap = cap;
    }
    for (int c = 0; c < k; c++) {
        double v = b->columns[c] >= 0 ? b->row[b->columns[c]] : NAN;
        if (b->desc->single)
            d->values32[(size_t)i * (size_t)k + (size_t)c] = (float)v;
        else
            d->values[(size_t)i * (size_t)k + (size_t)c] = v;
    }
    d->vertex_count = (size_t)i + 1;
    return LUCENT_OK;
}

/* Where we are, for messages: "line 12" (ASCII) or "byte 345" (binary). */
static void where(const body *b, char *dest, size_t size)
{
    if (b->ply->format == FMT_ASCII)
        snprintf(dest, size, "line %llu", (unsigned long long)b->ply->r.line);
    else
        snprintf(dest, size, "byte %llu", (unsigned long long)lucent_reader_offset(&b->ply->r));
}

static lucent_status store_face(body *b, uint64_t f, uint32_t n)
{
    lucent_ply_data *d = b->d;
    uint64_t vcount = b->ply->elements[b->ply->vertex_el].count;
    char at[48];
    if (n < 3) {
        where(b, at, sizeof at);
        return lucent_error(LUCENT_ERR_PARSE, "%s: %s: face %llu has %u vertices (a face needs 3 or more)",
                            b->ply->r.name, at, (unsigned long long)f, n);
    }
    for (uint32_t j = 0; j < n; j++)
        if (b->poly[j] >= vcount) {
            where(b, at, sizeof at);
            return lucent_error(LUCENT_ERR_PARSE,
                                "%s: %s: face %llu: vertex index %u out of range (the file has %llu vertices)",
                                b->ply->r.name, at, (unsigned long long)f, b->poly[j], (unsigned long long)vcount);
        }
    if (d->triangle_count + n - 2 > lucent_mesh_read_limit()) {
        where(b, at, sizeof at);
        return lucent_error(LUCENT_ERR_PARSE,
                            "%s: %s: face %llu: more than %llu triangles: above the read limit (the environment "
                            "variable LUCENT_MESH_MAX_ELEMENTS raises it)",
                            b->ply->r.name, at, (unsigned long long)f, (unsigned long long)lucent_mesh_read_limit());
    }
    if (d->triangle_count + n - 2 > b->tri_cap) {
        size_t cap = b->tri_cap ? 2 * b->tri_cap : 1024;
        while (cap < d->triangle_count + n - 2) cap *= 2;
        uint32_t *grown = realloc(d->triangles, cap * 3 * sizeof *grown);
        if (!grown) return oom(b);
        mesh_advise_large(grown, cap * 3 * sizeof *grown);
        d->triangles = grown, b->tri_cap = cap;
    }
    for (uint32_t j = 1; j + 1 < n; j++) {
        uint32_t *t = d->triangles + 3 * d->triangle_count++;
        t[0] = b->poly[0], t[1] = b->poly[j], t[2] = b->poly[j + 1];
    }
    d->polygon_count++;
    return LUCENT_OK;
}

static lucent_status list_count_check(body *b, double count, uint64_t row, const element *e, int is_face)
{
    char at[48];
    if (count < 0 || count != floor(count) || (is_face && count > MAX_POLYGON) || count > 1e9) {
        where(b, at, sizeof at);
        return lucent_error(LUCENT_ERR_PARSE, "%s: %s: %s %llu: bad list length %.17g%s", b->ply->r.name, at, e->name,
                            (unsigned long long)row, count, is_face ? " (at most 65536 vertices per face)" : "");
    }
    return LUCENT_OK;
}

static lucent_status ascii_element(body *b, int ei)
{
    lucent_ply *ply = b->ply;
    const element *e = &ply->elements[ei];
    int is_vertex = ei == ply->vertex_el, is_face = ei == ply->face_el && b->desc->faces != LUCENT_PLY_FACES_SKIP;
    if (e->prop_count == 0) return LUCENT_OK; /* rows of nothing */
    for (uint64_t i = 0; i < e->count; i++) {
        char *line;
        size_t len;
        do {
            lucent_status s = lucent_reader_line(&ply->r, &line, &len);
            if (s != LUCENT_OK) return s;
            if (!line)
                return lucent_error(LUCENT_ERR_PARSE, "%s: truncated: the file ends at line %llu, in %s %llu of %llu",
                                    ply->r.name, (unsigned long long)ply->r.line, e->name, (unsigned long long)i,
                                    (unsigned long long)e->count);
            while (len > 0 && (line[len - 1] == ' ' || line[len - 1] == '\t')) len--;
        } while (len == 0 || strspn(line, " \t") == len);
        const char *p = line, *end = line + len;
        for (int j = 0; j < e->prop_count; j++) {
            const prop *pr = &e->props[j];
            if (pr->count_type == T_NONE) {
                double v;
                if (!lucent_parse_double(&p, end, &v))
                    return lucent_error(LUCENT_ERR_PARSE, "%s: line %llu: %s %llu: property %s: %s", ply->r.name,
                                        (unsigned long long)ply->r.line, e->name, (unsigned long long)i, pr->name,
                                        p >= end ? "missing value" : "not a number");
                /* A float property holds a float: rounded as a binary file would store it. */
                if (is_vertex) b->row[j] = pr->type == T_F32 ? (double)(float)v : v;
                continue;
            }
            int64_t n;
            if (!lucent_parse_int64(&p, end, &n))
                return lucent_error(LUCENT_ERR_PARSE, "%s: line %llu: %s %llu: list %s: the length is %s", ply->r.name,
                                    (unsigned long long)ply->r.line, e->name, (unsigned long long)i, pr->name,
                                    p >= end ? "missing" : "not an integer");
            int this_face = is_face && j == ply->face_prop;
            lucent_status s = list_count_check(b, (double)n, i, e, this_face);
            if (s != LUCENT_OK) return s;
            if (this_face && !poly_room(b, (size_t)n)) return oom(b);
            for (int64_t k = 0; k < n; k++) {
                if (this_face) {
                    int64_t idx;
                    if (!lucent_parse_int64(&p, end, &idx) || idx < 0 || idx > UINT32_MAX)
                        return lucent_error(LUCENT_ERR_PARSE, "%s: line %llu: face %llu: vertex index %lld is %s",
                                            ply->r.name, (unsigned long long)ply->r.line, (unsigned long long)i,
                                            (long long)k, p >= end ? "missing" : "not a valid index");
                    b->poly[k] = (uint32_t)idx;
                } else {
                    double v;
                    if (!lucent_parse_double(&p, end, &v))
                        return lucent_error(LUCENT_ERR_PARSE, "%s: line %llu: %s %llu: list %s: %s", ply->r.name,
                                            (unsigned long long)ply->r.line, e->name, (unsigned long long)i, pr->name,
                                            p >= end ? "fewer items than its length" : "an item is not a number");
                }
            }
            if (this_face && (s = store_face(b, i, (uint32_t)n)) != LUCENT_OK) return s;
        }
        while (p < end && (*p == ' ' || *p == '\t')) p++;
        if (p < end)
            return lucent_error(LUCENT_ERR_PARSE, "%s: line %llu: %s %llu: more values than the header declares",
                                ply->r.name, (unsigned long long)ply->r.line, e->name, (unsigned long long)i);
        if (is_vertex) {
            lucent_status s = store_vertex(b, i);
            if (s != LUCENT_OK) return s;
        }
    }
    return LUCENT_OK;
}

static lucent_status binary_element(body *b, int ei)
{
    lucent_ply *ply = b->ply;
    lucent_reader *r = &ply->r;
    const element *e = &ply->elements[ei];
    int big = ply->format == FMT_BE;
    int is_vertex = ei == ply->vertex_el, is_face = ei == ply->face_el && b->desc->faces != LUCENT_PLY_FACES_SKIP;
    char what[192];
    for (uint64_t i = 0; i < e->count; i++) {
        if (e->fixed_size > 0 && !is_vertex) {
            /* A row we do not use: skip it whole. */
            size_t left = (size_t)e->fixed_size;
            while (left > 0) {
                lucent_status s = lucent_reader_fill(r, left);
                if (s != LUCENT_OK) return s;
                size_t have = r->len - r->pos < left ? r->len - r->pos : left;
                if (have == 0) {
                    snprintf(what, sizeof what, "%s %llu of %llu", e->name, (unsigned long long)i,
                             (unsigned long long)e->count);
                    return lucent_reader_bytes(r, NULL, left, what);
                }
                r->pos += have, left -= have;
            }
            continue;
        }
        for (int j = 0; j < e->prop_count; j++) {
            const prop *pr = &e->props[j];
            unsigned char raw[8];
            if (pr->count_type == T_NONE) {
                if (r->len - r->pos >= 8) {
                    memcpy(raw, r->buf + r->pos, (size_t)k_size[pr->type]);
                    r->pos += (size_t)k_size[pr->type];
                } else {
                    snprintf(what, sizeof what, "%s %llu of %llu", e->name, (unsigned long long)i,
                             (unsigned long long)e->count);
                    lucent_status s = lucent_reader_bytes(r, raw, (size_t)k_size[pr->type], what);
                    if (s != LUCENT_OK) return s;
                }
                if (is_vertex) b->row[j] = decode(raw, pr->type, big);
                continue;
            }
            snprintf(what, sizeof what, "%s %llu of %llu", e->name, (unsigned long long)i,
                     (unsigned long long)e->count);
            lucent_status s = lucent_reader_bytes(r, raw, (size_t)k_size[pr->count_type], what);
            if (s != LUCENT_OK) return s;
            double n = decode(raw, pr->count_type, big);
            int this_face = is_face && j == ply->face_prop;
            if ((s = list_count_check(b, n, i, e, this_face)) != LUCENT_OK) return s;
            if (this_face && !poly_room(b, (size_t)n)) return oom(b);
            size_t isz = (size_t)k_size[pr->type];
            for (uint64_t k = 0; k < (uint64_t)n; k++) {
                if ((s = lucent_reader_bytes(r, raw, isz, what)) != LUCENT_OK) return s;
                if (this_face) {
                    double idx = decode(raw, pr->type, big);
                    if (idx < 0 || idx > UINT32_MAX) {
                        char at[48];
                        where(b, at, sizeof at);
                        return lucent_error(LUCENT_ERR_PARSE, "%s: %s: face %llu: vertex index %.0f out of range",
                                            r->name, at, (unsigned long long)i, idx);
                    }
                    b->poly[k] = (uint32_t)idx;
                }
            }
            if (this_face && (s = store_face(b, i, (uint32_t)n)) != LUCENT_OK) return s;
        }
        if (is_vertex) {
            lucent_status s = store_vertex(b, i);
            if (s != LUCENT_OK) return s;
        }
    }
    return LUCENT_OK;
}

/* After the last element's rows: nothing but blank lines (ASCII) or nothing at all (binary), so that rows
 * beyond the header's counts are an error rather than silently left out. */
static lucent_status check_end(lucent_ply *ply)
{
    lucent_reader *r = &ply->r;
    const element *last = &ply->elements[ply->element_count - 1];
    if (ply->format != FMT_ASCII) {
        lucent_status s = lucent_reader_fill(r, 1);
        if (s != LUCENT_OK || r->len == r->pos) return s;
        return lucent_error(LUCENT_ERR_PARSE,
                            "%s: byte %llu: data after the last element's rows (the header declares %llu %s): more "
                            "rows than it says, or a false count",
                            r->name, (unsigned long long)lucent_reader_offset(r), (unsigned long long)last->count,
                            last->name);
    }
    for (;;) {
        char *line;
        size_t len;
        lucent_status s = lucent_reader_line(r, &line, &len);
        if (s != LUCENT_OK || !line) return s;
        if (strspn(line, " \t") < len)
            return lucent_error(LUCENT_ERR_PARSE,
                                "%s: line %llu: more rows than the header declares (%llu %s, the last element)",
                                r->name, (unsigned long long)r->line, (unsigned long long)last->count, last->name);
    }
}

/* The fewest bytes a row of e can take (ASCII: a digit and a separator per value). */
static uint64_t min_row_bytes(const element *e, int ascii)
{
    uint64_t n = 0;
    for (int j = 0; j < e->prop_count; j++)
        n += ascii ? 2 : (uint64_t)(e->props[j].count_type ? k_size[e->props[j].count_type] : k_size[e->props[j].type]);
    return n ? n : 1;
}

lucent_status lucent_ply_read(lucent_ply *ply, const lucent_ply_read_desc *desc, lucent_ply_data *dest)
{
    memset(dest, 0, sizeof *dest);
    lucent_reader *r = &ply->r;
    if (ply->read_done) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: a PLY body is read once", r->name);
    ply->read_done = 1;
    if (desc->count < 0 || (desc->count > 0 && !desc->names))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: bad PLY read request", r->name);
    if (ply->vertex_el < 0) return lucent_error(LUCENT_ERR_PARSE, "%s: no vertex element", r->name);
    const element *ve = &ply->elements[ply->vertex_el];
    if (ve->count > UINT32_MAX)
        return lucent_error(LUCENT_ERR_UNSUPPORTED, "%s: %llu vertices: at most 4294967295 are supported", r->name,
                            (unsigned long long)ve->count);
    if (desc->faces == LUCENT_PLY_FACES_REQUIRED && ply->face_el < 0)
        return lucent_error(LUCENT_ERR_PARSE,
                            "%s: no face element: this PLY holds points only (%llu vertices), a mesh needs faces",
                            r->name, (unsigned long long)ve->count);
    if (desc->faces != LUCENT_PLY_FACES_SKIP && ply->face_el >= 0) {
        if (ply->face_prop < 0)
            return lucent_error(LUCENT_ERR_PARSE, "%s: the face element has no vertex_indices list", r->name);
        if (!is_integer_type(ply->elements[ply->face_el].props[ply->face_prop].type))
            return lucent_error(LUCENT_ERR_PARSE, "%s: the face indices are not of an integer type", r->name);
    }
    /* Every count against what the rest of the file can hold, before anything is allocated. */
    uint64_t need = 0, bound = lucent_reader_bound(r);
    for (int i = 0; i < ply->element_count; i++) {
        const element *e = &ply->elements[i];
        uint64_t row = min_row_bytes(e, ply->format == FMT_ASCII);
        if (e->count > bound / row || need + e->count * row > bound)
            return lucent_error(LUCENT_ERR_PARSE,
                                "%s: the header declares %llu %s entries (at least %llu bytes each) but at most %llu "
                                "bytes follow the header%s",
                                r->name, (unsigned long long)e->count, e->name, (unsigned long long)row,
                                (unsigned long long)bound,
                                r->gz ? " (gzip data may inflate to at most 100 times its size: a larger claim is "
                                        "refused as a decompression bomb; gunzip the file to read it whole)"
                                      : ": truncated or a false count");
        need += e->count * row;
    }
    body b = {.ply = ply, .desc = desc, .d = dest};
    b.columns = malloc(((size_t)desc->count + 1) * sizeof *b.columns);
    b.row = calloc((size_t)ve->prop_count + 1, sizeof *b.row);
    b.checked = calloc((size_t)desc->count + 1, sizeof *b.checked);
    lucent_status s = LUCENT_OK;
    if (!b.columns || !b.row || !b.checked || !poly_room(&b, 16)) s = oom(&b);
    for (int c = 0; s == LUCENT_OK && c < desc->count; c++) {
        int k = lucent_ply_property_index(ply, desc->names[c]);
        b.columns[c] = k >= 0 ? ply->scalars[k] : -1;
        if (k < 0 && !desc->allow_missing)
            s = lucent_error(LUCENT_ERR_PARSE, "%s: the vertex element has no property %s", r->name, desc->names[c]);
    }
    dest->count = desc->count;
    /* Plain files: the counts were checked against the file's size, so room for them is honest; gzip:
     * a count is only bounded, so arrays start small and grow with what is read. */
    if (s == LUCENT_OK && !r->gz && ve->count > 0) {
        b.vertex_cap = 0;
        size_t esz = desc->single ? sizeof(float) : sizeof(double);
        void *v = mesh_alloc_large((size_t)ve->count * (size_t)desc->count * esz + 1);
        if (!v) s = oom(&b);
        if (desc->single)
            dest->values32 = v;
        else
            dest->values = v;
        b.vertex_cap = (size_t)ve->count;
    }
    for (int i = 0; s == LUCENT_OK && i < ply->element_count; i++)
        s = ply->format == FMT_ASCII ? ascii_element(&b, i) : binary_element(&b, i);
    if (s == LUCENT_OK && dest->vertex_count == 0 && ve->count > 0) s = LUCENT_ERR_INTERNAL;
    if (s == LUCENT_OK) s = check_end(ply);
    if (s == LUCENT_OK) s = lucent_reader_finish(r); /* .ply.gz: the stream whole, its CRC checked */
    free(b.columns);
    free(b.row);
    free(b.checked);
    free(b.poly);
    if (s != LUCENT_OK) lucent_ply_data_free(dest);
    return s;
}
