/* The JSON sidecar of a trace: what made the reference image and how well it converged. */
#include "base/json.h"
#include "lucent/trace.h"

static cJSON *error_json(const lucent_trace_error *e)
{
    cJSON *j = cJSON_CreateObject();
    cJSON_AddStringToObject(j, "of",
                            "se(Y) / Y per pixel, Y the Rec. 709 luminance, over object pixels (coverage >= 0.5)");
    cJSON_AddNumberToObject(j, "median", e->median);
    cJSON_AddNumberToObject(j, "p90", e->p90);
    cJSON_AddNumberToObject(j, "rms", e->rms);
    cJSON_AddNumberToObject(j, "pixels", (double)e->pixels);
    cJSON_AddNumberToObject(j, "dark_pixels", (double)e->dark_pixels);
    return j;
}

static double per(uint64_t a, uint64_t b) { return b ? (double)a / (double)b : 0.0; }

static cJSON *cost_json(const lucent_trace_cost *c)
{
    cJSON *j = cJSON_CreateObject();
    cJSON_AddNumberToObject(j, "paths", (double)c->paths);
    cJSON_AddNumberToObject(j, "scatters_per_path", per(c->scatters, c->paths));
    cJSON_AddNumberToObject(j, "bounces_per_path", per(c->bounces, c->paths));
    cJSON_AddNumberToObject(j, "ray_queries_per_path", per(c->rays, c->paths));
    cJSON_AddNumberToObject(j, "distance_queries_per_path", per(c->points, c->paths));
    cJSON_AddNumberToObject(j, "ray_queries_per_vertex", per(c->rays, c->scatters + c->bounces));
    cJSON_AddNumberToObject(j, "free_flights_without_query", per(c->free_flights, c->scatters + c->bounces));
    cJSON_AddNumberToObject(j, "nee_per_volume_vertex", per(c->nee, c->scatters));
    cJSON_AddNumberToObject(j, "light_paths", (double)c->photons);
    cJSON_AddNumberToObject(j, "light_paths_ended_at_entry", per(c->entry_ended, c->photons));
    return j;
}

static void add_run(cJSON *root, const lucent_trace_sidecar_desc *d)
{
    const lucent_trace_result *r = d->result;
    lucent_tracer_desc tracer = d->tracer ? *d->tracer : (lucent_tracer_desc){0};
    cJSON_AddStringToObject(root, "renderer", "lucent trace " LUCENT_VERSION_STRING);
    cJSON_AddStringToObject(root, "scene_file", d->scene_file ? d->scene_file : d->scene->path);
    cJSON_AddNumberToObject(root, "width", r->image->width);
    cJSON_AddNumberToObject(root, "height", r->image->height);
    cJSON_AddNumberToObject(root, "spp", (double)r->spp);
    cJSON_AddNumberToObject(root, "seed", (double)r->seed);
    cJSON_AddNumberToObject(root, "seconds", r->seconds);
    cJSON_AddNumberToObject(root, "samples_per_second", r->samples_per_second);
    cJSON_AddNumberToObject(root, "threads", d->threads);
    cJSON_AddBoolToObject(root, "subsurface_only", tracer.subsurface_only);
    cJSON_AddBoolToObject(root, "adaptive", tracer.adaptive);
    cJSON_AddBoolToObject(root, "boundary_nee_only", tracer.boundary_nee_only);
    cJSON_AddBoolToObject(root, "plain_flights", tracer.plain_flights);
    cJSON_AddBoolToObject(root, "nee_every_vertex", tracer.nee_every_vertex);
    cJSON_AddNumberToObject(root, "samples", (double)r->samples);
    cJSON_AddItemToObject(root, "relative_standard_error", error_json(&r->error));
    cJSON_AddNumberToObject(root, "truncated_paths", (double)r->truncated);
    cJSON_AddNumberToObject(root, "escaped_paths", (double)r->escaped);
    cJSON_AddNumberToObject(root, "nonfinite_contributions", (double)r->nonfinite);
    cJSON_AddItemToObject(root, "cost", cost_json(&r->cost));
}

lucent_status lucent_trace_write_sidecar(const char *path, const lucent_trace_sidecar_desc *d)
{
    if (!d->scene || !d->result || !d->result->image)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: a trace sidecar needs the scene and the result", path);
    cJSON *root = cJSON_CreateObject(), *scene = cJSON_Parse(d->scene->json);
    if (!root || !scene) {
        cJSON_Delete(root), cJSON_Delete(scene);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    add_run(root, d);
    cJSON_AddItemToObject(root, "scene", scene);
    lucent_status s = lucent_json_write_file(path, root);
    cJSON_Delete(root);
    return s;
}
