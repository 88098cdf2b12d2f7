/* Point clouds read as surfels (lucent_surfels_load, lucent/surfels.h) through Lucent's PLY reader:
 * positions and normals with optional colour and radius, or 3D Gaussian splatting files. Every value
 * is checked here, so that a bad one is named by its file, vertex and property. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/image.h"
#include "lucent/surfels.h"

enum { MAX_NAMES = 16 };

static const char *const k_plain[] = {"x", "y", "z", "nx", "ny", "nz"};
static const char *const k_color[] = {"red", "green", "blue"};
static const char *const k_splat[] = {"x",       "y",       "z",     "f_dc_0", "f_dc_1", "f_dc_2", "scale_0",
                                      "scale_1", "scale_2", "rot_0", "rot_1",  "rot_2",  "rot_3"};

/* The first of names the file lacks, or NULL. */
static const char *missing(const lucent_ply *ply, const char *const *names, int count)
{
    for (int i = 0; i < count; i++)
        if (lucent_ply_property_index(ply, names[i]) < 0) return names[i];
    return NULL;
}

/* How a missing property is missing: absent, or declared as a list. */
static const char *how_missing(const lucent_ply *ply, const char *name)
{
    return lucent_ply_property_is_list(ply, name) ? "is a list, not a number" : "missing";
}

/* What the file holds: the properties to read, in order, and where each part starts. */
typedef struct cloud_layout {
    const char *names[MAX_NAMES];
    int count;
    bool splat;
    int color, radius;     /* index of red / radius in names, -1 when absent */
    double color_scale[3]; /* 1 / the integer type's largest value, or 1 for floats */
} cloud_layout;

static lucent_status layout_of(const lucent_ply *ply, const char *path, cloud_layout *L)
{
    memset(L, 0, sizeof *L);
    L->color = L->radius = -1;
    const char *lack = missing(ply, k_plain, 3);
    if (lack)
        return lucent_error(LUCENT_ERR_PARSE, "%s: no vertex positions (property %s %s)", path, lack,
                            how_missing(ply, lack));
    L->splat = lucent_ply_property_index(ply, "scale_0") >= 0 || lucent_ply_property_index(ply, "rot_0") >= 0;
    if (L->splat && (lack = missing(ply, k_splat, 13)))
        return lucent_error(LUCENT_ERR_PARSE, "%s: a 3D Gaussian splatting file without the vertex property %s (%s)",
                            path, lack, how_missing(ply, lack));
    if (!L->splat && (lack = missing(ply, k_plain, 6)))
        return lucent_error(LUCENT_ERR_PARSE,
                            "%s: no vertex normals (property %s %s): a point cloud needs nx, ny, nz (or the "
                            "f_dc_*, scale_* and rot_* of a 3D Gaussian splatting file)",
                            path, lack, how_missing(ply, lack));
    L->count = L->splat ? 13 : 6;
    memcpy(L->names, L->splat ? k_splat : k_plain, (size_t)L->count * sizeof *L->names);
    if (!L->splat && !missing(ply, k_color, 3)) {
        L->color = L->count;
        for (int c = 0; c < 3; c++) {
            double top = lucent_ply_property_integer_max(ply, lucent_ply_property_index(ply, k_color[c]));
            L->color_scale[c] = top > 0 ? 1 / top : 1;
            L->names[L->count++] = k_color[c];
        }
    }
    if (!L->splat && lucent_ply_property_index(ply, "radius") >= 0)
        L->radius = L->count, L->names[L->count++] = "radius";
    return LUCENT_OK;
}

/* The radii a surfel may have: r^2 and 1 / r^2 stay normal floats in the renderer's Gaussians, so that a
 * surfel is neither too small nor too wide to be drawn at all (1e-45 or 3e38 rendered nothing). */
#define RADIUS_MIN 1e-18
#define RADIUS_MAX 1e18

typedef struct row_check {
    const char *path;
    const cloud_layout *L;
} row_check;

/* Each vertex as it is read (lucent_ply_read_desc.check), in double before it becomes a float: every value
 * finite and within float's range, normals not zero, radii in [RADIUS_MIN, RADIUS_MAX], rotations not zero. */
static lucent_status check_row(void *user, uint64_t i, const double *v)
{
    const row_check *rc = user;
    const cloud_layout *L = rc->L;
    unsigned long long n = (unsigned long long)i;
    for (int k = 0; k < L->count; k++) {
        if (!isfinite(v[k]))
            return lucent_error(LUCENT_ERR_PARSE, "%s: vertex %llu: %s is not finite (%g)", rc->path, n, L->names[k],
                                v[k]);
        if (fabs(v[k]) > FLT_MAX)
            return lucent_error(LUCENT_ERR_PARSE, "%s: vertex %llu: %s = %g does not fit a float (at most %g)",
                                rc->path, n, L->names[k], v[k], (double)FLT_MAX);
    }
    if (!L->splat && v[3] == 0 && v[4] == 0 && v[5] == 0)
        return lucent_error(LUCENT_ERR_PARSE, "%s: vertex %llu: the normal (nx, ny, nz) is zero", rc->path, n);
    if (L->radius >= 0 && !(v[L->radius] >= RADIUS_MIN && v[L->radius] <= RADIUS_MAX))
        return lucent_error(LUCENT_ERR_PARSE, "%s: vertex %llu: radius must be > 0, from %g to %g, got %g", rc->path, n,
                            RADIUS_MIN, RADIUS_MAX, v[L->radius]);
    if (L->splat && v[9] == 0 && v[10] == 0 && v[11] == 0 && v[12] == 0)
        return lucent_error(LUCENT_ERR_PARSE, "%s: vertex %llu: the rotation (rot_0..3) is zero", rc->path, n);
    return LUCENT_OK;
}

/* 3D Gaussian splatting (Kerbl et al. 2023): rot_0..3 is the quaternion (w, x, y, z), not normalised;
 * scale_0..2 the logs of the standard deviations along the rotation's columns. The normal is the
 * column of the smallest scale, the radius two standard deviations of the geometric mean of the other
 * two, the colour 0.5 + C0 f_dc with C0 = 1 / (2 sqrt(pi)) = 0.28209479 (spherical harmonics band 0),
 * an sRGB display value. Returns false when the radius is outside [RADIUS_MIN, RADIUS_MAX]. */
static bool gaussian_splat(const double *v, float *pos, float *nrm, float *radius, float *color)
{
    double len = sqrt(v[9] * v[9] + v[10] * v[10] + v[11] * v[11] + v[12] * v[12]);
    double w = v[9] / len, x = v[10] / len, y = v[11] / len, z = v[12] / len;
    double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                      {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                      {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
    int k = v[6] <= v[7] && v[6] <= v[8] ? 0 : v[7] <= v[8] ? 1 : 2; /* log scales: same order */
    for (int i = 0; i < 3; i++) pos[i] = (float)v[i], nrm[i] = (float)R[i][k];
    *radius = (float)(2 * exp(0.5 * (v[6 + (k + 1) % 3] + v[6 + (k + 2) % 3])));
    for (int c = 0; c < 3; c++) {
        double e = 0.5 + 0.28209479177387814 * v[3 + c];
        color[c] = lucent_srgb_decode((float)fmin(fmax(e, 0), 1));
    }
    double r = 2 * exp(0.5 * (v[6 + (k + 1) % 3] + v[6 + (k + 2) % 3]));
    return r >= RADIUS_MIN && r <= RADIUS_MAX;
}

/* Splat normals have no side: each is turned away from the cloud's centroid. */
static void orient_outward(size_t n, const float *pos, float *nrm)
{
    double c[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++)
        for (int a = 0; a < 3; a++) c[a] += pos[3 * i + a] / (double)n;
    for (size_t i = 0; i < n; i++) {
        double d = 0;
        for (int a = 0; a < 3; a++) d += (pos[3 * i + a] - c[a]) * nrm[3 * i + a];
        for (int a = 0; d < 0 && a < 3; a++) nrm[3 * i + a] = -nrm[3 * i + a];
    }
}

/* The values of the file as the arrays of lucent_surfels_from_points. */
static lucent_status unpack(const char *path, const cloud_layout *L, const lucent_ply_data *d, float *pos, float *nrm,
                            float *rad, float *col)
{
    size_t n = d->vertex_count;
    for (size_t i = 0; i < n; i++) {
        double v[MAX_NAMES];
        for (int k = 0; k < L->count; k++) v[k] = d->values32[(size_t)L->count * i + (size_t)k];
        if (L->splat) {
            if (!gaussian_splat(v, pos + 3 * i, nrm + 3 * i, rad + i, col + 3 * i))
                return lucent_error(LUCENT_ERR_PARSE,
                                    "%s: vertex %zu: the scales (scale_0..2) give a radius of %g, outside [%g, %g]",
                                    path, i, 2 * exp(0.5 * (v[6] + v[7] + v[8] - fmin(v[6], fmin(v[7], v[8])))),
                                    RADIUS_MIN, RADIUS_MAX);
            continue;
        }
        for (int a = 0; a < 3; a++) pos[3 * i + a] = (float)v[a], nrm[3 * i + a] = (float)v[3 + a];
        for (int c = 0; L->color >= 0 && c < 3; c++) {
            double e = v[L->color + c] * L->color_scale[c];
            col[3 * i + c] = lucent_srgb_decode((float)fmin(fmax(e, 0), 1));
        }
        if (L->radius >= 0) rad[i] = (float)v[L->radius];
    }
    if (L->splat) orient_outward(n, pos, nrm);
    return LUCENT_OK;
}

static lucent_status read_cloud(const char *path, cloud_layout *L, lucent_ply_data *d)
{
    lucent_ply *ply = NULL;
    lucent_status s = lucent_ply_open(path, &ply);
    if (s != LUCENT_OK) return s;
    s = layout_of(ply, path, L);
    size_t n = lucent_ply_vertex_count(ply);
    if (s == LUCENT_OK && n < 2)
        s = lucent_error(LUCENT_ERR_PARSE, "%s: holds %zu point%s: surfels need two at least", path, n,
                         n == 1 ? "" : "s");
    /* Surfels are floats: the values are kept as floats (half the memory), each vertex checked in double as it
     * is read, before the next one. */
    row_check rc = {path, L};
    if (s == LUCENT_OK)
        s = lucent_ply_read(
            ply,
            &(lucent_ply_read_desc){.names = L->names, .count = L->count, .single = 1, .check = check_row, .user = &rc},
            d);
    lucent_ply_close(ply);
    return s;
}

lucent_status lucent_surfels_load(const char *path, const lucent_surfels_desc *desc, lucent_surfels **dest)
{
    *dest = NULL;
    cloud_layout L;
    lucent_ply_data d = {0};
    lucent_status s = read_cloud(path, &L, &d);
    if (s != LUCENT_OK) return s;
    size_t n = d.vertex_count;
    bool radii = L.splat || L.radius >= 0, colors = L.splat || L.color >= 0;
    float *pos = malloc(3 * n * sizeof *pos), *nrm = malloc(3 * n * sizeof *nrm);
    float *rad = radii ? malloc(n * sizeof *rad) : NULL, *col = colors ? malloc(3 * n * sizeof *col) : NULL;
    if (!pos || !nrm || (radii && !rad) || (colors && !col))
        s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory (%zu points)", path, n);
    if (s == LUCENT_OK) s = unpack(path, &L, &d, pos, nrm, rad, col);
    lucent_ply_data_free(&d);
    if (s == LUCENT_OK && (s = lucent_surfels_from_points(n, pos, nrm, rad, col, desc, dest)) != LUCENT_OK)
        s = lucent_error_context(s, "%s", path);
    free(pos), free(nrm), free(rad), free(col);
    return s;
}
