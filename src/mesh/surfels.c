/* Surfels from meshes and point clouds, their radii from the k nearest neighbours and their
 * decimated levels (lucent/surfels.h). The neighbour search is a sorted uniform grid: points sorted
 * by cell, cells found by binary search, rings of cells searched outward until the k-th distance is
 * inside the searched block. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/surfels.h"

enum { KNN_MAX = 32, RING_LIMIT = 12, CHUNK = 4096 };

/* ---- the grid ---- */

typedef struct grid {
    double lo[3], h;
    int bits; /* per axis */
    size_t n;
    uint64_t *keys;  /* per sorted slot */
    uint32_t *order; /* sorted slot -> point */
    uint64_t *cell_key;
    size_t *cell_start; /* cell_count + 1 */
    size_t cell_count;
} grid;

typedef struct key_index {
    uint64_t key;
    uint32_t index;
} key_index;

static int compare_key_index(const void *a, const void *b)
{
    const key_index *x = a, *y = b;
    if (x->key != y->key) return x->key < y->key ? -1 : 1;
    return (x->index > y->index) - (x->index < y->index);
}

static int64_t cell_of(const grid *g, const float *p, int axis)
{
    int64_t c = (int64_t)floor((p[axis] - g->lo[axis]) / g->h);
    int64_t top = ((int64_t)1 << g->bits) - 1;
    return c < 0 ? 0 : c > top ? top : c;
}

static uint64_t pack(const grid *g, int64_t x, int64_t y, int64_t z)
{
    return ((uint64_t)x << (2 * g->bits)) | ((uint64_t)y << g->bits) | (uint64_t)z;
}

static void grid_free(grid *g)
{
    free(g->keys), free(g->order), free(g->cell_key), free(g->cell_start);
    memset(g, 0, sizeof *g);
}

/* Cells of side about twice the spacing a surface of the bounding box's area would have. */
static lucent_status grid_build(grid *g, const float *pos, size_t n)
{
    memset(g, 0, sizeof *g);
    double hi[3];
    for (int a = 0; a < 3; a++) g->lo[a] = DBL_MAX, hi[a] = -DBL_MAX;
    for (size_t i = 0; i < n; i++)
        for (int a = 0; a < 3; a++) g->lo[a] = fmin(g->lo[a], pos[3 * i + a]), hi[a] = fmax(hi[a], pos[3 * i + a]);
    double e[3], area;
    for (int a = 0; a < 3; a++) e[a] = hi[a] - g->lo[a];
    area = 2 * (e[0] * e[1] + e[1] * e[2] + e[2] * e[0]);
    double extent = fmax(e[0], fmax(e[1], e[2]));
    g->h = area > 0 ? 2 * sqrt(area / (double)n) : extent > 0 ? 2 * extent / (double)n : 1;
    g->bits = 21;
    while (extent / g->h >= (double)((1 << g->bits) - 1)) g->h *= 2;
    g->n = n;
    key_index *ki = malloc(n * sizeof *ki);
    g->keys = malloc(n * sizeof *g->keys), g->order = malloc(n * sizeof *g->order);
    g->cell_key = malloc(n * sizeof *g->cell_key), g->cell_start = malloc((n + 1) * sizeof *g->cell_start);
    if (!ki || !g->keys || !g->order || !g->cell_key || !g->cell_start) {
        free(ki);
        grid_free(g);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory (neighbour grid of %zu points)", n);
    }
    for (size_t i = 0; i < n; i++) {
        const float *p = pos + 3 * i;
        ki[i] = (key_index){pack(g, cell_of(g, p, 0), cell_of(g, p, 1), cell_of(g, p, 2)), (uint32_t)i};
    }
    qsort(ki, n, sizeof *ki, compare_key_index);
    for (size_t i = 0; i < n; i++) {
        g->keys[i] = ki[i].key, g->order[i] = ki[i].index;
        if (i == 0 || ki[i].key != ki[i - 1].key)
            g->cell_key[g->cell_count] = ki[i].key, g->cell_start[g->cell_count++] = i;
    }
    g->cell_start[g->cell_count] = n;
    free(ki);
    return LUCENT_OK;
}

/* The cell's slots [*begin, *end); false when empty. */
static bool grid_cell(const grid *g, uint64_t key, size_t *begin, size_t *end)
{
    size_t a = 0, b = g->cell_count;
    while (a < b) {
        size_t m = a + (b - a) / 2;
        if (g->cell_key[m] < key)
            a = m + 1;
        else
            b = m;
    }
    if (a == g->cell_count || g->cell_key[a] != key) return false;
    *begin = g->cell_start[a], *end = g->cell_start[a + 1];
    return true;
}

/* Keeps the k smallest squared distances, ascending, in d (found of them so far). */
static void keep(double *d, int k, int *found, double v)
{
    if (*found == k && v >= d[k - 1]) return;
    int i = *found < k ? (*found)++ : k - 1;
    while (i > 0 && d[i - 1] > v) d[i] = d[i - 1], i--;
    d[i] = v;
}

static void visit(const grid *g, const float *pos, size_t self, size_t begin, size_t end, double *d, int k, int *found)
{
    const float *p = pos + 3 * self;
    for (size_t s = begin; s < end; s++) {
        uint32_t j = g->order[s];
        if (j == self) continue;
        double dx = pos[3 * j] - p[0], dy = pos[3 * j + 1] - p[1], dz = pos[3 * j + 2] - p[2];
        keep(d, k, found, dx * dx + dy * dy + dz * dz);
    }
}

/* The distance from point i to its k-th nearest other point (the farthest found when there are fewer). */
static double knn_distance(const grid *g, const float *pos, size_t i, int k)
{
    double d[KNN_MAX];
    int found = 0;
    const float *p = pos + 3 * i;
    int64_t c[3] = {cell_of(g, p, 0), cell_of(g, p, 1), cell_of(g, p, 2)}, top = ((int64_t)1 << g->bits) - 1;
    size_t begin, end;
    for (int ring = 0; ring <= RING_LIMIT; ring++) {
        for (int64_t x = c[0] - ring; x <= c[0] + ring; x++)
            for (int64_t y = c[1] - ring; y <= c[1] + ring; y++)
                for (int64_t z = c[2] - ring; z <= c[2] + ring; z++) {
                    if (llabs(x - c[0]) != ring && llabs(y - c[1]) != ring && llabs(z - c[2]) != ring) continue;
                    if (x < 0 || y < 0 || z < 0 || x > top || y > top || z > top) continue;
                    if (grid_cell(g, pack(g, x, y, z), &begin, &end)) visit(g, pos, i, begin, end, d, k, &found);
                }
        /* Every point within ring h of p lies in the searched block. */
        if (found == k && d[k - 1] <= (double)ring * g->h * (double)ring * g->h) return sqrt(d[k - 1]);
    }
    found = 0; /* an outlier: all points */
    visit(g, pos, i, 0, g->n, d, k, &found);
    return found ? sqrt(d[found - 1]) : 0;
}

typedef struct knn_job {
    const grid *g;
    const float *pos;
    float *radii;
    int k;
} knn_job;

static lucent_status knn_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)thread;
    const knn_job *j = ctx;
    for (uint64_t i = begin; i < end; i++) j->radii[i] = (float)knn_distance(j->g, j->pos, (size_t)i, j->k);
    return LUCENT_OK;
}

/* radii[i] = the distance from point i to its k-th nearest (n >= 2). */
static lucent_status knn_radii(const float *pos, size_t n, int k, lucent_pool *pool, float *radii)
{
    grid g;
    lucent_status s = grid_build(&g, pos, n);
    if (s != LUCENT_OK) return s;
    knn_job job = {&g, pos, radii, k};
    s = lucent_parallel_for(pool, n, CHUNK, knn_chunk, &job);
    grid_free(&g);
    return s;
}

/* ---- the surfels ---- */

static int compare_floats(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

static double median(const float *v, size_t n)
{
    float *c = malloc(n * sizeof *c);
    if (!c) return v[0];
    memcpy(c, v, n * sizeof *c);
    qsort(c, n, sizeof *c, compare_floats);
    double m = c[n / 2];
    free(c);
    return m;
}

void lucent_surfels_destroy(lucent_surfels *s)
{
    if (!s) return;
    free(s->positions), free(s->normals), free(s->radii), free(s->colors);
    free(s->parent), free(s->child_start), free(s->children);
    free(s);
}

/* Room for `count` surfels in every array (contents kept). */
static lucent_status grow(lucent_surfels *s, size_t count, bool colors)
{
    float *p = realloc(s->positions, 3 * count * sizeof *p);
    if (p) s->positions = p;
    float *n = realloc(s->normals, 3 * count * sizeof *n);
    if (n) s->normals = n;
    float *r = realloc(s->radii, count * sizeof *r);
    if (r) s->radii = r;
    float *c = colors ? realloc(s->colors, 3 * count * sizeof *c) : NULL;
    if (c) s->colors = c;
    uint32_t *pa = realloc(s->parent, count * sizeof *pa);
    if (pa) s->parent = pa;
    uint32_t *cs = realloc(s->child_start, (count + 1) * sizeof *cs);
    if (cs) s->child_start = cs;
    uint32_t *ch = realloc(s->children, count * sizeof *ch);
    if (ch) s->children = ch;
    if (!p || !n || !r || (colors && !c) || !pa || !cs || !ch)
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory (%zu surfels)", count);
    return LUCENT_OK;
}

/* The cluster key of surfel i at cell size h: the cell and the normal's dominant axis and sign. */
static uint64_t cluster_key(const lucent_surfels *s, size_t i, const double lo[3], double h)
{
    const float *p = s->positions + 3 * i, *n = s->normals + 3 * i;
    uint64_t key = 0;
    for (int a = 0; a < 3; a++) {
        double c = floor((p[a] - lo[a]) / h);
        key = (key << 19) | (uint64_t)(c < 0 ? 0 : c > 524287 ? 524287 : c);
    }
    int axis = fabsf(n[0]) >= fabsf(n[1]) && fabsf(n[0]) >= fabsf(n[2]) ? 0 : fabsf(n[1]) >= fabsf(n[2]) ? 1 : 2;
    return (key << 3) | (uint64_t)(2 * axis + (n[axis] < 0));
}

/* Appends level l + 1 made from level l; *added: its surfel count. */
static lucent_status decimate(lucent_surfels *s, int l, double factor, int k, lucent_pool *pool, size_t *added)
{
    const lucent_surfel_level *src = &s->levels[l];
    double h = factor * src->spacing, lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX};
    for (size_t i = src->first; i < src->first + src->count; i++)
        for (int a = 0; a < 3; a++) lo[a] = fmin(lo[a], s->positions[3 * i + a]);
    double extent = 0;
    for (size_t i = src->first; i < src->first + src->count; i++)
        for (int a = 0; a < 3; a++) extent = fmax(extent, s->positions[3 * i + a] - lo[a]);
    while (extent / h >= 524287) h *= 2;
    key_index *ki = malloc(src->count * sizeof *ki);
    if (!ki) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory (decimating %zu surfels)", src->count);
    for (size_t i = 0; i < src->count; i++)
        ki[i] = (key_index){cluster_key(s, src->first + i, lo, h), (uint32_t)(src->first + i)};
    qsort(ki, src->count, sizeof *ki, compare_key_index);
    size_t clusters = 0;
    for (size_t i = 0; i < src->count; i++) clusters += i == 0 || ki[i].key != ki[i - 1].key;
    *added = clusters;
    size_t first = s->count;
    lucent_status st = grow(s, first + clusters, s->colors != NULL);
    for (size_t a = 0, c = 0; st == LUCENT_OK && a < src->count; c++) {
        size_t b = a;
        double centre[3] = {0, 0, 0}, normal[3] = {0, 0, 0}, color[3] = {0, 0, 0}, w = 0;
        for (; b < src->count && ki[b].key == ki[a].key; b++) {
            size_t i = ki[b].index;
            double wi = (double)s->radii[i] * s->radii[i];
            for (int d = 0; d < 3; d++) {
                centre[d] += s->positions[3 * i + d];
                normal[d] += wi * s->normals[3 * i + d];
                if (s->colors) color[d] += wi * s->colors[3 * i + d];
            }
            w += wi;
        }
        size_t rep = ki[a].index, o = first + c;
        double best = DBL_MAX, len = 0;
        for (size_t m = a; m < b; m++) { /* the member nearest the centroid (lowest index on ties) */
            size_t i = ki[m].index;
            double d2 = 0;
            for (int d = 0; d < 3; d++) {
                double x = s->positions[3 * i + d] - centre[d] / (double)(b - a);
                d2 += x * x;
            }
            if (d2 < best) best = d2, rep = i;
        }
        for (int d = 0; d < 3; d++) len += normal[d] * normal[d];
        len = sqrt(len);
        for (int d = 0; d < 3; d++) {
            s->positions[3 * o + d] = s->positions[3 * rep + d];
            s->normals[3 * o + d] = len > 1e-6 * w ? (float)(normal[d] / len) : s->normals[3 * rep + d];
            if (s->colors) s->colors[3 * o + d] = (float)(color[d] / w);
        }
        s->child_start[o] = (uint32_t)(src->first + a); /* children = the sorted members: below */
        for (size_t m = a; m < b; m++) s->children[src->first + m] = ki[m].index, s->parent[ki[m].index] = (uint32_t)o;
        s->parent[o] = UINT32_MAX;
        s->radii[o] = 0;
        a = b;
    }
    free(ki);
    if (st != LUCENT_OK) return st;
    /* children[] of this level sit at the previous level's slots: child_start indexes them. */
    s->child_start[first + clusters] = (uint32_t)(src->first + src->count);
    s->count = first + clusters;
    lucent_surfel_level *dst = &s->levels[l + 1];
    dst->first = first, dst->count = clusters;
    if (clusters >= 2)
        st = knn_radii(s->positions + 3 * first, clusters, k < (int)clusters ? k : (int)clusters - 1, pool,
                       s->radii + first);
    if (clusters == 1) s->radii[first] = (float)(h * sqrt(2.0));
    if (st == LUCENT_OK) dst->spacing = median(s->radii + first, clusters) / sqrt(2.0);
    return st;
}

static lucent_status check_points(size_t count, const float *pos, const float *nrm, const float *radii,
                                  const float *colors)
{
    if (count < 2) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "surfels need two points at least, got %zu", count);
    if (count >= UINT32_MAX / 2)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "too many points (%zu) for surfels", count);
    for (size_t i = 0; i < count; i++) {
        double len = 0;
        for (int a = 0; a < 3; a++) {
            if (!isfinite(pos[3 * i + a]) || !isfinite(nrm[3 * i + a]) || (colors && !isfinite(colors[3 * i + a])))
                return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "point %zu: a coordinate is not finite", i);
            len += (double)nrm[3 * i + a] * nrm[3 * i + a];
        }
        if (!(len > 1e-24)) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "point %zu: the normal is zero", i);
        if (radii && !(radii[i] > 0 && isfinite(radii[i])))
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "point %zu: the radius must be > 0, got %g", i,
                                (double)radii[i]);
    }
    return LUCENT_OK;
}

lucent_status lucent_surfels_from_points(size_t count, const float *pos, const float *nrm, const float *radii,
                                         const float *colors, const lucent_surfels_desc *desc, lucent_surfels **dest)
{
    *dest = NULL;
    lucent_surfels_desc d = desc ? *desc : (lucent_surfels_desc){0};
    if (!d.neighbours) d.neighbours = LUCENT_SURFEL_DEFAULT_K;
    if (!d.decimation) d.decimation = 2;
    if (!d.min_count) d.min_count = 64;
    if (!d.max_levels) d.max_levels = LUCENT_SURFEL_MAX_LEVELS;
    if (d.neighbours < 1 || d.neighbours > KNN_MAX || !(d.decimation > 1) || d.max_levels < 0)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "surfels: neighbours must be in [1, %d] and decimation > 1 (got %d, %g)", KNN_MAX,
                            d.neighbours, d.decimation);
    lucent_status st = check_points(count, pos, nrm, radii, colors);
    if (st != LUCENT_OK) return st;
    lucent_surfels *s = calloc(1, sizeof *s);
    if (!s) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    st = grow(s, count, colors != NULL);
    if (st == LUCENT_OK) {
        s->count = count, s->level_count = 1;
        s->levels[0] = (lucent_surfel_level){0, count, 0};
        memcpy(s->positions, pos, 3 * count * sizeof *pos);
        for (size_t i = 0; i < count; i++) {
            const float *n = nrm + 3 * i;
            double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
            for (int a = 0; a < 3; a++) s->normals[3 * i + a] = (float)(n[a] / len);
            s->parent[i] = UINT32_MAX, s->child_start[i] = 0;
        }
        s->child_start[count] = 0;
        if (colors) memcpy(s->colors, colors, 3 * count * sizeof *colors);
        s->radii_given = radii != NULL;
        if (radii)
            memcpy(s->radii, radii, count * sizeof *radii);
        else
            st = knn_radii(s->positions, count, d.neighbours < (int)count ? d.neighbours : (int)count - 1, d.pool,
                           s->radii);
    }
    if (st == LUCENT_OK) s->levels[0].spacing = median(s->radii, count) / sqrt(2.0);
    while (st == LUCENT_OK && s->level_count < d.max_levels && s->level_count < LUCENT_SURFEL_MAX_LEVELS &&
           s->levels[s->level_count - 1].count >= d.min_count) {
        size_t added = 0, before = s->levels[s->level_count - 1].count;
        st = decimate(s, s->level_count - 1, d.decimation, d.neighbours, d.pool, &added);
        if (st == LUCENT_OK) s->level_count++;
        if (added * 10 > before * 9) break; /* no longer shrinking */
    }
    /* child_start of level 0 (empty ranges): after the loop, since decimate writes its own. */
    if (st != LUCENT_OK) {
        lucent_surfels_destroy(s);
        return st;
    }
    *dest = s;
    return LUCENT_OK;
}

lucent_status lucent_surfels_from_mesh(const lucent_mesh *m, const lucent_surfels_desc *desc, lucent_surfels **dest)
{
    *dest = NULL;
    size_t n = 0;
    float *pos = malloc(3 * m->vertex_count * sizeof *pos), *nrm = malloc(3 * m->vertex_count * sizeof *nrm);
    if (!pos || !nrm) {
        free(pos), free(nrm);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory (surfels of %zu vertices)", m->vertex_count);
    }
    for (size_t v = 0; v < m->vertex_count; v++) {
        const double *q = m->normals + 3 * v;
        if (q[0] == 0 && q[1] == 0 && q[2] == 0) continue;
        for (int a = 0; a < 3; a++) pos[3 * n + a] = (float)m->positions[3 * v + a], nrm[3 * n + a] = (float)q[a];
        n++;
    }
    lucent_status s = lucent_surfels_from_points(n, pos, nrm, NULL, NULL, desc, dest);
    free(pos), free(nrm);
    return s;
}

void lucent_surfels_transform(lucent_surfels *sf, const double m[16])
{
    /* the cofactor matrix C of the linear part: M^-T = C / det, so normals go by C (times det's sign) */
    double a = m[0], b = m[4], c = m[8], d = m[1], e = m[5], f = m[9], g = m[2], h = m[6], k = m[10];
    double C[3][3] = {{e * k - f * h, -(d * k - f * g), d * h - e * g},
                      {-(b * k - c * h), a * k - c * g, -(a * h - b * g)},
                      {b * f - c * e, -(a * f - c * d), a * e - b * d}};
    double det = a * C[0][0] + b * C[0][1] + c * C[0][2], scale = cbrt(fabs(det)), sign = det < 0 ? -1 : 1;
    for (size_t i = 0; i < sf->count; i++) {
        float *p = sf->positions + 3 * i, *n = sf->normals + 3 * i;
        double q[3], r[3], len = 0;
        for (int j = 0; j < 3; j++) q[j] = m[j] * p[0] + m[4 + j] * p[1] + m[8 + j] * p[2] + m[12 + j];
        for (int j = 0; j < 3; j++)
            r[j] = sign * (C[j][0] * n[0] + C[j][1] * n[1] + C[j][2] * n[2]), len += r[j] * r[j];
        len = sqrt(len);
        for (int j = 0; j < 3; j++) p[j] = (float)q[j], n[j] = len > 0 ? (float)(r[j] / len) : n[j];
        sf->radii[i] = (float)(sf->radii[i] * scale);
    }
    for (int l = 0; l < sf->level_count; l++) sf->levels[l].spacing *= scale;
}
