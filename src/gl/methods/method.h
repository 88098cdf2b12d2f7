/* The renderer's methods: one file each under src/gl/methods/ (lambert.c, cdrf.c, ssss.c), each a
 * small table of functions, listed once in the table of frame.c. A method prepares what its frame needs
 * (rebuilding only what its settings changed) and draws the frame into the final target; the core
 * has already sized the targets and shadow maps, uploaded the frame block and drawn the shadow maps.
 *
 * Adding a method: a file here with its gl_method, its shaders under src/gl/shaders/, its settings
 * group (lucent/settings.h), one line in the table of frame.c and its name in lucent_render_method. */
#ifndef LUCENT_SRC_GL_METHODS_METHOD_H
#define LUCENT_SRC_GL_METHODS_METHOD_H

#include "gl/renderer.h"

struct cJSON;

typedef struct gl_method {
    const char *name;            /* "ssss": render.method in scene files */
    const char *const *settings; /* the keys of the settings it reads (NULL-terminated): compare's
                                    description, the viewer's panel */
    /* "<name>:<variant>" (e.g. "ssss:svd3"): sets the method's settings from the variant text; NULL:
     * the method takes no variant. */
    lucent_status (*variant)(const char *text, lucent_render_settings *s);
    const char *variant_doc; /* the variant's form: "<model>[rank] (model svd, preint, ...)" */
    /* Optional: the parts (LUCENT_BAKE_*) its prepare bakes for settings s (the viewer bakes them on
     * a thread of its own first); NULL: all of them. */
    unsigned (*bakes)(const lucent_renderer *r, const lucent_render_settings *s);
    size_t state_size; /* its own state, zeroed when first created */
    lucent_status (*prepare)(lucent_renderer *r, void *state, const lucent_render_settings *s);
    lucent_status (*draw)(lucent_renderer *r, void *state, const lucent_render_settings *s);
    /* Optional: what it knows of object i for lucent_renderer_object_info (after a frame). */
    void (*object_info)(const lucent_renderer *r, const void *state, int i, lucent_render_object_info *dest);
    /* Optional: adds its values to the sidecar of a frame it drew. */
    void (*sidecar)(const lucent_renderer *r, const void *state, const lucent_render_settings *s, struct cJSON *root);
    void (*release)(void *state); /* optional: its GL objects (the context is current) */
} gl_method;

/* The table, indexed by lucent_render_method. */
extern const gl_method *const gl_methods[LUCENT_METHOD_COUNT];

#endif
