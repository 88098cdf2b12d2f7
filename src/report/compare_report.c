/* The comparison report: every real-time method beside the path-traced reference, as HTML,
 * Markdown and CSV, and a chart of error against frame time. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "report/compare_internal.h"

static const char *k_style =
    "body{font-family:sans-serif;margin:2em auto;max-width:1400px;color:#222;line-height:1.4}"
    "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:.3em .6em;"
    "text-align:right}td:first-child,th:first-child{text-align:left}th{background:#f2f2f2}"
    "tr.best td{font-weight:bold}.grid{display:flex;flex-wrap:wrap;gap:12px;align-items:flex-start}"
    "figure{margin:0;text-align:center}figure img{display:block;image-rendering:pixelated}"
    "figcaption{font-size:.85em;max-width:40em}pre{background:#f7f7f7;padding:1em;overflow:auto;font-size:.8em}"
    ".note{color:#555;font-size:.9em}.warn{background:#fff3cd;border:1px solid #e0b000;padding:.6em 1em}"
    ".bar{display:flex;align-items:center;gap:.5em;font-size:.85em}";

double lucent_compare_net_error(double rel_rms, double reference_noise)
{
    return sqrt(fmax(rel_rms * rel_rms - reference_noise * reference_noise, 0.0));
}

bool lucent_compare_noise_known(const lucent_compare_scene *sc)
{
    return sc->reference_spp >= LUCENT_COMPARE_MIN_SPP && isfinite(sc->reference_noise) && sc->reference_noise >= 0;
}

static double net_of(const lucent_compare_scene *sc, int i)
{
    double e = sc->methods[i].rel_rms;
    return isfinite(e) ? lucent_compare_net_error(e, sc->reference_noise) : INFINITY;
}

static double raw_of(const lucent_compare_scene *sc, int i)
{
    double e = sc->methods[i].rel_rms;
    return isfinite(e) ? e : INFINITY;
}

double lucent_compare_pair_z(const lucent_compare_scene *sc, int i, int j)
{
    if (!sc->pair_se || i < 0 || j < 0 || i >= sc->method_count || j >= sc->method_count) return NAN;
    double ei = sc->methods[i].rel_rms, ej = sc->methods[j].rel_rms, d = ei * ei - ej * ej;
    double se = sc->pair_se[(size_t)i * (size_t)sc->method_count + (size_t)j];
    if (!isfinite(d)) return NAN;
    return se > 0 ? d / se : d == 0 ? 0 : copysign(INFINITY, d);
}

/* Whether method k shares the rank of leader: the paired test does not separate them (with pair_se),
 * else their net errors lie within the reference's noise of each other. */
static bool same_group(const lucent_compare_scene *sc, int leader, int k)
{
    if (sc->pair_se) {
        return fabs(lucent_compare_pair_z(sc, k, leader)) < LUCENT_COMPARE_Z; /* NaN, inf: apart */
    }
    return net_of(sc, k) - net_of(sc, leader) < sc->reference_noise;
}

bool lucent_compare_rank(const lucent_compare_scene *sc, int *order, int *rank)
{
    int n = sc->method_count;
    for (int i = 0; i < n; i++) order[i] = i, rank[i] = 0;
    if (!lucent_compare_noise_known(sc)) return false;
    for (int i = 1; i < n; i++) /* insertion sort by error: stable, few methods */
        for (int k = i; k > 0 && raw_of(sc, order[k]) < raw_of(sc, order[k - 1]); k--) {
            int t = order[k];
            order[k] = order[k - 1], order[k - 1] = t;
        }
    int leader = 0;
    for (int k = 0; k < n; k++) {
        if (k > 0 && !same_group(sc, order[leader], order[k])) leader = k;
        rank[order[k]] = leader + 1;
    }
    return true;
}

int lucent_compare_lambert_index(const lucent_compare_scene *sc)
{
    for (int i = 0; i < sc->method_count; i++)
        if (sc->methods[i].name && !strcmp(sc->methods[i].name, "lambert")) return i;
    return -1;
}

/* The method's frame time over Lambert's, or NaN. */
static double lambert_ratio(const lucent_compare_scene *sc, int i)
{
    int l = lucent_compare_lambert_index(sc);
    return l >= 0 && sc->methods[l].frame_ms > 0 ? sc->methods[i].frame_ms / sc->methods[l].frame_ms : NAN;
}

/* Whether method i shares its rank with another. */
static bool tied(const lucent_compare_scene *sc, const int *rank, int i)
{
    for (int k = 0; rank[i] && k < sc->method_count; k++)
        if (k != i && rank[k] == rank[i]) return true;
    return false;
}

/* The warning of a scene whose reference cannot rank the methods (NULL: none). */
static const char *noise_warning(const lucent_compare_scene *sc, char *dest, size_t size)
{
    if (lucent_compare_noise_known(sc)) return NULL;
    snprintf(dest, size,
             "the reference has %d sample%s per pixel, fewer than the %d from which its noise can be estimated: "
             "its noise is unknown, so are the errors net of it, and no method is ranked or marked best "
             "(render the reference longer: --spp or --time)",
             sc->reference_spp, sc->reference_spp == 1 ? "" : "s", LUCENT_COMPARE_MIN_SPP);
    return dest;
}

static void pct_or_unknown(lucent_strbuf *b, double v)
{
    if (isfinite(v))
        lucent_strbuf_printf(b, "%.2f%%", 100 * v);
    else
        lucent_strbuf_printf(b, "unknown");
}

static void html_figure(lucent_strbuf *b, const char *image, const char *caption, int width, int height)
{
    if (!image) return;
    lucent_strbuf_printf(b, "<figure><a href=\"");
    lucent_strbuf_xml(b, image);
    lucent_strbuf_printf(b, "\" title=\"click to enlarge\"><img src=\"");
    lucent_strbuf_xml(b, image);
    if (width > 0 && height > 0) lucent_strbuf_printf(b, "\" width=\"%d\" height=\"%d", width, height);
    lucent_strbuf_printf(b, "\" alt=\"");
    lucent_strbuf_xml(b, caption);
    lucent_strbuf_printf(b, "\"></a><figcaption>");
    lucent_strbuf_xml(b, caption);
    lucent_strbuf_printf(b, "</figcaption></figure>\n");
}

static bool any_worst(const lucent_compare_scene *sc)
{
    for (int i = 0; i < sc->method_count; i++)
        if (sc->methods[i].has_worst) return true;
    return false;
}

static bool any_flip(const lucent_compare_scene *sc)
{
    for (int i = 0; i < sc->method_count; i++)
        if (sc->methods[i].has_flip) return true;
    return false;
}

/* The z of the paired test of method order[k] against the next in order, as text ("" for the last). */
static void z_next(const lucent_compare_scene *sc, const int *order, int k, char *dest, size_t size)
{
    dest[0] = '\0';
    if (k + 1 >= sc->method_count || !sc->pair_se) return;
    double z = fabs(lucent_compare_pair_z(sc, order[k], order[k + 1])); /* sorted: at or above 0 */
    if (isinf(z))
        snprintf(dest, size, "exact");
    else if (isfinite(z))
        snprintf(dest, size, "%.1f", z);
}

/* What a rank and a tie mean, once per table. */
static void rank_note(lucent_strbuf *b, const lucent_compare_scene *sc)
{
    if (sc->pair_se) {
        lucent_strbuf_printf(b,
                             "<p class=\"note\">Ranked by the error. Methods share a rank when the paired test of "
                             "their squared errors against the same reference cannot tell them apart: the "
                             "difference e<sub>i</sub><sup>2</sup> - e<sub>j</sub><sup>2</sup> is within %.0f "
                             "standard errors of zero against the group's first (the reference's noise enters that "
                             "difference once, weighted by the two images' difference). The column z gives each "
                             "method's separation from the next one down. ",
                             LUCENT_COMPARE_Z);
        if (sc->se_inflation > 1)
            lucent_strbuf_printf(b,
                                 "Its standard errors are calibrated on %d independent reference runs: the "
                                 "per-pixel variances understate them by a factor of %.2f in variance (light paths "
                                 "land one photon in many pixels).",
                                 sc->reference_runs, sc->se_inflation);
        else if (sc->se_inflation > 0)
            lucent_strbuf_printf(b,
                                 "Its standard errors come from the per-pixel variances; %d independent "
                                 "reference runs found them not understated.",
                                 sc->reference_runs);
        else
            lucent_strbuf_printf(b, "Its standard errors come from the per-pixel variances (pixels independent: "
                                    "camera paths only).");
        lucent_strbuf_printf(b, " The best rank is in bold.</p>\n");
    } else {
        lucent_strbuf_printf(b,
                             "<p class=\"note\">Ranked by the error net of the reference's noise; methods whose net "
                             "errors differ by less than that noise (%.2f%%) share a rank (tied): the reference "
                             "cannot tell them apart. The best rank is in bold.</p>\n",
                             100 * sc->reference_noise);
    }
}

static void html_table(lucent_strbuf *b, const lucent_compare_scene *scene)
{
    lucent_compare_scene clipped = *scene; /* the table holds 64 methods at most */
    const lucent_compare_scene *sc = &clipped;
    int order[64], rank[64], n = clipped.method_count = scene->method_count < 64 ? scene->method_count : 64;
    if (clipped.method_count < scene->method_count) clipped.pair_se = NULL; /* its rows are the scene's */
    bool ranked = lucent_compare_rank(sc, order, rank), flip = any_flip(sc), worst = any_worst(sc);
    lucent_strbuf_printf(b, "<table><tr><th>rank</th><th>method</th><th>relative RMS error</th><th>net of the "
                            "reference's noise</th>");
    if (ranked && sc->pair_se) lucent_strbuf_printf(b, "<th>z against the next</th>");
    if (flip) lucent_strbuf_printf(b, "<th>FLIP (mean)</th>");
    if (worst) lucent_strbuf_printf(b, "<th>worst 1%% of pixels' share</th>");
    lucent_strbuf_printf(b, "<th>R</th><th>G</th><th>B</th><th>frame (ms, GPU)</th><th>frame / "
                            "Lambert's</th><th>setup (ms, CPU)</th><th>settings</th></tr>\n");
    for (int k = 0; k < n; k++) {
        int i = order[k];
        const lucent_compare_method *m = &sc->methods[i];
        bool best = ranked && rank[i] == 1, tie = ranked && tied(sc, rank, i);
        lucent_strbuf_printf(b, "<tr%s><td>", best ? " class=\"best\"" : "");
        if (ranked)
            lucent_strbuf_printf(b, "%d%s", rank[i], tie ? " (tied)" : "");
        else
            lucent_strbuf_printf(b, "&ndash;");
        lucent_strbuf_printf(b, "</td><td>");
        lucent_strbuf_xml(b, m->name);
        lucent_strbuf_printf(b, "</td><td>%.2f%%</td><td>", 100 * m->rel_rms);
        pct_or_unknown(b, ranked ? lucent_compare_net_error(m->rel_rms, sc->reference_noise) : NAN);
        lucent_strbuf_printf(b, "</td>");
        if (ranked && sc->pair_se) {
            char z[32];
            z_next(sc, order, k, z, sizeof z);
            lucent_strbuf_printf(b, "<td>%s</td>", z);
        }
        if (flip) {
            if (m->has_flip)
                lucent_strbuf_printf(b, "<td>%.4f</td>", m->flip);
            else
                lucent_strbuf_printf(b, "<td>&ndash;</td>");
        }
        if (worst) {
            if (m->has_worst)
                lucent_strbuf_printf(b, "<td>%.1f%%</td>", 100 * m->worst_share);
            else
                lucent_strbuf_printf(b, "<td>&ndash;</td>");
        }
        lucent_strbuf_printf(b, "<td>%.2f%%</td><td>%.2f%%</td><td>%.2f%%</td><td>%.3f</td><td>",
                             100 * m->rel_rms_rgb[0], 100 * m->rel_rms_rgb[1], 100 * m->rel_rms_rgb[2], m->frame_ms);
        double ratio = lambert_ratio(sc, i);
        if (isfinite(ratio))
            lucent_strbuf_printf(b, "%.2fx", ratio);
        else
            lucent_strbuf_printf(b, "&ndash;");
        lucent_strbuf_printf(b, "</td><td>%.0f</td><td>", m->setup_ms);
        lucent_strbuf_xml(b, m->settings ? m->settings : "");
        lucent_strbuf_printf(b, "</td></tr>\n");
    }
    lucent_strbuf_printf(b, "</table>\n");
    if (ranked) rank_note(b, sc);
    if (flip)
        lucent_strbuf_printf(b, "<p class=\"note\">FLIP: the mean over the object's pixels of LDR-FLIP (Andersson "
                                "et al. 2020) between the tonemapped images as shown, for an observer at 67 pixels "
                                "per degree: 0 where the two look the same, 1 for the largest difference.</p>\n");
    if (worst)
        lucent_strbuf_printf(b, "<p class=\"note\">Worst 1%% of pixels' share: the share of the method's squared "
                                "error that the worst 1%% of the object's pixels hold: 1%% where the error is spread "
                                "evenly, near 100%% where a few pixels (a rim, a seam) hold it all.</p>\n");
}

static double map_scale(const lucent_compare_scene *sc) { return sc->error_scale > 0 ? sc->error_scale : 0.5; }

static void html_images(lucent_strbuf *b, const lucent_compare_scene *sc)
{
    char caption[320];
    lucent_strbuf_printf(b,
                         "<p class=\"note\">Images at their native size (%d x %d); click one to see it alone, "
                         "to zoom.</p>\n<div class=\"grid\">\n",
                         sc->width, sc->height);
    snprintf(caption, sizeof caption, "reference: path tracer, %d spp", sc->reference_spp);
    html_figure(b, sc->reference_image, caption, sc->width, sc->height);
    for (int i = 0; i < sc->method_count; i++) {
        const lucent_compare_method *m = &sc->methods[i];
        snprintf(caption, sizeof caption, "%s: %.1f%%, %.2f ms", m->name, 100 * m->rel_rms, m->frame_ms);
        html_figure(b, m->image, caption, sc->width, sc->height);
    }
    double scale = map_scale(sc);
    lucent_strbuf_printf(b,
                         "</div>\n<p class=\"note\">Signed per-pixel relative error (method - reference) / "
                         "(reference + 0.01), the mean over R, G and B, on the object's pixels (black elsewhere): "
                         "blue where the method is too dark, orange where it is too bright, black where it is "
                         "exact; the colour grows linearly to full at %.0f%% and stays full beyond (a fixed scale, "
                         "the same for every map and scene).</p>\n",
                         100 * scale);
    if (sc->error_scale_image) {
        lucent_strbuf_printf(b, "<div class=\"bar\"><span>-%.0f%% (too dark)</span><img src=\"", 100 * scale);
        lucent_strbuf_xml(b, sc->error_scale_image);
        lucent_strbuf_printf(b,
                             "\" width=\"256\" height=\"14\" alt=\"colour bar\"><span>+%.0f%% (too bright)</span>"
                             "</div>\n",
                             100 * scale);
    }
    lucent_strbuf_printf(b, "<div class=\"grid\">\n");
    for (int i = 0; i < sc->method_count; i++) {
        snprintf(caption, sizeof caption, "%s: signed error", sc->methods[i].name);
        html_figure(b, sc->methods[i].error_image, caption, sc->width, sc->height);
    }
    lucent_strbuf_printf(b, "</div>\n");
    bool crops = false;
    for (int i = 0; i < sc->method_count; i++) crops |= sc->methods[i].crop_image != NULL;
    if (!crops) return;
    lucent_strbuf_printf(b,
                         "<p class=\"note\">The worst region of each method, zoomed: the square of the image "
                         "where its squared error against the reference sums highest; left to right the "
                         "reference, the method and the signed error (the scale above).</p>\n<div class=\"grid\">\n");
    for (int i = 0; i < sc->method_count; i++) {
        const lucent_compare_method *m = &sc->methods[i];
        if (!m->crop_image) continue;
        snprintf(caption, sizeof caption, "%s: pixels (%d, %d) to (%d, %d)", m->name, m->crop[0], m->crop[1],
                 m->crop[0] + m->crop[2] - 1, m->crop[1] + m->crop[2] - 1);
        html_figure(b, m->crop_image, caption, 0, 0);
    }
    lucent_strbuf_printf(b, "</div>\n");
}

/* The methods asked for that could not render the scene, with why (none: nothing). */
static void html_skipped(lucent_strbuf *b, const lucent_compare_scene *sc)
{
    if (sc->skipped_count <= 0) return;
    lucent_strbuf_printf(b, "<p class=\"warn\"><b>Not in the table:</b> ");
    for (int i = 0; i < sc->skipped_count; i++) {
        lucent_strbuf_printf(b, "%s<b>", i ? "; " : "");
        lucent_strbuf_xml(b, sc->skipped[i].method);
        lucent_strbuf_printf(b, "</b> (");
        lucent_strbuf_xml(b, sc->skipped[i].reason);
        lucent_strbuf_printf(b, ")");
    }
    lucent_strbuf_printf(b, ".</p>\n");
}

static void html_scene(lucent_strbuf *b, const lucent_compare_scene *sc)
{
    char warn[400];
    lucent_strbuf_printf(b, "<section id=\"");
    lucent_strbuf_xml(b, sc->name);
    lucent_strbuf_printf(b, "\"><h2>");
    lucent_strbuf_xml(b, sc->name);
    lucent_strbuf_printf(b, "</h2>\n<p>");
    lucent_strbuf_xml(b, sc->description ? sc->description : "");
    lucent_strbuf_printf(b, "</p>\n");
    if (noise_warning(sc, warn, sizeof warn)) {
        lucent_strbuf_printf(b, "<p class=\"warn\"><b>Warning:</b> ");
        lucent_strbuf_xml(b, warn);
        lucent_strbuf_printf(b, ".</p>\n");
    }
    lucent_strbuf_printf(b,
                         "<p>%d x %d pixels. Reference: Lucent's path tracer, %d samples per pixel in %.1f s; its own "
                         "relative standard error over the object is ",
                         sc->width, sc->height, sc->reference_spp, sc->reference_seconds);
    pct_or_unknown(b, lucent_compare_noise_known(sc) ? sc->reference_noise : NAN);
    lucent_strbuf_printf(b, ", so smaller differences are noise (the net column takes it out: sqrt(error^2 - "
                            "noise^2)). Real-time methods on: ");
    lucent_strbuf_xml(b, sc->device ? sc->device : "unknown");
    lucent_strbuf_printf(b, ".</p>\n");
    html_table(b, sc);
    html_skipped(b, sc);
    report_html_regions(b, sc);
    report_html_lights(b, sc);
    html_images(b, sc);
    if (sc->chart) {
        lucent_strbuf_printf(b, "<p><img src=\"");
        lucent_strbuf_xml(b, sc->chart);
        lucent_strbuf_printf(b, "\" alt=\"error against frame time\"></p>\n");
    }
    lucent_strbuf_printf(b, "<details><summary>The scene, after overrides</summary><pre>");
    lucent_strbuf_xml(b, sc->scene_json ? sc->scene_json : "");
    lucent_strbuf_printf(b, "</pre></details></section>\n");
}

/* A scene's ranks and its methods' net errors, for the summary. */
typedef struct summary_scene {
    int order[64], rank[64];
    bool ranked;
    int groups;    /* distinct ranks */
    double lo, hi; /* the best and the worst net error */
} summary_scene;

static void summary_rank(const lucent_compare_scene *sc, summary_scene *dest)
{
    *dest = (summary_scene){.lo = INFINITY, .hi = -INFINITY};
    dest->ranked = sc->method_count <= 64 && lucent_compare_rank(sc, dest->order, dest->rank);
    for (int k = 0; dest->ranked && k < sc->method_count; k++) {
        double e = net_of(sc, k);
        if (isfinite(e)) dest->lo = fmin(dest->lo, e), dest->hi = fmax(dest->hi, e);
        dest->groups += k == 0 || dest->rank[dest->order[k]] != dest->rank[dest->order[k - 1]];
    }
}

static int method_index(const lucent_compare_scene *sc, const char *name)
{
    for (int m = 0; m < sc->method_count && m < 64; m++)
        if (!strcmp(sc->methods[m].name, name)) return m;
    return -1;
}

/* The summary's row order: by mean rank over the scenes that rank, then by mean net error (unranked
 * last, in their order of first appearance). */
static void summary_order(const lucent_compare_scene *scenes, int count, const summary_scene *ss, const char **names,
                          int n)
{
    double key[64][2];
    for (int j = 0; j < n; j++) {
        double sum = 0, err = 0;
        int c = 0;
        for (int i = 0; i < count; i++) {
            int k = method_index(&scenes[i], names[j]);
            if (k >= 0 && ss[i].ranked) sum += ss[i].rank[k], err += net_of(&scenes[i], k), c++;
        }
        key[j][0] = c ? sum / c : INFINITY, key[j][1] = c ? err / c : INFINITY;
    }
    for (int i = 1; i < n; i++) /* stable insertion sort */
        for (int k = i;
             k > 0 && (key[k][0] < key[k - 1][0] || (key[k][0] == key[k - 1][0] && key[k][1] < key[k - 1][1])); k--) {
            double t0 = key[k][0], t1 = key[k][1];
            key[k][0] = key[k - 1][0], key[k][1] = key[k - 1][1], key[k - 1][0] = t0, key[k - 1][1] = t1;
            const char *u = names[k];
            names[k] = names[k - 1], names[k - 1] = u;
        }
}

static void summary_head(lucent_strbuf *b, const lucent_compare_scene *scenes, int count, const summary_scene *ss)
{
    lucent_strbuf_printf(b, "<table><tr><th>method</th>");
    for (int i = 0; i < count; i++) {
        lucent_strbuf_printf(b, "<th><a href=\"#");
        lucent_strbuf_xml(b, scenes[i].name);
        lucent_strbuf_printf(b, "\">");
        lucent_strbuf_xml(b, scenes[i].name);
        lucent_strbuf_printf(b, "</a></th>");
    }
    lucent_strbuf_printf(b, "</tr>\n<tr><td>reference noise (spp)</td>");
    for (int i = 0; i < count; i++) {
        lucent_strbuf_printf(b, "<td>");
        pct_or_unknown(b, lucent_compare_noise_known(&scenes[i]) ? scenes[i].reference_noise : NAN);
        lucent_strbuf_printf(b, " (%d)</td>", scenes[i].reference_spp);
    }
    lucent_strbuf_printf(b, "</tr>\n<tr><td>spread: best to worst (ranks)</td>");
    for (int i = 0; i < count; i++) {
        if (ss[i].ranked && isfinite(ss[i].lo))
            lucent_strbuf_printf(b, "<td>%.2f%% to %.2f%% (%d)</td>", 100 * ss[i].lo, 100 * ss[i].hi, ss[i].groups);
        else
            lucent_strbuf_printf(b, "<td>&ndash;</td>");
    }
    lucent_strbuf_printf(b, "</tr>\n");
}

/* The summary across scenes: per method its net error and rank in each scene (the methods ranked
 * best over the scenes first), per scene the reference's noise and the spread of the errors. */
static void html_summary(lucent_strbuf *b, const lucent_compare_scene *scenes, int count)
{
    const char *names[64];
    int n = 0;
    for (int i = 0; i < count; i++)
        for (int k = 0; k < scenes[i].method_count; k++) {
            bool seen = false;
            for (int j = 0; j < n; j++) seen |= !strcmp(names[j], scenes[i].methods[k].name);
            if (!seen && n < 64) names[n++] = scenes[i].methods[k].name;
        }
    summary_scene *ss = calloc((size_t)(count > 0 ? count : 1), sizeof *ss);
    if (!ss) return; /* the buffer's own out-of-memory is reported by lucent_strbuf_finish */
    for (int i = 0; i < count; i++) summary_rank(&scenes[i], &ss[i]);
    summary_order(scenes, count, ss, names, n);
    lucent_strbuf_printf(b,
                         "<h2 id=\"summary\">Summary across scenes</h2>\n<p class=\"note\">Per scene the error "
                         "net of the reference's noise and, in brackets, the rank. Methods of the same rank cannot "
                         "be told apart in that scene: the paired test of their squared errors against the same "
                         "reference puts them within %.0f standard errors of each other (where no test was made, "
                         "their net errors lie within the reference's noise). Bold: the best rank where it is "
                         "apart from some other method. The rows run from the best mean rank down; the spread "
                         "row gives the best and the worst net error and how many ranks the scene "
                         "separates. A scene whose reference noise is unknown ranks nothing.</p>\n",
                         LUCENT_COMPARE_Z);
    summary_head(b, scenes, count, ss);
    for (int j = 0; j < n; j++) {
        lucent_strbuf_printf(b, "<tr><td>");
        lucent_strbuf_xml(b, names[j]);
        lucent_strbuf_printf(b, "</td>");
        for (int i = 0; i < count; i++) {
            const lucent_compare_scene *sc = &scenes[i];
            int k = method_index(sc, names[j]);
            if (k < 0) {
                lucent_strbuf_printf(b, "<td>&ndash;</td>");
            } else if (!ss[i].ranked) {
                lucent_strbuf_printf(b, "<td>%.2f%% (not net; unranked)</td>", 100 * sc->methods[k].rel_rms);
            } else {
                bool best = ss[i].rank[k] == 1 && ss[i].groups > 1;
                lucent_strbuf_printf(b, "<td>%s%.2f%% (%d)%s</td>", best ? "<b>" : "",
                                     100 * lucent_compare_net_error(sc->methods[k].rel_rms, sc->reference_noise),
                                     ss[i].rank[k], best ? "</b>" : "");
            }
        }
        lucent_strbuf_printf(b, "</tr>\n");
    }
    lucent_strbuf_printf(b, "</table>\n");
    free(ss);
}

lucent_status lucent_compare_write_html(const char *path, const char *title, const lucent_compare_scene *scenes,
                                        int count)
{
    lucent_strbuf b = {0};
    lucent_strbuf_printf(&b, "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>");
    lucent_strbuf_xml(&b, title);
    lucent_strbuf_printf(&b, "</title><style>%s</style></head><body>\n<h1>", k_style);
    lucent_strbuf_xml(&b, title);
    lucent_strbuf_printf(&b, "</h1>\n<p>Each real-time method renders the same scene as the physically based "
                             "reference. The error is the relative RMS difference sqrt(sum (m - r)^2 / sum r^2) "
                             "over the pixels the object covers, in linear HDR values before tonemapping; the "
                             "frame time is the GPU time of one frame from timer queries.</p>\n<ul>");
    for (int i = 0; i < count; i++) {
        lucent_strbuf_printf(&b, "<li><a href=\"#");
        lucent_strbuf_xml(&b, scenes[i].name);
        lucent_strbuf_printf(&b, "\">");
        lucent_strbuf_xml(&b, scenes[i].name);
        lucent_strbuf_printf(&b, "</a></li>");
    }
    lucent_strbuf_printf(&b, "</ul>\n");
    if (count > 0) report_html_provenance(&b, scenes[0].provenance);
    for (int i = 0; i < count; i++) {
        char warn[400];
        if (!noise_warning(&scenes[i], warn, sizeof warn)) continue;
        lucent_strbuf_printf(&b, "<p class=\"warn\"><b>Warning:</b> ");
        lucent_strbuf_xml(&b, scenes[i].name);
        lucent_strbuf_printf(&b, ": ");
        lucent_strbuf_xml(&b, warn);
        lucent_strbuf_printf(&b, ".</p>\n");
    }
    html_summary(&b, scenes, count);
    for (int i = 0; i < count; i++) html_scene(&b, &scenes[i]);
    lucent_strbuf_printf(&b, "</body></html>\n");
    char *text;
    lucent_status s = lucent_strbuf_finish(&b, &text);
    if (s == LUCENT_OK) s = lucent_write_file(path, text, strlen(text));
    free(text);
    return s;
}

lucent_status lucent_compare_write_markdown(const char *path, const lucent_compare_scene *scenes, int count)
{
    lucent_strbuf b = {0};
    if (count > 0) report_md_provenance(&b, scenes[0].provenance);
    for (int i = 0; i < count; i++) {
        const lucent_compare_scene *sc = &scenes[i];
        char warn[400], noise[32];
        bool known = lucent_compare_noise_known(sc);
        if (known)
            snprintf(noise, sizeof noise, "%.2f%%", 100 * sc->reference_noise);
        else
            snprintf(noise, sizeof noise, "unknown");
        lucent_strbuf_printf(&b, "%s## %s\n\nReference: path tracer, %d spp, %.1f s (noise %s); %d x %d; GL: %s\n\n",
                             i ? "\n" : "", sc->name, sc->reference_spp, sc->reference_seconds, noise, sc->width,
                             sc->height, sc->device ? sc->device : "unknown");
        if (noise_warning(sc, warn, sizeof warn)) lucent_strbuf_printf(&b, "**Warning:** %s.\n\n", warn);
        int order[64], rank[64];
        bool ranked = sc->method_count <= 64 && lucent_compare_rank(sc, order, rank);
        bool zcol = ranked && sc->pair_se, flip = any_flip(sc), worst = any_worst(sc);
        lucent_strbuf_printf(&b,
                             "| rank | method | rel. RMS error | net of noise | R | G | B | frame ms | x Lambert | "
                             "setup ms |%s%s%s\n|---|---|---|---|---|---|---|---|---|---|%s%s%s\n",
                             zcol ? " z next |" : "", flip ? " FLIP |" : "", worst ? " worst 1% |" : "",
                             zcol ? "---|" : "", flip ? "---|" : "", worst ? "---|" : "");
        for (int j = 0; j < sc->method_count && j < 64; j++) {
            int k = ranked ? order[j] : j;
            const lucent_compare_method *m = &sc->methods[k];
            char r[24] = "-", net[24] = "unknown", ratio[24] = "-";
            if (ranked) {
                snprintf(r, sizeof r, "%s%d", tied(sc, rank, k) ? "=" : "", rank[k]);
                snprintf(net, sizeof net, "%.2f%%", 100 * lucent_compare_net_error(m->rel_rms, sc->reference_noise));
            }
            double q = lambert_ratio(sc, k);
            if (isfinite(q)) snprintf(ratio, sizeof ratio, "%.2f", q);
            const char *bold = ranked && rank[k] == 1 ? "**" : "";
            lucent_strbuf_printf(&b, "| %s | %s%s%s | %.2f%% | %s | %.2f%% | %.2f%% | %.2f%% | %.3f | %s | %.0f |", r,
                                 bold, m->name, bold, 100 * m->rel_rms, net, 100 * m->rel_rms_rgb[0],
                                 100 * m->rel_rms_rgb[1], 100 * m->rel_rms_rgb[2], m->frame_ms, ratio, m->setup_ms);
            if (zcol) {
                char z[32];
                z_next(sc, order, j, z, sizeof z);
                lucent_strbuf_printf(&b, " %s |", z[0] ? z : "-");
            }
            if (flip) {
                if (m->has_flip)
                    lucent_strbuf_printf(&b, " %.4f |", m->flip);
                else
                    lucent_strbuf_printf(&b, " - |");
            }
            if (worst) {
                if (m->has_worst)
                    lucent_strbuf_printf(&b, " %.1f%% |", 100 * m->worst_share);
                else
                    lucent_strbuf_printf(&b, " - |");
            }
            lucent_strbuf_printf(&b, "\n");
        }
        if (ranked)
            lucent_strbuf_printf(&b, "\n%s\n",
                                 sc->pair_se ? "Same rank (=): the paired test of the squared errors "
                                               "cannot tell the methods apart (|z| < 3); z next: "
                                               "the separation from the next row; worst 1%: the share of the squared "
                                               "error in the worst 1% of the object's pixels."
                                             : "Same rank (=): net errors within the reference's noise.");
        report_md_regions(&b, sc);
        report_md_lights(&b, sc);
        for (int j = 0; j < sc->skipped_count; j++)
            lucent_strbuf_printf(&b, "%s%s (skipped: %s)%s", j ? "; " : "\nNot in the table: ", sc->skipped[j].method,
                                 sc->skipped[j].reason, j + 1 == sc->skipped_count ? ".\n" : "");
    }
    char *text;
    lucent_status s = lucent_strbuf_finish(&b, &text);
    if (s == LUCENT_OK) s = lucent_write_file(path, text, strlen(text));
    free(text);
    return s;
}

/* CSV fields are names without commas or quotes in practice; quote them anyway. */
static void csv_field(lucent_strbuf *b, const char *text)
{
    lucent_strbuf_printf(b, "\"");
    for (const char *p = text ? text : ""; *p; p++) lucent_strbuf_printf(b, *p == '"' ? "\"\"" : "%c", *p);
    lucent_strbuf_printf(b, "\"");
}

lucent_status lucent_compare_write_csv(const char *path, const lucent_compare_scene *scenes, int count)
{
    lucent_strbuf b = {0};
    lucent_strbuf_printf(&b, "scene,method,rel_rms,rel_rms_r,rel_rms_g,rel_rms_b,frame_ms,setup_ms,"
                             "reference_spp,reference_noise,rel_rms_net,rank,frame_vs_lambert\n");
    for (int i = 0; i < count; i++) {
        const lucent_compare_scene *sc = &scenes[i];
        int order[64], rank[64];
        bool ranked = sc->method_count <= 64 && lucent_compare_rank(sc, order, rank);
        for (int k = 0; k < sc->method_count; k++) {
            const lucent_compare_method *m = &sc->methods[k];
            csv_field(&b, sc->name);
            lucent_strbuf_printf(&b, ",");
            csv_field(&b, m->name);
            lucent_strbuf_printf(&b, ",%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,", m->rel_rms, m->rel_rms_rgb[0],
                                 m->rel_rms_rgb[1], m->rel_rms_rgb[2], m->frame_ms, m->setup_ms, sc->reference_spp);
            if (ranked) /* unknown noise: empty noise, net error and rank */
                lucent_strbuf_printf(&b, "%.6g,%.6g,%d", sc->reference_noise,
                                     lucent_compare_net_error(m->rel_rms, sc->reference_noise), rank[k]);
            else
                lucent_strbuf_printf(&b, ",,");
            double q = k < 64 ? lambert_ratio(sc, k) : NAN;
            if (isfinite(q))
                lucent_strbuf_printf(&b, ",%.6g\n", q);
            else
                lucent_strbuf_printf(&b, ",\n");
        }
    }
    char *text;
    lucent_status s = lucent_strbuf_finish(&b, &text);
    if (s == LUCENT_OK) s = lucent_write_file(path, text, strlen(text));
    free(text);
    return s;
}

lucent_status lucent_compare_write_chart(const char *path, const lucent_compare_scene *sc)
{
    int n = sc->method_count;
    bool known = lucent_compare_noise_known(sc);
    lucent_plot_series *series = calloc((size_t)(n > 0 ? n : 1), sizeof *series);
    double *xy = calloc(2 * (size_t)(n > 0 ? n : 1), sizeof *xy);
    const char **labels = calloc((size_t)(n > 0 ? n : 1), sizeof *labels);
    if (!series || !xy || !labels) {
        free(series), free(xy), free(labels);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    }
    for (int i = 0; i < n; i++) {
        double e = sc->methods[i].rel_rms;
        xy[2 * i] = sc->methods[i].frame_ms,
               xy[2 * i + 1] = 100 * (known ? lucent_compare_net_error(e, sc->reference_noise) : e);
        labels[i] = sc->methods[i].name;
        series[i] =
            (lucent_plot_series){.label = sc->methods[i].name,
                                 .x = &xy[2 * i],
                                 .y = &xy[2 * i + 1],
                                 .count = 1,
                                 .markers = true,
                                 .marker = i % lucent_plot_marker_count() + (i % lucent_plot_marker_count() == 0),
                                 .point_labels = &labels[i]};
    }
    char title[200], band[80];
    snprintf(title, sizeof title, "%s: error against the reference and frame time%s", sc->name,
             known ? "" : " (reference noise unknown: raw errors)");
    snprintf(band, sizeof band, "reference noise (%.2f%%)", known ? 100 * sc->reference_noise : 0.0);
    lucent_plot_panel panel = {.title = title,
                               .x_label = "frame time (ms, GPU; logarithmic)",
                               .log_x = true,
                               .legend_outside = true,
                               .y_label = known ? "relative RMS error net of the reference's noise (%)"
                                                : "relative RMS error (%)",
                               .series = series,
                               .series_count = n,
                               .band_y1 = known ? 100 * sc->reference_noise : 0,
                               .band_label = known ? band : NULL};
    lucent_status s = lucent_plot_write_svg(
        path, &(lucent_plot_desc){.panels = &panel, .panel_count = 1, .panel_width = 760, .panel_height = 440});
    free(series), free(xy), free(labels);
    return s;
}
