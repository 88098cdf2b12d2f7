/* Multipole slabs and their layered composition (Donner & Jensen 2005, "Light Diffusion in
 * Multi-Layered Translucent Materials", SIGGRAPH 2005, Section 3 and 4).
 *
 * A slab of thickness d has an extrapolated boundary on each face, z_b = 2 A D (D = 1/(3 sigma_t'),
 * A = (1 + Fdr)/(1 - Fdr)), where Fdr comes from the relative index across that face: the slab's
 * index over the index above for the top face (z_b(0)), over the index below for the bottom face
 * (z_b(d)) (Donner & Jensen 2005, Section 3). Mirroring the dipole of z_r = l = 1/sigma_t' about
 * both extrapolated boundaries (u = -z_b(0) and u = d + z_b(d); period 2 (d + z_b(0) + z_b(d)))
 * gives the multipole with mismatched boundaries (Donner & Jensen 2005, Section 3, the multipole
 * pole positions with z_b(0) and z_b(d); the equation numbers were not checked against the PDF
 * here, the positions are re-derived from the two zero-fluence conditions):
 *   z_{r,i} = 2 i (d + z_b(0) + z_b(d)) + l,   z_{v,i} = 2 i (d + z_b(0) + z_b(d)) - l - 2 z_b(0),
 *   i = -n .. n,
 *   R(r) = alpha' sum_i [E(z_{r,i}, r) - E(z_{v,i}, r)],
 *   T(r) = alpha' sum_i [E(d - z_{r,i}, r) - E(d - z_{v,i}, r)],
 * with E the normal flux of a unit point source (profile/pole.h). z_b(0) = z_b(d) = z_b gives the
 * paper's symmetric form 2 i (d + 2 z_b) + l, 2 i (d + 2 z_b) - l - 2 z_b. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/profile.h"
#include "profile/layered.h"
#include "profile/pole.h"

enum { MULTIPOLE_DEFAULT_POLES = 10, MULTIPOLE_MAX_POLES = 1000, LAYERS_MAX = 16 };

/* Diffuse Fresnel reflectance for any relative index eta = n_inside / n_outside.
 * eta >= 1: Jensen et al. 2001's fit (lucent_fdr, material.c).
 * eta < 1 (the outside is denser: no total internal reflection): the fit of Egan & Hilgeman
 * 1979 ("Optical Properties of Inhomogeneous Materials", Academic Press), in the same convention,
 *   Fdr = -0.4399 + 0.7099/eta - 0.3319/eta^2 + 0.0636/eta^3
 * (the coefficients pbrt-v2 uses in core/reflection.h, Fdr). Checked here against the hemispherical
 * integral 2 int_0^1 F_r(eta, mu) mu dmu of the unpolarised Fresnel reflectance: within 0.0013 for
 * eta in [0.5, 1) (0.0611 vs fit 0.0618 at 1/1.3, 0.1606 vs 0.1611 at 0.5); it degrades below 0.5
 * (0.276 vs 0.420 at 1/3). Both fits give about 0.0016 at eta = 1 (exact: 0); that value is kept
 * (A = 1.0032 at a matched interface), so the two branches meet continuously. */
static double fdr_relative(double eta)
{
    if (eta >= 1.0) return lucent_fdr(eta);
    double r = 1.0 / eta;
    return -0.4399 + r * (0.7099 + r * (-0.3319 + r * 0.0636));
}

/* z_b = 2 A D, D = 1/(3 sigma_t'), for relative index eta. */
static double extrapolation_distance(double eta, double sigma_t_prime)
{
    double fdr = fdr_relative(eta);
    double a = (1.0 + fdr) / (1.0 - fdr);
    return 2.0 * a / (3.0 * sigma_t_prime);
}

static double index_or_vacuum(double eta) { return eta > 0.0 ? eta : 1.0; }

typedef struct slab {
    double alpha, s, d, l;
    double zb_top, zb_bottom; /* z_b(0) and z_b(d) */
    int n;
} slab;

static void slab_setup(const lucent_medium *md, const lucent_slab_desc *desc, slab *dest)
{
    double stp = md->sigma_a + md->sigma_s_prime;
    *dest = (slab){.alpha = md->sigma_s_prime / stp,
                   .s = sqrt(3.0 * md->sigma_a * stp),
                   .d = desc->thickness,
                   .l = 1.0 / stp,
                   .zb_top = extrapolation_distance(md->eta / index_or_vacuum(desc->eta_above), stp),
                   .zb_bottom = extrapolation_distance(md->eta / index_or_vacuum(desc->eta_below), stp),
                   .n = desc->poles ? desc->poles : MULTIPOLE_DEFAULT_POLES};
}

/* The same slab turned upside down (light entering through its bottom face). */
static slab slab_flipped(const slab *s)
{
    slab f = *s;
    f.zb_top = s->zb_bottom;
    f.zb_bottom = s->zb_top;
    return f;
}

/* Signed depths of pole pair i (Donner & Jensen 2005, multipole with z_b(0) != z_b(d)). */
static void slab_pair(const slab *s, int i, double *zr, double *zv)
{
    double shift = 2.0 * i * (s->d + s->zb_top + s->zb_bottom);
    *zr = shift + s->l;
    *zv = shift - s->l - 2.0 * s->zb_top;
}

static lucent_status check_index(double eta, const char *name)
{
    if (eta == 0.0 || (eta >= 1.0 && eta <= 3.0)) return LUCENT_OK;
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "slab: %s must be 0 (vacuum) or in [1, 3], got %g", name, eta);
}

static lucent_status slab_validate(const lucent_medium *md, const lucent_slab_desc *desc)
{
    lucent_status st = lucent_medium_validate(md);
    if (st != LUCENT_OK) return st;
    if (!(desc->thickness > 0.0) || !isfinite(desc->thickness))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "slab: thickness must be finite and > 0, got %g",
                            desc->thickness);
    if (desc->poles < 0 || desc->poles > MULTIPOLE_MAX_POLES)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "slab: poles must be in [0, %d], got %d", MULTIPOLE_MAX_POLES,
                            desc->poles);
    st = check_index(desc->eta_above, "eta_above");
    if (st == LUCENT_OK) st = check_index(desc->eta_below, "eta_below");
    return st;
}

/* Donner & Jensen 2005 place the source at depth l = 1/sigma_t'; for d < l it lies below the
 * slab and the multipole's T (or R, with unequal faces) can come out negative: a 0.25 mm Skin1
 * slab alone has T = -0.235 (red); on 5 mm of Skin2 the stack's red R is -0.069.
 * Such layers are still computed (the paper uses them); this says so through the log sink.
 * what: "slab" or "layers[i]". */
static void warn_if_thin(const lucent_material *m, double thickness, const char *what)
{
    double lmax = 0.0;
    int cmax = 0;
    for (int c = 0; c < 3; c++) {
        lucent_medium md;
        lucent_medium_from_material(m, c, &md);
        double l = 1.0 / (md.sigma_a + md.sigma_s_prime);
        if (l > lmax) lmax = l, cmax = c;
    }
    if (thickness < lmax)
        lucent_log(LUCENT_LOG_WARN,
                   "multipole: %s (%s): thickness %g mm is below its transport mean free path "
                   "1/sigma_t' = %g mm (channel %d); the diffusion multipole is inaccurate there "
                   "and its R or T can come out negative (values returned as computed)",
                   what, m->name, thickness, lmax, cmax);
}

/* Sums the dipole pairs of the slab: the flux at radius r through the top (dest[0]) and the
 * bottom (dest[1]) face, or, when r < 0, its integral over the plane. */
static void sum_poles(const lucent_medium *md, const lucent_slab_desc *slab_desc, double r, double dest[2])
{
    slab s;
    slab_setup(md, slab_desc, &s);
    double rsum = 0.0, tsum = 0.0;
    for (int i = -s.n; i <= s.n; i++) {
        double zr, zv, h[4];
        slab_pair(&s, i, &zr, &zv);
        h[0] = zr, h[1] = zv, h[2] = s.d - zr, h[3] = s.d - zv;
        double f[4];
        for (int k = 0; k < 4; k++) f[k] = r < 0 ? pole_flux_total(h[k], s.s) : pole_flux(h[k], s.s, r);
        rsum += f[0] - f[1];
        tsum += f[2] - f[3];
    }
    dest[0] = s.alpha * rsum;
    dest[1] = s.alpha * tsum;
}

void lucent_multipole_eval(const lucent_medium *md, const lucent_slab_desc *slab_desc, double r, double dest[2])
{
    dest[0] = dest[1] = NAN;
    if (slab_validate(md, slab_desc) != LUCENT_OK || !(r >= 0.0)) return;
    sum_poles(md, slab_desc, r, dest);
}

void lucent_multipole_totals(const lucent_medium *md, const lucent_slab_desc *slab_desc, double dest[2])
{
    dest[0] = dest[1] = NAN;
    if (slab_validate(md, slab_desc) != LUCENT_OK || !(md->sigma_a > 0.0)) return;
    sum_poles(md, slab_desc, -1.0, dest);
}

/* Bin integrals of R (which 0) or T (which 1) of one channel. */
static double slab_bin(const slab *s, int which, double r0, double r1)
{
    double sum = 0.0;
    for (int i = -s->n; i <= s->n; i++) {
        double zr, zv;
        slab_pair(s, i, &zr, &zv);
        double hr = which ? s->d - zr : zr, hv = which ? s->d - zv : zv;
        sum += pole_flux_bin(hr, s->s, r0, r1) - pole_flux_bin(hv, s->s, r0, r1);
    }
    return s->alpha * sum;
}

static void destroy_pair(lucent_profile *dest[2])
{
    for (int k = 0; k < 2; k++) {
        lucent_profile_destroy(dest[k]);
        dest[k] = NULL;
    }
}

static lucent_status create_pair(const lucent_profile_grid *g, const char *r_name, const char *t_name,
                                 lucent_profile *dest[2])
{
    dest[0] = dest[1] = NULL;
    lucent_status st = lucent_profile_create(g, r_name, &dest[0]);
    if (st == LUCENT_OK) st = lucent_profile_create(g, t_name, &dest[1]);
    if (st != LUCENT_OK) destroy_pair(dest);
    return st;
}

static lucent_status check_material_slab(const lucent_material *m, const lucent_slab_desc *desc)
{
    lucent_status st = lucent_material_validate(m);
    if (st != LUCENT_OK) return st;
    lucent_medium md;
    lucent_medium_from_material(m, 0, &md);
    return slab_validate(&md, desc);
}

lucent_status lucent_profile_multipole(const lucent_material *m, const lucent_slab_desc *desc,
                                       const lucent_profile_grid *grid, lucent_profile *dest[2])
{
    dest[0] = dest[1] = NULL;
    lucent_profile_grid g;
    lucent_status st = check_material_slab(m, desc);
    if (st == LUCENT_OK) st = lucent_profile_grid_resolve(grid, m, &g);
    if (st == LUCENT_OK) st = create_pair(&g, "multipole-R", "multipole-T", dest);
    if (st != LUCENT_OK) return st;
    warn_if_thin(m, desc->thickness, "slab");
    for (int c = 0; c < 3; c++) {
        lucent_medium md;
        slab s;
        lucent_medium_from_material(m, c, &md);
        slab_setup(&md, desc, &s);
        for (int j = 0; j < g.count; j++) {
            double r0 = j * g.dr, r1 = (j + 1) * g.dr;
            for (int k = 0; k < 2; k++) dest[k]->value[c][j] = bin_average(slab_bin(&s, k, r0, r1), r0, r1);
        }
    }
    return LUCENT_OK;
}

/* ---- Layered composition in the frequency domain ----
 * The 2-D Fourier transform of a radial f is its Hankel transform F(k) = 2 pi int f(r) J0(kr) r dr.
 * For a point source, F[E(h, .)](k) = sign(h) e^{-|h| sqrt(s^2 + k^2)} / 2 (the transform of
 * e^{-sD}/(4 pi D) is e^{-|h| q}/(2 q), q = sqrt(s^2 + k^2), and E = -d/dh of it). */
static double pole_hat(double h, double q)
{
    if (h == 0.0) return 0.0;
    return (h > 0.0 ? 0.5 : -0.5) * exp(-fabs(h) * q);
}

/* R and T of one slab at frequency k. */
static void slab_hat(const slab *s, double k, double *r_hat, double *t_hat)
{
    double q = sqrt(s->s * s->s + k * k), rs = 0.0, ts = 0.0;
    for (int i = -s->n; i <= s->n; i++) {
        double zr, zv;
        slab_pair(s, i, &zr, &zv);
        rs += pole_hat(zr, q) - pole_hat(zv, q);
        ts += pole_hat(s->d - zr, q) - pole_hat(s->d - zv, q);
    }
    *r_hat = s->alpha * rs;
    *t_hat = s->alpha * ts;
}

/* A stack at one frequency: reflectance from the top (rt) and from the bottom (rb),
 * transmittance downwards (td) and upwards (tu). A layer's two faces see different relative
 * indices, so rb != rt and tu != td in general. */
typedef struct stack_hat {
    double rt, rb, td, tu;
} stack_hat;

/* Donner & Jensen 2005, the adding rule with the inter-reflection series summed, for a stack a
 * above a stack b (primes: seen from below):
 *   R12 = R1 + T1 R2 T1' / (1 - R1' R2),    T12 = T1 T2 / (1 - R1' R2),
 *   R12' = R2' + T2' R1' T2 / (1 - R1' R2), T12' = T2' T1' / (1 - R1' R2). */
static stack_hat stack_add(stack_hat a, stack_hat b)
{
    double den = 1.0 - a.rb * b.rt;
    return (stack_hat){.rt = a.rt + a.td * b.rt * a.tu / den,
                       .rb = b.rb + b.tu * a.rb * b.td / den,
                       .td = a.td * b.td / den,
                       .tu = b.tu * a.tu / den};
}

/* One layer at frequency k; seen from below too unless last (nothing is below it then). */
static stack_hat layer_hat(const slab *s, double k, int last)
{
    stack_hat h;
    slab_hat(s, k, &h.rt, &h.td);
    if (last) {
        h.rb = h.tu = NAN; /* never read: only the stack's rt and td are output */
    } else if (s->zb_top == s->zb_bottom) {
        h.rb = h.rt, h.tu = h.td; /* symmetric slab */
    } else {
        slab f = slab_flipped(s);
        slab_hat(&f, k, &h.rb, &h.tu);
    }
    return h;
}

static stack_hat stack_eval(const slab *slabs, int count, double k)
{
    stack_hat acc = layer_hat(&slabs[0], k, count == 1);
    for (int i = 1; i < count; i++) acc = stack_add(acc, layer_hat(&slabs[i], k, i == count - 1));
    return acc;
}

/* 8-point Gauss-Legendre on [-1, 1]. */
static const double gl_x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
static const double gl_w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

typedef struct inverse_ctx {
    const slab *slabs; /* stacks x count layers, stack t at slabs + t count */
    int count, edges;
    int stacks;           /* 3, or 3 per set of a spectral mixture */
    const double *weight; /* NULL: channel c is stack c; else channel c is sum_t weight[c stacks + t] stack t */
    double dr;
    double *j1;        /* [edges]: J1(k r_e) of the node being added */
    double *cum[2][3]; /* C(r_e) = 2 pi int_0^{r_e} f r dr = int_0^inf F(k) r_e J1(k r_e) dk */
} inverse_ctx;

/* J1(k e dr) for e = 0 .. edges - 1. Below z = 60 the C library's j1; above, Hankel's asymptotic
 * expansion (Abramowitz & Stegun 9.2.5, 9.2.9, 9.2.10 with mu = 4: P to z^-4, Q to z^-5; within
 * 1.2e-11 of j1 relative to the envelope sqrt(2 / (pi z)) for z >= 60, checked against glibc), its
 * cos and sin stepped by rotation and recomputed every 256 edges. */
static void j1_row(double k, double dr, int edges, double *dest)
{
    const double z_asym = 60.0;
    double step = k * dr, c = 0.0, sn = 0.0, cs = cos(step), ss = sin(step);
    int since = 256;
    for (int e = 0; e < edges; e++) {
        double z = e * step;
        if (z < z_asym) {
            dest[e] = j1(z);
            continue;
        }
        if (since >= 256) {
            c = cos(z - 0.75 * M_PI), sn = sin(z - 0.75 * M_PI), since = 0;
        } else {
            double c1 = c * cs - sn * ss;
            sn = sn * cs + c * ss, c = c1;
        }
        since++;
        double iz = 1.0 / z, z2 = iz * iz;
        double p = 1.0 + z2 * (15.0 / 128.0 - z2 * (14175.0 / 98304.0));
        double q = iz * (3.0 / 8.0 - z2 * (315.0 / 3072.0 - z2 * (1091475.0 / 3932160.0)));
        dest[e] = sqrt(2.0 * iz / M_PI) * (p * c - q * sn);
    }
}

/* Adds the contribution of one quadrature node (k, weight w) to every channel and edge. */
static void inverse_node(inverse_ctx *x, double k, double w)
{
    double fr[3] = {0.0, 0.0, 0.0}, ft[3] = {0.0, 0.0, 0.0};
    for (int t = 0; t < x->stacks; t++) {
        stack_hat h = stack_eval(x->slabs + (size_t)t * (size_t)x->count, x->count, k);
        if (!x->weight) {
            fr[t] = h.rt, ft[t] = h.td;
            continue;
        }
        for (int c = 0; c < 3; c++) {
            double wt = x->weight[c * x->stacks + t];
            fr[c] += wt * h.rt, ft[c] += wt * h.td;
        }
    }
    j1_row(k, x->dr, x->edges, x->j1);
    for (int e = 1; e < x->edges; e++) {
        double v = w * e * x->dr * x->j1[e];
        for (int c = 0; c < 3; c++) {
            x->cum[0][c][e] += fr[c] * v;
            x->cum[1][c][e] += ft[c] * v;
        }
    }
}

static void inverse_panel(inverse_ctx *x, double k0, double k1)
{
    double mid = 0.5 * (k0 + k1), half = 0.5 * (k1 - k0);
    for (int i = 0; i < 4; i++) {
        inverse_node(x, mid - half * gl_x[i], half * gl_w[i]);
        inverse_node(x, mid + half * gl_x[i], half * gl_w[i]);
    }
}

/* Smallest pole height of the stacks (all channels): the transforms decay like e^{-h_min k}.
 * Floored at half the smallest l = 1/sigma_t', so a layer whose thickness is close to l
 * (source on its bottom face) has its highest frequencies cut (see docs/profiles.md). */
static double stack_min_height(const slab *slabs, int n)
{
    double h = INFINITY, lmin = INFINITY;
    for (int i = 0; i < n; i++) {
        lmin = fmin(lmin, slabs[i].l);
        h = fmin(h, fmin(slabs[i].l, fabs(slabs[i].d - slabs[i].l)));
    }
    return fmax(h, 0.5 * lmin);
}

/* Gauss-Legendre panels of width 2 pi / r_max (one period of J1(k r_max); 8 nodes integrate
 * e^{i pi t} on [-1, 1] to ~1e-15) up to k_max = 36 / h_min (e^{-36} ~ 2e-16); the first panel is
 * refined geometrically towards k = 0, where F varies on the scale s. */
static void inverse_all(inverse_ctx *x)
{
    double rmax = (x->edges - 1) * x->dr;
    double w = 2.0 * M_PI / rmax;
    double kmax = fmax(36.0 / stack_min_height(x->slabs, x->stacks * x->count), 2.0 * w);
    double lo = w * ldexp(1.0, -30);
    inverse_panel(x, 0.0, lo);
    for (double k = lo; k < w; k *= 2.0) inverse_panel(x, k, fmin(2.0 * k, w));
    int panels = (int)ceil((kmax - w) / w);
    for (int p = 0; p < panels; p++) inverse_panel(x, w + p * w, w + (p + 1) * w);
}

static lucent_status layers_check(const lucent_layer *layers, int count)
{
    if (count < 1 || count > LAYERS_MAX)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "layers: count must be in [1, %d], got %d", LAYERS_MAX, count);
    for (int i = 0; i < count; i++) {
        lucent_status st = check_material_slab(&layers[i].material, &layers[i].slab);
        if (st != LUCENT_OK) return lucent_error_context(st, "layers[%d]", i);
    }
    return LUCENT_OK;
}

/* Each layer's faces take the indices of its neighbours (Donner & Jensen 2005, layered model: the
 * boundary condition of an interface comes from the relative index across it); the top layer's
 * eta_above and the bottom layer's eta_below are the media around the stack. */
static void layers_slabs(const lucent_layer *layers, int count, slab *dest)
{
    for (int i = 0; i < count; i++) {
        lucent_slab_desc desc = layers[i].slab;
        if (i > 0) desc.eta_above = layers[i - 1].material.eta;
        if (i + 1 < count) desc.eta_below = layers[i + 1].material.eta;
        for (int c = 0; c < 3; c++) {
            lucent_medium md;
            lucent_medium_from_material(&layers[i].material, c, &md);
            slab_setup(&md, &desc, &dest[c * count + i]);
        }
    }
}

static void layers_fill(inverse_ctx *x, lucent_profile *dest[2])
{
    inverse_all(x);
    for (int c = 0; c < 3; c++) {
        for (int k = 0; k < 2; k++)
            for (int j = 0; j + 1 < x->edges; j++) {
                double r0 = j * x->dr, r1 = (j + 1) * x->dr;
                double bin = x->cum[k][c][j + 1] - x->cum[k][c][j];
                dest[k]->value[c][j] = bin_average(bin, r0, r1);
            }
    }
}

/* Allocates the cumulative sums and the J1 row, inverts, fills dest's values. */
static lucent_status inverse_run(inverse_ctx *x, lucent_profile *dest[2])
{
    double *block = calloc((size_t)x->edges * 7u, sizeof *block);
    if (!block) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "layers: %d bins", x->edges - 1);
    for (int k = 0; k < 2; k++)
        for (int c = 0; c < 3; c++) x->cum[k][c] = block + (size_t)(k * 3 + c) * (size_t)x->edges;
    x->j1 = block + 6u * (size_t)x->edges;
    layers_fill(x, dest);
    free(block);
    return LUCENT_OK;
}

lucent_status lucent_profile_layered(const lucent_layer *layers, int count, const lucent_profile_grid *grid,
                                     lucent_profile *dest[2])
{
    dest[0] = dest[1] = NULL;
    lucent_profile_grid g;
    lucent_status st = layers_check(layers, count);
    if (st == LUCENT_OK) st = lucent_profile_grid_resolve(grid, &layers[0].material, &g);
    if (st == LUCENT_OK) st = create_pair(&g, "layered-R", "layered-T", dest);
    if (st != LUCENT_OK) return st;
    for (int i = 0; i < count; i++) {
        char what[32];
        snprintf(what, sizeof what, "layers[%d]", i);
        warn_if_thin(&layers[i].material, layers[i].slab.thickness, what);
    }
    slab slabs[3 * LAYERS_MAX];
    layers_slabs(layers, count, slabs);
    inverse_ctx x = {.slabs = slabs, .count = count, .stacks = 3, .edges = g.count + 1, .dr = g.dr};
    st = inverse_run(&x, dest);
    if (st != LUCENT_OK) destroy_pair(dest);
    return st;
}

/* ---- Spectral mixtures (src/profile/layered.h) ---- */

void layered_hat(const lucent_layer *layers, int count, double k, double rt[3], double td[3])
{
    slab slabs[3 * LAYERS_MAX];
    layers_slabs(layers, count, slabs);
    for (int c = 0; c < 3; c++) {
        stack_hat h = stack_eval(slabs + (size_t)c * (size_t)count, count, k);
        rt[c] = h.rt, td[c] = h.td;
    }
}

lucent_status layered_mix_check(const lucent_layer *layers, int count) { return layers_check(layers, count); }

lucent_status layered_profile_mix(const lucent_layer *sets, int set_count, int count, const double *weight,
                                  const lucent_profile_grid *grid, lucent_profile *dest[2])
{
    dest[0] = dest[1] = NULL;
    lucent_status st = LUCENT_OK;
    for (int i = 0; i < set_count && st == LUCENT_OK; i++) st = layers_check(sets + (size_t)i * (size_t)count, count);
    if (st == LUCENT_OK) st = create_pair(grid, "layered-R", "layered-T", dest);
    if (st != LUCENT_OK) return st;
    slab *slabs = malloc((size_t)set_count * 3u * (size_t)count * sizeof *slabs);
    if (!slabs) {
        destroy_pair(dest);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "layers: %d sets", set_count);
    }
    /* set i's channel c is stack 3 i + c, its layers at slabs + (3 i + c) count */
    slab tmp[3 * LAYERS_MAX];
    for (int i = 0; i < set_count; i++) {
        layers_slabs(sets + (size_t)i * (size_t)count, count, tmp);
        memcpy(slabs + (size_t)i * 3u * (size_t)count, tmp, 3u * (size_t)count * sizeof *tmp);
    }
    inverse_ctx x = {.slabs = slabs,
                     .count = count,
                     .stacks = 3 * set_count,
                     .weight = weight,
                     .edges = grid->count + 1,
                     .dr = grid->dr};
    st = inverse_run(&x, dest);
    free(slabs);
    if (st != LUCENT_OK) destroy_pair(dest);
    return st;
}
