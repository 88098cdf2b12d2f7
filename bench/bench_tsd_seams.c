/* Seam visibility of texture-space diffusion (issue 14, acceptance: "seams invisible in the diffused
 * result"). Renders the scene with tsd (seams followed, and tsd_seams=false: each chart blurred alone)
 * and ssss:svd3, and compares the two tsd images with ssss's pixel by pixel, binned by the distance
 * (texels) of the pixel's texel to the nearest seam of tsd's atlas: sum(tsd - ssss) / sum(ssss), signed
 * and absolute. A seam line (darker or brighter than the chart around it) shows as a step in the first
 * bins against the next; ssss has no seams. The pixel's surface point comes from the renderer's position output, its face is the
 * nearest one (a grid of the faces), its texel the face's coordinates there, in the atlas tsd makes
 * (lucent_mesh_uv_atlas at tsd_size, the call tsd.c makes). Anchor: ssss:svd3 of the same frame.
 * Only pixels facing the camera (n.v >= 0.5) count. Usage: bench_tsd_seams [SCENE.json] [SIZE_PX] [OVERLAY.png] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_cache.h"
#include "gl/renderer.h"
#include "lucent/render.h"
#include "mesh/internal.h"

static void fail(const char *what)
{
    fprintf(stderr, "bench_tsd_seams: %s: %s\n", what, lucent_last_error());
    exit(1);
}

/* ---- the seam band in texture space ---- */

static const double *corner(const lucent_mesh *m, size_t f, uint32_t v)
{
    for (int k = 0; k < 3; k++)
        if (m->faces[3 * f + (size_t)k] == v) return m->uvs + 6 * f + 2 * k;
    return NULL;
}

static void mark_segment(float *b, int size, const double *p, const double *q, double band)
{
    double ax = p[0] * size, ay = p[1] * size, bx = q[0] * size, by = q[1] * size;
    double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
    int x0 = (int)fmax(0, floor(fmin(ax, bx) - band)), x1 = (int)fmin(size - 1, ceil(fmax(ax, bx) + band));
    int y0 = (int)fmax(0, floor(fmin(ay, by) - band)), y1 = (int)fmin(size - 1, ceil(fmax(ay, by) + band));
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            double px = x + 0.5 - ax, py = y + 0.5 - ay, t = l2 > 0 ? fmin(fmax((px * dx + py * dy) / l2, 0), 1) : 0;
            float d = (float)hypot(px - t * dx, py - t * dy), *at = b + (size_t)y * (size_t)size + (size_t)x;
            if (d < *at) *at = d;
        }
}

/* Per texel the distance of its centre to the nearest seam edge (its two faces give its corners
 * different coordinates), in texels, up to `band` (beyond: band). */
static float *seam_distance(const lucent_mesh *m, int size, double band, size_t *seam_edges)
{
    float *b = malloc((size_t)size * (size_t)size * sizeof *b);
    for (size_t i = 0; b && i < (size_t)size * (size_t)size; i++) b[i] = (float)band;
    uint32_t *next = malloc(3 * m->face_count * sizeof *next);
    if (!b || !next || mesh_face_neighbours(m, next) != LUCENT_OK) fail("seam band");
    *seam_edges = 0;
    for (size_t i = 0; i < 3 * m->face_count; i++) {
        size_t f = i / 3, g = next[i];
        if (g == UINT32_MAX) continue;
        uint32_t va = m->faces[i], vb = m->faces[3 * f + (i + 1) % 3];
        const double *pa = corner(m, f, va), *pb = corner(m, f, vb), *qa = corner(m, g, va), *qb = corner(m, g, vb);
        if (!qa || !qb || (pa[0] == qa[0] && pa[1] == qa[1] && pb[0] == qb[0] && pb[1] == qb[1])) continue;
        mark_segment(b, size, pa, pb, band);
        ++*seam_edges;
    }
    free(next);
    return b;
}

/* ---- pixel -> face: a grid of face bounding boxes ---- */

typedef struct face_grid {
    double lo[3], h;
    int n[3];
    uint32_t *start, *face;
} face_grid;

static int cell_of(const face_grid *g, const double *p, int a)
{
    int c = (int)floor((p[a] - g->lo[a]) / g->h);
    return c < 0 ? 0 : c >= g->n[a] ? g->n[a] - 1 : c;
}

static void grid_build(const lucent_mesh *m, face_grid *g)
{
    double hi[3] = {-INFINITY, -INFINITY, -INFINITY}, edge = 0;
    for (int a = 0; a < 3; a++) g->lo[a] = INFINITY;
    for (size_t v = 0; v < m->vertex_count; v++)
        for (int a = 0; a < 3; a++)
            g->lo[a] = fmin(g->lo[a], m->positions[3 * v + a]), hi[a] = fmax(hi[a], m->positions[3 * v + a]);
    for (size_t f = 0; f < m->face_count; f++)
        edge += v3_length(
            v3_sub(v3_load(m->positions + 3 * m->faces[3 * f]), v3_load(m->positions + 3 * m->faces[3 * f + 1])));
    g->h = 2 * edge / (double)m->face_count;
    for (int a = 0; a < 3; a++) g->n[a] = (int)((hi[a] - g->lo[a]) / g->h) + 1;
    size_t cells = (size_t)g->n[0] * (size_t)g->n[1] * (size_t)g->n[2];
    g->start = calloc(cells + 1, sizeof *g->start);
    g->face = malloc(m->face_count * sizeof *g->face);
    uint32_t *cell = malloc(m->face_count * sizeof *cell);
    if (!g->start || !g->face || !cell) fail("face grid");
    for (size_t f = 0; f < m->face_count; f++) {
        double c[3] = {0};
        for (int k = 0; k < 3; k++)
            for (int a = 0; a < 3; a++) c[a] += m->positions[3 * m->faces[3 * f + k] + a] / 3;
        cell[f] = (uint32_t)(((size_t)cell_of(g, c, 2) * g->n[1] + cell_of(g, c, 1)) * g->n[0] + cell_of(g, c, 0));
        g->start[cell[f] + 1]++;
    }
    for (size_t c = 0; c < cells; c++) g->start[c + 1] += g->start[c];
    uint32_t *fill = malloc((cells + 1) * sizeof *fill);
    memcpy(fill, g->start, (cells + 1) * sizeof *fill);
    for (size_t f = 0; f < m->face_count; f++) g->face[fill[cell[f]]++] = (uint32_t)f;
    free(fill), free(cell);
}

/* The texture coordinates of p on its nearest face (closest point on the triangle, Ericson 2005 5.1.5
 * by barycentric clamping in the plane). false: no face in the 27 cells about p. */
static bool uv_at(const lucent_mesh *m, const face_grid *g, const double *p, double uv[2])
{
    double best = INFINITY;
    int c[3];
    for (int a = 0; a < 3; a++) c[a] = cell_of(g, p, a);
    for (int z = c[2] - 1; z <= c[2] + 1; z++)
        for (int y = c[1] - 1; y <= c[1] + 1; y++)
            for (int x = c[0] - 1; x <= c[0] + 1; x++) {
                if (x < 0 || y < 0 || z < 0 || x >= g->n[0] || y >= g->n[1] || z >= g->n[2]) continue;
                size_t cell = ((size_t)z * g->n[1] + y) * g->n[0] + x;
                for (uint32_t i = g->start[cell]; i < g->start[cell + 1]; i++) {
                    uint32_t f = g->face[i];
                    v3 a = v3_load(m->positions + 3 * m->faces[3 * f]),
                       b = v3_load(m->positions + 3 * m->faces[3 * f + 1]);
                    v3 cc = v3_load(m->positions + 3 * m->faces[3 * f + 2]), q = v3_load(p);
                    v3 e0 = v3_sub(b, a), e1 = v3_sub(cc, a), d = v3_sub(q, a);
                    double d00 = v3_dot(e0, e0), d01 = v3_dot(e0, e1), d11 = v3_dot(e1, e1);
                    double d20 = v3_dot(d, e0), d21 = v3_dot(d, e1), den = d00 * d11 - d01 * d01;
                    if (!(fabs(den) > 0)) continue;
                    double s = (d11 * d20 - d01 * d21) / den, t = (d00 * d21 - d01 * d20) / den;
                    s = fmax(s, 0), t = fmax(t, 0);
                    if (s + t > 1) s /= s + t, t = 1 - s;
                    v3 cp = v3_add(a, v3_add(v3_scale(e0, s), v3_scale(e1, t)));
                    double dist = v3_length(v3_sub(cp, q));
                    if (dist < best) {
                        best = dist;
                        const double *w = m->uvs + 6 * f;
                        uv[0] = w[0] + s * (w[2] - w[0]) + t * (w[4] - w[0]);
                        uv[1] = w[1] + s * (w[3] - w[1]) + t * (w[5] - w[1]);
                    }
                }
            }
    return best < INFINITY;
}

/* ---- the renders ---- */

static lucent_render_result render(lucent_renderer *r, lucent_render_settings s, const char *method, bool seams)
{
    if (lucent_render_method_parse(method, &s.view.method, &s) != LUCENT_OK) fail(method);
    s.tsd.seams = seams;
    lucent_render_result res;
    if (lucent_render(r, &s, &res) != LUCENT_OK) fail(method);
    return res;
}

int main(int argc, char **argv)
{
    char scene_path[1024];
    snprintf(scene_path, sizeof scene_path, "%s/data/scenes/bunny-skin.json", LUCENT_SOURCE_DIR);
    if (argc > 1) snprintf(scene_path, sizeof scene_path, "%s", argv[1]);
    int px = argc > 2 ? atoi(argv[2]) : 512;
    lucent_scene *sc = NULL;
    if (lucent_scene_load(scene_path, NULL, &sc) != LUCENT_OK) fail("scene");
    lucent_gl_context *ctx = NULL;
    lucent_renderer *r = NULL;
    if (bench_renderer_create(sc, &ctx, &r) != LUCENT_OK) fail("GL context and renderer");
    gl_renderer_set_aov(r, true);
    lucent_render_settings s = sc->render;
    s.view.width = s.view.height = px;
    lucent_render_result ref = render(r, s, "ssss:svd3", true), on = render(r, s, "tsd", true);
    lucent_image *pos = NULL, *nrm = NULL;
    if (gl_renderer_read_aov(r, 1, &pos) != LUCENT_OK || gl_renderer_read_aov(r, 0, &nrm) != LUCENT_OK)
        fail("positions and normals");
    lucent_render_result off = render(r, s, "tsd", false);

    /* object 0's atlas, as tsd.c makes it */
    lucent_mesh m = *sc->objects[0].mesh;
    m.uvs = NULL;
    if (lucent_mesh_uv_atlas(&m, &(lucent_uv_atlas_desc){.texture_size = s.tsd.size}, NULL) != LUCENT_OK) fail("atlas");
    size_t seam_edges = 0;
    float *dist = seam_distance(&m, s.tsd.size, 16, &seam_edges);
    face_grid g = {0};
    grid_build(&m, &g);
    /* distance bins (texels): [0, 1), [1, 2), [2, 4), [4, 8), [8, 16), 16 and beyond */
    enum { BINS = 6 };
    static const double edge_of[BINS] = {1, 2, 4, 8, 16, INFINITY};
    double level[BINS] = {0}, diff[BINS][2] = {{0}}, absd[BINS][2] = {{0}};
    size_t count[BINS] = {0};
    const char *overlay = argc > 3 ? argv[3] : NULL; /* the tsd image, pixels within a texel of a seam greener */
    lucent_image *ov = NULL;
    if (overlay && lucent_image_create(px, px, 3, &ov) != LUCENT_OK) fail("overlay");
    for (size_t i = 0; ov && i < 3 * (size_t)px * (size_t)px; i++) ov->data[i] = on.image->data[i];
    for (size_t i = 0; i < (size_t)px * (size_t)px; i++) {
        const float *q = pos->data + 4 * i;
        double p[3] = {q[0], q[1], q[2]}, uv[2];
        if (ref.mask->data[i] < 0.5f || q[3] != 0 || !uv_at(&m, &g, p, uv)) continue;
        /* facing the camera (n.v >= 0.5): grazing pixels, where screen-space ssss differs most, left out */
        const float *nn = nrm->data + 4 * i;
        double vv[3], vl = 0, ndv = 0;
        for (int a = 0; a < 3; a++) vv[a] = sc->camera.position[a] - p[a], vl += vv[a] * vv[a];
        for (int a = 0; a < 3; a++) ndv += nn[a] * vv[a] / sqrt(vl);
        if (ndv < 0.5) continue;
        int n = s.tsd.size, tx = (int)fmin(fmax(uv[0] * n, 0), n - 1), ty = (int)fmin(fmax(uv[1] * n, 0), n - 1);
        double d = dist[(size_t)ty * (size_t)n + (size_t)tx];
        if (ov && d < 1) ov->data[3 * i] = 0, ov->data[3 * i + 2] = 0, ov->data[3 * i + 1] += 0.3f;
        int k = 0;
        while (k < BINS - 1 && d >= edge_of[k]) k++;
        double a = 0, b = 0, c = 0;
        for (int ch = 0; ch < 3; ch++)
            a += ref.image->data[3 * i + ch], b += on.image->data[3 * i + ch], c += off.image->data[3 * i + ch];
        level[k] += a, count[k]++;
        diff[k][0] += b - a, diff[k][1] += c - a, absd[k][0] += fabs(b - a), absd[k][1] += fabs(c - a);
    }
    printf("%s, %dx%d, tsd_size %d: %zu seam edges in the atlas; object pixels by the distance of their texel to "
           "the nearest seam (texels); per bin sum(tsd - ssss:svd3) / sum(ssss) (signed, then absolute)\n",
           sc->name, px, px, s.tsd.size, seam_edges);
    printf("%-10s %8s %22s %22s %10s\n", "texels", "pixels", "tsd (seams followed)", "tsd_seams=false", "difference");
    for (int k = 0; k < BINS; k++) {
        char name[32];
        snprintf(name, sizeof name, k == BINS - 1 ? ">= %g" : "%g - %g", k ? edge_of[k - 1] : 0, edge_of[k]);
        if (!count[k]) continue;
        printf("%-10s %8zu %+10.2f%% %9.2f%% %+10.2f%% %9.2f%% %+9.2f%%\n", name, count[k], 100 * diff[k][0] / level[k],
               100 * absd[k][0] / level[k], 100 * diff[k][1] / level[k], 100 * absd[k][1] / level[k],
               100 * (diff[k][0] - diff[k][1]) / level[k]);
    }
    if (ov && lucent_image_write(overlay, ov, NULL) != LUCENT_OK) fail(overlay);
    lucent_image_destroy(ov);
    free(dist), free(g.start), free(g.face), free(m.uvs);
    lucent_image_destroy(pos), lucent_image_destroy(nrm);
    lucent_render_result_free(&ref), lucent_render_result_free(&on), lucent_render_result_free(&off);
    lucent_renderer_destroy(r);
    lucent_gl_destroy(ctx);
    lucent_scene_destroy(sc);
    return 0;
}
