/* The public face of the path tracer: creating a tracer from a scene (what it can converge on),
 * rendering passes until the samples, the time or the target error say stop, and the result. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/dist.h"
#include "trace/field.h"
#include "trace/film.h"
#include "trace/internal.h"

/* The share of the fluence gradient the walk follows (media.c, field.c): measured on the benchmark
 * sphere, 0.7 beats 0 (the analog walk) and 1 (variance of the dark half 1.3x lower than either). */
#define WALK_STRENGTH 0.7

static const char *scene_name(const lucent_scene *s) { return s->path[0] ? s->path : "scene"; }

static tr_boundary boundary_of(const lucent_scene_object *o, int model)
{
    double eta = o->material.eta;
    tr_boundary_kind k = eta == 1.0 ? TR_BOUNDARY_MATCHED : o->roughness > 0 ? TR_BOUNDARY_ROUGH : TR_BOUNDARY_SMOOTH;
    return (tr_boundary){.kind = k,
                         .eta = eta,
                         .alpha = o->roughness,
                         .cycles3 = k == TR_BOUNDARY_ROUGH && model == LUCENT_BOUNDARY_CYCLES3};
}

static void describe_light(const lucent_light *l, char *buf, size_t size)
{
    if (l->type == LUCENT_LIGHT_POINT)
        snprintf(buf, size, "a point light");
    else
        snprintf(buf, size, "a directional light with angular_radius 0");
}

/* The refusal rule: a delta light can reach an object's medium only through its boundary, and
 * through a smooth one only along measure-zero refracted directions that no sampling finds. */
static lucent_status check_convergence(const lucent_scene *sc)
{
    for (int li = 0; li < sc->light_count; li++) {
        const lucent_light *l = &sc->lights[li];
        bool delta = l->type == LUCENT_LIGHT_POINT || (l->type == LUCENT_LIGHT_DIRECTIONAL && !(l->angular_radius > 0));
        for (int oi = 0; delta && oi < sc->object_count; oi++) {
            const lucent_scene_object *o = &sc->objects[oi];
            if (!o->visible || boundary_of(o, LUCENT_BOUNDARY_WALTER).kind != TR_BOUNDARY_SMOOTH) continue;
            char what[64];
            describe_light(l, what, sizeof what);
            return lucent_error(LUCENT_ERR_UNSUPPORTED,
                                "%s: lights[%d] (%s, a delta light) can reach the inside of objects[%d] \"%s\" only "
                                "through its smooth boundary (roughness 0, eta %g): a path tracer cannot converge on "
                                "that (its subsurface light would be missing, not rendered); give the light an "
                                "angular_radius > 0 or the object a roughness > 0",
                                scene_name(sc), li, what, oi, o->name, o->material.eta);
        }
    }
    return LUCENT_OK;
}

static void build_object(const lucent_scene_object *o, int index, int model, tr_object *dest)
{
    *dest = (tr_object){.scene_index = index, .boundary = boundary_of(o, model)};
    for (int c = 0; c < 3; c++) {
        dest->sigma_s[c] = o->material.sigma_s[c];
        dest->sigma_t[c] = o->material.sigma_a[c] + o->material.sigma_s[c];
        dest->g[c] = o->material.g[c];
    }
    dest->g_mean = (dest->g[0] + dest->g[1] + dest->g[2]) / 3.0;
    dest->sigma_t_min = fmax(fmin(dest->sigma_t[0], fmin(dest->sigma_t[1], dest->sigma_t[2])), 1e-12);
    dest->dense = true;
    for (int c = 0; c < 3; c++)
        dest->dense &= dest->sigma_s[c] >= TR_DENSE_ALBEDO * dest->sigma_t[c] && dest->sigma_t[c] > 0;
}

/* Ray offsets: a few thousand float ulps of the scene's largest coordinate. */
static double scene_eps(const lucent_scene *sc)
{
    double lo[3], hi[3], m = 1.0;
    lucent_scene_bounds(sc, lo, hi);
    for (int i = 0; i < 3 && lo[0] <= hi[0]; i++) m = fmax(m, fmax(fabs(lo[i]), fabs(hi[i])));
    return 2e-5 * m;
}

static lucent_status build(lucent_tracer *tr)
{
    const lucent_scene *sc = tr->scene;
    int *map = malloc((size_t)(sc->object_count + 1) * sizeof *map);
    tr->objects = calloc((size_t)(sc->object_count + 1), sizeof *tr->objects);
    if (!map || !tr->objects) {
        free(map);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: out of memory");
    }
    for (int i = 0; i < sc->object_count; i++)
        if (sc->objects[i].visible && !sc->objects[i].points) { /* a point cloud has no surface to trace */
            map[tr->object_count] = i;
            build_object(&sc->objects[i], i, tr->render.trace.boundary_model, &tr->objects[tr->object_count]);
            tr->has_matched |= tr->objects[tr->object_count++].boundary.kind == TR_BOUNDARY_MATCHED;
        }
    lucent_status s = tr_geometry_create(sc, map, tr->object_count, &tr->geometry);
    free(map);
    if (s == LUCENT_OK) s = tr_lights_build(tr);
    tr->walk_strength = WALK_STRENGTH;
    if (s == LUCENT_OK) s = tr_film_create(tr->render.view.width, tr->render.view.height, tr->desc.adaptive, &tr->film);
    tr->eps = scene_eps(sc);
    if (s == LUCENT_OK) tr_light_paths_setup(tr);
    if (s == LUCENT_OK) s = tr_depth_setup(tr);
    return s;
}

lucent_status lucent_tracer_create(const lucent_scene *scene, const lucent_tracer_desc *desc, lucent_tracer **dest)
{
    if (!dest) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "trace: no destination for the tracer");
    *dest = NULL;
    if (!scene) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "trace: no scene");
    lucent_status s = check_convergence(scene);
    if (s != LUCENT_OK) return s;
    lucent_tracer *tr = calloc(1, sizeof *tr);
    if (!tr) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: out of memory");
    tr->scene = scene;
    tr->render = scene->render;
    if (desc) tr->desc = *desc;
    s = build(tr);
    if (s != LUCENT_OK) {
        lucent_tracer_destroy(tr);
        return s;
    }
    *dest = tr;
    return LUCENT_OK;
}

void lucent_tracer_destroy(lucent_tracer *tr)
{
    if (!tr) return;
    tr_field_destroy(tr);
    tr_geometry_destroy(tr->geometry);
    tr_film_destroy(tr->film);
    for (int o = 0; tr->objects && o < tr->object_count; o++) tr_depth_destroy(tr->objects[o].depth);
    free(tr->objects);
    free(tr->lights);
    free(tr);
}

void lucent_tracer_reset(lucent_tracer *tr)
{
    if (tr) tr_film_reset(tr->film);
}

/* Resolves the desc's defaults from the scene and checks it. */
static lucent_status resolve(const lucent_tracer *tr, const lucent_trace_desc *in, lucent_trace_desc *d)
{
    *d = in ? *in : (lucent_trace_desc){0};
    if (d->spp < 0) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "trace: spp must be >= 0 (got %d)", d->spp);
    if (!isfinite(d->time_limit))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "trace: time_limit must be a finite number of seconds");
    if (!(d->target_error >= 0) || !isfinite(d->target_error))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "trace: target_error must be >= 0 (got %g)", d->target_error);
    if (!d->spp) d->spp = tr->render.trace.spp;
    if (!d->seed) d->seed = tr->film->passes ? tr->film->seed : tr->render.trace.seed;
    if (d->time_limit == 0) d->time_limit = tr->render.trace.time_limit;
    if (!d->label) d->label = "trace";
    if (tr->film->passes && d->seed != tr->film->seed)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "trace: the estimate has %llu passes of seed %llu; seed %llu cannot continue it "
                            "(lucent_tracer_reset starts a new one)",
                            (unsigned long long)tr->film->passes, (unsigned long long)tr->film->seed,
                            (unsigned long long)d->seed);
    return LUCENT_OK;
}

/* Whether a camera path walks in some medium the field would steer: not when the light paths carry
 * every object's subsurface light (camera paths that enter one end there). */
static bool camera_walks(const lucent_tracer *tr)
{
    if (tr->camera_side_lights > 0) return tr->object_count > 0;
    for (int o = 0; o < tr->object_count; o++)
        if (!tr->objects[o].light_paths) return true;
    return false;
}

/* Whether to stop after this pass (agreeing on status first). Ranks share the pass schedule: every
 * rank measures the error of the whole image, and rank 0's decision (its clock) holds for all. */
static lucent_status should_stop(const lucent_tracer *tr, const lucent_trace_desc *d, double start,
                                 lucent_status status, bool *stop)
{
    *stop = d->time_limit > 0 && lucent_clock_seconds() - start >= d->time_limit;
    if (status == LUCENT_OK && d->target_error > 0 && tr->film->passes >= 16) {
        double e = INFINITY;
        status = tr_film_error_rms(tr->film, &e);
        *stop |= e <= d->target_error;
    }
    return lucent_dist_bcast_flag(status, stop);
}

/* A part (--part K/N) runs its tiles of a fixed number of passes, with no exchange between parts:
 * nothing that needs the whole image between passes. */
static lucent_status check_part(const lucent_tracer *tr, const lucent_trace_desc *d)
{
    if (!lucent_dist_part(NULL, NULL)) return LUCENT_OK;
    const char *what = tr->desc.adaptive     ? "adaptive sampling"
                       : d->time_limit > 0   ? "a time limit"
                       : d->target_error > 0 ? "a target error"
                                             : NULL;
    if (what)
        return lucent_error(LUCENT_ERR_UNSUPPORTED,
                            "trace: --part runs a fixed number of samples without talking to the other parts; "
                            "%s needs the whole image after every pass (use mpirun for that, docs/scale.md)",
                            what);
    return LUCENT_OK;
}

lucent_status lucent_tracer_render(lucent_tracer *tr, const lucent_trace_desc *desc, lucent_trace_result *dest)
{
    if (!tr || !dest) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "trace: no tracer or no result");
    memset(dest, 0, sizeof *dest);
    lucent_trace_desc d;
    lucent_status s = resolve(tr, desc, &d);
    if (s == LUCENT_OK) s = check_part(tr, &d);
    if (s != LUCENT_OK) return s;
    double start = lucent_clock_seconds();        /* the guiding field's pre-pass counts as rendering time */
    bool merge = lucent_dist_share().stride == 0; /* a merge of parts: no path is traced here */
    /* under a time limit the field's photons get at most a quarter of it (the passes the rest) */
    double field_deadline = d.time_limit > 0 ? start + 0.25 * d.time_limit : 0;
    if (!merge && !tr->fields && tr->walk_strength > 0 && camera_walks(tr) &&
        (s = tr_field_build(tr, d.pool, field_deadline)) != LUCENT_OK)
        return s;
    tr->film->seed = d.seed;
    uint64_t per_pass =
        (uint64_t)tr->render.view.width * (uint64_t)tr->render.view.height * (tr->desc.adaptive ? 5 : 1);
    lucent_progress *progress = lucent_progress_begin(d.label, (uint64_t)d.spp * per_pass);
    lucent_progress_set_deadline(progress, d.time_limit); /* the bar follows whichever limit stops the run */
    double deadline = d.time_limit > 0 ? start + d.time_limit : 0, pass_start = lucent_clock_seconds();
    for (int i = 0; i < d.spp && s == LUCENT_OK; i++) {
        bool stop = false, cut = false; /* a cut pass is past the deadline, so should_stop (which all
                                           processes agree on) stops too */
        s = tr_light_pass(tr, tr->film, d.pool, deadline, &cut);
        if (s == LUCENT_OK && !cut) s = tr_film_pass(tr, tr->film, d.pool, progress, deadline, &cut);
        s = should_stop(tr, &d, start, s, &stop);
        if (stop) break;
    }
    lucent_progress_end(progress);
    /* A time limit that ends before the first pass would give a black image that looks like a result: the
     * run fails instead, saying why (docs/trace.md). */
    if (s == LUCENT_OK && !merge && d.time_limit > 0 && tr->film->passes == 0)
        s = lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                         "%s: %s: no pass completed within the time limit of %g s (%.3g s of it went to the set-up "
                         "before the first pass): raise the time limit (render.time_limit, --time)",
                         tr->scene && tr->scene->path[0] ? tr->scene->path : "(scene)", d.label, d.time_limit,
                         pass_start - start);
    tr->film->seconds += lucent_clock_seconds() - start;
    if (!lucent_dist_active()) return s == LUCENT_OK ? tr_film_result(tr->film, dest) : s;
    tr_film *total = NULL; /* the estimate of every process (or part) together */
    s = tr_film_total(tr->film, s, &total);
    if (s == LUCENT_OK) s = tr_film_result(total, dest);
    tr_film_destroy(total);
    return s;
}
