/* compare's peers: a real engine renders the scene with the parameters `lucent fit` gives each material
 * (lucent/engine.h), beside Lucent's own methods. Blender 3.4 (Debian's `blender`), headless, through
 * scripts/peer/blender_scene.py (embedded): Cycles' Random Walk or Christensen-Burley, or EEVEE. The scene
 * goes to Blender as JSON and raw meshes in a private folder (removed afterwards), the image comes back as
 * a linear EXR. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "base/embedded.h"
#include "base/json.h"
#include "eval/internal.h"
#include "lucent/engine.h"
#include "lucent/output.h"

extern char **environ;

static const struct {
    const char *name, *engine, *method, *title;
    lucent_engine_id fit;
} k_peers[] = {
    {"blender-cycles", "CYCLES", "RANDOM_WALK", "Cycles, Random Walk", LUCENT_ENGINE_BLENDER3_RANDOM_WALK},
    {"blender-cycles-burley", "CYCLES", "BURLEY", "Cycles, Christensen-Burley", LUCENT_ENGINE_BLENDER3_BURLEY},
    {"blender-eevee", "BLENDER_EEVEE", "BURLEY", "EEVEE, Christensen-Burley", LUCENT_ENGINE_BLENDER3_BURLEY},
};
enum { PEER_COUNT = sizeof k_peers / sizeof k_peers[0], PEER_MAX_MATERIALS = 16 };

/* "blender-cycles-burley:hand" -> kind, hand. */
static lucent_status parse(const char *spec, int *kind, bool *hand)
{
    size_t n = strcspn(spec ? spec : "", ":");
    *hand = spec && spec[n] == ':' && !strcmp(spec + n + 1, "hand");
    for (int k = 0; spec && k < PEER_COUNT; k++)
        if (strlen(k_peers[k].name) == n && !strncmp(spec, k_peers[k].name, n) && (!spec[n] || *hand)) {
            *kind = k;
            return LUCENT_OK;
        }
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                        "unknown peer \"%s\" (blender-cycles, blender-cycles-burley, blender-eevee; \":hand\" after "
                        "one: the hand mapping instead of the fit)",
                        spec ? spec : "");
}

lucent_status eval_peer_check(const char *spec)
{
    int k;
    bool hand;
    return parse(spec, &k, &hand);
}

/* The program to run: desc's, $LUCENT_BLENDER, or blender found on PATH. */
static lucent_status find_blender(const char *given, const char *peer, char *dest, size_t size)
{
    const char *name = given ? given : getenv("LUCENT_BLENDER");
    if (!name || !*name) name = "blender";
    if (strchr(name, '/')) {
        if (access(name, X_OK) == 0) return snprintf(dest, size, "%s", name) < (int)size ? LUCENT_OK : LUCENT_ERR_IO;
    } else {
        const char *path = getenv("PATH");
        for (const char *p = path ? path : "/usr/bin:/bin"; p && *p;) {
            size_t n = strcspn(p, ":");
            if (n && snprintf(dest, size, "%.*s/%s", (int)n, p, name) < (int)size && access(dest, X_OK) == 0)
                return LUCENT_OK;
            p += n + (p[n] == ':');
        }
    }
    return lucent_error(LUCENT_ERR_UNSUPPORTED,
                        "peer %s: Blender not found (\"%s\"): install Debian's blender (make setup does), or name "
                        "the program with LUCENT_BLENDER",
                        peer, name);
}

/* ---- the scene Blender builds ---- */

typedef struct peer_run {
    const eval_peer_desc *d;
    int kind;
    bool hand;
    char dir[EVAL_PATH_SIZE];
    lucent_cache *cache;
    int material_count;
    lucent_material materials[PEER_MAX_MATERIALS];
    lucent_engine_fit_result fits[PEER_MAX_MATERIALS];
} peer_run;

/* The fit (or hand mapping) of material m, computed once per distinct material. */
static lucent_status fit_of(peer_run *p, const lucent_material *m, const lucent_engine_fit_result **dest)
{
    for (int i = 0; i < p->material_count; i++)
        if (!memcmp(&p->materials[i], m, sizeof *m)) return *dest = &p->fits[i], LUCENT_OK;
    if (p->material_count == PEER_MAX_MATERIALS)
        return lucent_error(LUCENT_ERR_UNSUPPORTED, "peer: at most %d materials", PEER_MAX_MATERIALS);
    lucent_engine_target t;
    lucent_status s = lucent_engine_target_build(
        &(lucent_engine_target_desc){.material = m, .pool = p->d->pool, .cache = p->cache}, &t);
    int i = p->material_count;
    lucent_engine_fit_desc fd = {.pool = p->d->pool};
    if (s == LUCENT_OK)
        s = p->hand ? lucent_engine_hand(&t, k_peers[p->kind].fit, &fd, &p->fits[i])
                    : lucent_engine_fit(&t, k_peers[p->kind].fit, &fd, &p->fits[i]);
    lucent_engine_target_free(&t);
    if (s != LUCENT_OK) return s;
    p->materials[i] = *m;
    p->material_count++;
    *dest = &p->fits[i];
    return LUCENT_OK;
}

/* The object's mesh as Blender reads it: positions, normals (float32) and triangles (uint32), each
 * triangle wound so that its face agrees with its vertices' normals (Blender's BSSRDF enters from the
 * face's front). */
static lucent_status write_mesh(const char *path, const lucent_mesh *m)
{
    size_t nv = m->vertex_count, nt = m->face_count, size = nv * 24 + nt * 12;
    unsigned char *buf = malloc(size ? size : 1);
    if (!buf) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    float *f = (float *)buf;
    for (size_t i = 0; i < 3 * nv; i++) f[i] = (float)m->positions[i], f[3 * nv + i] = (float)m->normals[i];
    uint32_t *t = (uint32_t *)(buf + nv * 24);
    for (size_t i = 0; i < nt; i++) {
        const uint32_t *v = m->faces + 3 * i;
        const double *a = m->positions + 3 * v[0], *b = m->positions + 3 * v[1], *c = m->positions + 3 * v[2];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double dot = 0.0;
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 3; j++) dot += n[j] * m->normals[3 * v[k] + j];
        t[3 * i] = v[0], t[3 * i + 1] = dot < 0 ? v[2] : v[1], t[3 * i + 2] = dot < 0 ? v[1] : v[2];
    }
    lucent_status s = lucent_write_file_now(path, buf, size);
    free(buf);
    return s;
}

static cJSON *numbers(const double *v, int n)
{
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; a && i < n; i++) cJSON_AddItemToArray(a, lucent_json_number_item(v[i]));
    return a;
}

/* The Principled BSDF inputs of a fit, and the boundary's specular and roughness of the object. */
static cJSON *principled(const lucent_engine_fit_result *r, const lucent_scene_object *o)
{
    static const char *const inputs[] = {"Base Color",        "Subsurface",     "Subsurface Color",
                                         "Subsurface Radius", "Subsurface IOR", "Subsurface Anisotropy"};
    cJSON *j = cJSON_CreateObject();
    for (size_t i = 0; j && i < sizeof inputs / sizeof inputs[0]; i++) {
        const lucent_engine_param *p = lucent_engine_fit_param(r, inputs[i]);
        if (p) cJSON_AddItemToObject(j, inputs[i], numbers(p->value, p->count));
        if (p && p->count == 1) cJSON_ReplaceItemInObject(j, inputs[i], lucent_json_number_item(p->value[0]));
    }
    /* Principled v1: F0 = 0.08 Specular; its Roughness is squared into GGX's alpha */
    cJSON_AddItemToObject(j, "Specular", lucent_json_number_item(o->specular_f0 / 0.08));
    cJSON_AddItemToObject(j, "Roughness", lucent_json_number_item(sqrt(o->roughness)));
    return j;
}

static lucent_status add_lights(const lucent_scene *sc, cJSON *root)
{
    cJSON *a = cJSON_AddArrayToObject(root, "lights");
    for (int i = 0; a && i < sc->light_count; i++) {
        const lucent_light *l = &sc->lights[i];
        double e[3] = {l->color[0] * l->intensity, l->color[1] * l->intensity, l->color[2] * l->intensity};
        cJSON *j = cJSON_CreateObject();
        if (!j) break;
        cJSON_AddItemToArray(a, j);
        if (l->type == LUCENT_LIGHT_DIRECTIONAL) {
            cJSON_AddStringToObject(j, "type", "directional");
            cJSON_AddItemToObject(j, "direction", numbers(l->direction, 3));
            cJSON_AddItemToObject(j, "irradiance", numbers(e, 3));
            cJSON_AddItemToObject(j, "angular_radius", lucent_json_number_item(l->angular_radius));
        } else if (l->type == LUCENT_LIGHT_ENVIRONMENT) {
            cJSON_AddStringToObject(j, "type", "environment");
            cJSON_AddItemToObject(j, "radiance", numbers(e, 3));
        } else {
            return lucent_error(LUCENT_ERR_UNSUPPORTED,
                                "%s: lights[%d]: the Blender peer takes directional and "
                                "environment lights, not %s ones",
                                sc->path, i, lucent_light_type_name(l->type));
        }
    }
    return LUCENT_OK;
}

static lucent_status add_objects(peer_run *p, cJSON *root)
{
    const lucent_scene *sc = p->d->scene;
    cJSON *a = cJSON_AddArrayToObject(root, "objects");
    lucent_status s = LUCENT_OK;
    for (int i = 0; a && i < sc->object_count && s == LUCENT_OK; i++) {
        const lucent_scene_object *o = &sc->objects[i];
        if (!o->visible || o->points || !o->mesh || !o->mesh->face_count) continue;
        const lucent_engine_fit_result *fit = NULL;
        char mesh[EVAL_PATH_SIZE];
        s = fit_of(p, &o->material, &fit);
        if (s == LUCENT_OK) s = eval_path_printf(mesh, sizeof mesh, "%s/mesh%d.bin", p->dir, i);
        if (s == LUCENT_OK) s = write_mesh(mesh, o->mesh);
        if (s != LUCENT_OK) return lucent_error_context(s, "peer: object %s", o->name);
        cJSON *j = cJSON_CreateObject();
        if (!j) break;
        cJSON_AddItemToArray(a, j);
        cJSON_AddStringToObject(j, "name", o->name);
        cJSON_AddStringToObject(j, "mesh", mesh);
        cJSON_AddItemToObject(j, "vertices", lucent_json_number_item((double)o->mesh->vertex_count));
        cJSON_AddItemToObject(j, "triangles", lucent_json_number_item((double)o->mesh->face_count));
        cJSON_AddStringToObject(j, "subsurface_method", k_peers[p->kind].method);
        cJSON_AddItemToObject(j, "principled", principled(fit, o));
    }
    return s;
}

static lucent_status write_scene(peer_run *p, const char *script_path, const char *scene_path, const char *exr)
{
    const lucent_scene *sc = p->d->scene;
    const lucent_embedded_file *script = lucent_embedded("scripts/peer/blender_scene.py");
    if (!script) return lucent_error(LUCENT_ERR_INTERNAL, "peer: the Blender script is not embedded");
    lucent_status s = lucent_write_file_now(script_path, script->data, script->size);
    cJSON *root = cJSON_CreateObject();
    if (s == LUCENT_OK && !root) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    if (s == LUCENT_OK) {
        cJSON_AddItemToObject(root, "width", lucent_json_number_item(sc->render.view.width));
        cJSON_AddItemToObject(root, "height", lucent_json_number_item(sc->render.view.height));
        cJSON_AddStringToObject(root, "output", exr);
        cJSON_AddStringToObject(root, "engine", k_peers[p->kind].engine);
        cJSON_AddItemToObject(root, "samples", lucent_json_number_item(p->d->spp > 0 ? p->d->spp : 64));
        cJSON_AddItemToObject(root, "seed", lucent_json_number_item((double)(p->d->seed % 1000000)));
        cJSON_AddItemToObject(root, "threads",
                              lucent_json_number_item(p->d->pool ? lucent_pool_threads(p->d->pool) : 1));
        cJSON *cam = cJSON_AddObjectToObject(root, "camera");
        cJSON_AddItemToObject(cam, "position", numbers(sc->camera.position, 3));
        cJSON_AddItemToObject(cam, "target", numbers(sc->camera.target, 3));
        cJSON_AddItemToObject(cam, "up", numbers(sc->camera.up, 3));
        cJSON_AddItemToObject(cam, "fov_y", lucent_json_number_item(sc->camera.fov_y));
        cJSON_AddItemToObject(cam, "near", lucent_json_number_item(sc->camera.near_plane));
        cJSON_AddItemToObject(cam, "far", lucent_json_number_item(sc->camera.far_plane));
        s = add_lights(sc, root);
    }
    if (s == LUCENT_OK) s = add_objects(p, root);
    if (s == LUCENT_OK) s = lucent_json_write_file_direct(scene_path, root);
    cJSON_Delete(root);
    return s;
}

/* ---- running Blender ---- */

/* The last line of Blender's log that says what went wrong (an error or a traceback's end). */
static void log_tail(const char *log, char *dest, size_t size)
{
    char *text = NULL;
    dest[0] = '\0';
    if (lucent_read_file(log, &text, NULL) != LUCENT_OK) return;
    for (char *line = strtok(text, "\n"); line; line = strtok(NULL, "\n"))
        if (strstr(line, "rror") || strstr(line, "blender_scene:")) snprintf(dest, size, "%s", line);
    free(text);
}

static lucent_status run_blender(const char *program, const char *script, const char *scene, const char *log,
                                 const char *peer)
{
    char *argv[] = {(char *)program, "-b", "--factory-startup", "-noaudio", "-P",
                    (char *)script,  "--", (char *)scene,       NULL};
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 1, log, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
    pid_t pid;
    int e = posix_spawn(&pid, program, &fa, NULL, argv, environ), status = 0;
    posix_spawn_file_actions_destroy(&fa);
    if (e) return lucent_error(LUCENT_ERR_IO, "peer %s: cannot run %s: %s", peer, program, strerror(e));
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return lucent_error(LUCENT_ERR_IO, "peer %s: waiting for %s: %s", peer, program, strerror(errno));
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return LUCENT_OK;
    char tail[300];
    log_tail(log, tail, sizeof tail);
    return lucent_error(LUCENT_ERR_IO, "peer %s: %s %s %d%s%s", peer, program,
                        WIFEXITED(status) ? "exited with" : "was ended by signal",
                        WIFEXITED(status) ? WEXITSTATUS(status) : WTERMSIG(status), tail[0] ? ": " : "", tail);
}

static void remove_dir(const char *dir, int objects)
{
    static const char *const files[] = {"scene.json", "blender_scene.py", "blender.log", "image.exr"};
    char path[EVAL_PATH_SIZE];
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++)
        if (snprintf(path, sizeof path, "%s/%s", dir, files[i]) < (int)sizeof path) unlink(path);
    for (int i = 0; i < objects; i++)
        if (snprintf(path, sizeof path, "%s/mesh%d.bin", dir, i) < (int)sizeof path) unlink(path);
    rmdir(dir);
}

lucent_status eval_peer_render(const eval_peer_desc *d, eval_peer_result *dest)
{
    *dest = (eval_peer_result){0};
    peer_run p = {.d = d};
    char program[EVAL_PATH_SIZE], script[EVAL_PATH_SIZE], scene[EVAL_PATH_SIZE], exr[EVAL_PATH_SIZE],
        log[EVAL_PATH_SIZE];
    lucent_status s = parse(d->spec, &p.kind, &p.hand);
    if (s == LUCENT_OK) s = find_blender(d->blender, d->spec, program, sizeof program);
    if (s != LUCENT_OK) return s;
    const char *tmp = getenv("TMPDIR");
    s = eval_path_printf(p.dir, sizeof p.dir, "%s/lucent-peer-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (s == LUCENT_OK && !mkdtemp(p.dir))
        return lucent_error(LUCENT_ERR_IO, "peer %s: cannot make a folder in %s: %s", d->spec,
                            tmp && *tmp ? tmp : "/tmp", strerror(errno));
    if (s == LUCENT_OK && d->cache_dir) s = lucent_cache_create(d->cache_dir, &p.cache);
    if (s == LUCENT_OK) s = eval_path_printf(script, sizeof script, "%s/blender_scene.py", p.dir);
    if (s == LUCENT_OK) s = eval_path_printf(scene, sizeof scene, "%s/scene.json", p.dir);
    if (s == LUCENT_OK) s = eval_path_printf(exr, sizeof exr, "%s/image.exr", p.dir);
    if (s == LUCENT_OK) s = eval_path_printf(log, sizeof log, "%s/blender.log", p.dir);
    double t0 = lucent_clock_seconds();
    if (s == LUCENT_OK) s = write_scene(&p, script, scene, exr);
    double t1 = lucent_clock_seconds();
    if (s == LUCENT_OK) s = run_blender(program, script, scene, log, d->spec);
    lucent_image *img = NULL;
    if (s == LUCENT_OK) s = lucent_image_load(exr, &img);
    if (s == LUCENT_OK) s = lucent_image_convert_channels(img, 3, &dest->image);
    lucent_image_destroy(img);
    dest->seconds = lucent_clock_seconds() - t1;
    if (s == LUCENT_OK)
        snprintf(dest->settings, sizeof dest->settings, "Blender %s, %s, %d spp, %s; fit %.1f s, render %.1f s", "3.4",
                 k_peers[p.kind].title, d->spp > 0 ? d->spp : 64,
                 p.hand ? "hand mapping (radius 1/sigma_tr, colour T)" : "fitted parameters (lucent fit)", t1 - t0,
                 dest->seconds);
    for (int i = 0; i < p.material_count; i++) lucent_engine_fit_result_free(&p.fits[i]);
    lucent_cache_destroy(p.cache);
    remove_dir(p.dir, d->scene->object_count);
    if (s != LUCENT_OK) {
        lucent_image_destroy(dest->image);
        dest->image = NULL;
    }
    return s;
}
