/* The published spectra of data/spectra.json (compiled into the binary, read once), the wavelength
 * bands and their colour weights, CIELAB, ITA and CIEDE2000. See lucent/spectral.h, docs/skin.md. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "base/embedded.h"
#include "base/json.h"
#include "lucent/spectral.h"
#include "material/spectra.h"

#define SPECTRA_FILE "data/spectra.json"

static pthread_once_t g_once = PTHREAD_ONCE_INIT;
static lucent_spectra g_spectra;
static char g_failure[512];

/* A table of count samples start, start + step, ... read from node n. */
static lucent_status read_table(const lucent_json_node *n, const char *key, int count, double *dest)
{
    return lucent_json_numbers(n, key, count, false, dest);
}

static lucent_status read_grid(const lucent_json_node *n, double start, double step)
{
    double s, d;
    lucent_status st = lucent_json_number(n, "start_nm", &s);
    if (st == LUCENT_OK) st = lucent_json_number(n, "step_nm", &d);
    if (st == LUCENT_OK && (s != start || d != step))
        st = lucent_json_fail(n, NULL, LUCENT_ERR_PARSE, "expected samples from %g nm every %g nm", start, step);
    return st;
}

static lucent_status read_power(const lucent_json_node *root, const char *key, double *a, double *b)
{
    lucent_json_node n;
    lucent_status s = lucent_json_object(root, key, true, &n);
    if (s == LUCENT_OK) s = lucent_json_number(&n, "a", a);
    if (s == LUCENT_OK) s = lucent_json_number(&n, "b", b);
    return s;
}

static lucent_status read_scattering(const lucent_json_node *root, lucent_spectra *sp)
{
    static const char *const kinds[3] = {"epidermis", "dermis", "hypodermis"};
    lucent_json_node n, k;
    lucent_status s = lucent_json_object(root, "scattering", true, &n);
    for (int i = 0; i < 3 && s == LUCENT_OK; i++) {
        s = lucent_json_object(&n, kinds[i], true, &k);
        if (s == LUCENT_OK) s = lucent_json_number(&k, "a_prime", &sp->scatter[i][0]);
        if (s == LUCENT_OK) s = lucent_json_number(&k, "f_ray", &sp->scatter[i][1]);
        if (s == LUCENT_OK) s = lucent_json_number(&k, "b_mie", &sp->scatter[i][2]);
    }
    return s;
}

static lucent_status read_spectra(const lucent_json_node *root, lucent_spectra *sp)
{
    lucent_json_node cie, d65, hb, base, srgb;
    lucent_status s = lucent_json_object(root, "cie1931", true, &cie);
    if (s == LUCENT_OK) s = read_grid(&cie, SPECTRA_CIE_START, SPECTRA_CIE_STEP);
    if (s == LUCENT_OK) s = read_table(&cie, "x", SPECTRA_CIE_COUNT, sp->cmf[0]);
    if (s == LUCENT_OK) s = read_table(&cie, "y", SPECTRA_CIE_COUNT, sp->cmf[1]);
    if (s == LUCENT_OK) s = read_table(&cie, "z", SPECTRA_CIE_COUNT, sp->cmf[2]);
    if (s == LUCENT_OK) s = lucent_json_object(root, "d65", true, &d65);
    if (s == LUCENT_OK) s = read_grid(&d65, SPECTRA_CIE_START, SPECTRA_CIE_STEP);
    if (s == LUCENT_OK) s = read_table(&d65, "values", SPECTRA_CIE_COUNT, sp->d65);
    if (s == LUCENT_OK) s = lucent_json_object(root, "hemoglobin", true, &hb);
    if (s == LUCENT_OK) s = read_grid(&hb, SPECTRA_HB_START, SPECTRA_HB_STEP);
    if (s == LUCENT_OK) s = read_table(&hb, "oxy", SPECTRA_HB_COUNT, sp->hb[0]);
    if (s == LUCENT_OK) s = read_table(&hb, "deoxy", SPECTRA_HB_COUNT, sp->hb[1]);
    if (s == LUCENT_OK) s = lucent_json_number(&hb, "molar_mass_g_per_mol", &sp->hb_molar_mass);
    if (s == LUCENT_OK) s = lucent_json_number(&hb, "blood_g_per_liter", &sp->hb_per_liter);
    if (s == LUCENT_OK) s = read_power(root, "eumelanin", &sp->eumelanin[0], &sp->eumelanin[1]);
    if (s == LUCENT_OK) s = read_power(root, "pheomelanin", &sp->pheomelanin[0], &sp->pheomelanin[1]);
    if (s == LUCENT_OK) s = lucent_json_object(root, "baseline", true, &base);
    if (s == LUCENT_OK) s = lucent_json_number(&base, "a", &sp->baseline[0]);
    if (s == LUCENT_OK) s = lucent_json_number(&base, "c", &sp->baseline[1]);
    if (s == LUCENT_OK) s = lucent_json_number(&base, "l0", &sp->baseline[2]);
    if (s == LUCENT_OK) s = lucent_json_number(&base, "w", &sp->baseline[3]);
    if (s == LUCENT_OK) s = read_scattering(root, sp);
    if (s == LUCENT_OK) s = lucent_json_object(root, "srgb", true, &srgb);
    if (s == LUCENT_OK) s = read_table(&srgb, "xyz_to_rgb", 9, sp->xyz_to_rgb);
    return s;
}

static void load(void)
{
    const lucent_embedded_file *f = lucent_embedded(SPECTRA_FILE);
    cJSON *json = NULL;
    if (!f) {
        snprintf(g_failure, sizeof g_failure, "%s is not built into this binary", SPECTRA_FILE);
        return;
    }
    lucent_status s = lucent_json_parse_text((const char *)f->data, SPECTRA_FILE " (built in)", &json);
    if (s == LUCENT_OK) {
        lucent_json_node root = lucent_json_root(json, SPECTRA_FILE " (built in)", "");
        s = read_spectra(&root, &g_spectra);
    }
    if (s != LUCENT_OK) snprintf(g_failure, sizeof g_failure, "%s", lucent_last_error());
    cJSON_Delete(json);
    lucent_clear_error();
}

const lucent_spectra *lucent_spectra_get(void)
{
    pthread_once(&g_once, load);
    return g_failure[0] ? NULL : &g_spectra;
}

lucent_status lucent_spectra_ready(void)
{
    return lucent_spectra_get() ? LUCENT_OK : lucent_error(LUCENT_ERR_INTERNAL, "%s", g_failure);
}

/* Linear interpolation of a table (start, step, count) at x, clamped to its ends. */
double lucent_spectra_lerp(const double *table, double start, double step, int count, double x)
{
    double t = (x - start) / step;
    if (!(t > 0.0)) return table[0];
    if (t >= count - 1) return table[count - 1];
    int i = (int)t;
    double f = t - i;
    return table[i] + f * (table[i + 1] - table[i]);
}

/* ---- chromophores ---- */

/* Prahl: mu_a = 2.303 e x / 64500 cm^-1 for x g Hb per litre; 0.1 of it in mm^-1. */
double lucent_blood_absorption(double nm, double saturation)
{
    const lucent_spectra *sp = lucent_spectra_get();
    if (!sp) return NAN;
    double oxy = lucent_spectra_lerp(sp->hb[0], SPECTRA_HB_START, SPECTRA_HB_STEP, SPECTRA_HB_COUNT, nm);
    double deoxy = lucent_spectra_lerp(sp->hb[1], SPECTRA_HB_START, SPECTRA_HB_STEP, SPECTRA_HB_COUNT, nm);
    double e = saturation * oxy + (1.0 - saturation) * deoxy;
    return 0.1 * 2.303 * e * sp->hb_per_liter / sp->hb_molar_mass;
}

/* Donner & Jensen 2006: sigma_a,em = 6.6e10 lambda^-3.33, sigma_a,pm = 2.9e14 lambda^-4.75 mm^-1. */
double lucent_melanin_absorption(double nm, double eumelanin)
{
    const lucent_spectra *sp = lucent_spectra_get();
    if (!sp) return NAN;
    double em = sp->eumelanin[0] * pow(nm, -sp->eumelanin[1]);
    double pm = sp->pheomelanin[0] * pow(nm, -sp->pheomelanin[1]);
    return eumelanin * em + (1.0 - eumelanin) * pm;
}

/* Donner & Jensen 2006 (Jacques, Saidi): 0.0244 + 8.53 exp(-(lambda - 154) / 66.2) mm^-1. */
double lucent_baseline_absorption(double nm)
{
    const lucent_spectra *sp = lucent_spectra_get();
    if (!sp) return NAN;
    return sp->baseline[0] + sp->baseline[1] * exp(-(nm - sp->baseline[2]) / sp->baseline[3]);
}

/* ---- bands and colour ---- */

/* integral over [a, b] of f g, f and g the linear interpolants of two 5 nm tables: Simpson's rule on
 * each piece between knots (exact for their quadratic product). */
static double integrate_product(const double *f, const double *g, double a, double b)
{
    double sum = 0.0, x = a;
    while (x < b - 1e-12) {
        double knot =
            SPECTRA_CIE_START + SPECTRA_CIE_STEP * (floor((x - SPECTRA_CIE_START) / SPECTRA_CIE_STEP + 1e-9) + 1);
        double y = fmin(knot, b), m = 0.5 * (x + y);
        double fx = lucent_spectra_lerp(f, SPECTRA_CIE_START, SPECTRA_CIE_STEP, SPECTRA_CIE_COUNT, x);
        double fm = lucent_spectra_lerp(f, SPECTRA_CIE_START, SPECTRA_CIE_STEP, SPECTRA_CIE_COUNT, m);
        double fy = lucent_spectra_lerp(f, SPECTRA_CIE_START, SPECTRA_CIE_STEP, SPECTRA_CIE_COUNT, y);
        double gx = lucent_spectra_lerp(g, SPECTRA_CIE_START, SPECTRA_CIE_STEP, SPECTRA_CIE_COUNT, x);
        double gm = lucent_spectra_lerp(g, SPECTRA_CIE_START, SPECTRA_CIE_STEP, SPECTRA_CIE_COUNT, m);
        double gy = lucent_spectra_lerp(g, SPECTRA_CIE_START, SPECTRA_CIE_STEP, SPECTRA_CIE_COUNT, y);
        sum += (y - x) / 6.0 * (fx * gx + 4.0 * fm * gm + fy * gy);
        x = y;
    }
    return sum;
}

lucent_status lucent_bands_make(int count, lucent_bands *dest)
{
    lucent_status s = lucent_spectra_ready();
    if (s != LUCENT_OK) return s;
    if (count == 0) count = LUCENT_BANDS_DEFAULT;
    if (count < 1 || count > LUCENT_BANDS_MAX)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "bands: must be in [1, %d], got %d", LUCENT_BANDS_MAX, count);
    const lucent_spectra *sp = lucent_spectra_get();
    memset(dest, 0, sizeof *dest);
    dest->count = count;
    dest->width = (LUCENT_SPECTRAL_MAX_NM - LUCENT_SPECTRAL_MIN_NM) / count;
    double norm = integrate_product(sp->cmf[1], sp->d65, LUCENT_SPECTRAL_MIN_NM, LUCENT_SPECTRAL_MAX_NM);
    for (int b = 0; b < count; b++) {
        double lo = LUCENT_SPECTRAL_MIN_NM + b * dest->width, hi = lo + dest->width;
        dest->center[b] = 0.5 * (lo + hi);
        for (int i = 0; i < 3; i++) dest->xyz[i][b] = integrate_product(sp->cmf[i], sp->d65, lo, hi) / norm;
        for (int c = 0; c < 3; c++) {
            const double *m = sp->xyz_to_rgb + 3 * c; /* IEC 61966-2-1 */
            dest->rgb[c][b] = m[0] * dest->xyz[0][b] + m[1] * dest->xyz[1][b] + m[2] * dest->xyz[2][b];
        }
    }
    for (int c = 0; c < 3; c++) {
        double sum = 0.0, wsum = 0.0;
        for (int b = 0; b < count; b++) sum += dest->rgb[c][b], wsum += dest->xyz[c][b];
        dest->white_xyz[c] = wsum;
        dest->rgb_unbalanced[c] = sum;
        for (int b = 0; b < count; b++) dest->rgb[c][b] /= sum; /* the white balance */
    }
    return LUCENT_OK;
}

void lucent_bands_xyz(const lucent_bands *b, const double *reflectance, double xyz[3])
{
    for (int i = 0; i < 3; i++) {
        xyz[i] = 0.0;
        for (int k = 0; k < b->count; k++) xyz[i] += b->xyz[i][k] * reflectance[k];
    }
}

void lucent_bands_rgb(const lucent_bands *b, const double *reflectance, double rgb[3])
{
    for (int c = 0; c < 3; c++) {
        rgb[c] = 0.0;
        for (int k = 0; k < b->count; k++) rgb[c] += b->rgb[c][k] * reflectance[k];
    }
}

void lucent_bands_rgb_to_xyz(const lucent_bands *b, const double rgb[3], double xyz[3])
{
    const double *m = lucent_spectra_get()->xyz_to_rgb; /* the bands exist: the tables were read */
    double u[3], inv[9];
    for (int c = 0; c < 3; c++) u[c] = rgb[c] * b->rgb_unbalanced[c];
    double det =
        m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
    inv[0] = (m[4] * m[8] - m[5] * m[7]) / det, inv[1] = (m[2] * m[7] - m[1] * m[8]) / det;
    inv[2] = (m[1] * m[5] - m[2] * m[4]) / det, inv[3] = (m[5] * m[6] - m[3] * m[8]) / det;
    inv[4] = (m[0] * m[8] - m[2] * m[6]) / det, inv[5] = (m[2] * m[3] - m[0] * m[5]) / det;
    inv[6] = (m[3] * m[7] - m[4] * m[6]) / det, inv[7] = (m[1] * m[6] - m[0] * m[7]) / det;
    inv[8] = (m[0] * m[4] - m[1] * m[3]) / det;
    for (int i = 0; i < 3; i++) xyz[i] = inv[3 * i] * u[0] + inv[3 * i + 1] * u[1] + inv[3 * i + 2] * u[2];
}

/* Chardon, Cretois & Hourseau 1991: ITA = arctan((L* - 50) / b*) 180 / pi. */
double lucent_ita(const double lab[3]) { return atan2(lab[0] - 50.0, lab[2]) * 180.0 / M_PI; }

/* Del Bino et al. 2006. */
const char *lucent_ita_category(double ita)
{
    if (ita > 55.0) return "very light";
    if (ita > 41.0) return "light";
    if (ita > 28.0) return "intermediate";
    if (ita > 10.0) return "tan";
    if (ita > -30.0) return "brown";
    return "dark";
}
