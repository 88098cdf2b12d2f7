/* Every use of an individual render setting in the evaluations, kept together: the method a
 * compare run applies, its description in the tables (the settings the method reads, from the
 * settings table), the tonemapping of its PNGs and the size --scale gives a scene. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "eval/internal.h"
#include "lucent/kernel.h"
#include "lucent/scene.h"

lucent_status eval_method_settings(const char *method, lucent_render_settings *rs)
{
    return lucent_render_method_parse(method, &rs->view.method, rs);
}

bool eval_method_unavailable(const lucent_render_settings *rs, const lucent_scene *scene, char *reason, size_t size)
{
    if (rs->view.method != LUCENT_METHOD_SSSS || rs->ssss.kernel != LUCENT_KERNEL_MANUAL) return false;
    for (int i = 0; i < scene->object_count; i++) {
        lucent_manual_params p;
        if (lucent_manual_preset(scene->objects[i].material.name, &p) != LUCENT_OK) {
            snprintf(reason, size, "object \"%s\": %s", scene->objects[i].name, lucent_last_error());
            return true;
        }
    }
    return false;
}

void eval_image_samples(int samples, lucent_render_settings *rs)
{
    if (samples > 0)
        rs->view.samples = samples;
    else if (rs->view.samples <= 1)
        rs->view.samples = LUCENT_COMPARE_DEFAULT_SAMPLES;
}

void eval_method_describe(const lucent_render_settings *rs, char *dest, size_t size)
{
    lucent_render_method_describe(rs, dest, size);
    size_t len = strlen(dest);
    if (rs->view.samples > 1 && len < size) snprintf(dest + len, size - len, "; %d pixel samples", rs->view.samples);
}

lucent_tonemap_desc eval_tonemap(const lucent_render_settings *rs)
{
    return (lucent_tonemap_desc){.op = rs->view.tonemap, .exposure = (float)rs->view.exposure};
}

void eval_scale_overrides(const lucent_scene *scene, double scale, char width[48], char height[48])
{
    snprintf(width, 48, "render.width=%ld", lround(fmax(1, scene->render.view.width * scale)));
    snprintf(height, 48, "render.height=%ld", lround(fmax(1, scene->render.view.height * scale)));
}
