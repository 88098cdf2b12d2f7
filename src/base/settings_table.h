/* Declaring a settings group (lucent/settings.h): one line per setting, beside the code that reads
 * it. Each macro checks at compile time that the member has the type the setting says:
 *
 *   static const lucent_setting k_ssss[] = {
 *       SETTING_INT("taps", ssss.taps, 17, 1, 255, LUCENT_SETTING_ODD, "taps per 1-D pass"),
 *       ...
 *   };
 *   const lucent_settings_group gl_ssss_settings = SETTINGS_GROUP("ssss", "the blur", k_ssss);
 *
 * Internal to the library. */
#ifndef LUCENT_SRC_BASE_SETTINGS_TABLE_H
#define LUCENT_SRC_BASE_SETTINGS_TABLE_H

#include <math.h>
#include <stddef.h>

#include "base/json.h"
#include "lucent/settings.h"

#define SETTING_MEMBER_(member) (((lucent_render_settings *)0)->member)
/* 0, or a compile error when cond is false. */
#define SETTING_ASSERT_(cond) (0 * sizeof(char[(cond) ? 1 : -1]))
#define SETTING_AT_(member, cond)                                                                                      \
    .offset = offsetof(lucent_render_settings, member) + SETTING_ASSERT_(cond), .size = sizeof SETTING_MEMBER_(member)

#define SETTING_BOOL(key_, member, def_, doc_)                                                                         \
    {                                                                                                                  \
        .key = key_, .type = LUCENT_SETTING_BOOL,                                                                      \
        SETTING_AT_(member, _Generic(SETTING_MEMBER_(member), bool : 1, default : 0)), .def = (def_) ? 1 : 0,          \
        .doc = doc_                                                                                                    \
    }
#define SETTING_INT(key_, member, def_, lo_, hi_, flags_, doc_)                                                        \
    {                                                                                                                  \
        .key = key_, .type = LUCENT_SETTING_INT,                                                                       \
        SETTING_AT_(member, _Generic(SETTING_MEMBER_(member), int : 1, default : 0)), .def = def_, .lo = lo_,          \
        .hi = hi_, .flags = flags_, .doc = doc_                                                                        \
    }
#define SETTING_REAL(key_, member, def_, lo_, hi_, doc_)                                                               \
    {                                                                                                                  \
        .key = key_, .type = LUCENT_SETTING_REAL,                                                                      \
        SETTING_AT_(member, _Generic(SETTING_MEMBER_(member), double : 1, default : 0)), .def = def_, .lo = lo_,       \
        .hi = hi_, .doc = doc_                                                                                         \
    }
#define SETTING_COLOR(key_, member, def_, lo_, hi_, doc_)                                                              \
    {                                                                                                                  \
        .key = key_, .type = LUCENT_SETTING_COLOR,                                                                     \
        SETTING_AT_(member, _Generic(SETTING_MEMBER_(member), double * : 1, default : 0) &&                            \
                                sizeof SETTING_MEMBER_(member) == 3 * sizeof(double)),                                 \
        .def = def_, .lo = lo_, .hi = hi_, .doc = doc_                                                                 \
    }
#define SETTING_SEED(key_, member, def_, lo_, hi_, doc_)                                                               \
    {                                                                                                                  \
        .key = key_, .type = LUCENT_SETTING_SEED,                                                                      \
        SETTING_AT_(member, _Generic(SETTING_MEMBER_(member), uint64_t : 1, default : 0)), .def = def_, .lo = lo_,     \
        .hi = hi_, .doc = doc_                                                                                         \
    }
/* An enum member (stored as int): its names from choice(i). */
#define SETTING_CHOICE(key_, member, def_, choice_, doc_)                                                              \
    {                                                                                                                  \
        .key = key_, .type = LUCENT_SETTING_CHOICE,                                                                    \
        SETTING_AT_(member, sizeof SETTING_MEMBER_(member) == sizeof(int)), .def_text = def_, .choice = choice_,       \
        .doc = doc_                                                                                                    \
    }
/* A char[] member; choice_ (may be NULL) lists the values it may take. */
#define SETTING_TEXT(key_, member, def_, choice_, doc_)                                                                \
    {                                                                                                                  \
        .key = key_, .type = LUCENT_SETTING_TEXT,                                                                      \
        SETTING_AT_(member, _Generic(SETTING_MEMBER_(member), char * : 1, default : 0)), .def_text = def_,             \
        .choice = choice_, .doc = doc_                                                                                 \
    }

#define SETTINGS_GROUP(name_, doc_, table)                                                                             \
    {                                                                                                                  \
        .name = name_, .doc = doc_, .settings = table, .count = (int)(sizeof table / sizeof table[0])                  \
    }

/* The name function of a NULL-terminated list of names. */
#define SETTINGS_NAMES(fn, ...)                                                                                        \
    static const char *fn(int i)                                                                                       \
    {                                                                                                                  \
        static const char *const names[] = {__VA_ARGS__, NULL};                                                        \
        return i >= 0 && i < (int)(sizeof names / sizeof names[0]) ? names[i] : NULL;                                  \
    }

/* A table of groups in reading order. The registry (src/scene/settings.c) owns the one the library
 * uses and passes it to the functions below; base knows no group by name. */
typedef struct settings_table {
    const lucent_settings_group *const *groups;
    int count;
} settings_table;

/* The engine behind the public functions of lucent/settings.h, over table t. */
lucent_render_settings settings_table_defaults(const settings_table *t);
const lucent_setting *settings_table_find(const settings_table *t, const char *key,
                                          const lucent_settings_group **group);
lucent_status settings_table_check(const settings_table *t, const lucent_render_settings *s);
void settings_table_describe(const settings_table *t, const lucent_render_settings *s, const char *group,
                             const char *const *skip, char *dest, size_t size);
lucent_status settings_table_help(const settings_table *t, bool markdown, char **dest);

/* Reads the members of `render` (a scene's "render" object; absent: the defaults) into dest, checking
 * every key against the table and every value against its range. Errors name the file and path:
 * "scene.json: render.taps: must be odd (a centre tap and pairs), got 16". */
lucent_status settings_table_read_json(const settings_table *t, const lucent_json_node *render,
                                       lucent_render_settings *dest);

/* Adds every setting of every group to object (the sidecar's "settings"); returns false when out of
 * memory. */
bool settings_table_write_json(const settings_table *t, const lucent_render_settings *s, cJSON *object);

/* The same over the library's registry (src/scene/settings.c). */
lucent_status lucent_settings_read_json(const lucent_json_node *render, lucent_render_settings *dest);
bool lucent_settings_write_json(const lucent_render_settings *s, cJSON *object);

/* The index of name among choice's names (case-insensitive); -1 when absent. */
int lucent_settings_choice_index(const char *(*choice)(int), const char *name);

/* "a, b, c": choice's names, for messages. */
void lucent_settings_choice_list(const char *(*choice)(int), char *dest, size_t size);

#endif
