/* compare's measures: the object mask, the reference's own noise, the error maps, and the image
 * files of a method or reference. */
#include <math.h>
#include <stdbool.h>

#include "eval/internal.h"

uint64_t lucent_compare_object_mask(const lucent_image *c, float *dest)
{
    uint64_t count = 0;
    for (size_t i = 0; i < (size_t)c->width * (size_t)c->height; i++) dest[i] = 0;
    for (int y = 1; y + 1 < c->height; y++)
        for (int x = 1; x + 1 < c->width; x++) {
            bool inside = true;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) inside = inside && lucent_image_get(c, x + dx, y + dy, 0) >= 0.999f;
            dest[(size_t)y * (size_t)c->width + (size_t)x] = inside;
            count += inside;
        }
    return count;
}

double lucent_compare_reference_noise(const lucent_image *m, const lucent_image *v, const float *mask)
{
    double var = 0, sq = 0;
    for (size_t i = 0; i < (size_t)m->width * (size_t)m->height; i++)
        for (int c = 0; c < 3 && (!mask || mask[i] > 0.5f); c++) {
            double r = m->data[i * (size_t)m->channels + (size_t)c];
            var += v->data[i * (size_t)v->channels + (size_t)c], sq += r * r;
        }
    return sq > 0 ? sqrt(var / sq) : 0;
}

lucent_status lucent_compare_error_map(const lucent_image *img, const lucent_image *ref, const float *mask,
                                       lucent_image **dest)
{
    lucent_image *err = NULL;
    *dest = NULL;
    lucent_status s = lucent_image_error_map(img, ref, true, 0.01f, &err);
    for (size_t i = 0; s == LUCENT_OK && mask && i < (size_t)err->width * (size_t)err->height; i++)
        err->data[i] *= mask[i];
    if (s == LUCENT_OK) s = lucent_image_heatmap(err, LUCENT_COMPARE_ERROR_MAP_SCALE, dest);
    lucent_image_destroy(err);
    return s;
}

lucent_status lucent_compare_write_image(const char *dir, const char *stem, const lucent_image *img,
                                         const lucent_tonemap_desc *tonemap)
{
    char path[EVAL_PATH_SIZE];
    lucent_image *t;
    lucent_status s = eval_path_printf(path, sizeof path, "%s/%s.exr", dir, stem);
    if (s == LUCENT_OK) s = lucent_image_write(path, img, NULL);
    if (s == LUCENT_OK) s = lucent_image_clone(img, &t);
    if (s != LUCENT_OK) return s;
    lucent_image_tonemap(t, tonemap);
    s = eval_path_printf(path, sizeof path, "%s/%s.png", dir, stem);
    if (s == LUCENT_OK) s = lucent_image_write(path, t, NULL);
    lucent_image_destroy(t);
    return s;
}
