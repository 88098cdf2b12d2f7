/* Next-event estimation and the multiple-importance-sampling weights (Veach 1997, ch. 9, the balance
 * heuristic, combined with the hero channel's balance over channels; docs/trace.md gives the
 * derivation). A light connection x -> y -> light (x a volume vertex, y the boundary point where the
 * light refracts in) can be made three ways:
 *   S1 at x: draw the inside direction w from the guide q, meet the boundary at y, sample the light
 *      at y (density p_l);
 *   S2 at y, reached by the walk from x (phase function and free flight past y: p_k(w) T_k(d) for
 *      channel k's sampling), sampling the light at y (p_l);
 *   S3: the same walk, then the BSDF at y draws the direction (p_b) and it reaches the light (only for
 *      lights that can be hit: not delta lights).
 * With prefix ratios r_k, every strategy divides the path's contribution by the same
 *   Den = (1/3) sum_k r_k [q p_l + p_k T_k (p_l + p_b Tch_k)],
 * (Tch_k the transmittance of the stretch beyond y, non-zero only through index-matched media), so
 * the three weights sum to one for every path. */
#include <math.h>

#include "trace/path.h"

void tr_path_add(tr_path *p, const double v[3])
{
    if (!isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2])) {
        p->stats->nonfinite++;
        return;
    }
    for (int c = 0; c < 3; c++) p->L[c] += v[c];
}

void tr_path_add_at(tr_path *p, long pixel, const double v[3])
{
    if (!p->to_camera) {
        tr_path_add(p, v);
        return;
    }
    if (!isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2])) {
        p->stats->nonfinite++;
        return;
    }
    double s[3] = {v[0] * p->splat_scale, v[1] * p->splat_scale, v[2] * p->splat_scale};
    tr_splat(p->splats, pixel, s);
}

const tr_light *tr_path_pick(tr_path *p, int object, double *ratio)
{
    *ratio = 1.0;
    /* a light path connects to the camera only out of a served object: what leaves the others toward
     * the camera is the camera paths' (they enter those objects with every light) */
    if (p->to_camera) return object >= 0 && p->tr->objects[object].light_paths ? &p->tr->camera_light : NULL;
    const tr_light *l = tr_light_pick(p->tr, tr_u(p), p->camera_side);
    if (l) *ratio = tr_light_pick_ratio(l, p->camera_side);
    return l;
}

/* A light path's connection reaches the camera through boundary point y: the radiance BTDF of that
 * direction, f(camera <- inside), is the one evaluated (f(inside <- camera)) over eta^2 (radiance
 * reciprocity, f(a <- b) / eta_a^2 = f(b <- a) / eta_b^2, Veach 1997 eq. 5.14). */
static double camera_btdf_factor(const tr_path *p, const tr_boundary *b)
{
    return p->to_camera ? 1.0 / (b->eta * b->eta) : 1.0;
}

/* The point where an inside ray from x along w leaves object `object`, or false (a hole, another
 * object, or a face seen from its outer side). */
static bool exit_point(const lucent_tracer *tr, v3 x, v3 w, int object, tr_hit *h)
{
    return tr_intersect(tr->geometry, x, w, 0.0, INFINITY, h) && h->object == object && v3_dot(w, h->n) > 0;
}

/* Samples light l at boundary point y (outward normal n) for viewer direction o: BSDF value f, its
 * density pb for the light's direction, and the visibility transmittance; false when nothing arrives. */
typedef struct connection {
    tr_light_sample ls;
    double f, pb, cos, T[3], Tw[3];
    long pixel; /* a light path's: where the connection lands in the image */
} connection;

static bool connect_boundary(tr_path *p, const tr_light *l, double ratio, v3 y, v3 n, const tr_boundary *b, v3 o,
                             connection *c)
{
    const lucent_tracer *tr = p->tr;
    if (!tr_light_sample_from(l, y, n, tr_u(p), tr_u(p), &c->ls)) return false;
    c->ls.pdf *= ratio;
    c->pixel = p->to_camera ? tr_light_paths_importance(tr, y, c->ls.le) : -1;
    if (p->to_camera && c->pixel < 0) return false; /* outside the view */
    c->f = tr_bsdf_eval(b, n, o, c->ls.w, &c->pb) * camera_btdf_factor(p, b);
    if (!(c->f > 0)) return false;
    c->cos = fabs(v3_dot(c->ls.w, n));
    v3 from = v3_madd(y, n, tr->eps); /* off the surface: the light's own distance from there */
    double dist = tr_light_distance(l, from, c->ls.w, c->ls.dist);
    double tmax = isfinite(dist) ? dist * (1.0 - 1e-6) - tr->eps : INFINITY;
    return tr_transmittance(tr, from, c->ls.w, tmax, -1, c->T, c->Tw);
}

/* Russian roulette on the connection's light sample and shadow ray once the exit point is known (Arvo
 * & Kirk 1990): the connection crosses s of medium, so it brings at most exp(-sigma_min s) of its
 * light; it goes on with probability min(1, exp(1 - sigma_min s)) overall, that is, given the deep
 * vertex roulette's 1 / weight already passed, P = min(1, exp(1 - sigma_min s) weight), and its value
 * is weighted by 1 / P. Unbiased; the weighted value stays below what a connection of one mean free
 * path brings. Dense media only, and not with nee_every_vertex (today's estimator). */
static double exit_probability(const tr_path *p, const tr_object *ob, double s, double weight)
{
    if (!ob->dense || p->tr->desc.nee_every_vertex) return 1.0;
    double e = 1.0 - ob->sigma_t_min * s;
    if (e >= 0 && weight >= 1.0) return 1.0; /* without calling exp */
    return lucent_at_most(1.0, exp(e) * weight);
}

/* The exit roulette decided before the exit ray where it can be, from a lower bound on the ray's
 * distance: how far it stays in the vertex's safe sphere, then the lattice's free run (depth.c; the
 * margin is integrator.c's). u is drawn once P is sure to be below 1 (the bound past (1 + ln weight) /
 * sigma_min), and the connection ends without the ray when the bound passes the s at which P falls to
 * u. It is the decision the roulette would make after the ray, since s is at least the bound: the same
 * estimator. A volume vertex whose safe sphere leaves less than FREE_RUN_DEPTH_MFP does not try (its
 * run mostly stops at once). *u stays NaN when not drawn. */
#define FREE_RUN_DEPTH_MFP 0.1

static bool exit_roulette_early(tr_path *p, const tr_guide *g, double weight, v3 w, double *u)
{
    const tr_object *ob = &p->tr->objects[g->object];
    *u = NAN;
    if (!ob->depth || !ob->dense || p->tr->desc.nee_every_vertex) return true;
    double sigma = ob->sigma_t_min;
    if (!g->surface && !(g->depth > FREE_RUN_DEPTH_MFP / sigma)) return true;
    v3 x = g->surface ? v3_madd(g->x, g->n, -p->tr->eps) : g->x;
    double lw = log(weight), t_sure = (1.0 + lw) / sigma, margin = 4.0 * p->tr->eps;
    double t = tr_depth_free_run(ob->depth, x, w, g->surface ? 0.0 : tr_path_safe_run(p, x, w), t_sure, margin);
    if (!(t > t_sure)) return true;
    *u = tr_u(p);
    double t_kill = (1.0 + lw - log(*u)) / sigma;
    return tr_depth_free_run(ob->depth, x, w, t, t_kill, margin) < t_kill;
}

static bool exit_roulette(tr_path *p, const tr_object *ob, double s, double u, double *weight)
{
    double P = exit_probability(p, ob, s, *weight);
    if (P >= 1.0) return true;
    if (isnan(u)) u = tr_u(p);
    if (!(u < P)) return false;
    *weight /= P;
    return true;
}

void tr_nee_through(tr_path *p, tr_guide *g)
{
    const lucent_tracer *tr = p->tr;
    const tr_object *ob = &tr->objects[g->object];
    double ratio;
    const tr_light *l = tr_path_pick(p, g->object, &ratio);
    if (!l) return;
    v3 w, from = g->surface ? v3_madd(g->x, g->n, -tr->eps) : g->x;
    double u0 = tr_u(p), u1 = tr_u(p), u2 = tr_u(p);
    tr_hit h;
    connection c;
    /* the ray toward the light that prepares the guide waits until a walk-like draw survives the exit
     * roulette (q(w) needs it only then): the same estimate, fewer rays */
    tr_guide_select(g, l);
    if (tr_guide_draw_needs_ray(g, u0)) tr_guide_prepare(tr, g, l);
    double weight = p->nee_weight, u;
    if (!tr_guide_sample(tr, g, u0, u1, u2, &w) || !exit_roulette_early(p, g, weight, w, &u) ||
        !exit_point(tr, from, w, g->object, &h))
        return;
    v3 y = v3_madd(from, w, h.t);
    if (!exit_roulette(p, ob, h.t, u, &weight)) return;
    tr_guide_prepare(tr, g, l);
    if (!connect_boundary(p, l, ratio, y, h.n, &ob->boundary, v3_neg(w), &c)) return;
    tr_transform tf;
    tr_path_transform(p, g->object, from, &tf);
    double q = tr_guide_pdf(tr, g, w), pb = c.ls.delta ? 0.0 : c.pb, den = 0, v[3], f[3], pw[3];
    tr_guide_vertex(tr, g, &tf, w, f, pw);
    /* a light path at the boundary vertex where it entered: f(inside <- outside), eta^2 f(outside <- inside) */
    if (p->to_camera && g->surface && v3_dot(g->o, g->n) > 0)
        for (int k = 0; k < 3; k++) f[k] *= ob->boundary.eta * ob->boundary.eta;
    for (int k = 0; k < 3; k++) {
        double sk = tr_walk_sigma(ob, &tf, k, w), e = exp(-ob->sigma_t[k] * h.t);
        double walk = pw[k] * tr_walk_decay(sk, ob->sigma_t[k], e, h.t);
        den += p->r[k] * (q * c.ls.pdf + walk * (c.ls.pdf + pb * c.Tw[k]));
        v[k] = weight * p->beta[k] * f[k] * e * c.f * c.cos * c.ls.le[k] * c.T[k];
    }
    den /= 3.0;
    if (!(den > 0)) return;
    for (int k = 0; k < 3; k++) v[k] /= den;
    tr_path_add_at(p, c.pixel, v);
}

void tr_nee_volume_matched(tr_path *p, v3 x)
{
    const lucent_tracer *tr = p->tr;
    const tr_object *ob = &tr->objects[p->medium];
    double ratio;
    const tr_light *l = tr_path_pick(p, p->medium, &ratio);
    tr_light_sample ls;
    if (!l || p->to_camera || !tr_light_sample_from(l, x, v3_make(0, 0, 0), tr_u(p), tr_u(p), &ls)) return;
    ls.pdf *= ratio;
    double T[3], Tw[3], tmax = isfinite(ls.dist) ? ls.dist * (1.0 - 1e-6) : INFINITY;
    if (!tr_transmittance(tr, x, ls.w, tmax, p->medium, T, Tw)) return;
    double mu = v3_dot(p->d, ls.w), den = 0, v[3];
    tr_transform tf;
    tr_field_lookup(tr, p->medium, x, &tf);
    for (int k = 0; k < 3; k++) {
        double walk = ls.delta ? 0.0 : tr_walk_pdf(ob, &tf, k, p->d, ls.w) * Tw[k];
        den += p->r[k] * (ls.pdf + walk);
        v[k] = p->beta[k] * lucent_hg_phase(mu, ob->g[k]) * ls.le[k] * T[k];
    }
    den /= 3.0;
    if (!(den > 0)) return;
    for (int k = 0; k < 3; k++) v[k] /= den;
    tr_path_add(p, v);
}

/* The S1 term c_k / r_k(x) of the header for light l: next-event estimation from the previous volume
 * vertex, in the path's current normalisation: q(w) / (p_h(w) T_h). */
static double guide_term(tr_path *p, tr_guide *g, v3 w, double walk_h, const tr_light *l)
{
    tr_guide_prepare(p->tr, g, l);
    return tr_guide_pdf(p->tr, g, w) / walk_h;
}

void tr_nee_surface(tr_path *p, v3 y, v3 n, int object, bool inside)
{
    const tr_boundary *b = &p->tr->objects[object].boundary;
    double ratio;
    const tr_light *l = tr_path_pick(p, object, &ratio);
    connection c;
    if (!l || !connect_boundary(p, l, ratio, y, n, b, v3_neg(p->d), &c)) return;
    double g = inside && p->from_volume ? guide_term(p, &p->guide, p->d, p->walk_h, l) : 0.0;
    double pb = c.ls.delta ? 0.0 : c.pb, den = 0, v[3];
    for (int k = 0; k < 3; k++) {
        den += p->r[k] * pb * c.Tw[k] + (p->r[k] + p->rx[k] * g) * c.ls.pdf;
        v[k] = p->beta[k] * c.f * c.cos * c.ls.le[k] * c.T[k];
    }
    den /= 3.0;
    if (!(den > 0)) return;
    for (int k = 0; k < 3; k++) v[k] /= den;
    tr_path_add_at(p, c.pixel, v);
}

double tr_mis_hit_weight(tr_path *p, const tr_light *l, v3 w)
{
    tr_mis *m = &p->mis;
    if (m->kind == MIS_NONE) return 1.0;
    double pl = tr_light_pdf(l, m->p, m->n, w) * tr_light_pick_ratio(l, p->camera_side);
    if (!(pl > 0)) return 1.0;
    double g = m->has_guide ? guide_term(p, &m->guide, m->w, m->walk_h, l) : 0.0, walk = 0, other = 0;
    for (int k = 0; k < 3; k++) {
        walk += m->a[k] * m->pb[k] * m->tc[k];
        other += (m->a[k] + m->rx[k] * g) * pl;
    }
    return walk > 0 ? walk / (walk + other) : 0.0;
}
