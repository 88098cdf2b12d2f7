/* Showing a frame in a window: the final target tonemapped (the settings' operator and exposure)
 * and sRGB-encoded into the window's framebuffer. */
#include <math.h>

#include "gl/renderer.h"

lucent_status lucent_render_present(lucent_renderer *r)
{
    if (!r->ctx->window || !r->have_frame) return LUCENT_OK;
    lucent_status s = lucent_gl_make_current(r->ctx);
    if (s == LUCENT_OK && !r->present_program)
        s = gl_program_build(gl_embedded_source, NULL, "fullscreen.vert.glsl", "present.frag.glsl", NULL,
                             &r->present_program);
    if (s != LUCENT_OK) return s;
    int w, h;
    gl_window_size(r->ctx, &w, &h);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glViewport(0, 0, w, h);
    glUseProgram(r->present_program);
    glBindVertexArray(r->empty_vao);
    glBindTextureUnit(0, r->targets.final);
    glUniform1i(glGetUniformLocation(r->present_program, "u_tonemap"), (int)r->last.view.tonemap);
    glUniform1f(glGetUniformLocation(r->present_program, "u_exposure"), (float)exp2(r->last.view.exposure));
    glUniform2f(glGetUniformLocation(r->present_program, "u_scale"), (float)r->targets.width / (float)(w > 0 ? w : 1),
                (float)r->targets.height / (float)(h > 0 ? h : 1));
    glDrawArrays(GL_TRIANGLES, 0, 3);
    gl_window_swap(r->ctx);
    return gl_check("presenting the frame");
}
