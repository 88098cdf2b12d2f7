/* Lambert: the diffuse term max(n.l, 0) with the specular lobe, no subsurface light (the baseline
 * every method is measured against; Kubo Table 1). */
#include "gl/methods/surface.h"

typedef struct lambert_state {
    GLuint program;
} lambert_state;

static lucent_status prepare(lucent_renderer *r, void *state, const lucent_render_settings *s)
{
    (void)s;
    return gl_surface_program(r, "lambert.frag.glsl", NULL, &((lambert_state *)state)->program);
}

static lucent_status draw(lucent_renderer *r, void *state, const lucent_render_settings *s)
{
    gl_surface_draw(r, ((lambert_state *)state)->program, 0, s, NULL, NULL);
    gl_compose(r, s, 0);
    return LUCENT_OK;
}

static unsigned bakes(const lucent_renderer *r, const lucent_render_settings *s) { return (void)r, (void)s, 0u; }

const gl_method gl_method_lambert = {
    .name = "lambert",
    .settings = (const char *const[]){NULL},
    .bakes = bakes,
    .state_size = sizeof(lambert_state),
    .prepare = prepare,
    .draw = draw,
};
