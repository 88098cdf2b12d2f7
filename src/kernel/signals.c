/* Test signals of Freude 2014, section 6.2: the vertical white-black edge (Figures 6.3-6.5) and
 * a circle with two tilted adjacent squares (Figures 6.6-6.10); or any user image. */
#include <math.h>
#include <string.h>

#include "lucent/convolve.h"

#define SUPERSAMPLE 4

/* Coverage of a shape at a sample point (x, y) in units of s = min(width, height), measured from
 * the image centre, x right and y down; returns the value of the shape there (0: outside). */
typedef float (*shape_fn)(double x, double y);

static float edge_shape(double x, double y)
{
    (void)y;
    return x < 0.0 ? 1.0f : 0.0f;
}

static float shapes_shape(double x, double y)
{
    /* the circle: centre (-0.25, 0), radius 0.2, value 1 */
    double cx = x + 0.25, cy = y;
    if (cx * cx + cy * cy < 0.2 * 0.2) return 1.0f;
    /* two squares of side a, rotated by 30 degrees, sharing the side whose midpoint is m:
     * coordinates along u = (cos t, sin t) and v = (-sin t, cos t) from m */
    const double a = 0.22, mx = 0.22, my = 0.0, t = 30.0 * M_PI / 180.0;
    double dx = x - mx, dy = y - my;
    double pu = dx * cos(t) + dy * sin(t), pv = -dx * sin(t) + dy * cos(t);
    if (fabs(pv) >= 0.5 * a) return 0.0f;
    if (pu > -a && pu < 0.0) return 1.0f; /* upper left */
    if (pu >= 0.0 && pu < a) return 0.5f; /* lower right */
    return 0.0f;
}

/* Renders a shape into a new RGB image, each pixel the mean of SUPERSAMPLE^2 samples. */
static lucent_status render(int width, int height, shape_fn shape, lucent_image **dest)
{
    lucent_status s = lucent_image_create(width, height, 3, dest);
    if (s != LUCENT_OK) return s;
    double scale = width < height ? width : height;
    for (int y = 0; y < height; y++) {
        for (int x = 0; x < width; x++) {
            double sum = 0.0;
            for (int j = 0; j < SUPERSAMPLE; j++)
                for (int i = 0; i < SUPERSAMPLE; i++) {
                    double px = x + (i + 0.5) / SUPERSAMPLE - 0.5 * width;
                    double py = y + (j + 0.5) / SUPERSAMPLE - 0.5 * height;
                    sum += shape(px / scale, py / scale);
                }
            float v = (float)(sum / (SUPERSAMPLE * SUPERSAMPLE));
            for (int c = 0; c < 3; c++) lucent_image_set(*dest, x, y, c, v);
        }
    }
    return LUCENT_OK;
}

lucent_status lucent_signal_edge(int width, int height, lucent_image **dest)
{
    return render(width, height, edge_shape, dest);
}

lucent_status lucent_signal_shapes(int width, int height, lucent_image **dest)
{
    return render(width, height, shapes_shape, dest);
}

lucent_status lucent_signal_load(const char *spec, int width, int height, lucent_image **dest)
{
    *dest = NULL;
    if (!spec || !*spec)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "signal: expected \"edge\", \"shapes\" or an image path");
    if (width <= 0) width = LUCENT_SIGNAL_DEFAULT_SIZE;
    if (height <= 0) height = LUCENT_SIGNAL_DEFAULT_SIZE;
    if (strcmp(spec, "edge") == 0) return lucent_signal_edge(width, height, dest);
    if (strcmp(spec, "shapes") == 0) return lucent_signal_shapes(width, height, dest);
    lucent_image *img = NULL;
    lucent_status s = lucent_image_load(spec, &img);
    if (s != LUCENT_OK) return s;
    if (img->channels != 1) {
        *dest = img;
        return LUCENT_OK;
    }
    s = lucent_image_convert_channels(img, 3, dest);
    lucent_image_destroy(img);
    return s;
}
