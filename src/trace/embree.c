/* The ray-tracing scene: one Embree 3 triangle geometry per visible object, built robust (watertight
 * traversal, so rays do not slip between neighbouring triangles), and the outward face normals in
 * double precision (the faces are counter-clockwise seen from outside). Embree's types stay here. */
#include <embree3/rtcore.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "trace/internal.h"

struct tr_geometry {
    RTCDevice device;
    RTCScene scene;
    int count;
    int *object;              /* geomID -> tracer object index */
    const lucent_mesh **mesh; /* geomID -> its mesh (double positions, for distances) */
    double **planes;          /* geomID -> 4 doubles per face: outward unit normal n and n . v0 */
    double far;               /* rays reaching further than this from the origin get their distance in double */
    char error[256];          /* the first error Embree reported */
};

static void on_error(void *user, enum RTCError code, const char *text)
{
    tr_geometry *g = user;
    if (!g->error[0]) snprintf(g->error, sizeof g->error, "Embree error %d: %s", (int)code, text ? text : "");
}

static double *face_planes(const lucent_mesh *m)
{
    double *p = malloc((m->face_count ? m->face_count : 1) * 4 * sizeof *p);
    if (!p) return NULL;
    for (size_t f = 0; f < m->face_count; f++) {
        const uint32_t *v = m->faces + 3 * f;
        v3 a = v3_load(m->positions + 3 * v[0]), b = v3_load(m->positions + 3 * v[1]);
        v3 c = v3_load(m->positions + 3 * v[2]);
        v3 n = v3_normalize(v3_cross(v3_sub(b, a), v3_sub(c, a)));
        p[4 * f] = n.x, p[4 * f + 1] = n.y, p[4 * f + 2] = n.z, p[4 * f + 3] = v3_dot(n, a);
    }
    return p;
}

static lucent_status add_mesh(tr_geometry *g, const lucent_mesh *m, int object, const char *name)
{
    RTCGeometry geom = rtcNewGeometry(g->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *vb = geom ? rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                               m->vertex_count)
                     : NULL;
    unsigned *ib = vb ? rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                m->face_count)
                      : NULL;
    if (!ib) {
        if (geom) rtcReleaseGeometry(geom);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: %s: cannot build the ray-tracing geometry (%s)", name,
                            g->error[0] ? g->error : "out of memory");
    }
    for (size_t i = 0; i < 3 * m->vertex_count; i++) {
        vb[i] = (float)m->positions[i];
        g->far = fmax(g->far, 8.0 * fabs(m->positions[i]));
    }
    for (size_t i = 0; i < 3 * m->face_count; i++) ib[i] = m->faces[i];
    rtcCommitGeometry(geom);
    unsigned id = rtcAttachGeometry(g->scene, geom);
    rtcReleaseGeometry(geom);
    if (id != (unsigned)g->count) return lucent_error(LUCENT_ERR_INTERNAL, "trace: unexpected Embree geometry id");
    g->object[g->count] = object;
    g->mesh[g->count] = m;
    g->planes[g->count] = face_planes(m);
    if (!g->planes[g->count]) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: out of memory");
    g->count++;
    return LUCENT_OK;
}

static lucent_status geometry_start(int count, tr_geometry **dest)
{
    tr_geometry *g = calloc(1, sizeof *g);
    if (g) g->object = calloc((size_t)count + 1, sizeof *g->object);
    if (g && g->object) g->planes = calloc((size_t)count + 1, sizeof *g->planes);
    if (g && g->planes) g->mesh = calloc((size_t)count + 1, sizeof *g->mesh);
    if (!g || !g->mesh) {
        tr_geometry_destroy(g);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: out of memory");
    }
    *dest = g;
    g->device = rtcNewDevice(NULL);
    if (!g->device)
        return lucent_error(LUCENT_ERR_INTERNAL, "trace: cannot create the Embree device (error %d)",
                            (int)rtcGetDeviceError(NULL));
    rtcSetDeviceErrorFunction(g->device, on_error, g);
    g->scene = rtcNewScene(g->device);
    if (!g->scene) return lucent_error(LUCENT_ERR_INTERNAL, "trace: %s", g->error);
    rtcSetSceneFlags(g->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(g->scene, RTC_BUILD_QUALITY_HIGH);
    return LUCENT_OK;
}

lucent_status tr_geometry_create(const lucent_scene *scene, const int *object_of, int count, tr_geometry **dest)
{
    *dest = NULL;
    tr_geometry *g = NULL;
    lucent_status s = geometry_start(count, &g);
    for (int i = 0; s == LUCENT_OK && i < count; i++) {
        const lucent_scene_object *o = &scene->objects[object_of[i]];
        if (!o->mesh)
            s = lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "trace: objects[%d] has no mesh", object_of[i]);
        else if (o->mesh->face_count)
            s = add_mesh(g, o->mesh, i, o->name);
    }
    if (s == LUCENT_OK) {
        rtcCommitScene(g->scene);
        if (g->error[0]) s = lucent_error(LUCENT_ERR_INTERNAL, "trace: %s", g->error);
    }
    if (s != LUCENT_OK) {
        tr_geometry_destroy(g);
        return s;
    }
    *dest = g;
    return LUCENT_OK;
}

void tr_geometry_destroy(tr_geometry *g)
{
    if (!g) return;
    if (g->scene) rtcReleaseScene(g->scene);
    if (g->device) rtcReleaseDevice(g->device);
    for (int i = 0; g->planes && i < g->count; i++) free(g->planes[i]);
    free(g->planes);
    free(g->mesh);
    free(g->object);
    free(g);
}

/* Queries made by this thread (tr_geometry_queries). */
static _Thread_local uint64_t t_rays, t_points;

void tr_geometry_queries(uint64_t *rays, uint64_t *points) { *rays = t_rays, *points = t_points; }

bool tr_intersect(const tr_geometry *g, v3 o, v3 d, double tnear, double tfar, tr_hit *hit)
{
    t_rays++;
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRayHit rh = {.ray = {.org_x = (float)o.x,
                                   .org_y = (float)o.y,
                                   .org_z = (float)o.z,
                                   .tnear = (float)tnear,
                                   .dir_x = (float)d.x,
                                   .dir_y = (float)d.y,
                                   .dir_z = (float)d.z,
                                   .tfar = tfar < FLT_MAX ? (float)tfar : INFINITY,
                                   .mask = 0xFFFFFFFFu},
                           .hit = {.geomID = RTC_INVALID_GEOMETRY_ID}};
    rtcIntersect1(g->scene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    /* Embree's geometric normal of a counter-clockwise triangle points outward (as (v1 - v0) x (v2 - v0)). */
    hit->n = v3_normalize(v3_make(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
    hit->object = g->object[rh.hit.geomID];
    hit->prim = (int)rh.hit.primID, hit->u = rh.hit.u, hit->v = rh.hit.v;
    hit->t = rh.ray.tfar;
    double reach = fmax(fabs(o.x), fmax(fabs(o.y), fabs(o.z))) + hit->t;
    if (reach > g->far) { /* float precision of a long ray: redo the distance in double on the plane */
        const double *p = g->planes[rh.hit.geomID] + 4 * (size_t)rh.hit.primID;
        v3 n = v3_make(p[0], p[1], p[2]);
        double dn = v3_dot(d, n), t = dn != 0 ? (p[3] - v3_dot(o, n)) / dn : hit->t;
        if (fabs(t - hit->t) <= 1e-3 * (1.0 + hit->t)) hit->t = t, hit->n = n;
    }
    return true;
}

bool tr_occluded(const tr_geometry *g, v3 o, v3 d, double tfar)
{
    t_rays++;
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRay ray = {.org_x = (float)o.x,
                         .org_y = (float)o.y,
                         .org_z = (float)o.z,
                         .dir_x = (float)d.x,
                         .dir_y = (float)d.y,
                         .dir_z = (float)d.z,
                         .tfar = tfar < FLT_MAX ? (float)tfar : INFINITY,
                         .mask = 0xFFFFFFFFu};
    rtcOccluded1(g->scene, &ctx, &ray);
    return ray.tfar < 0; /* Embree sets tfar to -inf when something is hit */
}

/* The squared distance from p to triangle abc: the closest point lies in the face, on an edge or at a
 * vertex, told apart by the signs of the barycentric projections (the Voronoi regions of the
 * triangle; Ericson, Real-Time Collision Detection, 2005, section 5.1.5). */
static double triangle_distance2(v3 p, v3 a, v3 b, v3 c, v3 *closest)
{
    v3 ab = v3_sub(b, a), ac = v3_sub(c, a), ap = v3_sub(p, a);
    double d1 = v3_dot(ab, ap), d2 = v3_dot(ac, ap);
    v3 q;
    if (d1 <= 0 && d2 <= 0) {
        q = a;
    } else {
        v3 bp = v3_sub(p, b), cp = v3_sub(p, c);
        double d3 = v3_dot(ab, bp), d4 = v3_dot(ac, bp), d5 = v3_dot(ab, cp), d6 = v3_dot(ac, cp);
        double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
        if (d3 >= 0 && d4 <= d3)
            q = b;
        else if (d6 >= 0 && d5 <= d6)
            q = c;
        else if (vc <= 0 && d1 >= 0 && d3 <= 0)
            q = v3_madd(a, ab, d1 / (d1 - d3));
        else if (vb <= 0 && d2 >= 0 && d6 <= 0)
            q = v3_madd(a, ac, d2 / (d2 - d6));
        else if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
            q = v3_madd(b, v3_sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)));
        else {
            double den = 1.0 / (va + vb + vc);
            q = v3_add(a, v3_add(v3_scale(ab, vb * den), v3_scale(ac, vc * den)));
        }
    }
    v3 e = v3_sub(p, q);
    *closest = q;
    return v3_dot(e, e);
}

typedef struct distance_query {
    const tr_geometry *g;
    v3 p;
    double d2;  /* the smallest squared distance found so far */
    v3 closest; /* the point of the surface at that distance */
} distance_query;

static bool on_point_query(struct RTCPointQueryFunctionArguments *args)
{
    distance_query *q = args->userPtr;
    const lucent_mesh *m = q->g->mesh[args->geomID];
    const uint32_t *f = m->faces + 3 * (size_t)args->primID;
    v3 c;
    double d2 = triangle_distance2(q->p, v3_load(m->positions + 3 * f[0]), v3_load(m->positions + 3 * f[1]),
                                   v3_load(m->positions + 3 * f[2]), &c);
    if (!(d2 < q->d2)) return false;
    q->d2 = d2, q->closest = c;
    args->query->radius = (float)sqrt(d2) * (1.0f + 1e-6f); /* shrink the search (never below the distance) */
    return true;
}

double tr_distance_bound(const tr_geometry *g, v3 p, double rmax, v3 *closest)
{
    t_points++;
    struct RTCPointQuery query = {.x = (float)p.x, .y = (float)p.y, .z = (float)p.z, .radius = (float)rmax};
    struct RTCPointQueryContext ctx;
    rtcInitPointQueryContext(&ctx);
    distance_query q = {.g = g, .p = p, .d2 = rmax * rmax, .closest = p};
    rtcPointQuery(g->scene, &query, &ctx, on_point_query, &q);
    if (closest) *closest = q.closest;
    return sqrt(q.d2);
}

const char *lucent_trace_embree_version(void)
{
    static char text[32] = "unknown";
    RTCDevice device = rtcNewDevice(NULL);
    if (device) {
        long v = (long)rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION); /* e.g. 31305 */
        if (v > 0) snprintf(text, sizeof text, "%ld.%ld.%ld", v / 10000, v / 100 % 100, v % 100);
        rtcReleaseDevice(device);
    }
    return text;
}
