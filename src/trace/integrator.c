/* One camera path: a volumetric random walk through dielectric boundaries with next-event estimation
 * at every vertex (nee.c). Outside media the ray flies to the next surface; inside object o's medium a
 * free-flight distance is drawn for the hero channel h (p(t) = sigma*_h exp(-sigma*_h t), sigma* the
 * walk's transform of sigma_t, media.c); a scattering vertex multiplies channel c by
 * sigma_s,c exp(-sigma_t,c t) over the hero's density and draws a direction (Henyey-Greenstein, or the
 * transform's); reaching the boundary first multiplies by exp(-sigma_t,c d) / exp(-sigma*_h d). Bounds: render.max_bounces surface events and
 * render.max_scatter scatterings end a path (counted as truncated), and a ray inside a medium that
 * meets no surface at all has left a mesh through a hole and ends (counted as escaped), so open
 * meshes cannot hang the tracer. Russian roulette ends paths of small throughput without bias. */
#include <math.h>

#include "trace/path.h"

#define RR_START 3 /* vertices before Russian roulette */

static void rescale(tr_path *p)
{
    double m = tr_max3(p->r);
    if (!(m > 0) || (m > 1e-100 && m < 1e100)) return;
    for (int c = 0; c < 3; c++) p->r[c] /= m, p->beta[c] /= m;
}

static void roulette(tr_path *p)
{
    if (p->bounces + p->scatters < RR_START) return;
    double s = tr_max3(p->beta) * p->eta_scale / tr_mean3(p->r);
    if (!(s > 0)) {
        p->done = true;
        return;
    }
    if (s >= 1.0) return;
    if (tr_u(p) >= s) p->done = true;
    for (int c = 0; c < 3; c++) p->beta[c] /= s;
}

/* Adds light l's radiance le seen along the walk, weighted against the other strategies. */
static void add_found(void *ctx, const tr_light *l, const double le[3])
{
    tr_path *p = ctx;
    if (p->camera_side && l->light_paths) return; /* the light paths' */
    double w = tr_mis_hit_weight(p, l, p->d) / tr_mean3(p->r), v[3];
    for (int c = 0; c < 3; c++) v[c] = p->beta[c] * le[c] * w;
    tr_path_add(p, v);
}

static void escaped(tr_path *p)
{
    p->done = true;
    if (p->to_camera) return; /* a light path never meets the camera's pinhole */
    if (p->camera_ray) {
        const double *bg = p->tr->render.view.background;
        tr_path_add(p, bg);
    }
    tr_lights_escaped(p->tr, p->d, add_found, p);
}

/* The MIS record left by a rough boundary vertex y that the walk leaves in direction i (pdf pb). */
static void record_surface(tr_path *p, v3 y, v3 n, double pb, bool inside)
{
    tr_mis *m = &p->mis;
    *m = (tr_mis){.kind = MIS_SURFACE, .p = y, .n = n, .tc = {1, 1, 1}};
    for (int c = 0; c < 3; c++) m->a[c] = p->r[c], m->pb[c] = pb;
    if (inside && p->from_volume) {
        m->has_guide = true;
        m->guide = p->guide;
        m->w = p->d;
        m->walk_h = p->walk_h;
        for (int c = 0; c < 3; c++) m->rx[c] = p->rx[c];
    }
}

/* Crosses an index-matched surface: no vertex, the MIS record carries on. */
static void pass_through(tr_path *p, const tr_hit *h, v3 y)
{
    bool entering = v3_dot(p->d, h->n) < 0;
    p->medium = entering ? h->object : -1;
    p->o = v3_madd(y, h->n, entering ? -p->tr->eps : p->tr->eps);
}

/* A photon's first arrival at a served object, y on its boundary: the entry roulette (light_paths.c).
 * False when the photon ends there. */
static bool entry_roulette(tr_path *p, v3 y)
{
    tr_photon_entry *e = p->entry;
    e->arrived = true;
    e->cell = tr_entry_cell(p->tr, y);
    e->q_cell = e->q && e->cell >= 0 ? e->q[e->cell] : 1.0;
    e->went_on = e->q_cell >= 1.0 || tr_u(p) < e->q_cell;
    if (!e->went_on) {
        p->stats->entry_ended++;
        p->done = true;
        return false;
    }
    if (e->q_cell < 1.0)
        for (int c = 0; c < 3; c++) p->beta[c] /= e->q_cell;
    return true;
}

static void surface(tr_path *p, const tr_hit *h)
{
    const lucent_tracer *tr = p->tr;
    v3 y = v3_madd(p->o, p->d, h->t), n = h->n;
    const tr_boundary *b = &tr->objects[h->object].boundary;
    bool first = p->camera_ray, inside = v3_dot(p->d, n) > 0, drop_reflection = first && tr->desc.subsurface_only;
    p->camera_ray = false;
    p->safe_r = 0;                                                        /* a new stretch of medium */
    if (!inside && p->bounces > 0 && !tr->render.trace.interreflection) { /* light between surfaces */
        p->done = true;
        return;
    }
    if (++p->bounces > tr->render.trace.max_bounces || v3_dot(n, n) == 0) {
        p->stats->truncated += p->bounces > tr->render.trace.max_bounces;
        p->done = true;
        return;
    }
    if (b->kind == TR_BOUNDARY_MATCHED) {
        pass_through(p, h, y);
        return;
    }
    if (p->entry && !p->entry->arrived && !inside && tr->objects[h->object].light_paths && !entry_roulette(p, y))
        return;
    tr_guide g = {.x = y, .surface = true, .n = n, .o = v3_neg(p->d), .object = h->object};
    /* a light path connects to the camera from inside only: what the boundary reflects from outside
     * toward the camera is the camera paths' */
    if (b->kind == TR_BOUNDARY_ROUGH && !drop_reflection && (inside || !p->to_camera))
        tr_nee_surface(p, y, n, h->object, inside);
    bool through = b->kind == TR_BOUNDARY_ROUGH && !tr->desc.boundary_nee_only;
    bool enters_lp = p->primary && !inside && tr->objects[h->object].light_paths; /* entering: light paths' */
    p->camera_side |= enters_lp;
    if (through) tr_nee_through(p, &g);
    tr_bsdf_sample bs;
    double u0 = tr_u(p), u1 = tr_u(p), u2 = tr_u(p);
    if (!tr_bsdf_sample_dir(b, n, v3_neg(p->d), u0, u1, u2, &bs) || (drop_reflection && !bs.transmit)) {
        p->done = true;
        return;
    }
    p->primary = false;
    /* set where it enters, and kept to its end: every light it finds after that of a served light
     * reached the camera out of the served object, which the light paths count */
    if (enters_lp) p->camera_side = bs.transmit;
    if (p->camera_side && tr->camera_side_lights == 0) { /* all its light is the light paths' */
        p->done = true;
        return;
    }
    if (bs.delta)
        p->mis = (tr_mis){.kind = MIS_NONE};
    else
        record_surface(p, y, n, bs.pdf, inside);
    /* a light path carries power: the radiance scaling of the boundary does not apply (field.c too) */
    for (int c = 0; c < 3; c++) p->beta[c] *= p->to_camera ? bs.weight / bs.scale : bs.weight;
    if (!p->to_camera) p->eta_scale /= bs.scale;
    if (bs.transmit) p->medium = inside ? -1 : h->object;
    p->from_volume = through && v3_dot(bs.i, n) < 0;
    if (p->from_volume) {
        p->guide = g;
        p->walk_h = bs.pdf;
        for (int c = 0; c < 3; c++) p->rx[c] = p->r[c];
    }
    p->o = v3_madd(y, n, v3_dot(bs.i, n) > 0 ? tr->eps : -tr->eps);
    p->d = bs.i;
    roulette(p);
}

static void step_outside(tr_path *p)
{
    tr_hit h;
    bool hit = tr_intersect(p->tr->geometry, p->o, p->d, 0.0, INFINITY, &h);
    double ts;
    int sphere = tr_sphere_light_hit(p->tr, p->o, p->d, hit ? h.t : INFINITY, &ts);
    if (sphere >= 0) {
        const tr_light *l = &p->tr->lights[sphere];
        if (!p->to_camera) add_found(p, l, l->radiance);
        p->done = true;
    } else if (!hit) {
        escaped(p);
    } else {
        surface(p, &h);
    }
}

/* Multiplies beta by the physics over the hero's sampling density, and r by channel k's density
 * over the hero's, for a stretch of length s in medium ob started in direction p->d (toward-light
 * direction u): exp(-sigma_t,c s) against the walk's exp(-sigma*_k s), and for a scattering vertex
 * sigma_s,c against sigma*_k. */
static void attenuate(tr_path *p, const tr_object *ob, double s, bool scatter, const tr_transform *tf)
{
    int h = p->hero;
    double sw[3], eb[3], er[3], ew = 1.0;
    for (int k = 0; k < 3; k++) sw[k] = tr_walk_sigma(ob, tf, k, p->d);
    double sh = sw[h], st = ob->sigma_t[h];
    /* exp is the walk's costliest call: a factor whose exponent is zero (the hero's own r, and in the
     * analog walk its beta) is 1, and one whose exponent equals another's (sigma* = sigma_t in the
     * analog walk) is reused; the same values bit for bit, 3 exp calls per analog scattering, not 8 */
    for (int c = 0; c < 3; c++) eb[c] = ob->sigma_t[c] == sh ? 1.0 : exp(-(ob->sigma_t[c] - sh) * s);
    for (int c = 0; c < 3; c++) er[c] = c == h ? 1.0 : sw[c] == ob->sigma_t[c] ? eb[c] : exp(-(sw[c] - sh) * s);
    if (p->from_volume || p->mis.kind != MIS_NONE) ew = exp(-sh * s);
    p->tw *= eb[h] * (scatter ? st / sh : 1.0);
    for (int c = 0; c < 3; c++) {
        p->beta[c] *= eb[c] * (scatter ? ob->sigma_s[c] / sh : 1.0);
        p->r[c] *= er[c] * (scatter ? sw[c] / sh : 1.0);
        if (p->mis.kind != MIS_NONE) p->mis.tc[c] *= c == h ? ew : exp(-sw[c] * s);
    }
    if (p->from_volume) p->walk_h *= ew;
}

/* Draws the walk's next direction and records the vertex. */
static void scatter_direction(tr_path *p, const tr_object *ob, v3 x, const tr_transform *tf)
{
    v3 w = tr_walk_sample(ob, tf, p->hero, p->d, tr_u(p), tr_u(p), tr_u(p));
    double ph[3], pw[3];
    tr_walk_phase_pdf(ob, tf, p->d, w, ph, pw);
    double p_h = pw[p->hero];
    p->tw *= ph[p->hero] / p_h;
    for (int c = 0; c < 3; c++) p->rx[c] = p->r[c];
    for (int c = 0; c < 3; c++) p->beta[c] *= ph[c] / p_h, p->r[c] *= pw[c] / p_h;
    p->from_volume = ob->boundary.kind == TR_BOUNDARY_ROUGH && !p->tr->desc.boundary_nee_only;
    p->walk_h = p_h;
    if (ob->boundary.kind == TR_BOUNDARY_MATCHED) {
        p->mis = (tr_mis){.kind = MIS_VOLUME, .p = x, .tc = {1, 1, 1}};
        for (int c = 0; c < 3; c++) p->mis.a[c] = p->rx[c], p->mis.pb[c] = pw[c];
    } else { /* nothing else of the record is read (zeroing it whole cost 0.5% of the dragon's run) */
        p->mis.kind = MIS_NONE;
    }
    p->o = x;
    p->d = w;
}

/* ---- free flights bounded by the distance to the boundary ----
 * In a dense, nearly non-absorbing medium (marble: a mean free path of 0.4 mm, albedo 0.999) a walk
 * takes hundreds of flights, and each asked Embree for the boundary ahead although most end far from
 * it. The object's depth lattice (depth.c) gives, at any point, the radius of a sphere about it that
 * holds no surface. A flight that stays inside the union of two such spheres, the path's current one
 * (about an earlier vertex) and one about the flight's end, cannot have crossed a surface, so it needs
 * no ray query: the same decision the query would have made, so the estimate is unchanged (tested bit
 * for bit). Next-event estimation from a vertex at depth d (a lower bound from the sphere) reaches
 * the boundary through at least d of medium, so it contributes at most about exp(-sigma_min d) of a
 * shallow vertex's; it is made with probability P = min(1, exp(1 - sigma_min d)) and weighted by 1 / P
 * (Russian roulette on an estimator: unbiased, and its weighted value stays below a shallow vertex's).
 * Both only in dense media (tr_object.depth, TR_DENSE_ALBEDO): elsewhere walks are short. */
#define SAFE_REFRESH 0.5 /* a vertex asks the lattice for a new sphere once the old one is this far used up */

/* How far the flight from p->o along p->d stays inside the safe sphere (0 when there is none). */
static double safe_reach(const tr_path *p) { return tr_path_safe_run(p, p->o, p->d); }

/* A lower bound on the distance from x to any surface (0 outside the safe sphere). */
static double safe_depth(const tr_path *p, v3 x)
{
    double d = p->safe_r > 0 ? p->safe_r - v3_length(v3_sub(x, p->safe_c)) : 0.0;
    return d > 0 ? d : 0.0;
}

/* The lattice's sphere about x, less a margin for the float precision of Embree's hit points. */
static double lattice_radius(const tr_path *p, const tr_object *ob, v3 x)
{
    return tr_depth_bound(ob->depth, p->tr->geometry, x) - 4.0 * p->tr->eps;
}

/* A new safe sphere about volume vertex x once the old one is used up to SAFE_REFRESH of its radius
 * (a lookup at every vertex cost more than the ray queries its larger spheres saved: docs/trace.md);
 * r: the lattice's radius at x when the flight there already looked it up (else NaN). */
static void refresh_safe(tr_path *p, const tr_object *ob, v3 x, double r)
{
    if (!ob->depth) return;
    double depth = safe_depth(p, x);
    if (p->safe_r > 0 && depth >= (1.0 - SAFE_REFRESH) * p->safe_r) return;
    if (isnan(r)) r = lattice_radius(p, ob, x);
    if (r > depth) p->safe_c = x, p->safe_r = r;
}

/* The probability of making the next-event estimate at volume vertex x (see above). */
static double nee_probability(const tr_path *p, const tr_object *ob, double depth)
{
    if (p->tr->desc.nee_every_vertex) return 1.0;
    double e = 1.0 - ob->sigma_t_min * depth;
    return e >= 0 ? 1.0 : exp(e); /* within a mean free path: 1, without calling exp */
}

/* A vertex's guide takes the ray toward the light of an earlier vertex of its walk within this many
 * mean free paths (guide.c; not with nee_every_vertex, the plain estimator): on the dragon in marble,
 * 1 gave 0.955 of the CPU time per sample with 2% more variance; 2 and more, more variance for the
 * same time (docs/trace.md). */
#define GUIDE_REUSE_MFP 1.0

/* A scattering at distance t along the flight; r_end: the lattice's radius there if looked up (else NaN). */
static void scatter(tr_path *p, const tr_object *ob, double t, const tr_transform *tf, double r_end)
{
    v3 x = v3_madd(p->o, p->d, t);
    attenuate(p, ob, t, true, tf);
    rescale(p);
    p->analog |= p->tw > TR_TW_MAX;
    p->stats->scatters++;
    tr_guide *g = &p->guide; /* a volume vertex's guide: no surface, nothing prepared; the fields those
                                flags guard are not read, so they are not zeroed (the dragon: scatter's
                                own time 2.7% of the run less, the image the same bit for bit) */
    tr_guide_move(g, x, p->medium, p->tr->desc.nee_every_vertex ? 0.0 : GUIDE_REUSE_MFP / ob->sigma_t_min);
    g->d_in = p->d;
    refresh_safe(p, ob, x, r_end);
    if (ob->boundary.kind == TR_BOUNDARY_ROUGH && !p->tr->desc.boundary_nee_only) {
        g->depth = safe_depth(p, x);
        double pn = nee_probability(p, ob, g->depth);
        if (pn >= 1.0 || tr_u(p) < pn) {
            p->nee_weight = 1.0 / pn;
            p->stats->nee++;
            tr_nee_through(p, &p->guide);
            p->nee_weight = 1.0;
        }
    } else if (ob->boundary.kind == TR_BOUNDARY_MATCHED) {
        tr_nee_volume_matched(p, x);
    }
    if (++p->scatters >= p->tr->render.trace.max_scatter) {
        p->stats->truncated++;
        p->done = true;
        return;
    }
    tr_transform here;
    tr_path_transform(p, p->medium, x, &here);
    scatter_direction(p, ob, x, &here);
    roulette(p);
}

static void step_inside(tr_path *p)
{
    const tr_object *ob = &p->tr->objects[p->medium];
    tr_transform tf;
    tr_path_transform(p, p->medium, p->o, &tf);
    double t = -log(1.0 - tr_u(p)) / tr_walk_sigma(ob, &tf, p->hero, p->d);
    double reach = safe_reach(p), r_end = NAN;
    if (!(t < reach) && ob->depth) { /* the spheres about the flight's two ends may cover it */
        v3 x = v3_madd(p->o, p->d, t);
        r_end = lattice_radius(p, ob, x);
        if (t - r_end < reach) p->safe_c = x, p->safe_r = r_end, reach = INFINITY;
    }
    if (t < reach) { /* ends inside the safe sphere: no surface on the way */
        p->stats->free_flights++;
        scatter(p, ob, t, &tf, r_end);
        return;
    }
    tr_hit h;
    if (!tr_intersect(p->tr->geometry, p->o, p->d, 0.0, INFINITY, &h)) {
        p->stats->escaped++; /* left the mesh through a hole */
        p->done = true;
    } else if (t < h.t) {
        scatter(p, ob, t, &tf, r_end);
    } else {
        attenuate(p, ob, h.t, false, &tf);
        surface(p, &h);
    }
}

/* Runs path p to its end; whether it met a surface. */
static bool run(tr_path *p)
{
    uint64_t rays0, points0, rays1, points1;
    tr_geometry_queries(&rays0, &points0);
    p->hero = (int)(tr_u(p) * 3.0);
    if (p->hero > 2) p->hero = 2;
    bool covered = false;
    while (!p->done) {
        if (p->medium < 0)
            step_outside(p);
        else
            step_inside(p);
        covered |= p->bounces > 0;
    }
    p->stats->bounces += (uint64_t)p->bounces;
    tr_geometry_queries(&rays1, &points1);
    p->stats->rays += rays1 - rays0, p->stats->points += points1 - points0;
    return covered;
}

bool tr_trace_path(const lucent_tracer *tr, double px, double py, lucent_rng *rng, double dest[3], tr_stats *stats)
{
    tr_path p = {.tr = tr,
                 .rng = rng,
                 .stats = stats,
                 .beta = {1, 1, 1},
                 .r = {1, 1, 1},
                 .eta_scale = 1,
                 .tw = 1,
                 .medium = -1,
                 .nee_weight = 1,
                 .camera_ray = true,
                 .primary = true};
    double o[3], d[3];
    lucent_camera_ray(&tr->scene->camera, tr->render.view.width, tr->render.view.height, px, py, o, d);
    p.o = v3_load(o), p.d = v3_load(d);
    stats->paths++;
    bool covered = run(&p);
    for (int c = 0; c < 3; c++) dest[c] = p.L[c];
    return covered;
}

void tr_trace_light_path(const lucent_tracer *tr, v3 o, v3 d, const double beta[3], double scale, lucent_rng *rng,
                         struct tr_splats *splats, tr_photon_entry *entry, tr_stats *stats)
{
    tr_path p = {.tr = tr,
                 .rng = rng,
                 .stats = stats,
                 .beta = {beta[0], beta[1], beta[2]},
                 .r = {1, 1, 1},
                 .eta_scale = 1,
                 .tw = 1,
                 .analog = true, /* the field steers toward the lights, not the camera */
                 .medium = -1,
                 .nee_weight = 1,
                 .o = o,
                 .d = d,
                 .to_camera = true,
                 .splats = splats,
                 .splat_scale = scale,
                 .entry = entry};
    stats->photons++;
    run(&p);
}
