// The viewer's user interface (ui.h): Dear ImGui behind a C interface. The only C++ of Lucent.
#include <epoxy/gl.h> // before GLFW and the backends

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>

#include "backends/imgui_impl_glfw.h"
#include "backends/imgui_impl_opengl3.h"
#include "imgui.h"
#include "ui.h"

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
    return ImGui_ImplGlfw_InitForOpenGL(w, true) && ImGui_ImplOpenGL3_Init("#version 330 core");
}

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

bool ui_key_pressed(int key) { return !ImGui::GetIO().WantCaptureKeyboard && ImGui::IsKeyPressed(key, false); }

void ui_panel_begin(const char *title, float x, float y, float w, float h)
{
    ImGui::SetNextWindowPos(ImVec2(x, y));
    ImGui::SetNextWindowSize(ImVec2(w, h));
    ImGui::Begin(title, nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
}

void ui_panel_end(void) { ImGui::End(); }

bool ui_header(const char *label, bool open_default)
{
    return ImGui::CollapsingHeader(label, open_default ? ImGuiTreeNodeFlags_DefaultOpen : 0);
}

void ui_text(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    ImGui::TextV(fmt, ap);
    va_end(ap);
}

void ui_text_colored(float r, float g, float b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    ImGui::TextColoredV(ImVec4(r, g, b, 1), fmt, ap);
    va_end(ap);
}

void ui_text_wrapped(const char *text) { ImGui::TextWrapped("%s", text); }
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

bool ui_button(const char *label) { return ImGui::Button(label); }
bool ui_checkbox(const char *label, bool *v) { return ImGui::Checkbox(label, v); }
bool ui_radio(const char *label, int *v, int value) { return ImGui::RadioButton(label, v, value); }

bool ui_drag_double(const char *label, double *v, double lo, double hi, bool logarithmic, const char *format)
{
    double speed = logarithmic ? 0.01 : (hi - lo) / 500.0;
    if (!(speed > 0) || !isfinite(speed) || speed > 1e3) speed = 0.01 * (fabs(*v) > 0 ? fabs(*v) : 1.0);
    ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp | (logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
    return ImGui::DragScalar(label, ImGuiDataType_Double, v, (float)speed, &lo, &hi, format ? format : "%.4g", flags);
}

bool ui_drag_double3(const char *label, double v[3], double lo, double hi, bool logarithmic, const char *format)
{
    ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp | (logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
    float speed = logarithmic ? 0.01f : (float)((hi - lo) / 500.0);
    return ImGui::DragScalarN(label, ImGuiDataType_Double, v, 3, speed, &lo, &hi, format ? format : "%.4g", flags);
}

bool ui_drag_int(const char *label, int *v, int lo, int hi)
{
    return ImGui::DragInt(label, v, hi - lo > 200 ? 1.0f : 0.2f, lo, hi, "%d", ImGuiSliderFlags_AlwaysClamp);
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
    return ImGui::Combo(label, current, combo_item, &c, count);
}

bool ui_color3(const char *label, double rgb[3])
{
    float f[3] = {(float)rgb[0], (float)rgb[1], (float)rgb[2]};
    if (!ImGui::ColorEdit3(label, f, ImGuiColorEditFlags_Float)) return false;
    for (int i = 0; i < 3; i++) rgb[i] = f[i];
    return true;
}

bool ui_input_text(const char *label, char *buf, size_t size)
{
    return ImGui::InputText(label, buf, size, ImGuiInputTextFlags_EnterReturnsTrue);
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
}

void ui_plot(const char *label, const ui_series *series, int count, float height, bool log_y)
{
    ImGui::TextUnformatted(label);
    ImVec2 p0 = ImGui::GetCursorScreenPos(), size(ImGui::GetContentRegionAvail().x, height);
    ImGui::Dummy(size);
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
