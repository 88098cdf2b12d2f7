/* The direction distribution q(w) of next-event estimation through a rough boundary, from a volume
 * vertex x (docs/trace.md, "Next-event estimation through the boundary"). The estimator integrates
 * over the inside direction w, so any q that covers the integrand is unbiased; this one is the mixture
 *   q(w) = P_PHASE p_HG(w; d_in, g_mean) + (1 - P_PHASE) p_lobe(w),
 * where p_lobe is the distribution of the directions in which light from the chosen light refracts
 * into the medium at n0, the outward normal of the boundary point that a ray from x toward the light
 * meets: a visible microfacet normal m is drawn for the light's direction l (Heitz 2018) and l is
 * refracted through m; w is the reverse of the refracted direction t. Its density is the visible-normal
 * density times the refraction Jacobian (Walter et al. 2007, eq. 17):
 *   p_lobe(w) = D_l(m) eta^2 |t . m| / (l . m + eta t . m)^2.
 * For a vertex near a lit surface, the boundary point met along w has nearly the normal n0, so the
 * BTDF toward the light divided by q stays bounded: the lobe follows the integrand. Light from the
 * environment has no direction: q is then the phase function alone. At a boundary vertex (where a
 * camera path enters, or reflects inside) the BSDF's inward directions take the phase function's
 * place.
 *
 * A volume vertex within GUIDE_REUSE_MFP (integrator.c) of where an earlier vertex of its walk traced
 * the ray toward the same light takes that ray's direction and n0 instead of tracing its own
 * (tr_guide_move): the lobe is then the one built there, still a density over w that covers the
 * integrand where the phase share does, and it is a function of the path so far only, so the estimate
 * stays unbiased; the multiple importance sampling evaluates q(w) with the same stored n0 (the guide
 * is copied into the MIS record). A vertex hands on only what it prepared or inherited itself, for
 * one light, and preparing for another light traces a ray as before. */
#include <math.h>

#include "trace/guide.h"

#define P_PHASE 0.3

static bool has_target(const tr_guide *g) { return g->light && g->light->type != LUCENT_LIGHT_ENVIRONMENT; }

void tr_guide_select(tr_guide *g, const tr_light *l)
{
    if (g->light == l) return;
    g->light = l;
    g->prepared = g->has_n0 = false;
}

void tr_guide_move(tr_guide *g, v3 x, int object, double radius)
{
    tr_guide_prep next = g->inherited;
    if (g->prepared && g->has_n0)
        next = (tr_guide_prep){.light = g->light, .from = g->from, .toward = g->toward, .n0 = g->n0};
    if (g->object != object || v3_dot(v3_sub(x, next.from), v3_sub(x, next.from)) > radius * radius) next.light = NULL;
    g->inherited = next;
    g->x = x, g->object = object, g->surface = false;
    g->light = NULL, g->prepared = g->has_n0 = false;
}

void tr_guide_prepare(const lucent_tracer *tr, tr_guide *g, const tr_light *l)
{
    tr_guide_select(g, l);
    if (g->prepared) return;
    v3 from = g->surface ? v3_madd(g->x, g->n, -tr->eps) : g->x;
    g->prepared = true;
    if (!has_target(g)) return;
    if (g->inherited.light == l) {
        g->has_n0 = true;
        g->from = g->inherited.from, g->toward = g->inherited.toward, g->n0 = g->inherited.n0;
        return;
    }
    g->toward = l->type == LUCENT_LIGHT_DIRECTIONAL ? l->toward : v3_normalize(v3_sub(l->position, g->x));
    tr_hit h;
    if (tr_intersect(tr->geometry, from, g->toward, 0.0, INFINITY, &h) && h.object == g->object &&
        v3_dot(h.n, g->toward) > 0) {
        g->has_n0 = true;
        g->n0 = h.n;
        g->from = from;
    }
}

static double phase_share(const tr_guide *g) { return has_target(g) ? P_PHASE : 1.0; }

bool tr_guide_draw_needs_ray(const tr_guide *g, double u0) { return u0 >= phase_share(g); }

bool tr_guide_sample(const lucent_tracer *tr, const tr_guide *g, double u0, double u1, double u2, v3 *w)
{
    const tr_object *ob = &tr->objects[g->object];
    double share = phase_share(g);
    if (u0 < share && g->surface) {
        tr_bsdf_sample bs;
        return tr_bsdf_sample_dir(&ob->boundary, g->n, g->o, u0 / share, u1, u2, &bs) && v3_dot(bs.i, g->n) < 0 &&
               (*w = bs.i, true);
    }
    if (u0 < share) {
        *w = lucent_hg_sample(g->d_in, ob->g_mean, u1, u2);
        return true;
    }
    if (!g->has_n0) return false;
    v3 m = lucent_ggx_sample_visible(g->toward, g->n0, ob->boundary.alpha, u1, u2), t;
    if (!lucent_refract(v3_neg(g->toward), m, ob->boundary.eta, &t) || v3_dot(t, g->n0) >= 0) return false;
    *w = v3_neg(t);
    return !g->surface || v3_dot(*w, g->n) < 0; /* from a boundary vertex, only inward */
}

static double lobe_pdf(const tr_object *ob, const tr_guide *g, v3 w)
{
    double eta = ob->boundary.eta;
    v3 t = v3_neg(w), l = g->toward;
    if (v3_dot(t, g->n0) >= 0) return 0;
    v3 m = lucent_ggx_half_transmit(l, t, 1.0, eta, g->n0); /* Walter eqs. 16, 17 */
    double lm = v3_dot(l, m), tm = v3_dot(t, m);
    if (lm <= 0 || tm >= 0) return 0;
    return lucent_ggx_visible_pdf(l, g->n0, m, ob->boundary.alpha) * lucent_ggx_jacobian_transmit(lm, tm, 1.0, eta);
}

/* The walk-like share of q: the BSDF's inward directions at a boundary vertex, else the phase function. */
static double own_pdf(const tr_object *ob, const tr_guide *g, v3 w)
{
    if (!g->surface) return lucent_hg_phase(v3_dot(g->d_in, w), ob->g_mean);
    double pdf;
    if (v3_dot(w, g->n) >= 0) return 0;
    tr_bsdf_eval(&ob->boundary, g->n, g->o, w, &pdf);
    return pdf;
}

double tr_guide_pdf(const lucent_tracer *tr, const tr_guide *g, v3 w)
{
    const tr_object *ob = &tr->objects[g->object];
    if (g->surface && v3_dot(w, g->n) >= 0) return 0;
    double share = phase_share(g), q = share * own_pdf(ob, g, w);
    if (share < 1.0 && g->has_n0) q += (1.0 - share) * lobe_pdf(ob, g, w);
    return q;
}

void tr_guide_vertex(const lucent_tracer *tr, const tr_guide *g, const tr_transform *tf, v3 w, double f[3],
                     double pdf[3])
{
    const tr_object *ob = &tr->objects[g->object];
    if (g->surface) {
        double p, fb = tr_bsdf_eval(&ob->boundary, g->n, g->o, w, &p) * fabs(v3_dot(w, g->n));
        for (int k = 0; k < 3; k++) f[k] = fb, pdf[k] = p;
        return;
    }
    tr_walk_phase_pdf(ob, tf, g->d_in, w, f, pdf);
}
