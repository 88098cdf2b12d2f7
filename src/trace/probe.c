/* lucent_tracer_probe: what the camera sees through each pixel's centre, and which lights reach it,
 * for measuring an image by region (lucent compare). */
#include <math.h>
#include <stdlib.h>

#include "trace/internal.h"

void lucent_trace_probe_free(lucent_trace_probe *p)
{
    if (!p) return;
    free(p->object), free(p->triangle), free(p->bary), free(p->position), free(p->normal), free(p->unoccluded);
    *p = (lucent_trace_probe){0};
}

/* Unit direction from p toward light l and the distance to it (INFINITY for directions). */
static v3 toward_light(const lucent_light *l, v3 p, double *dist)
{
    if (l->type == LUCENT_LIGHT_POINT || l->type == LUCENT_LIGHT_SPHERE) {
        v3 d = v3_sub(v3_load(l->position), p);
        *dist = v3_length(d);
        return v3_normalize(d);
    }
    *dist = INFINITY;
    return v3_normalize(v3_neg(v3_load(l->direction)));
}

static void probe_pixel(const lucent_tracer *tr, int x, int y, lucent_trace_probe *p)
{
    size_t i = (size_t)y * (size_t)p->width + (size_t)x;
    double o[3], d[3];
    lucent_camera_ray(&tr->scene->camera, p->width, p->height, x + 0.5, y + 0.5, o, d);
    tr_hit h;
    p->object[i] = p->triangle[i] = -1;
    if (!tr_intersect(tr->geometry, v3_load(o), v3_load(d), 0, INFINITY, &h)) return;
    v3 at = v3_madd(v3_load(o), v3_load(d), h.t);
    p->object[i] = tr->objects[h.object].scene_index, p->triangle[i] = h.prim;
    p->bary[2 * i] = h.u, p->bary[2 * i + 1] = h.v;
    p->position[3 * i] = (float)at.x, p->position[3 * i + 1] = (float)at.y, p->position[3 * i + 2] = (float)at.z;
    p->normal[3 * i] = (float)h.n.x, p->normal[3 * i + 1] = (float)h.n.y, p->normal[3 * i + 2] = (float)h.n.z;
    for (int k = 0; k < p->light_count; k++) {
        const lucent_light *l = &tr->scene->lights[k];
        unsigned char *u = &p->unoccluded[i * (size_t)p->light_count + (size_t)k];
        if (l->type == LUCENT_LIGHT_ENVIRONMENT) {
            *u = 1;
            continue;
        }
        double dist;
        v3 w = toward_light(l, at, &dist);
        /* leave the surface on the light's side */
        v3 start = v3_madd(at, h.n, v3_dot(w, h.n) >= 0 ? tr->eps : -tr->eps);
        double far =
            isfinite(dist) ? fmax(dist - (l->type == LUCENT_LIGHT_SPHERE ? l->radius : 0) - tr->eps, 0) : INFINITY;
        *u = !tr_occluded(tr->geometry, start, w, far);
    }
}

lucent_status lucent_tracer_probe(const lucent_tracer *tr, lucent_trace_probe *dest)
{
    *dest = (lucent_trace_probe){
        .width = tr->render.view.width, .height = tr->render.view.height, .light_count = tr->scene->light_count};
    size_t n = (size_t)dest->width * (size_t)dest->height;
    dest->object = malloc(n * sizeof *dest->object);
    dest->triangle = malloc(n * sizeof *dest->triangle);
    dest->bary = calloc(2 * n, sizeof *dest->bary);
    dest->position = calloc(3 * n, sizeof *dest->position);
    dest->normal = calloc(3 * n, sizeof *dest->normal);
    dest->unoccluded = calloc(n * (size_t)(dest->light_count > 0 ? dest->light_count : 1), 1);
    if (!dest->object || !dest->triangle || !dest->bary || !dest->position || !dest->normal || !dest->unoccluded) {
        lucent_trace_probe_free(dest);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: probe: out of memory");
    }
    for (int y = 0; y < dest->height; y++)
        for (int x = 0; x < dest->width; x++) probe_pixel(tr, x, y, dest);
    return LUCENT_OK;
}
