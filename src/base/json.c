/* JSON helpers: reading with errors that name the file and the JSON path. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/file_internal.h"
#include "base/json.h"

static void location(const char *text, const char *at, int *line, int *column)
{
    *line = 1;
    *column = 1;
    for (const char *p = text; p < at && *p; p++) {
        if (*p == '\n')
            (*line)++, *column = 1;
        else
            (*column)++;
    }
}

/* Finds the name of the last field opened before `at` ("key": ...), for messages about
 * broken values; copies it into dest (empty when there is none). */
static void field_before(const char *text, const char *at, char *dest, size_t size)
{
    dest[0] = '\0';
    const char *p = at;
    while (p > text && p[-1] != ':') p--;
    if (p == text) return;
    const char *q = p - 1; /* at the ':' */
    while (q > text && (q[-1] == ' ' || q[-1] == '\t' || q[-1] == '\n' || q[-1] == '\r')) q--;
    if (q == text || q[-1] != '"') return;
    const char *close = --q, *open = close;
    while (open > text && open[-1] != '"') open--;
    if (open == text) return;
    size_t n = (size_t)(close - open) < size - 1 ? (size_t)(close - open) : size - 1;
    memcpy(dest, open, n);
    dest[n] = '\0';
}

lucent_status lucent_json_parse_text(const char *text, const char *name, cJSON **dest)
{
    const char *end = NULL;
    *dest = cJSON_ParseWithOpts(text, &end, 1);
    if (*dest) return LUCENT_OK;
    if (!end) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory parsing JSON", name);
    int line, column;
    location(text, end, &line, &column);
    char field[64], in_field[80] = "";
    field_before(text, end, field, sizeof field);
    if (field[0]) snprintf(in_field, sizeof in_field, " (in field \"%.60s\")", field);
    if (!*end) return lucent_error(LUCENT_ERR_PARSE, "%s: line %d: invalid JSON: unexpected end of file", name, line);
    char near[16];
    size_t n = 0;
    while (n < sizeof near - 1 && end[n] && end[n] != '\n' && end[n] != '\r') near[n] = end[n], n++;
    near[n] = '\0';
    const char *why = (strncmp(end, "NaN", 3) == 0 || strncmp(end, "Inf", 3) == 0 || strncmp(end, "-Inf", 4) == 0 ||
                       strncmp(end, "nan", 3) == 0)
                          ? "not a number JSON allows"
                          : "invalid JSON";
    return lucent_error(LUCENT_ERR_PARSE, "%s: line %d, column %d%s: %s near '%s'", name, line, column, in_field, why,
                        near);
}

lucent_status lucent_json_parse_file(const char *file, cJSON **dest)
{
    char *text;
    size_t size;
    *dest = NULL;
    lucent_status s = lucent_read_file(file, &text, &size);
    if (s != LUCENT_OK) return s;
    if (strlen(text) != size)
        s = lucent_error(LUCENT_ERR_PARSE, "%s: invalid JSON: contains a NUL byte", file);
    else
        s = lucent_json_parse_text(text, file, dest);
    free(text);
    return s;
}

lucent_json_node lucent_json_root(const cJSON *json, const char *file, const char *path)
{
    lucent_json_node n = {.json = json, .file = file ? file : "<json>"};
    snprintf(n.path, sizeof n.path, "%s", path ? path : "");
    return n;
}

static bool valid_utf8(const unsigned char *s);

/* A key as messages show it: as it is when it is UTF-8 without control characters, else with every byte of
 * 0x80 and above (when it is not UTF-8) and every control character written as \xNN, so that a message never
 * carries invalid text or terminal escapes ("rend\xC0\x80er: unknown field"). */
void lucent_json_printable(const char *key, char *dest, size_t size)
{
    bool utf8 = valid_utf8((const unsigned char *)key);
    size_t at = 0;
    for (const unsigned char *k = (const unsigned char *)key; *k && at + 5 < size; k++)
        if (*k < 0x20 || *k == 0x7f || (*k >= 0x80 && !utf8))
            at += (size_t)snprintf(dest + at, size - at, "\\x%02X", *k);
        else
            dest[at++] = (char)*k;
    dest[at] = '\0';
}

static void child_path(const lucent_json_node *n, const char *key, char *dest, size_t size)
{
    int len;
    char shown[256];
    if (key) lucent_json_printable(key, shown, sizeof shown);
    if (!key)
        len = snprintf(dest, size, "%s", n->path);
    else if (n->path[0])
        len = snprintf(dest, size, "%s.%s", n->path, shown);
    else
        len = snprintf(dest, size, "%s", shown);
    if (len >= (int)size) memcpy(dest + size - 4, "...", 4); /* absurdly deep: shortened */
}

lucent_status lucent_json_fail(const lucent_json_node *n, const char *key, lucent_status status, const char *fmt, ...)
{
    char where[sizeof n->path + 64], what[1024];
    child_path(n, key, where, sizeof where);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    if (where[0]) return lucent_error(status, "%s: %s: %s", n->file, where, what);
    return lucent_error(status, "%s: %s", n->file, what);
}

static const char *type_name(const cJSON *j)
{
    if (!j) return "nothing";
    if (cJSON_IsNumber(j)) return "a number";
    if (cJSON_IsString(j)) return "a string";
    if (cJSON_IsBool(j)) return "a boolean";
    if (cJSON_IsNull(j)) return "null";
    if (cJSON_IsArray(j)) return "an array";
    if (cJSON_IsObject(j)) return "an object";
    return "an unknown value";
}

bool lucent_json_has(const lucent_json_node *n, const char *key)
{
    return cJSON_IsObject(n->json) && cJSON_GetObjectItemCaseSensitive(n->json, key) != NULL;
}

lucent_status lucent_json_member(const lucent_json_node *n, const char *key, bool required, lucent_json_node *dest)
{
    if (!cJSON_IsObject(n->json))
        return lucent_json_fail(n, NULL, LUCENT_ERR_PARSE, "expected an object, got %s", type_name(n->json));
    *dest = (lucent_json_node){.json = cJSON_GetObjectItemCaseSensitive(n->json, key), .file = n->file};
    child_path(n, key, dest->path, sizeof dest->path);
    if (!dest->json && required) return lucent_json_fail(n, key, LUCENT_ERR_PARSE, "missing field");
    return LUCENT_OK;
}

static lucent_status member_of_type(const lucent_json_node *n, const char *key, bool required,
                                    cJSON_bool (*is)(const cJSON *), const char *want, lucent_json_node *dest)
{
    lucent_status s = lucent_json_member(n, key, required, dest);
    if (s != LUCENT_OK || !dest->json || is(dest->json)) return s;
    return lucent_json_fail(dest, NULL, LUCENT_ERR_PARSE, "expected %s, got %s", want, type_name(dest->json));
}

lucent_status lucent_json_object(const lucent_json_node *n, const char *key, bool required, lucent_json_node *dest)
{
    return member_of_type(n, key, required, cJSON_IsObject, "an object", dest);
}

lucent_status lucent_json_array(const lucent_json_node *n, const char *key, bool required, lucent_json_node *dest,
                                int *count)
{
    lucent_status s = member_of_type(n, key, required, cJSON_IsArray, "an array", dest);
    *count = (s == LUCENT_OK && dest->json) ? cJSON_GetArraySize(dest->json) : 0;
    return s;
}

lucent_status lucent_json_element(const lucent_json_node *n, int index, lucent_json_node *dest)
{
    *dest = (lucent_json_node){.json = cJSON_GetArrayItem(n->json, index), .file = n->file};
    if (snprintf(dest->path, sizeof dest->path, "%s[%d]", n->path, index) >= (int)sizeof dest->path)
        memcpy(dest->path + sizeof dest->path - 4, "...", 4);
    if (!cJSON_IsArray(n->json) || !dest->json)
        return lucent_json_fail(n, NULL, LUCENT_ERR_PARSE, "has no element %d", index);
    return LUCENT_OK;
}

static lucent_status finite_number(const lucent_json_node *n, double *dest)
{
    if (!cJSON_IsNumber(n->json))
        return lucent_json_fail(n, NULL, LUCENT_ERR_PARSE, "expected a number, got %s", type_name(n->json));
    double v = n->json->valuedouble;
    if (!isfinite(v)) return lucent_json_fail(n, NULL, LUCENT_ERR_PARSE, "expected a finite number");
    *dest = v;
    return LUCENT_OK;
}

lucent_status lucent_json_number(const lucent_json_node *n, const char *key, double *dest)
{
    lucent_json_node m;
    lucent_status s = lucent_json_member(n, key, true, &m);
    return s != LUCENT_OK ? s : finite_number(&m, dest);
}

lucent_status lucent_json_number_or(const lucent_json_node *n, const char *key, double def, double *dest)
{
    lucent_json_node m;
    lucent_status s = lucent_json_member(n, key, false, &m);
    if (s != LUCENT_OK) return s;
    if (!m.json) {
        *dest = def;
        return LUCENT_OK;
    }
    return finite_number(&m, dest);
}

lucent_status lucent_json_numbers(const lucent_json_node *n, const char *key, int count, bool allow_scalar,
                                  double *dest)
{
    lucent_json_node m;
    lucent_status s = lucent_json_member(n, key, true, &m);
    if (s != LUCENT_OK) return s;
    if (allow_scalar && cJSON_IsNumber(m.json)) {
        double v = 0; /* set by finite_number; initialised for GCC -O3 -Wmaybe-uninitialized */
        if ((s = finite_number(&m, &v)) != LUCENT_OK) return s;
        for (int i = 0; i < count; i++) dest[i] = v;
        return LUCENT_OK;
    }
    if (!cJSON_IsArray(m.json) || cJSON_GetArraySize(m.json) != count)
        return lucent_json_fail(&m, NULL, LUCENT_ERR_PARSE, "expected %d numbers%s, got %s", count,
                                allow_scalar ? " or one number" : "",
                                cJSON_IsArray(m.json) ? "an array of another length" : type_name(m.json));
    for (int i = 0; i < count; i++) {
        lucent_json_node e;
        if ((s = lucent_json_element(&m, i, &e)) != LUCENT_OK) return s;
        if ((s = finite_number(&e, &dest[i])) != LUCENT_OK) return s;
    }
    return LUCENT_OK;
}

/* True when s is UTF-8 as RFC 3629 defines it: no overlong forms, no surrogates, nothing past U+10FFFF. JSON
 * text is UTF-8 (RFC 8259 section 8.1); a string that is not would make every JSON output invalid. */
static bool valid_utf8(const unsigned char *s)
{
    while (*s) {
        unsigned c = *s++;
        if (c < 0x80) continue;
        int n = c >= 0xf0 ? 3 : c >= 0xe0 ? 2 : c >= 0xc2 ? 1 : -1;
        if (n < 0 || c > 0xf4) return false;
        unsigned cp = c & (0x3fu >> n);
        for (int i = 0; i < n; i++, s++) {
            if ((*s & 0xc0) != 0x80) return false;
            cp = cp << 6 | (*s & 0x3fu);
        }
        if ((n == 2 && cp < 0x800) || (n == 3 && cp < 0x10000) || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff))
            return false;
    }
    return true;
}

lucent_status lucent_json_string_or(const lucent_json_node *n, const char *key, const char *def, const char **dest)
{
    lucent_json_node m;
    lucent_status s = member_of_type(n, key, def == NULL, cJSON_IsString, "a string", &m);
    if (s != LUCENT_OK) return s;
    if (m.json && !valid_utf8((const unsigned char *)m.json->valuestring))
        return lucent_json_fail(&m, NULL, LUCENT_ERR_PARSE, "not valid UTF-8 text");
    *dest = m.json ? m.json->valuestring : def;
    return LUCENT_OK;
}

lucent_status lucent_json_string(const lucent_json_node *n, const char *key, const char **dest)
{
    return lucent_json_string_or(n, key, NULL, dest);
}

lucent_status lucent_json_bool_or(const lucent_json_node *n, const char *key, bool def, bool *dest)
{
    lucent_json_node m;
    lucent_status s = member_of_type(n, key, false, cJSON_IsBool, "true or false", &m);
    if (s != LUCENT_OK) return s;
    *dest = m.json ? cJSON_IsTrue(m.json) : def;
    return LUCENT_OK;
}

static bool in_list(const char *name, const char *const *list)
{
    for (; *list; list++)
        if (strcmp(name, *list) == 0) return true;
    return false;
}

lucent_status lucent_json_check_keys(const lucent_json_node *n, const char *const *known)
{
    if (!cJSON_IsObject(n->json))
        return lucent_json_fail(n, NULL, LUCENT_ERR_PARSE, "expected an object, got %s", type_name(n->json));
    for (const cJSON *c = n->json->child; c; c = c->next) {
        if (!in_list(c->string, known)) {
            char list[512] = "";
            for (const char *const *k = known; *k; k++)
                snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k == known ? "" : ", ", *k);
            return lucent_json_fail(n, c->string, LUCENT_ERR_PARSE, "unknown field (known: %s)", list);
        }
        for (const cJSON *d = c->next; d; d = d->next)
            if (strcmp(c->string, d->string) == 0)
                return lucent_json_fail(n, c->string, LUCENT_ERR_PARSE, "field given twice");
    }
    return LUCENT_OK;
}

static lucent_status write_json(const char *path, const cJSON *json, bool direct)
{
    char *text = cJSON_Print(json);
    if (!text) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory printing JSON", path);
    size_t len = strlen(text);
    char *with_newline = realloc(text, len + 2);
    if (!with_newline) {
        free(text);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory printing JSON", path);
    }
    with_newline[len] = '\n';
    lucent_status s =
        direct ? base_write_file_direct(path, with_newline, len + 1) : lucent_write_file(path, with_newline, len + 1);
    free(with_newline);
    return s;
}

lucent_status lucent_json_write_file(const char *path, const cJSON *json) { return write_json(path, json, false); }

lucent_status lucent_json_write_file_direct(const char *path, const cJSON *json)
{
    return write_json(path, json, true);
}

/* cJSON prints numbers with 15 significant digits, which does not give every double back; this
 * writes the shortest of %.15g, %.16g, %.17g that does (non-finite values as null). */
cJSON *lucent_json_number_item(double value)
{
    char text[32];
    if (!isfinite(value)) return cJSON_CreateNull();
    for (int digits = 15; digits <= 17; digits++) {
        snprintf(text, sizeof text, "%.*g", digits, value);
        if (strtod(text, NULL) == value) break;
    }
    return cJSON_CreateRaw(text);
}

cJSON *lucent_json_add_number(cJSON *object, const char *key, double value)
{
    cJSON *n = lucent_json_number_item(value);
    if (n && !cJSON_AddItemToObject(object, key, n)) {
        cJSON_Delete(n);
        return NULL;
    }
    return n;
}

cJSON *lucent_json_add_numbers(cJSON *object, const char *key, const double *values, int count)
{
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; a && i < count; i++) {
        cJSON *n = lucent_json_number_item(values[i]);
        if (!n || !cJSON_AddItemToArray(a, n)) {
            cJSON_Delete(n);
            cJSON_Delete(a);
            a = NULL;
        }
    }
    if (a && !cJSON_AddItemToObject(object, key, a)) {
        cJSON_Delete(a);
        return NULL;
    }
    return a;
}
