/* Lights: which one next-event estimation picks, how each is sampled from a point, the density of
 * that sampling (for multiple importance sampling, Veach 1997 ch. 9), what a ray that escapes or hits
 * a sphere light sees, and the transmittance of shadow rays.
 *
 *   directional, angular radius 0: a delta light of irradiance E (on a surface facing it);
 *   directional, angular radius a > 0: a disc of uniform radiance E / Omega, Omega = 2 pi (1 - cos a),
 *       sampled uniformly in its cone;
 *   point: a delta light of intensity I, irradiance I / d^2;
 *   sphere of radius r: uniform radiance I / (pi r^2) (intensity I seen from anywhere), sampled
 *       uniformly in the cone it subtends;
 *   environment: uniform radiance L, sampled cosine-weighted about a surface's outward normal, or
 *       uniformly over the sphere from a point inside a medium. */
#include <math.h>
#include <stdlib.h>

#include "trace/internal.h"

/* 1 - cos a, accurate for small a. */
static double one_minus_cos(double a)
{
    double s = sin(0.5 * a);
    return 2.0 * s * s;
}

static void build_one(const lucent_light *in, int index, tr_light *l)
{
    *l = (tr_light){
        .type = in->type, .scene_index = index, .position = v3_load(in->position), .radius = in->radius, .delta = true};
    double scale = in->intensity;
    if (in->type == LUCENT_LIGHT_DIRECTIONAL) {
        l->toward = v3_neg(v3_normalize(v3_load(in->direction)));
        if (in->angular_radius > 0) {
            l->delta = false;
            l->solid_angle = 2.0 * M_PI * one_minus_cos(in->angular_radius);
            l->cos_cone = 1.0 - one_minus_cos(in->angular_radius);
            scale /= l->solid_angle;
        }
    } else if (in->type == LUCENT_LIGHT_SPHERE) {
        l->delta = false;
        scale /= M_PI * in->radius * in->radius;
    } else if (in->type == LUCENT_LIGHT_ENVIRONMENT) {
        l->delta = false;
    }
    for (int c = 0; c < 3; c++) l->radiance[c] = in->color[c] * scale;
}

/* A rough share of the light's power at the scene: irradiance facing it. */
static double power_proxy(const lucent_light *in, v3 centre, double radius)
{
    double c[3] = {in->color[0] * in->intensity, in->color[1] * in->intensity, in->color[2] * in->intensity};
    double y = tr_luminance(c);
    if (in->type == LUCENT_LIGHT_ENVIRONMENT) return M_PI * y;
    if (in->type == LUCENT_LIGHT_DIRECTIONAL) return y;
    double d = fmax(v3_length(v3_sub(v3_load(in->position), centre)), fmax(radius, 1e-3));
    return y / (d * d);
}

lucent_status tr_lights_build(lucent_tracer *tr)
{
    const lucent_scene *sc = tr->scene;
    int n = sc->light_count;
    if (n > TR_MAX_LIGHTS)
        return lucent_error(LUCENT_ERR_UNSUPPORTED, "%s: the path tracer takes at most %d lights (got %d)",
                            sc->path[0] ? sc->path : "scene", TR_MAX_LIGHTS, n);
    tr->lights = calloc((size_t)(n ? n : 1), sizeof *tr->lights);
    if (!tr->lights) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: out of memory");
    tr->light_count = n;
    double lo[3], hi[3], w[TR_MAX_LIGHTS], sum = 0;
    lucent_scene_bounds(sc, lo, hi);
    v3 centre = v3_scale(v3_add(v3_load(lo), v3_load(hi)), 0.5);
    double radius = lo[0] <= hi[0] ? 0.5 * v3_length(v3_sub(v3_load(hi), v3_load(lo))) : 1.0;
    int lit = 0; /* lights that give light: a dark one (intensity 0) is never picked */
    for (int i = 0; i < n; i++) {
        build_one(&sc->lights[i], i, &tr->lights[i]);
        w[i] = power_proxy(&sc->lights[i], centre, radius);
        sum += w[i];
        lit += w[i] > 0;
    }
    double acc = 0, best = 0;
    for (int i = 0; i < n; i++) {
        tr->lights[i].select = w[i] > 0 ? 0.75 * w[i] / sum + 0.25 / lit : 0.0;
        acc += tr->lights[i].select;
        tr->select_cdf[i] = acc;
        if (sc->lights[i].type != LUCENT_LIGHT_ENVIRONMENT && w[i] > best)
            best = w[i], tr->walk_target = &tr->lights[i];
    }
    return LUCENT_OK;
}

const tr_light *tr_light_pick(const lucent_tracer *tr, double u, bool camera_side)
{
    const double *cdf = camera_side ? tr->select_cdf_cam : tr->select_cdf;
    if (tr->light_count == 0 || !(cdf[tr->light_count - 1] > 0)) return NULL;
    u *= cdf[tr->light_count - 1];
    for (int i = 0; i < tr->light_count - 1; i++)
        if (u < cdf[i]) return &tr->lights[i];
    return &tr->lights[tr->light_count - 1];
}

/* Uniform direction in the cone of axis a and 1 - cos(half-angle) = omc. */
static v3 sample_cone(v3 a, double omc, double u1, double u2)
{
    return lucent_around(a, 1.0 - u1 * omc, 2.0 * M_PI * u2);
}

static bool sample_sphere_light(const tr_light *l, v3 p, double u1, double u2, tr_light_sample *s)
{
    v3 to = v3_sub(l->position, p);
    double dc = v3_length(to);
    if (!(dc > l->radius)) return false;
    double sin_max = l->radius / dc, cos_max = sqrt(fmax(0.0, 1.0 - sin_max * sin_max));
    double omc = sin_max * sin_max / (1.0 + cos_max);
    s->w = sample_cone(v3_scale(to, 1.0 / dc), omc, u1, u2);
    double b = v3_dot(s->w, to), disc = l->radius * l->radius - (dc * dc - b * b);
    s->dist = fmax(0.0, b - sqrt(fmax(0.0, disc)));
    s->pdf = l->select / (2.0 * M_PI * omc);
    return true;
}

static void sample_environment(const tr_light *l, v3 n, double u1, double u2, tr_light_sample *s)
{
    if (v3_dot(n, n) > 0) {
        double mu = sqrt(u1); /* cosine-weighted: pdf = cos / pi */
        s->w = lucent_around(n, mu, 2.0 * M_PI * u2);
        s->pdf = l->select * mu * M_1_PI;
    } else {
        s->w = lucent_around(v3_make(0, 0, 1), 1.0 - 2.0 * u1, 2.0 * M_PI * u2);
        s->pdf = l->select * (0.25 * M_1_PI);
    }
    s->dist = INFINITY;
}

bool tr_light_sample_from(const tr_light *l, v3 p, v3 n, double u1, double u2, tr_light_sample *s)
{
    *s = (tr_light_sample){.dist = INFINITY, .pdf = l->select, .delta = l->delta};
    double scale = 1.0;
    if (l->type == LUCENT_LIGHT_DIRECTIONAL) {
        s->w = l->delta ? l->toward : sample_cone(l->toward, 1.0 - l->cos_cone, u1, u2);
        if (!l->delta) s->pdf = l->select / l->solid_angle;
    } else if (l->type == LUCENT_LIGHT_POINT) {
        v3 to = v3_sub(l->position, p);
        s->dist = v3_length(to);
        if (!(s->dist > 0)) return false;
        s->w = v3_scale(to, 1.0 / s->dist);
        scale = 1.0 / (s->dist * s->dist);
    } else if (l->type == LUCENT_LIGHT_SPHERE) {
        if (!sample_sphere_light(l, p, u1, u2, s)) return false;
    } else {
        sample_environment(l, n, u1, u2, s);
    }
    if (v3_dot(n, n) > 0 && v3_dot(s->w, n) <= 0) return false;
    for (int c = 0; c < 3; c++) s->le[c] = l->radiance[c] * scale;
    return s->pdf > 0;
}

double tr_light_pdf(const tr_light *l, v3 p, v3 n, v3 w)
{
    if (l->delta) return 0;
    bool surface = v3_dot(n, n) > 0;
    if (surface && v3_dot(w, n) <= 0) return 0;
    if (l->type == LUCENT_LIGHT_DIRECTIONAL)
        return v3_dot(w, l->toward) >= l->cos_cone ? l->select / l->solid_angle : 0;
    if (l->type == LUCENT_LIGHT_ENVIRONMENT)
        return surface ? l->select * v3_dot(w, n) * M_1_PI : l->select * (0.25 * M_1_PI);
    v3 to = v3_sub(l->position, p);
    double dc = v3_length(to);
    if (!(dc > l->radius)) return 0;
    double sin_max = l->radius / dc, cos_max = sqrt(fmax(0.0, 1.0 - sin_max * sin_max));
    if (v3_dot(w, to) < cos_max * dc) return 0;
    return l->select / (2.0 * M_PI * sin_max * sin_max / (1.0 + cos_max));
}

void tr_lights_escaped(const lucent_tracer *tr, v3 w, tr_light_fn fn, void *ctx)
{
    for (int i = 0; i < tr->light_count; i++) {
        const tr_light *l = &tr->lights[i];
        bool seen = l->type == LUCENT_LIGHT_ENVIRONMENT ||
                    (l->type == LUCENT_LIGHT_DIRECTIONAL && !l->delta && v3_dot(w, l->toward) >= l->cos_cone);
        if (seen) fn(ctx, l, l->radiance);
    }
}

/* Nearest t > 0 where o + t d meets the sphere (c, r), or INFINITY. */
static double sphere_hit(v3 c, double r, v3 o, v3 d)
{
    v3 oc = v3_sub(o, c);
    double b = v3_dot(oc, d), q = v3_dot(oc, oc) - r * r, disc = b * b - q;
    if (disc < 0) return INFINITY;
    double sq = sqrt(disc), t0 = -b - sq, t1 = -b + sq;
    return t0 > 0 ? t0 : (t1 > 0 && q > 0 ? t1 : INFINITY);
}

double tr_light_distance(const tr_light *l, v3 o, v3 w, double dist)
{
    if (l->type != LUCENT_LIGHT_SPHERE) return dist;
    double t = sphere_hit(l->position, l->radius, o, w);
    return isfinite(t) ? t : dist;
}

int tr_sphere_light_hit(const lucent_tracer *tr, v3 o, v3 d, double tfar, double *t)
{
    int best = -1;
    *t = tfar;
    for (int i = 0; i < tr->light_count; i++) {
        const tr_light *l = &tr->lights[i];
        if (l->type != LUCENT_LIGHT_SPHERE) continue;
        double th = sphere_hit(l->position, l->radius, o, d);
        if (th < *t) *t = th, best = i;
    }
    return best;
}

/* Multiplies T by exp(-sigma_t s) and Tw by the walk's exp(-sigma* s) for a stretch in medium m. */
static void stretch(const lucent_tracer *tr, int m, v3 o, v3 d, double s, double T[3], double Tw[3])
{
    const tr_object *ob = &tr->objects[m];
    tr_transform tf;
    tr_field_lookup(tr, m, o, &tf);
    for (int c = 0; c < 3; c++) {
        double sw = tr_walk_sigma(ob, &tf, c, d), e = exp(-ob->sigma_t[c] * s);
        T[c] *= e;
        Tw[c] *= tr_walk_decay(sw, ob->sigma_t[c], e, s);
    }
}

bool tr_transmittance(const lucent_tracer *tr, v3 o, v3 d, double tmax, int medium, double T[3], double Tw[3])
{
    double spare[3];
    if (!Tw) Tw = spare;
    T[0] = T[1] = T[2] = Tw[0] = Tw[1] = Tw[2] = 1.0;
    double ts;
    if (medium < 0 && !tr->has_matched) /* nothing to pass through: any surface blocks */
        return !tr_occluded(tr->geometry, o, d, tmax) && tr_sphere_light_hit(tr, o, d, tmax, &ts) < 0;
    for (int crossings = 0; crossings < 256; crossings++) {
        tr_hit h;
        bool hit = tr_intersect(tr->geometry, o, d, 0.0, tmax, &h);
        double seg = hit ? h.t : tmax;
        if (tr_sphere_light_hit(tr, o, d, seg, &ts) >= 0) return false;
        if (medium >= 0) {
            if (!isfinite(seg)) return false; /* inside a medium with no way out: a hole */
            stretch(tr, medium, o, d, seg, T, Tw);
        }
        if (!hit) return true;
        if (tr->objects[h.object].boundary.kind != TR_BOUNDARY_MATCHED) return false;
        double side = v3_dot(d, h.n) < 0 ? -1.0 : 1.0; /* entering: offset inward */
        medium = side < 0 ? h.object : -1;
        o = v3_madd(v3_madd(o, d, h.t), h.n, side * tr->eps);
        tmax -= h.t;
    }
    return false;
}
