/* Sum-of-Gaussians fits of radial profiles (d'Eon & Luebke 2007, GPU Gems 3, ch. 14):
 * R(r) ~ sum_i w_i G(v_i, r), G(v, r) = exp(-r^2 / (2v)) / (2 pi v).
 *
 * Variable projection: for fixed variances the weights solve a non-negative least-squares
 * problem (Lawson & Hanson's active set on the normal equations); the variances, as log v,
 * are moved by Levenberg-Marquardt with Kaufman's Jacobian -P_perp (dA/dtheta) w. The residual
 * is weighted by sqrt(r dr), i.e. the fit minimises sum_j r_j dr (R_j - fit_j)^2, the r-weighted
 * error d'Eon minimises. Several starts (geometric spreads of variances between the profile's
 * 5% and 95% energy radii, then jittered ones) are run and the best kept. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/profile.h"
#include "profile/pole.h"

enum { SOG_DEFAULT_STARTS = 8, SOG_DEFAULT_ITERATIONS = 300, N_MAX = LUCENT_SOG_MAX };

double lucent_gaussian(double v, double r) { return exp(-r * r / (2.0 * v)) / (2.0 * M_PI * v); }

double lucent_sog_eval(const lucent_sog *s, int c, double r)
{
    double sum = 0.0;
    for (int i = 0; i < s->count; i++) sum += s->weight[c][i] * lucent_gaussian(s->variance[c][i], r);
    return sum;
}

/* ---- Small dense linear algebra (n <= 16) ---- */

/* Cholesky factorisation of the k x k matrix a (row stride N_MAX) in place; false if not SPD. */
static bool cholesky(double a[N_MAX][N_MAX], int k)
{
    for (int j = 0; j < k; j++) {
        double d = a[j][j];
        for (int p = 0; p < j; p++) d -= a[j][p] * a[j][p];
        if (!(d > 0.0)) return false;
        a[j][j] = sqrt(d);
        for (int i = j + 1; i < k; i++) {
            double s = a[i][j];
            for (int p = 0; p < j; p++) s -= a[i][p] * a[j][p];
            a[i][j] = s / a[j][j];
        }
    }
    return true;
}

/* Solves L L^T x = b (in place in b) with the factor from cholesky. */
static void cholesky_solve(double l[N_MAX][N_MAX], int k, double *b)
{
    for (int i = 0; i < k; i++) {
        for (int p = 0; p < i; p++) b[i] -= l[i][p] * b[p];
        b[i] /= l[i][i];
    }
    for (int i = k - 1; i >= 0; i--) {
        for (int p = i + 1; p < k; p++) b[i] -= l[p][i] * b[p];
        b[i] /= l[i][i];
    }
}

/* Factorises the Gram matrix restricted to the index set idx (k entries) into l; a tiny ridge
 * is added when the columns are numerically dependent. */
static void gram_factor(const double g[N_MAX][N_MAX], const int *idx, int k, double l[N_MAX][N_MAX])
{
    for (double ridge = 0.0;; ridge = ridge ? ridge * 100.0 : 1e-14) {
        for (int i = 0; i < k; i++)
            for (int j = 0; j < k; j++) l[i][j] = g[idx[i]][idx[j]] + (i == j ? ridge * g[idx[i]][idx[i]] : 0.0);
        if (cholesky(l, k)) return;
    }
}

/* Non-negative least squares on the normal equations G x = h (Lawson & Hanson 1974, ch. 23).
 * x has n entries; on return active[i] says whether x[i] > 0. */
static void nnls(const double g[N_MAX][N_MAX], const double *h, int n, double *x, bool *active)
{
    double l[N_MAX][N_MAX], z[N_MAX];
    int idx[N_MAX];
    double hmax = 0.0;
    for (int i = 0; i < n; i++) hmax = fmax(hmax, fabs(h[i]));
    for (int i = 0; i < n; i++) x[i] = 0.0, active[i] = false;
    for (int outer = 0; outer < 3 * n; outer++) {
        int best = -1;
        double wbest = 1e-13 * hmax;
        for (int i = 0; i < n; i++) {
            if (active[i]) continue;
            double w = h[i];
            for (int j = 0; j < n; j++) w -= g[i][j] * x[j];
            if (w > wbest) wbest = w, best = i;
        }
        if (best < 0) return;
        active[best] = true;
        for (int inner = 0; inner < 3 * n; inner++) {
            int k = 0;
            for (int i = 0; i < n; i++)
                if (active[i]) idx[k++] = i;
            gram_factor(g, idx, k, l);
            for (int i = 0; i < k; i++) z[i] = h[idx[i]];
            cholesky_solve(l, k, z);
            double alpha = 1.0;
            for (int i = 0; i < k; i++)
                if (z[i] <= 0.0) alpha = fmin(alpha, x[idx[i]] / (x[idx[i]] - z[i]));
            for (int i = 0; i < k; i++) x[idx[i]] += alpha * (z[i] - x[idx[i]]);
            if (alpha >= 1.0) break;
            for (int i = 0; i < k; i++)
                if (x[idx[i]] <= 0.0) x[idx[i]] = 0.0, active[idx[i]] = false;
        }
    }
}

/* ---- The fitting problem ---- */
typedef struct sog_problem {
    int m, n, channels, first; /* samples, Gaussians, channels fitted together, first channel */
    double dr, lo, hi;         /* bin width; bounds of log v */
    double *sw;                /* sqrt(r_j dr) */
    double *y[3];              /* weighted targets sw_j R_j */
    double norm2[3];           /* sum of y^2 */
    double *a, *da;            /* weighted basis and its d/dlog v, m x n (column-major) */
    double *res;               /* residual, channels x m */
    double *jac;               /* Jacobian, (channels x m) x n (column-major) */
    double w[3][N_MAX];        /* weights of the last evaluation */
} sog_problem;

/* Weighted bin averages of G(v) and their derivatives with respect to log v:
 * 2 pi int_bin G r dr = e^{-a} - e^{-b}, a = r0^2/(2v), b = r1^2/(2v); d/dlog v: a e^{-a} - b e^{-b}. */
static void sog_basis(sog_problem *p, const double *theta)
{
    for (int i = 0; i < p->n; i++) {
        double v = exp(theta[i]), a = 0.0, ea = 1.0;
        double *col = p->a + (size_t)i * p->m, *dcol = p->da + (size_t)i * p->m;
        for (int j = 0; j < p->m; j++) {
            double r1 = (j + 1) * p->dr, b = r1 * r1 / (2.0 * v), eb = exp(-b);
            double area = M_PI * (2.0 * j + 1.0) * p->dr * p->dr;
            double diff = ea > 1e-300 ? ea * -expm1(a - b) : 0.0; /* e^{-a} - e^{-b} */
            col[j] = p->sw[j] * diff / area;
            dcol[j] = p->sw[j] * (a * ea - b * eb) / area;
            a = b, ea = eb;
        }
    }
}

static double dot(const double *x, const double *y, int m)
{
    double s = 0.0;
    for (int j = 0; j < m; j++) s += x[j] * y[j];
    return s;
}

/* x -= A_P (A_P^T A_P)^{-1} A_P^T x: the projection off the active columns. */
static void project_out(const sog_problem *p, double l[N_MAX][N_MAX], const int *idx, int k, double *x)
{
    double u[N_MAX];
    for (int i = 0; i < k; i++) u[i] = dot(p->a + (size_t)idx[i] * p->m, x, p->m);
    cholesky_solve(l, k, u);
    for (int i = 0; i < k; i++) {
        const double *col = p->a + (size_t)idx[i] * p->m;
        for (int j = 0; j < p->m; j++) x[j] -= u[i] * col[j];
    }
}

/* Weights, residual and Jacobian rows of one channel; returns its squared residual. */
static double sog_channel(sog_problem *p, double g[N_MAX][N_MAX], int c)
{
    double h[N_MAX], l[N_MAX][N_MAX];
    bool active[N_MAX];
    int idx[N_MAX], k = 0, n = p->n, m = p->m;
    for (int i = 0; i < n; i++) h[i] = dot(p->a + (size_t)i * m, p->y[c], m);
    nnls(g, h, n, p->w[c], active);
    double *res = p->res + (size_t)c * m;
    memcpy(res, p->y[c], (size_t)m * sizeof *res);
    for (int i = 0; i < n; i++) {
        const double *col = p->a + (size_t)i * m;
        for (int j = 0; j < m; j++) res[j] -= p->w[c][i] * col[j];
        if (active[i]) idx[k++] = i;
    }
    if (k) gram_factor(g, idx, k, l);
    for (int i = 0; i < n; i++) { /* Kaufman: J_i = -P_perp (dA_i/dtheta_i) w_i */
        double *jc = p->jac + (size_t)i * p->channels * m + (size_t)c * m;
        const double *dcol = p->da + (size_t)i * m;
        for (int j = 0; j < m; j++) jc[j] = -p->w[c][i] * dcol[j];
        if (k && p->w[c][i] != 0.0) project_out(p, l, idx, k, jc);
    }
    return dot(res, res, m);
}

/* Evaluates the projected cost at theta, filling weights, residual and Jacobian. */
static double sog_eval(sog_problem *p, const double *theta)
{
    double g[N_MAX][N_MAX];
    sog_basis(p, theta);
    for (int i = 0; i < p->n; i++)
        for (int j = 0; j <= i; j++) g[i][j] = g[j][i] = dot(p->a + (size_t)i * p->m, p->a + (size_t)j * p->m, p->m);
    double cost = 0.0;
    for (int c = 0; c < p->channels; c++) cost += sog_channel(p, g, c);
    return cost;
}

/* One Levenberg-Marquardt step proposal: (J^T J + lambda (diag + eps)) delta = -J^T r. */
static bool lm_step(const sog_problem *p, double lambda, double *delta)
{
    double jtj[N_MAX][N_MAX];
    int n = p->n, rows = p->channels * p->m;
    double dmax = 0.0;
    for (int i = 0; i < n; i++) {
        const double *ji = p->jac + (size_t)i * rows;
        delta[i] = -dot(ji, p->res, rows);
        for (int j = 0; j <= i; j++) jtj[i][j] = jtj[j][i] = dot(ji, p->jac + (size_t)j * rows, rows);
        dmax = fmax(dmax, jtj[i][i]);
    }
    if (!(dmax > 0.0)) return false;
    for (int i = 0; i < n; i++) jtj[i][i] += lambda * (jtj[i][i] + 1e-9 * dmax);
    if (!cholesky(jtj, n)) return false;
    cholesky_solve(jtj, n, delta);
    return true;
}

static void clamp_theta(const sog_problem *p, double *theta)
{
    for (int i = 0; i < p->n; i++) theta[i] = fmin(fmax(theta[i], p->lo), p->hi);
}

/* Copies the state that an evaluation overwrites (residual, Jacobian, weights). */
static void sog_save(const sog_problem *p, double *buf, double w[3][N_MAX], bool restore)
{
    size_t len = (size_t)p->channels * (size_t)p->m * (size_t)(p->n + 1);
    if (restore) {
        memcpy(p->res, buf, len * sizeof *buf); /* res and jac are contiguous */
        memcpy(((sog_problem *)p)->w, w, sizeof p->w);
    } else {
        memcpy(buf, p->res, len * sizeof *buf);
        memcpy(w, p->w, sizeof p->w);
    }
}

/* Runs LM from theta (updated in place); returns the final cost (state left at theta). Stops
 * when the cost is negligible, stalls (relative decrease < 1e-12), or the step is below 1e-10. */
static double sog_minimise(sog_problem *p, double *theta, int iterations, double *backup)
{
    double cost = sog_eval(p, theta), lambda = 1e-3, trial[N_MAX], delta[N_MAX], w[3][N_MAX];
    double total = p->norm2[0] + p->norm2[1] + p->norm2[2];
    for (int it = 0; it < iterations && cost > 1e-28 * total; it++) {
        bool accepted = false;
        double before = cost, step = 0.0;
        sog_save(p, backup, w, false);
        while (!accepted && lambda < 1e12) {
            if (!lm_step(p, lambda, delta)) break;
            step = 0.0;
            for (int i = 0; i < p->n; i++) trial[i] = theta[i] + delta[i], step = fmax(step, fabs(delta[i]));
            clamp_theta(p, trial);
            double c = sog_eval(p, trial);
            if (c < cost) {
                memcpy(theta, trial, (size_t)p->n * sizeof *theta);
                cost = c;
                lambda = fmax(lambda / 3.0, 1e-12);
                accepted = true;
            } else {
                lambda *= 4.0;
                sog_save(p, backup, w, true); /* back to the state at theta */
            }
        }
        if (!accepted || before - cost <= 1e-12 * before || step < 1e-10) break;
    }
    return cost;
}

/* Radius within which a fraction q of the (channels') reflectance lies. */
static double energy_radius(const lucent_profile *p, const sog_problem *pr, double q)
{
    double total = 0.0, acc = 0.0;
    for (int c = 0; c < pr->channels; c++) total += lucent_profile_total(p, pr->first + c);
    for (int j = 0; j < p->count; j++) {
        for (int c = 0; c < pr->channels; c++)
            acc += p->value[pr->first + c][j] * M_PI * (2.0 * j + 1.0) * p->dr * p->dr;
        if (acc >= q * total) return (j + 1) * p->dr;
    }
    return p->count * p->dr;
}

/* Start k: variances spread geometrically over [v05, v95] (the variances of single Gaussians
 * holding 5% / 95% of the energy within those radii), widened for later starts and, from the
 * third start on, jittered by a fixed-seed RNG so the fit stays deterministic. */
static void sog_start(const sog_problem *p, double lv05, double lv95, int k, lucent_rng *rng, double *theta)
{
    double mid = 0.5 * (lv05 + lv95), half = 0.5 * (lv95 - lv05) * (1.0 + 0.35 * k);
    for (int i = 0; i < p->n; i++) {
        double t = p->n == 1 ? 0.0 : -1.0 + 2.0 * i / (p->n - 1);
        double jitter = k >= 2 ? (lucent_rng_uniform(rng) - 0.5) * 2.0 * half / p->n : 0.0;
        theta[i] = mid + t * half + jitter;
    }
    clamp_theta(p, theta);
}

static lucent_status sog_check(const lucent_profile *p, const lucent_sog_desc *desc)
{
    if (!p || p->count < 2 || !(p->dr > 0.0))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "sog: profile: needs count >= 2 and dr > 0");
    if (desc->count < 1 || desc->count > LUCENT_SOG_MAX)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "sog: count (N) must be in [1, %d], got %d", LUCENT_SOG_MAX,
                            desc->count);
    if (desc->starts < 0 || desc->starts > 1000)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "sog: starts must be in [0, 1000], got %d", desc->starts);
    if (desc->max_iterations < 0)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "sog: max_iterations must be >= 0, got %d",
                            desc->max_iterations);
    for (int c = 0; c < 3; c++)
        for (int j = 0; j < p->count; j++)
            if (!isfinite(p->value[c][j]))
                return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "sog: profile: value[%d][%d] is not finite", c, j);
    return LUCENT_OK;
}

static lucent_status sog_alloc(sog_problem *pr, const lucent_profile *p, int channels, int first)
{
    size_t m = (size_t)p->count, n = (size_t)pr->n;
    pr->m = p->count, pr->channels = channels, pr->first = first, pr->dr = p->dr;
    pr->sw = calloc(m * (1 + 3 + 2 * n + 3 + 3 * n + 3 * (n + 1)), sizeof(double));
    if (!pr->sw) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "sog: %d bins", p->count);
    for (int c = 0; c < 3; c++) pr->y[c] = pr->sw + m * (1 + c);
    pr->a = pr->sw + 4 * m;
    pr->da = pr->a + n * m;
    pr->res = pr->da + n * m;
    pr->jac = pr->res + (size_t)channels * m; /* contiguous with res (sog_save) */
    for (int j = 0; j < p->count; j++) {
        pr->sw[j] = sqrt(p->r[j] * p->dr);
        for (int c = 0; c < channels; c++) pr->y[c][j] = pr->sw[j] * p->value[first + c][j];
    }
    for (int c = 0; c < channels; c++) pr->norm2[c] = dot(pr->y[c], pr->y[c], pr->m);
    pr->lo = log(0.01 * p->dr * p->dr);                          /* sigma >= dr / 10 */
    pr->hi = log(4.0 * (p->count * p->dr) * (p->count * p->dr)); /* sigma <= 2 r_max */
    return LUCENT_OK;
}

/* Writes the fit of pr (channels first..first+channels-1) into dest, sorted by variance. */
static void sog_store(const sog_problem *pr, const double *theta, lucent_sog *dest)
{
    int order[N_MAX];
    for (int i = 0; i < pr->n; i++) order[i] = i;
    for (int i = 1; i < pr->n; i++) /* insertion sort by variance */
        for (int j = i; j > 0 && theta[order[j]] < theta[order[j - 1]]; j--) {
            int t = order[j];
            order[j] = order[j - 1], order[j - 1] = t;
        }
    for (int c = 0; c < pr->channels; c++) {
        int ch = pr->first + c;
        for (int i = 0; i < pr->n; i++) {
            dest->variance[ch][i] = exp(theta[order[i]]);
            dest->weight[ch][i] = pr->w[c][order[i]];
        }
        double r2 = dot(pr->res + (size_t)c * pr->m, pr->res + (size_t)c * pr->m, pr->m);
        dest->rms[ch] = pr->norm2[c] > 0.0 ? sqrt(r2 / pr->norm2[c]) : 0.0;
    }
}

/* Fits channels [first, first + channels) of p together (shared variances). */
static lucent_status sog_fit_group(const lucent_profile *p, const lucent_sog_desc *desc, int first, int channels,
                                   lucent_sog *dest)
{
    sog_problem pr = {.n = desc->count};
    lucent_status st = sog_alloc(&pr, p, channels, first);
    if (st != LUCENT_OK) return st;
    double r05 = energy_radius(p, &pr, 0.05), r95 = energy_radius(p, &pr, 0.95);
    double lv05 = log(r05 * r05 / (-2.0 * log(0.95))), lv95 = log(r95 * r95 / (-2.0 * log(0.05)));
    int starts = desc->starts ? desc->starts : SOG_DEFAULT_STARTS;
    int iters = desc->max_iterations ? desc->max_iterations : SOG_DEFAULT_ITERATIONS;
    double theta[N_MAX], best[N_MAX] = {0}, best_cost = INFINITY;
    lucent_rng rng;
    lucent_rng_init(0x50c5eedu, (uint64_t)first, &rng);
    double total = pr.norm2[0] + pr.norm2[1] + pr.norm2[2];
    double *backup = pr.jac + (size_t)pr.n * 3u * (size_t)pr.m;
    for (int k = 0; k < starts && !(best_cost <= 1e-24 * total); k++) {
        sog_start(&pr, lv05, lv95, k, &rng, theta);
        double cost = sog_minimise(&pr, theta, iters, backup);
        if (cost < best_cost) best_cost = cost, memcpy(best, theta, sizeof best);
    }
    if (!isfinite(best_cost)) { /* every start diverged: nothing to store */
        free(pr.sw);
        return lucent_error(LUCENT_ERR_NUMERIC, "sog: the fit did not converge");
    }
    sog_eval(&pr, best);
    sog_store(&pr, best, dest);
    free(pr.sw);
    return LUCENT_OK;
}

lucent_status lucent_sog_fit(const lucent_profile *p, const lucent_sog_desc *desc, lucent_sog *dest)
{
    lucent_status st = sog_check(p, desc);
    if (st != LUCENT_OK) return st;
    lucent_sog out;
    memset(&out, 0, sizeof out);
    out.count = desc->count;
    if (desc->shared_variances)
        st = sog_fit_group(p, desc, 0, 3, &out);
    else
        for (int c = 0; c < 3 && st == LUCENT_OK; c++) st = sog_fit_group(p, desc, c, 1, &out);
    if (st == LUCENT_OK) *dest = out;
    return st;
}

lucent_status lucent_profile_from_sog(const lucent_sog *s, const lucent_profile_grid *grid, lucent_profile **dest)
{
    *dest = NULL;
    if (s->count < 1 || s->count > LUCENT_SOG_MAX)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "sog: count (N) must be in [1, %d], got %d", LUCENT_SOG_MAX,
                            s->count);
    for (int c = 0; c < 3; c++)
        for (int i = 0; i < s->count; i++)
            if (!(s->variance[c][i] > 0.0) || !isfinite(s->variance[c][i]))
                return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "sog: variance[%d][%d] must be finite and > 0, got %g",
                                    c, i, s->variance[c][i]);
    lucent_status st = lucent_profile_create(grid, "sog", dest);
    if (st != LUCENT_OK) return st;
    lucent_profile *p = *dest;
    for (int c = 0; c < 3; c++)
        for (int j = 0; j < p->count; j++) {
            double r0 = j * p->dr, r1 = (j + 1) * p->dr, sum = 0.0;
            for (int i = 0; i < s->count; i++) {
                double v = s->variance[c][i];
                double a = r0 * r0 / (2.0 * v), b = r1 * r1 / (2.0 * v);
                sum += s->weight[c][i] * exp(-a) * -expm1(a - b); /* e^{-a} - e^{-b} */
            }
            p->value[c][j] = bin_average(sum, r0, r1);
        }
    return LUCENT_OK;
}

/* GPU Gems 3, ch. 14, Figure 14-13: variance (mm^2) and red, green, blue weights of skin. */
void lucent_sog_deon_skin(lucent_sog *dest)
{
    static const double v[6] = {0.0064, 0.0484, 0.187, 0.567, 1.99, 7.41};
    static const double w[3][6] = {{0.233, 0.100, 0.118, 0.113, 0.358, 0.078},
                                   {0.455, 0.336, 0.198, 0.007, 0.004, 0.0},
                                   {0.649, 0.344, 0.0, 0.007, 0.0, 0.0}};
    memset(dest, 0, sizeof *dest);
    dest->count = 6;
    for (int c = 0; c < 3; c++)
        for (int i = 0; i < 6; i++) dest->variance[c][i] = v[i], dest->weight[c][i] = w[c][i];
}
