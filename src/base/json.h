/* JSON helpers over cJSON whose errors carry the file and the JSON path:
 *   "scene.json: scene.lights[1].direction: expected 3 numbers".
 * Internal header: cJSON types stay out of include/lucent/. */
#ifndef LUCENT_SRC_BASE_JSON_H
#define LUCENT_SRC_BASE_JSON_H

#include <cjson/cJSON.h>

#include "lucent/base.h"

/* A JSON value together with where it came from (file, path). Cheap to copy; no allocation. */
typedef struct lucent_json_node {
    const cJSON *json; /* NULL when the member is absent */
    const char *file;  /* not owned: must outlive the node */
    char path[240];    /* "materials[3].sigma_a" */
} lucent_json_node;

/* Parses a file; errors name the file and the line and column of the first problem. */
lucent_status lucent_json_parse_file(const char *file, cJSON **dest);

/* Parses text; `name` stands for the file in error messages. */
lucent_status lucent_json_parse_text(const char *text, const char *name, cJSON **dest);

/* Returns a node for a document's root; `path` names it in messages ("" for none). */
lucent_json_node lucent_json_root(const cJSON *json, const char *file, const char *path);

/* text for a message: as it is when it is UTF-8 without control characters, else with every control character
 * and (text that is not UTF-8) every byte from 0x80 written as \xNN; cut to fit size. */
void lucent_json_printable(const char *text, char *dest, size_t size);

/* Sets an error at n's path (or at n's path + "." + key when key is non-NULL):
 * "<file>: <path>: <message>". Returns status. */
lucent_status lucent_json_fail(const lucent_json_node *n, const char *key, lucent_status status, const char *fmt, ...)
    LUCENT_PRINTF(4, 5);

/* True when n is an object that has member key. */
bool lucent_json_has(const lucent_json_node *n, const char *key);

/* Fills dest with member key of object n (dest->json is NULL when absent and not required). */
lucent_status lucent_json_member(const lucent_json_node *n, const char *key, bool required, lucent_json_node *dest);

/* Fills dest with member key, which must be an object (absent is an error when required). */
lucent_status lucent_json_object(const lucent_json_node *n, const char *key, bool required, lucent_json_node *dest);

/* Fills dest with member key, which must be an array; *count receives its length (0 if absent). */
lucent_status lucent_json_array(const lucent_json_node *n, const char *key, bool required, lucent_json_node *dest,
                                int *count);

/* Fills dest with element index of array n. */
lucent_status lucent_json_element(const lucent_json_node *n, int index, lucent_json_node *dest);

/* Reads a required finite number. */
lucent_status lucent_json_number(const lucent_json_node *n, const char *key, double *dest);

/* Reads an optional finite number; *dest = def when absent. */
lucent_status lucent_json_number_or(const lucent_json_node *n, const char *key, double def, double *dest);

/* Reads exactly `count` finite numbers (an array), or, when allow_scalar, one number repeated. */
lucent_status lucent_json_numbers(const lucent_json_node *n, const char *key, int count, bool allow_scalar,
                                  double *dest);

/* Reads a required string (pointer into the document). */
lucent_status lucent_json_string(const lucent_json_node *n, const char *key, const char **dest);

/* Reads an optional string; *dest = def when absent. */
lucent_status lucent_json_string_or(const lucent_json_node *n, const char *key, const char *def, const char **dest);

/* Reads an optional boolean; *dest = def when absent. */
lucent_status lucent_json_bool_or(const lucent_json_node *n, const char *key, bool def, bool *dest);

/* Fails on any member of object n whose name is not in the NULL-terminated list `known`
 * (catches typos such as "sigma_a " or "eta_"). */
lucent_status lucent_json_check_keys(const lucent_json_node *n, const char *const *known);

/* Writes json to path atomically, pretty-printed, with a final newline. */
lucent_status lucent_json_write_file(const char *path, const cJSON *json);
/* The same outside the command's output set (lucent/output.h), renamed at once: for the disk cache. */
lucent_status lucent_json_write_file_direct(const char *path, const cJSON *json);

/* A number item that reads back exactly (cJSON's own keeps 15 digits; non-finite: null). */
cJSON *lucent_json_number_item(double value);

/* Adds a number that reads back exactly to object under key; returns it (NULL when out of memory). */
cJSON *lucent_json_add_number(cJSON *object, const char *key, double value);

/* Adds an array of count numbers (each read back exactly) to object under key; returns it (NULL
 * when out of memory). */
cJSON *lucent_json_add_numbers(cJSON *object, const char *key, const double *values, int count);

#endif /* LUCENT_SRC_BASE_JSON_H */
