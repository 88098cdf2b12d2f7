// The viewer's user interface (ui.h): Dear ImGui behind a C interface. The only C++ of Lucent.
#include <epoxy/gl.h> // before GLFW and the backends

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "backends/imgui_impl_glfw.h"
#include "backends/imgui_impl_opengl3.h"
#include "imgui.h"
#include "ui.h"

static GLFWwindow *g_window;
static void (*g_key_fn)(void *, int);
static void *g_key_user;
static bool g_open_all;
static float g_widest; // the right edge of the widest item of the panel being drawn
static ui_layout g_layout;

// Every widget of the panel: its right edge (label included) for ui_panel_layout.
static void measured(void) { g_widest = fmaxf(g_widest, ImGui::GetItemRectMax().x); }

// Dear ImGui 1.86 keeps a key's state, not its presses: one pressed and released between two frames
// is lost. GLFW's callback sees each press: queue it for the viewer, then let ImGui have it.
static void key_callback(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    ImGui_ImplGlfw_KeyCallback(w, key, scancode, action, mods);
    if (action == GLFW_PRESS && g_key_fn) g_key_fn(g_key_user, key);
}

// The label of a widget when it fits beside one of the item width (or of at least 40% of the panel,
// narrowed); else the label as text on its own line and the widget, hidden-labelled, across.
static const char *fit_label(const char *label, char *id, size_t size)
{
    const char *hash = strstr(label, "##");
    float avail = ImGui::GetContentRegionAvail().x, spacing = ImGui::GetStyle().ItemInnerSpacing.x;
    float text = ImGui::CalcTextSize(label, hash).x, widget = ImGui::CalcItemWidth();
    if (hash == label || widget + spacing + text <= avail) return label;
    if (avail - spacing - text >= 0.4f * avail) {
        ImGui::SetNextItemWidth(avail - spacing - text);
        return label;
    }
    ImGui::TextUnformatted(label, hash);
    measured();
    ImGui::SetNextItemWidth(avail);
    snprintf(id, size, "##%s", label);
    return id;
}

extern "C" {

bool ui_init(void *glfw_window)
{
    GLFWwindow *w = static_cast<GLFWwindow *>(glfw_window);
    glfwSetKeyCallback(w, nullptr); // the viewer decides what Escape does, not the renderer's window
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr; // no imgui.ini beside the user's files
    ImGui::StyleColorsDark();
    ImGui::GetStyle().WindowRounding = 0;
    bool ok = ImGui_ImplGlfw_InitForOpenGL(w, true) && ImGui_ImplOpenGL3_Init("#version 330 core");
    glfwSetKeyCallback(w, key_callback); // after ImGui's, which it calls
    g_window = w;
    return ok;
}

void ui_on_key(void (*fn)(void *, int), void *user) { g_key_fn = fn, g_key_user = user; }

void ui_inject_key(int key)
{
    int scancode = glfwGetKeyScancode(key);
    key_callback(g_window, key, scancode, GLFW_PRESS, 0);
    key_callback(g_window, key, scancode, GLFW_RELEASE, 0);
}

void ui_open_all(bool open) { g_open_all = open; }

void ui_panel_layout(ui_layout *dest) { *dest = g_layout; }

void ui_shutdown(void)
{
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

void ui_frame_begin(void)
{
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void ui_frame_end(void)
{
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void ui_clear(void)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(0.12f, 0.12f, 0.13f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
}

void ui_get_input(ui_input *d)
{
    const ImGuiIO &io = ImGui::GetIO();
    d->x = io.MousePos.x, d->y = io.MousePos.y;
    d->dx = io.MouseDelta.x, d->dy = io.MouseDelta.y;
    if (!isfinite(d->dx) || !isfinite(d->dy) || fabsf(d->dx) > 1e5f) d->dx = d->dy = 0;
    d->wheel = io.MouseWheel;
    for (int i = 0; i < 3; i++) d->down[i] = io.MouseDown[i];
    d->shift = io.KeyShift, d->ctrl = io.KeyCtrl;
    d->over_ui = io.WantCaptureMouse;
    d->typing = io.WantCaptureKeyboard;
}

void ui_panel_begin(const char *title, float x, float y, float w, float h)
{
    ImGui::SetNextWindowPos(ImVec2(x, y));
    ImGui::SetNextWindowSize(ImVec2(w, h));
    ImGui::Begin(title, nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    g_widest = 0;
}

void ui_panel_end(void)
{
    const ImGuiStyle &st = ImGui::GetStyle();
    g_layout.content_h = ImGui::GetCursorPosY() - st.ItemSpacing.y + st.WindowPadding.y; // from the panel's top
    g_layout.widest = g_widest - ImGui::GetWindowPos().x;
    g_layout.visible_w = ImGui::GetWindowContentRegionMax().x;
    g_layout.visible_h = ImGui::GetWindowHeight();
    ImGui::End();
}

bool ui_header(const char *label, bool open_default)
{
    if (g_open_all) ImGui::SetNextItemOpen(true);
    // not measured: a header spans into the panel's padding by design
    return ImGui::CollapsingHeader(label, open_default ? ImGuiTreeNodeFlags_DefaultOpen : 0);
}

void ui_text(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    ImGui::PushTextWrapPos(0);
    ImGui::TextV(fmt, ap);
    ImGui::PopTextWrapPos();
    va_end(ap);
    measured();
}

void ui_text_colored(float r, float g, float b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    ImGui::PushTextWrapPos(0);
    ImGui::TextColoredV(ImVec4(r, g, b, 1), fmt, ap);
    ImGui::PopTextWrapPos();
    va_end(ap);
    measured();
}

void ui_text_wrapped(const char *text)
{
    ImGui::TextWrapped("%s", text);
    measured();
}
void ui_separator(void) { ImGui::Separator(); }
void ui_same_line(void) { ImGui::SameLine(); }
void ui_push_id(int id) { ImGui::PushID(id); }
void ui_pop_id(void) { ImGui::PopID(); }

void ui_item_width(float w)
{
    static bool pushed = false;
    if (pushed) ImGui::PopItemWidth();
    pushed = w > 0;
    if (pushed) ImGui::PushItemWidth(w);
}

bool ui_button(const char *label)
{
    bool pressed = ImGui::Button(label);
    return measured(), pressed;
}

bool ui_checkbox(const char *label, bool *v)
{
    const char *hash = strstr(label, "##");
    float avail = ImGui::GetContentRegionAvail().x,
          box = ImGui::GetFrameHeight() + ImGui::GetStyle().ItemInnerSpacing.x;
    if (ImGui::CalcTextSize(label, hash).x + box <= avail) {
        bool changed = ImGui::Checkbox(label, v);
        return measured(), changed;
    }
    ImGui::PushID(label); // the box, then its label wrapped beside it
    bool changed = ImGui::Checkbox("##box", v);
    ImGui::PopID();
    measured();
    ImGui::SameLine();
    ImGui::PushTextWrapPos(0);
    ImGui::TextUnformatted(label, hash);
    ImGui::PopTextWrapPos();
    return measured(), changed;
}

bool ui_radio(const char *label, int *v, int value)
{
    bool changed = ImGui::RadioButton(label, v, value);
    return measured(), changed;
}

bool ui_drag_double(const char *label, double *v, double lo, double hi, bool logarithmic, const char *format)
{
    char id[256];
    label = fit_label(label, id, sizeof id);
    double speed = logarithmic ? 0.01 : (hi - lo) / 500.0;
    if (!(speed > 0) || !isfinite(speed) || speed > 1e3) speed = 0.01 * (fabs(*v) > 0 ? fabs(*v) : 1.0);
    ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp | (logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
    bool changed =
        ImGui::DragScalar(label, ImGuiDataType_Double, v, (float)speed, &lo, &hi, format ? format : "%.4g", flags);
    return measured(), changed;
}

bool ui_drag_double3(const char *label, double v[3], double lo, double hi, bool logarithmic, const char *format)
{
    char id[256];
    label = fit_label(label, id, sizeof id);
    ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp | (logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
    float speed = logarithmic ? 0.01f : (float)((hi - lo) / 500.0);
    bool changed =
        ImGui::DragScalarN(label, ImGuiDataType_Double, v, 3, speed, &lo, &hi, format ? format : "%.4g", flags);
    return measured(), changed;
}

bool ui_drag_int(const char *label, int *v, int lo, int hi)
{
    char id[256];
    label = fit_label(label, id, sizeof id);
    bool changed = ImGui::DragInt(label, v, hi - lo > 200 ? 1.0f : 0.2f, lo, hi, "%d", ImGuiSliderFlags_AlwaysClamp);
    return measured(), changed;
}

struct combo_names {
    const char *(*names)(void *, int);
    void *user;
};

static bool combo_item(void *data, int i, const char **out)
{
    const combo_names *c = static_cast<const combo_names *>(data);
    *out = c->names(c->user, i);
    return *out != nullptr;
}

bool ui_combo(const char *label, int *current, const char *(*names)(void *user, int i), void *user)
{
    int count = 0;
    while (names(user, count)) count++;
    combo_names c = {names, user};
    char id[256];
    label = fit_label(label, id, sizeof id);
    bool changed = ImGui::Combo(label, current, combo_item, &c, count);
    return measured(), changed;
}

bool ui_color3(const char *label, double rgb[3])
{
    float f[3] = {(float)rgb[0], (float)rgb[1], (float)rgb[2]};
    char id[256];
    label = fit_label(label, id, sizeof id);
    bool changed = ImGui::ColorEdit3(label, f, ImGuiColorEditFlags_Float);
    measured();
    if (!changed) return false;
    for (int i = 0; i < 3; i++) rgb[i] = f[i];
    return true;
}

bool ui_input_text(const char *label, char *buf, size_t size)
{
    char id[256];
    label = fit_label(label, id, sizeof id);
    bool enter = ImGui::InputText(label, buf, size, ImGuiInputTextFlags_EnterReturnsTrue);
    return measured(), enter;
}

void ui_tooltip(const char *text)
{
    if (!ImGui::IsItemHovered()) return;
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30);
    ImGui::TextUnformatted(text);
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
}

void ui_progress(float fraction, const char *overlay)
{
    if (fraction < 0) fraction = 0.5f + 0.5f * sinf((float)ImGui::GetTime() * 4); // busy
    ImGui::ProgressBar(fraction, ImVec2(-1, 0), overlay);
    measured();
}

void ui_plot(const char *label, const ui_series *series, int count, float height, bool log_y)
{
    ImGui::PushTextWrapPos(0);
    ImGui::TextUnformatted(label);
    ImGui::PopTextWrapPos();
    measured();
    ImVec2 p0 = ImGui::GetCursorScreenPos(), size(ImGui::GetContentRegionAvail().x, height);
    ImGui::Dummy(size);
    measured();
    ImDrawList *dl = ImGui::GetWindowDrawList();
    ImVec2 p1(p0.x + size.x, p0.y + size.y);
    dl->AddRectFilled(p0, p1, IM_COL32(20, 20, 24, 255));
    dl->AddRect(p0, p1, IM_COL32(90, 90, 100, 255));
    double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
    auto fy = [log_y](double y) { return log_y ? (y > 0 ? log10(y) : NAN) : y; };
    for (int s = 0; s < count; s++)
        for (int i = 0; i < series[s].count; i++) {
            double y = fy(series[s].y[i]);
            if (!isfinite(y)) continue;
            xlo = fmin(xlo, series[s].x[i]), xhi = fmax(xhi, series[s].x[i]);
            ylo = fmin(ylo, y), yhi = fmax(yhi, y);
        }
    if (!(xhi > xlo) || !(yhi >= ylo)) return;
    if (log_y) ylo = fmax(ylo, yhi - 6); // six decades
    if (!log_y) ylo = fmin(ylo, 0);
    if (yhi == ylo) yhi = ylo + 1;
    const float m = 4;
    auto px = [&](double x) { return p0.x + m + (float)((x - xlo) / (xhi - xlo)) * (size.x - 2 * m); };
    auto py = [&](double y) { return p1.y - m - (float)((fmax(y, ylo) - ylo) / (yhi - ylo)) * (size.y - 2 * m); };
    dl->PushClipRect(p0, p1, true);
    if (!log_y && ylo < 0) dl->AddLine(ImVec2(p0.x, py(0)), ImVec2(p1.x, py(0)), IM_COL32(70, 70, 80, 255));
    for (int s = 0; s < count; s++) {
        const ui_series &se = series[s];
        bool have = false;
        ImVec2 last;
        for (int i = 0; i < se.count; i++) {
            double y = fy(se.y[i]);
            if (!isfinite(y)) {
                have = false;
                continue;
            }
            ImVec2 p(px(se.x[i]), py(y));
            if (se.stems) {
                dl->AddLine(ImVec2(p.x, py(log_y ? ylo : 0)), p, se.rgba);
                dl->AddCircleFilled(p, 2, se.rgba);
            } else if (have) {
                dl->AddLine(last, p, se.rgba, 1.5f);
            }
            last = p, have = true;
        }
    }
    dl->PopClipRect();
    char text[64];
    snprintf(text, sizeof text, log_y ? "1e%.1f" : "%.3g", yhi);
    dl->AddText(ImVec2(p0.x + 3, p0.y + 1), IM_COL32(160, 160, 170, 255), text);
    snprintf(text, sizeof text, "%.3g .. %.3g mm", xlo, xhi);
    dl->AddText(ImVec2(p1.x - ImGui::CalcTextSize(text).x - 3, p1.y - ImGui::GetFontSize() - 1),
                IM_COL32(160, 160, 170, 255), text);
}

void ui_overlay_text(float x, float y, const char *text)
{
    ImDrawList *dl = ImGui::GetForegroundDrawList();
    ImVec2 s = ImGui::CalcTextSize(text);
    dl->AddRectFilled(ImVec2(x - 4, y - 3), ImVec2(x + s.x + 4, y + s.y + 3), IM_COL32(0, 0, 0, 160));
    dl->AddText(ImVec2(x, y), IM_COL32(235, 235, 235, 255), text);
}

void ui_overlay_line(float x0, float y0, float x1, float y1, uint32_t rgba, float thickness)
{
    ImGui::GetForegroundDrawList()->AddLine(ImVec2(x0, y0), ImVec2(x1, y1), rgba, thickness);
}

void ui_texture_set(unsigned *tex, const uint8_t *rgba, int width, int height)
{
    if (!*tex) {
        GLuint t;
        glGenTextures(1, &t);
        *tex = t;
    }
    glBindTexture(GL_TEXTURE_2D, *tex);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glBindTexture(GL_TEXTURE_2D, 0);
}

void ui_texture_free(unsigned *tex)
{
    if (*tex) {
        GLuint t = *tex;
        glDeleteTextures(1, &t);
    }
    *tex = 0;
}

void ui_background_image(unsigned tex, float x0, float y0, float x1, float y1)
{
    ImGui::GetBackgroundDrawList()->AddImage((ImTextureID)(uintptr_t)tex, ImVec2(x0, y0), ImVec2(x1, y1));
}

void ui_background_image_uv(unsigned tex, float x0, float y0, float x1, float y1, float u0, float v0, float u1,
                            float v1)
{
    ImGui::GetBackgroundDrawList()->AddImage((ImTextureID)(uintptr_t)tex, ImVec2(x0, y0), ImVec2(x1, y1),
                                             ImVec2(u0, v0), ImVec2(u1, v1));
}

bool ui_read_window(int width, int height, uint8_t *rgba)
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    for (int y = 0; y < height / 2; y++) // GL's rows run from the bottom
        for (int x = 0; x < 4 * width; x++) {
            uint8_t *a = rgba + (size_t)y * 4 * width + x, *b = rgba + (size_t)(height - 1 - y) * 4 * width + x, t = *a;
            *a = *b, *b = t;
        }
    return glGetError() == GL_NO_ERROR;
}

} // extern "C"
