/* The viewer's user interface: a C interface over Dear ImGui (Debian's libimgui-dev with its GLFW
 * and OpenGL 3 backends), implemented by ui.cpp, the viewer's one C++ file. Widgets return true when
 * the user changed their value. Coordinates are framebuffer pixels from the window's top-left. */
#ifndef LUCENT_VIEWER_UI_H
#define LUCENT_VIEWER_UI_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Starts ImGui on a GLFW window (a GLFWwindow *) whose OpenGL context is current. */
bool ui_init(void *glfw_window);
void ui_shutdown(void);
void ui_frame_begin(void);
void ui_frame_end(void); /* draws the UI into the current framebuffer */
void ui_clear(void);     /* clears the window (dark grey) */

/* What the mouse and keyboard did this frame, outside the UI's own windows. */
typedef struct ui_input {
    float x, y, dx, dy, wheel; /* cursor and its motion, wheel steps */
    bool down[3];              /* left, right, middle held */
    bool shift, ctrl;
    bool over_ui; /* the UI wants the mouse */
    bool typing;  /* the UI wants the keyboard */
} ui_input;
void ui_get_input(ui_input *dest);

/* Key presses as GLFW reports them, queued by its key callback (after Dear ImGui's): fn(user, key)
 * for each press, so that a tap shorter than a frame still counts. ui_inject_key plays a tap (press
 * and release) through the same callback, as glfwPollEvents would (scripts, tests). */
void ui_on_key(void (*fn)(void *user, int glfw_key), void *user);
void ui_inject_key(int glfw_key);

/* A fixed panel (no move, no resize by the user); ui_panel_end always. Labels that do not fit
 * beside their widget go on a line of their own above it; text wraps at the panel's edge. */
void ui_panel_begin(const char *title, float x, float y, float w, float h);
void ui_panel_end(void);
bool ui_header(const char *label, bool open_default); /* a collapsing section */
void ui_open_all(bool open);                          /* every section opens (panel checks) */

/* The last panel's layout: the height its content needs, the right edge of its widest item, and
 * the panel's visible content width and height (pixels). */
typedef struct ui_layout {
    float content_h, widest, visible_w, visible_h;
} ui_layout;
void ui_panel_layout(ui_layout *dest);
void ui_text(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void ui_text_colored(float r, float g, float b, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
void ui_text_wrapped(const char *text);
void ui_separator(void);
void ui_same_line(void);
void ui_push_id(int id);
void ui_pop_id(void);
void ui_item_width(float w); /* for the next widgets (0: the default) */
bool ui_button(const char *label);
bool ui_checkbox(const char *label, bool *v);
bool ui_radio(const char *label, int *v, int value);
bool ui_drag_double(const char *label, double *v, double lo, double hi, bool logarithmic, const char *format);
bool ui_drag_double3(const char *label, double v[3], double lo, double hi, bool logarithmic, const char *format);
bool ui_drag_int(const char *label, int *v, int lo, int hi);
/* names(user, i) gives the i-th name, NULL past the last. */
bool ui_combo(const char *label, int *current, const char *(*names)(void *user, int i), void *user);
bool ui_color3(const char *label, double rgb[3]);
bool ui_input_text(const char *label, char *buf, size_t size); /* true when Enter was pressed */
void ui_tooltip(const char *text);                             /* for the last item, when hovered */
void ui_progress(float fraction, const char *overlay);         /* fraction < 0: busy, no fraction */

/* A plot of up to 4 series sharing x (log10 of y when log_y; values <= 0 skipped), with stems at
 * the points of series marked stems. */
typedef struct ui_series {
    const double *x, *y;
    int count;
    uint32_t rgba; /* 0xAABBGGRR */
    bool stems;
} ui_series;
void ui_plot(const char *label, const ui_series *series, int count, float height, bool log_y);

/* Text and lines over everything (the view's overlay). */
void ui_overlay_text(float x, float y, const char *text);
void ui_overlay_line(float x0, float y0, float x1, float y1, uint32_t rgba, float thickness);

/* RGBA8 textures (top row first) drawn by the UI: *tex 0 creates one. */
void ui_texture_set(unsigned *tex, const uint8_t *rgba, int width, int height);
void ui_texture_free(unsigned *tex);
void ui_background_image(unsigned tex, float x0, float y0, float x1, float y1);
void ui_background_image_uv(unsigned tex, float x0, float y0, float x1, float y1, float u0, float v0, float u1,
                            float v1);

/* The window's framebuffer as RGBA8, top row first (after drawing, before the swap). */
bool ui_read_window(int width, int height, uint8_t *rgba);

#ifdef __cplusplus
}
#endif

#endif
