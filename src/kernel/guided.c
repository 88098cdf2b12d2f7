/* Guided optimisation, Freude 2014 (5.19)-(5.20): per channel, the separable a minimising
 *   sum_ij Gamma_ij (R_ij - a_i a_j)^2   subject to  ||a||_1^2 = ||R_d||_1,
 *   Gamma(x, y; k, b) = (x^2 + y^2)^(k/2) (1 - e^(-b x^2)) (1 - e^(-b y^2))   (b = 0: no damping),
 * with x, y in [-1, 1] across the grid for the b term (as the thesis defines b). The kernel is
 * even, so a is too: the unknowns are the half vector b_m = a_(half +- m) >= 0, for which the
 * 1-norm constraint is the linear equality sum_m mu_m b_m = sqrt(||R_d||_1) (mu_0 = 1, else 2).
 * The constraint is built in (a hard constraint, not the thesis's soft one): b = T c / (mu . c),
 * c >= 0, minimised by NLopt's L-BFGS with analytic gradients,
 * coarse to fine: level s optimises knots every s samples (b linear between them), started from
 * the previous level, the coarsest from the pre-integration kernel. */
#include <math.h>
#include <nlopt.h>
#include <stdlib.h>

#include "kernel/internal.h"

typedef struct guided_problem {
    int m;              /* half + 1 unknowns b_0..b_half */
    const double *w;    /* m x m: mu_p mu_q Gamma_pq / scale */
    const double *r;    /* m x m: quadrant of R_d */
    double target;      /* sqrt(||R_d||_1) = mu . b */
    int stride;         /* knot spacing of this level */
    int knots;          /* knot count */
    double *b, *grad_b; /* m each: the fine vector and its gradient */
} guided_problem;

static int knot_index(const guided_problem *g, int k)
{
    int i = k * g->stride;
    return i < g->m - 1 ? i : g->m - 1;
}

/* b = P x: linear between knots. */
static void expand(guided_problem *g, const double *x)
{
    for (int k = 0; k + 1 < g->knots; k++) {
        int i0 = knot_index(g, k), i1 = knot_index(g, k + 1);
        for (int i = i0; i <= i1; i++) {
            double f = i1 > i0 ? (double)(i - i0) / (i1 - i0) : 0;
            g->b[i] = (1 - f) * x[k] + f * x[k + 1];
        }
    }
    if (g->knots == 1) g->b[0] = x[0];
}

/* grad_x = P^T grad_b (each fine sample counted once). */
static void reduce(const guided_problem *g, double *grad_x)
{
    for (int k = 0; k < g->knots; k++) grad_x[k] = 0;
    for (int k = 0; k + 1 < g->knots; k++) {
        int i0 = knot_index(g, k), i1 = knot_index(g, k + 1);
        for (int i = i0; i < i1 || (i == i1 && k + 2 == g->knots); i++) {
            double f = i1 > i0 ? (double)(i - i0) / (i1 - i0) : 0;
            grad_x[k] += (1 - f) * g->grad_b[i];
            grad_x[k + 1] += f * g->grad_b[i];
        }
    }
}

/* f = sum_pq w_pq (r_pq - b_p b_q)^2 with b = T c / (mu . c), so that the 1-norm constraint
 * mu . b = T holds exactly for any c >= 0. df/db_m = -4 sum_q w_mq (r_mq - b_m b_q) b_q, and
 * df/dc = (T / (mu . c)) (df/db - (df/db . b / T) mu). */
static double objective(unsigned n, const double *x, double *grad, void *ctx)
{
    (void)n;
    guided_problem *g = ctx;
    expand(g, x);
    double s = 0, f = 0, gb = 0;
    for (int i = 0; i < g->m; i++) s += (i ? 2 : 1) * g->b[i];
    if (!(s > 0)) return HUGE_VAL;
    for (int i = 0; i < g->m; i++) g->b[i] *= g->target / s;
    for (int p = 0; p < g->m; p++) {
        double gp = 0;
        for (int q = 0; q < g->m; q++) {
            double e = g->r[p * g->m + q] - g->b[p] * g->b[q], we = g->w[p * g->m + q] * e;
            f += we * e;
            gp += we * g->b[q];
        }
        g->grad_b[p] = -4 * gp;
        gb += g->grad_b[p] * g->b[p];
    }
    for (int i = 0; i < g->m; i++) g->grad_b[i] = (g->target / s) * (g->grad_b[i] - gb / g->target * (i ? 2 : 1));
    if (grad) reduce(g, grad);
    return f;
}

static lucent_status solve_level(guided_problem *g, int max_eval, double *x)
{
    nlopt_opt opt = nlopt_create(NLOPT_LD_LBFGS, (unsigned)g->knots);
    if (!opt) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel guided: nlopt_create failed");
    nlopt_set_lower_bounds1(opt, 0);
    nlopt_set_min_objective(opt, objective, g);
    nlopt_set_ftol_rel(opt, 1e-9);
    nlopt_set_maxeval(opt, max_eval);
    double f;
    nlopt_result res = nlopt_optimize(opt, x, &f);
    nlopt_destroy(opt);
    if (res < 0 && res != NLOPT_ROUNDOFF_LIMITED)
        return lucent_error(LUCENT_ERR_NUMERIC, "kernel guided: NLopt L-BFGS failed (%d)", (int)res);
    objective((unsigned)g->knots, x, NULL, g); /* leaves the constrained b in g->b */
    return LUCENT_OK;
}

/* Gamma (5.20) times the quadrant multiplicities, scaled so that sum w r^2 = 1. */
static void weights(const lucent_kernel2d *gt, int c, const lucent_kernel_desc *d, double *w, double *r)
{
    int m = gt->half + 1, n = kernel_n(gt->half);
    double scale = 0;
    for (int p = 0; p < m; p++)
        for (int q = 0; q < m; q++) {
            double x = (double)q / gt->half, y = (double)p / gt->half;
            double gamma = d->k == 0 ? 1 : pow(x * x + y * y, d->k / 2);
            if (d->b > 0) gamma *= (1 - exp(-d->b * x * x)) * (1 - exp(-d->b * y * y));
            r[p * m + q] = gt->value[c][(gt->half + p) * n + gt->half + q];
            w[p * m + q] = gamma * (p ? 2 : 1) * (q ? 2 : 1);
            scale += w[p * m + q] * r[p * m + q] * r[p * m + q];
        }
    for (int i = 0; i < m * m; i++) w[i] /= scale > 0 ? scale : 1;
}

static lucent_status guided_channel(const lucent_kernel2d *gt, int c, const lucent_kernel_desc *d, double *w, double *r,
                                    double *work, lucent_kernel *k)
{
    int m = gt->half + 1, n = kernel_n(gt->half);
    guided_problem g = {.m = m, .w = w, .r = r, .b = work, .grad_b = work + m};
    double *x = work + 2 * m, norm = 0;
    weights(gt, c, d, w, r);
    for (int i = 0; i < n * n; i++) norm += fabs(gt->value[c][i]);
    g.target = sqrt(norm);
    int max_eval = d->max_evaluations > 0 ? d->max_evaluations : lucent_kernel_defaults(d->model).max_evaluations;
    int stride = 1;
    while (stride * 8 < m) stride *= 2;
    for (int i = 0; i < m; i++) g.b[i] = k->a[c][gt->half + i]; /* pre-integration start */
    lucent_status st = LUCENT_OK;
    for (; stride >= 1 && st == LUCENT_OK; stride /= 2) {
        g.stride = stride;
        g.knots = (m - 1 + stride - 1) / stride + 1;
        for (int kk = 0; kk < g.knots; kk++) x[kk] = fmax(g.b[knot_index(&g, kk)], 0);
        st = solve_level(&g, max_eval, x);
    }
    for (int i = 0; i < m; i++) k->a[c][gt->half + i] = k->a[c][gt->half - i] = g.b[i];
    return st;
}

lucent_status kernel_guided(const lucent_kernel2d *gt, const lucent_kernel_desc *d, lucent_kernel *k)
{
    if (!(d->k >= 0 && d->k <= 8) || !(d->b >= 0 && d->b <= 1e4))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel guided: k must be in [0, 8] and b in "
                                                         "[0, 1e4]");
    lucent_status st = kernel_preint(gt, k);
    int m = gt->half + 1;
    double *w = malloc((size_t)m * m * sizeof *w), *r = malloc((size_t)m * m * sizeof *r),
           *work = malloc((size_t)3 * m * sizeof *work);
    if (st == LUCENT_OK && (!w || !r || !work))
        st = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel guided: out of memory");
    for (int c = 0; c < 3 && st == LUCENT_OK; c++) st = guided_channel(gt, c, d, w, r, work, k);
    free(w);
    free(r);
    free(work);
    if (st != LUCENT_OK) return st;
    double norm[3];
    lucent_kernel_norm1(k, norm);
    k->constraint_error = 0;
    for (int c = 0; c < 3; c++) k->constraint_error = fmax(k->constraint_error, fabs(norm[c] - 1));
    return LUCENT_OK;
}
