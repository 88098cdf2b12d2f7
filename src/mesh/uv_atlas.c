/* Texture atlases for meshes without texture coordinates (the Stanford scans), for texture-space
 * diffusion (d'Eon, Luebke & Enderton 2007), and the measures of any mesh's coordinates.
 *
 * Charts: region growing over edge-adjacent faces from a seed, keeping faces whose normal lies
 * within max_angle of the seed's (a normal cone), each chart projected onto the plane of its seed's
 * normal. A face joins only when its projected triangle overlaps no triangle of the chart already
 * there (a separating-axis test through a hash grid), so no chart overlaps itself by construction;
 * the projection's stretch is bounded by 1 / cos(max_angle) across the slope and 1 along it.
 * Packing: each chart turned to its smallest bounding box (angles in 5 degree steps), then shelves
 * in decreasing height, the boxes grown by the gutter, the square side grown until the shelves fit:
 * charts never share a texel and stand gutter texels apart at texture_size. Why not LSCM: it lowers
 * stretch, but can fold and needs a per-chart solver; with the cone bound the planar stretch is
 * already low (docs/tsd.md gives the figures) and the stretch maps of TSD correct what remains. */
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "base/optics.h"
#include "lucent/image.h"
#include "mesh/internal.h"

/* ---- face adjacency through sorted edge keys ---- */

typedef struct edge_key {
    uint64_t key;
    uint32_t slot; /* 3 f + k: the edge from corner k to k + 1 of face f */
} edge_key;

static int cmp_edge(const void *a, const void *b)
{
    const edge_key *x = a, *y = b;
    return x->key < y->key ? -1 : x->key > y->key ? 1 : (x->slot > y->slot) - (x->slot < y->slot);
}

/* The face across each edge slot (internal.h). */
lucent_status mesh_face_neighbours(const lucent_mesh *m, uint32_t *next)
{
    size_t n = 3 * m->face_count;
    edge_key *e = malloc((n + 1) * sizeof *e);
    if (!e) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory for the atlas");
    for (size_t i = 0; i < n; i++) {
        uint64_t a = m->faces[i], b = m->faces[i - i % 3 + (i + 1) % 3];
        e[i].key = a < b ? a << 32 | b : b << 32 | a, e[i].slot = (uint32_t)i;
    }
    qsort(e, n, sizeof *e, cmp_edge);
    for (size_t i = 0; i < n; i++) next[i] = UINT32_MAX;
    for (size_t i = 0; i < n;) {
        size_t j = i;
        while (j < n && e[j].key == e[i].key) j++;
        if (j - i == 2) next[e[i].slot] = e[i + 1].slot / 3, next[e[i + 1].slot] = e[i].slot / 3;
        i = j;
    }
    free(e);
    return LUCENT_OK;
}

/* ---- a chart's projected triangles in a hash grid ---- */

typedef struct tri2 {
    double p[3][2];
} tri2;

typedef struct grid {
    double h;          /* cell size */
    size_t cap;        /* slots, a power of two */
    uint64_t *key;     /* cell key + 1, 0: empty */
    int32_t *head;     /* first entry of the cell */
    uint32_t *touched; /* slots used by this chart (cleared between charts) */
    size_t touched_count;
    uint32_t *ent_face; /* entries: face and next entry in the cell */
    int32_t *ent_next;
    size_t ent_count, ent_cap;
} grid;

static uint64_t cell_key(int64_t x, int64_t y)
{
    return ((uint64_t)(x + (1 << 30)) << 32 | (uint64_t)(y + (1 << 30))) + 1;
}

static size_t cell_slot(const grid *g, uint64_t key, bool *found)
{
    uint64_t h = key * 0x9E3779B97F4A7C15ull;
    size_t s = (size_t)(h >> 20) & (g->cap - 1);
    while (g->key[s] && g->key[s] != key) s = (s + 1) & (g->cap - 1);
    *found = g->key[s] == key;
    return s;
}

static void grid_clear(grid *g)
{
    for (size_t i = 0; i < g->touched_count; i++) g->key[g->touched[i]] = 0;
    g->touched_count = 0, g->ent_count = 0;
}

static void tri_box(const tri2 *t, double lo[2], double hi[2])
{
    for (int i = 0; i < 2; i++) {
        lo[i] = fmin(t->p[0][i], fmin(t->p[1][i], t->p[2][i]));
        hi[i] = fmax(t->p[0][i], fmax(t->p[1][i], t->p[2][i]));
    }
}

/* Interiors overlap: no edge normal of either triangle separates them (by more than eps). */
static bool tri_overlap(const tri2 *a, const tri2 *b, double eps)
{
    const tri2 *t[2] = {a, b};
    for (int w = 0; w < 2; w++)
        for (int k = 0; k < 3; k++) {
            const double *p = t[w]->p[k], *q = t[w]->p[(k + 1) % 3];
            double ax = q[1] - p[1], ay = p[0] - q[0], len = hypot(ax, ay);
            if (!(len > 0)) continue;
            double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
            for (int s = 0; s < 2; s++)
                for (int j = 0; j < 3; j++) {
                    double d = (ax * t[s]->p[j][0] + ay * t[s]->p[j][1]) / len;
                    lo[s] = fmin(lo[s], d), hi[s] = fmax(hi[s], d);
                }
            if (hi[0] <= lo[1] + eps || hi[1] <= lo[0] + eps) return false;
        }
    return true;
}

/* Calls the cells of t's box: query (returns true on an overlap) or insert face f. */
static bool grid_visit(grid *g, const tri2 *t, uint32_t f, bool insert, const tri2 *proj, double eps)
{
    double lo[2], hi[2];
    tri_box(t, lo, hi);
    int64_t x0 = (int64_t)floor(lo[0] / g->h), x1 = (int64_t)floor(hi[0] / g->h);
    int64_t y0 = (int64_t)floor(lo[1] / g->h), y1 = (int64_t)floor(hi[1] / g->h);
    for (int64_t x = x0; x <= x1; x++)
        for (int64_t y = y0; y <= y1; y++) {
            bool found;
            uint64_t key = cell_key(x, y);
            size_t s = cell_slot(g, key, &found);
            if (!insert) {
                for (int32_t e = found ? g->head[s] : -1; e >= 0; e = g->ent_next[e])
                    if (tri_overlap(t, &proj[g->ent_face[e]], eps)) return true;
                continue;
            }
            if (!found) g->key[s] = key, g->head[s] = -1, g->touched[g->touched_count++] = (uint32_t)s;
            g->ent_face[g->ent_count] = f, g->ent_next[g->ent_count] = g->head[s];
            g->head[s] = (int32_t)g->ent_count++;
        }
    return false;
}

static size_t box_cells(const grid *g, const tri2 *t)
{
    double lo[2], hi[2];
    tri_box(t, lo, hi);
    return (size_t)((floor(hi[0] / g->h) - floor(lo[0] / g->h) + 1) * (floor(hi[1] / g->h) - floor(lo[1] / g->h) + 1));
}

/* ---- segmentation ---- */

typedef struct atlas_work {
    const lucent_mesh *m;
    v3 *normal;      /* unit face normals (zero: degenerate) */
    uint32_t *next;  /* face across each edge slot */
    int32_t *chart;  /* per face */
    uint32_t *order; /* faces chart by chart */
    uint32_t *chart_start;
    int chart_count;
    tri2 *proj; /* each face in its chart's plane */
    grid g;
} atlas_work;

static void project(const atlas_work *w, uint32_t f, v3 t, v3 b, tri2 *dest)
{
    for (int k = 0; k < 3; k++) {
        v3 p = v3_load(w->m->positions + 3 * w->m->faces[3 * f + k]);
        dest->p[k][0] = v3_dot(p, t), dest->p[k][1] = v3_dot(p, b);
    }
}

static bool grow_ok(atlas_work *w, uint32_t f, v3 n, double cos_max, v3 t, v3 b, double eps)
{
    if (w->chart[f] >= 0 || v3_dot(w->normal[f], n) < cos_max) return false;
    project(w, f, t, b, &w->proj[f]);
    if (box_cells(&w->g, &w->proj[f]) > 64) return false; /* a sliver across the chart: its own chart */
    return !grid_visit(&w->g, &w->proj[f], f, false, w->proj, eps);
}

static lucent_status segment(atlas_work *w, double max_angle)
{
    const lucent_mesh *m = w->m;
    double cos_max = cos(max_angle * M_PI / 180), edge = 0;
    for (size_t f = 0; f < m->face_count; f++) {
        v3 p[3];
        for (int k = 0; k < 3; k++) p[k] = v3_load(m->positions + 3 * m->faces[3 * f + k]);
        v3 c = v3_cross(v3_sub(p[1], p[0]), v3_sub(p[2], p[0]));
        w->normal[f] = v3_normalize(c);
        edge += v3_length(v3_sub(p[1], p[0]));
        w->chart[f] = -1;
    }
    w->g.h = fmax(2 * edge / (double)m->face_count, 1e-300);
    double eps = 1e-9 * w->g.h;
    size_t done = 0;
    w->chart_count = 0;
    for (size_t seed = 0; seed < m->face_count; seed++) {
        if (w->chart[seed] >= 0) continue;
        v3 n = w->normal[seed], t, b;
        if (v3_dot(n, n) == 0) n = v3_make(0, 0, 1);
        lucent_basis(n, &t, &b);
        int c = w->chart_count++;
        w->chart_start[c] = (uint32_t)done;
        grid_clear(&w->g);
        w->chart[seed] = c, w->order[done++] = (uint32_t)seed;
        project(w, (uint32_t)seed, t, b, &w->proj[seed]);
        /* a degenerate face or a sliver across many cells: a chart of its own */
        if (v3_dot(w->normal[seed], w->normal[seed]) == 0 || box_cells(&w->g, &w->proj[seed]) > 64) continue;
        grid_visit(&w->g, &w->proj[seed], (uint32_t)seed, true, w->proj, eps);
        for (size_t q = w->chart_start[c]; q < done; q++) { /* breadth first: compact charts */
            uint32_t f = w->order[q];
            for (int k = 0; k < 3; k++) {
                uint32_t g = w->next[3 * f + (uint32_t)k];
                if (g == UINT32_MAX || !grow_ok(w, g, n, cos_max, t, b, eps)) continue;
                if (w->g.ent_count + 64 > w->g.ent_cap || 2 * (w->g.touched_count + 64) > w->g.cap) continue;
                w->chart[g] = c, w->order[done++] = g;
                grid_visit(&w->g, &w->proj[g], g, true, w->proj, eps);
            }
        }
    }
    w->chart_start[w->chart_count] = (uint32_t)done;
    return LUCENT_OK;
}

/* ---- packing ---- */

typedef struct chart_box {
    int chart;
    double angle, lo[2], size[2]; /* after turning by angle */
    double at[2];                 /* packed position of lo */
} chart_box;

static void turned_box(const atlas_work *w, int c, double angle, double lo[2], double size[2])
{
    double cs = cos(angle), sn = sin(angle), hi[2] = {-INFINITY, -INFINITY};
    lo[0] = lo[1] = INFINITY;
    for (uint32_t q = w->chart_start[c]; q < w->chart_start[c + 1]; q++)
        for (int k = 0; k < 3; k++) {
            const double *p = w->proj[w->order[q]].p[k];
            double x = cs * p[0] - sn * p[1], y = sn * p[0] + cs * p[1];
            lo[0] = fmin(lo[0], x), lo[1] = fmin(lo[1], y), hi[0] = fmax(hi[0], x), hi[1] = fmax(hi[1], y);
        }
    size[0] = hi[0] - lo[0], size[1] = hi[1] - lo[1];
}

static int cmp_height(const void *a, const void *b)
{
    const chart_box *x = a, *y = b;
    if (x->size[1] != y->size[1]) return x->size[1] < y->size[1] ? 1 : -1;
    return (x->chart > y->chart) - (x->chart < y->chart);
}

/* Shelves of width side, boxes grown by gap; the height used. */
static double shelves(chart_box *box, int n, double side, double gap)
{
    double x = 0, y = 0, shelf = 0;
    for (int i = 0; i < n; i++) {
        double bw = box[i].size[0] + gap, bh = box[i].size[1] + gap;
        if (x > 0 && x + bw > side) y += shelf, x = 0, shelf = 0;
        box[i].at[0] = x + 0.5 * gap, box[i].at[1] = y + 0.5 * gap;
        x += bw, shelf = fmax(shelf, bh);
    }
    return y + shelf;
}

static lucent_status pack(atlas_work *w, const lucent_uv_atlas_desc *d, lucent_mesh *mesh)
{
    int n = w->chart_count;
    chart_box *box = malloc((size_t)n * sizeof *box + 1);
    if (!box) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory for the atlas");
    double area = 0, largest = 0;
    for (int c = 0; c < n; c++) {
        chart_box *bx = &box[c];
        bx->chart = c, bx->size[0] = bx->size[1] = INFINITY;
        for (int a = 0; a < 18; a++) {
            double lo[2], size[2], angle = a * 5 * M_PI / 180;
            turned_box(w, c, angle, lo, size);
            if (size[0] * size[1] < bx->size[0] * bx->size[1] || a == 0)
                bx->angle = angle, memcpy(bx->lo, lo, sizeof lo), memcpy(bx->size, size, sizeof size);
        }
        if (bx->size[1] > bx->size[0]) { /* lying down: lower shelves */
            bx->angle += 0.5 * M_PI;
            turned_box(w, c, bx->angle, bx->lo, bx->size);
        }
        area += bx->size[0] * bx->size[1], largest = fmax(largest, fmax(bx->size[0], bx->size[1]));
    }
    qsort(box, (size_t)n, sizeof *box, cmp_height);
    double g = d->gutter / d->texture_size; /* gutter as a fraction of the side */
    double side = fmax(sqrt(area), largest) / (1 - 2 * g), gap = 0;
    for (int it = 0; it < 2000; it++) {
        gap = g * side;
        if (largest + gap <= side && shelves(box, n, side, gap) <= side) break;
        side *= 1.01;
    }
    for (int i = 0; i < n; i++) {
        const chart_box *bx = &box[i];
        double cs = cos(bx->angle), sn = sin(bx->angle);
        for (uint32_t q = w->chart_start[bx->chart]; q < w->chart_start[bx->chart + 1]; q++) {
            uint32_t f = w->order[q];
            for (int k = 0; k < 3; k++) {
                const double *p = w->proj[f].p[k];
                double x = cs * p[0] - sn * p[1] - bx->lo[0], y = sn * p[0] + cs * p[1] - bx->lo[1];
                mesh->uvs[6 * f + 2 * k] = (bx->at[0] + x) / side;
                mesh->uvs[6 * f + 2 * k + 1] = (bx->at[1] + y) / side;
            }
        }
    }
    free(box);
    return LUCENT_OK;
}

lucent_status lucent_mesh_uv_atlas(lucent_mesh *mesh, const lucent_uv_atlas_desc *desc, lucent_uv_stats *stats)
{
    lucent_uv_atlas_desc d = desc ? *desc : (lucent_uv_atlas_desc){0};
    if (!(d.max_angle > 0)) d.max_angle = LUCENT_UV_ATLAS_ANGLE;
    if (d.texture_size <= 0) d.texture_size = LUCENT_UV_ATLAS_TEXTURE;
    if (!(d.gutter > 0)) d.gutter = LUCENT_UV_ATLAS_GUTTER;
    if (d.max_angle >= 90 || d.gutter * 4 >= d.texture_size)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "atlas: max_angle must be below 90 degrees and the gutter "
                                                         "below a quarter of the texture");
    if (mesh->face_count == 0) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "atlas: the mesh has no faces");
    size_t nf = mesh->face_count, cap = 64;
    while (cap < 8 * nf) cap *= 2;
    atlas_work w = {.m = mesh};
    w.normal = malloc(nf * sizeof *w.normal);
    w.next = malloc(3 * nf * sizeof *w.next);
    w.chart = malloc(nf * sizeof *w.chart);
    w.order = malloc(nf * sizeof *w.order);
    w.chart_start = malloc((nf + 1) * sizeof *w.chart_start);
    w.proj = malloc(nf * sizeof *w.proj);
    w.g.cap = cap, w.g.ent_cap = 4 * nf + 64;
    w.g.key = calloc(cap, sizeof *w.g.key);
    w.g.head = malloc(cap * sizeof *w.g.head);
    w.g.touched = malloc(cap * sizeof *w.g.touched);
    w.g.ent_face = malloc(w.g.ent_cap * sizeof *w.g.ent_face);
    w.g.ent_next = malloc(w.g.ent_cap * sizeof *w.g.ent_next);
    double *uvs = malloc(6 * nf * sizeof *uvs);
    lucent_status s = w.normal && w.next && w.chart && w.order && w.chart_start && w.proj && w.g.key && w.g.head &&
                              w.g.touched && w.g.ent_face && w.g.ent_next && uvs
                          ? LUCENT_OK
                          : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory for the atlas");
    if (s == LUCENT_OK) s = mesh_face_neighbours(mesh, w.next);
    if (s == LUCENT_OK) s = segment(&w, d.max_angle);
    double *old = mesh->uvs;
    if (s == LUCENT_OK) mesh->uvs = uvs, uvs = old, s = pack(&w, &d, mesh);
    if (s != LUCENT_OK && mesh->uvs != old) uvs = mesh->uvs, mesh->uvs = old; /* unchanged on failure */
    if (s == LUCENT_OK && stats) {
        s = lucent_mesh_uv_stats_compute(mesh, stats);
        stats->chart_count = w.chart_count;
    }
    free(uvs);
    free(w.normal), free(w.next), free(w.chart), free(w.order), free(w.chart_start), free(w.proj);
    free(w.g.key), free(w.g.head), free(w.g.touched), free(w.g.ent_face), free(w.g.ent_next);
    return s;
}

/* ---- measures ---- */

lucent_status lucent_mesh_uv_stats_compute(const lucent_mesh *m, lucent_uv_stats *dest)
{
    *dest = (lucent_uv_stats){0};
    if (!m->uvs) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "the mesh has no texture coordinates");
    /* Sander, Snyder, Gortler & Hoppe 2001, Eq. 2-3: S_s, S_t the partial derivatives of the map from
     * texture to surface, a = S_s.S_s, b = S_s.S_t, c = S_t.S_t, L2 = sqrt((a + c) / 2),
     * Linf = sqrt((a + c + sqrt((a - c)^2 + 4 b^2)) / 2); the mesh's L2 the area-weighted root mean
     * square, both scaled by sqrt(area_2d / area_3d) so that 1 is an isometry up to scale. */
    double sum2 = 0, a3 = 0, a2 = 0, worst = 0, lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t f = 0; f < m->face_count; f++) {
        const double *t = m->uvs + 6 * f;
        v3 q[3];
        for (int k = 0; k < 3; k++) q[k] = v3_load(m->positions + 3 * m->faces[3 * f + k]);
        double area3 = 0.5 * v3_length(v3_cross(v3_sub(q[1], q[0]), v3_sub(q[2], q[0])));
        double area2 = 0.5 * ((t[2] - t[0]) * (t[5] - t[1]) - (t[4] - t[0]) * (t[3] - t[1]));
        for (int k = 0; k < 3; k++)
            lo[0] = fmin(lo[0], t[2 * k]), hi[0] = fmax(hi[0], t[2 * k]), lo[1] = fmin(lo[1], t[2 * k + 1]),
            hi[1] = fmax(hi[1], t[2 * k + 1]);
        if (!(area3 > 0)) continue;
        if (!(fabs(area2) > 0)) {
            dest->degenerate_faces++;
            continue;
        }
        v3 ss = v3_scale(
            v3_add(v3_add(v3_scale(q[0], t[3] - t[5]), v3_scale(q[1], t[5] - t[1])), v3_scale(q[2], t[1] - t[3])),
            1 / (2 * area2));
        v3 st = v3_scale(
            v3_add(v3_add(v3_scale(q[0], t[4] - t[2]), v3_scale(q[1], t[0] - t[4])), v3_scale(q[2], t[2] - t[0])),
            1 / (2 * area2));
        double a = v3_dot(ss, ss), b = v3_dot(ss, st), c = v3_dot(st, st);
        sum2 += area3 * 0.5 * (a + c), a3 += area3, a2 += fabs(area2);
        worst = fmax(worst, sqrt(0.5 * (a + c + sqrt((a - c) * (a - c) + 4 * b * b))));
        if (area2 < 0) dest->flipped_faces++;
    }
    double norm = a3 > 0 ? sqrt(a2 / a3) : 0;
    dest->stretch_l2 = a3 > 0 ? sqrt(sum2 / a3) * norm : 0;
    dest->stretch_max = worst * norm;
    dest->uv_area = a2;
    for (int i = 0; i < 2; i++) dest->uv_min[i] = lo[i], dest->uv_max[i] = hi[i];
    return LUCENT_OK;
}

/* The texel centres of a size x size raster of [0, 1]^2 strictly inside face f (by inset texels),
 * each given to fn. */
static void raster_face(const lucent_mesh *m, size_t f, int size, double inset, void (*fn)(void *, size_t, size_t),
                        void *ctx)
{
    const double *t = m->uvs + 6 * f;
    double p[3][2];
    for (int k = 0; k < 3; k++) p[k][0] = t[2 * k] * size, p[k][1] = t[2 * k + 1] * size;
    double area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
    if (!(fabs(area) > 0)) return;
    double sgn = area > 0 ? 1 : -1;
    int x0 = (int)fmax(0, floor(fmin(p[0][0], fmin(p[1][0], p[2][0])))),
        x1 = (int)fmin(size - 1, ceil(fmax(p[0][0], fmax(p[1][0], p[2][0]))));
    int y0 = (int)fmax(0, floor(fmin(p[0][1], fmin(p[1][1], p[2][1])))),
        y1 = (int)fmin(size - 1, ceil(fmax(p[0][1], fmax(p[1][1], p[2][1]))));
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            double cx = x + 0.5, cy = y + 0.5;
            bool in = true;
            for (int k = 0; k < 3 && in; k++) {
                const double *a = p[k], *b = p[(k + 1) % 3];
                double ex = b[0] - a[0], ey = b[1] - a[1], len = hypot(ex, ey);
                double e = sgn * (ex * (cy - a[1]) - ey * (cx - a[0]));
                in = len > 0 && e > inset * len;
            }
            if (in) fn(ctx, (size_t)x, (size_t)y);
        }
}

typedef struct count_ctx {
    uint16_t *count;
    size_t size;
} count_ctx;

static void count_texel(void *ctx, size_t x, size_t y)
{
    count_ctx *c = ctx;
    if (c->count[y * c->size + x] < UINT16_MAX) c->count[y * c->size + x]++;
}

lucent_status lucent_mesh_uv_overlaps(const lucent_mesh *m, int size, size_t *overlapping, size_t *covered)
{
    if (!m->uvs) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "the mesh has no texture coordinates");
    if (size < 1 || size > 16384) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "raster size must be 1..16384");
    count_ctx c = {calloc((size_t)size * (size_t)size, sizeof *c.count), (size_t)size};
    if (!c.count) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (size_t f = 0; f < m->face_count; f++) raster_face(m, f, size, 1e-3, count_texel, &c);
    size_t over = 0, cov = 0;
    for (size_t i = 0; i < (size_t)size * (size_t)size; i++) over += c.count[i] > 1, cov += c.count[i] > 0;
    free(c.count);
    if (overlapping) *overlapping = over;
    if (covered) *covered = cov;
    return LUCENT_OK;
}

/* ---- charts as UV-connected components, and their picture ---- */

static uint32_t find(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
}

static bool same_uv(const double *a, const double *b) { return a[0] == b[0] && a[1] == b[1]; }

lucent_status lucent_mesh_uv_charts(const lucent_mesh *m, uint32_t *chart, size_t *count)
{
    if (!m->uvs) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "the mesh has no texture coordinates");
    uint32_t *next = malloc((3 * m->face_count + 1) * sizeof *next);
    if (!next) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    lucent_status s = mesh_face_neighbours(m, next);
    for (size_t f = 0; f < m->face_count; f++) chart[f] = (uint32_t)f;
    for (size_t i = 0; s == LUCENT_OK && i < 3 * m->face_count; i++) {
        uint32_t g = next[i], f = (uint32_t)(i / 3), k = (uint32_t)(i % 3);
        if (g == UINT32_MAX || g < f) continue;
        uint32_t a = m->faces[i], b = m->faces[3 * f + (k + 1) % 3];
        const double *ua = NULL, *ub = NULL;
        for (int j = 0; j < 3; j++) {
            if (m->faces[3 * g + (uint32_t)j] == a) ua = m->uvs + 6 * g + 2 * j;
            if (m->faces[3 * g + (uint32_t)j] == b) ub = m->uvs + 6 * g + 2 * j;
        }
        if (ua && ub && same_uv(ua, m->uvs + 6 * f + 2 * k) && same_uv(ub, m->uvs + 6 * f + 2 * ((k + 1) % 3)))
            chart[find(chart, f)] = find(chart, g);
    }
    size_t n = 0;
    for (size_t f = 0; s == LUCENT_OK && f < m->face_count; f++) {
        uint32_t r = find(chart, (uint32_t)f);
        if (r == f) next[f] = (uint32_t)n++;
    }
    for (size_t f = 0; s == LUCENT_OK && f < m->face_count; f++) chart[f] = find(chart, (uint32_t)f);
    for (size_t f = 0; s == LUCENT_OK && f < m->face_count; f++) chart[f] = next[chart[f]];
    free(next);
    if (count) *count = n;
    return s;
}

typedef struct paint_ctx {
    lucent_image *img;
    float rgb[3];
} paint_ctx;

static void paint_texel(void *ctx, size_t x, size_t y)
{
    paint_ctx *c = ctx;
    float *px = c->img->data + 3 * ((size_t)(c->img->height - 1 - (int)y) * (size_t)c->img->width + x); /* v up */
    memcpy(px, c->rgb, sizeof c->rgb);
}

lucent_status lucent_mesh_uv_paint(const lucent_mesh *m, int size, lucent_image **dest)
{
    *dest = NULL;
    if (!m->uvs) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "the mesh has no texture coordinates");
    uint32_t *chart = malloc((m->face_count + 1) * sizeof *chart);
    if (!chart) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    lucent_status s = lucent_mesh_uv_charts(m, chart, NULL);
    if (s == LUCENT_OK) s = lucent_image_create(size, size, 3, dest);
    for (size_t i = 0; s == LUCENT_OK && i < (size_t)size * (size_t)size * 3; i++) (*dest)->data[i] = 0.02f;
    for (size_t f = 0; s == LUCENT_OK && f < m->face_count; f++) {
        /* a chart's colour from a hash of its index, shaded by the face's facing (z of its normal) */
        uint64_t h = (chart[f] + 1) * 0x9E3779B97F4A7C15ull;
        v3 q[3];
        for (int k = 0; k < 3; k++) q[k] = v3_load(m->positions + 3 * m->faces[3 * f + k]);
        v3 n = v3_normalize(v3_cross(v3_sub(q[1], q[0]), v3_sub(q[2], q[0])));
        float shade = (float)(0.75 + 0.25 * n.z);
        paint_ctx c = {*dest, {0}};
        for (int i = 0; i < 3; i++) c.rgb[i] = shade * (0.15f + 0.85f * (float)((h >> (16 * i + 8)) & 255) / 255.0f);
        raster_face(m, f, size, 0, paint_texel, &c);
    }
    free(chart);
    if (s != LUCENT_OK) lucent_image_destroy(*dest), *dest = NULL;
    return s;
}

/* ---- seams split for the GPU and glTF ---- */

lucent_status lucent_mesh_uv_split(const lucent_mesh *m, lucent_uv_split *dest)
{
    *dest = (lucent_uv_split){0};
    if (!m->uvs) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "the mesh has no texture coordinates");
    size_t nc = 3 * m->face_count, cap = 64;
    while (cap < 2 * nc) cap *= 2;
    uint32_t *slot = malloc(cap * sizeof *slot);
    dest->vertex = malloc((nc + 1) * sizeof *dest->vertex);
    dest->uv = malloc((2 * nc + 1) * sizeof *dest->uv);
    dest->faces = malloc((nc + 1) * sizeof *dest->faces);
    if (!slot || !dest->vertex || !dest->uv || !dest->faces) {
        free(slot), lucent_uv_split_free(dest);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory splitting texture seams");
    }
    memset(slot, 0xff, cap * sizeof *slot);
    size_t n = 0;
    for (size_t i = 0; i < nc; i++) {
        uint32_t v = m->faces[i];
        const double *uv = m->uvs + 2 * i;
        uint64_t bits[2];
        memcpy(bits, uv, sizeof bits);
        uint64_t h = ((v * 0x9E3779B97F4A7C15ull) ^ bits[0]) * 0xBF58476D1CE4E5B9ull ^ bits[1];
        size_t s = (size_t)(h * 0x94D049BB133111EBull >> 17) & (cap - 1);
        while (slot[s] != UINT32_MAX && !(dest->vertex[slot[s]] == v && same_uv(dest->uv + 2 * slot[s], uv)))
            s = (s + 1) & (cap - 1);
        if (slot[s] == UINT32_MAX) {
            slot[s] = (uint32_t)n, dest->vertex[n] = v;
            memcpy(dest->uv + 2 * n, uv, 2 * sizeof *uv), n++;
        }
        dest->faces[i] = slot[s];
    }
    free(slot);
    dest->count = n;
    return LUCENT_OK;
}

void lucent_uv_split_free(lucent_uv_split *s)
{
    free(s->vertex), free(s->uv), free(s->faces);
    *s = (lucent_uv_split){0};
}
