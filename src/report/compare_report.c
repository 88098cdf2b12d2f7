/* The comparison report: every real-time method beside the path-traced reference, as HTML,
 * Markdown and CSV, and a chart of error against frame time. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/strbuf.h"
#include "lucent/report.h"

static const char *k_style =
    "body{font-family:sans-serif;margin:2em auto;max-width:1200px;color:#222;line-height:1.4}"
    "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:.3em .6em;"
    "text-align:right}td:first-child,th:first-child{text-align:left}th{background:#f2f2f2}"
    "tr.best td{font-weight:bold}.grid{display:flex;flex-wrap:wrap;gap:12px}"
    "figure{margin:0;text-align:center}figure img{display:block;max-width:256px;image-rendering:pixelated}"
    "figcaption{font-size:.85em}pre{background:#f7f7f7;padding:1em;overflow:auto;font-size:.8em}"
    ".note{color:#555;font-size:.9em}";

double lucent_compare_net_error(double rel_rms, double reference_noise)
{
    return sqrt(fmax(rel_rms * rel_rms - reference_noise * reference_noise, 0.0));
}

/* The index of the method with the smallest error (-1 when none is finite). */
static int best_method(const lucent_compare_scene *sc)
{
    int best = -1;
    for (int i = 0; i < sc->method_count; i++)
        if (isfinite(sc->methods[i].rel_rms) && (best < 0 || sc->methods[i].rel_rms < sc->methods[best].rel_rms))
            best = i;
    return best;
}

static void html_figure(lucent_strbuf *b, const char *image, const char *caption)
{
    if (!image) return;
    lucent_strbuf_printf(b, "<figure><img src=\"");
    lucent_strbuf_xml(b, image);
    lucent_strbuf_printf(b, "\" alt=\"");
    lucent_strbuf_xml(b, caption);
    lucent_strbuf_printf(b, "\"><figcaption>");
    lucent_strbuf_xml(b, caption);
    lucent_strbuf_printf(b, "</figcaption></figure>\n");
}

static void html_table(lucent_strbuf *b, const lucent_compare_scene *sc)
{
    int best = best_method(sc);
    lucent_strbuf_printf(b, "<table><tr><th>method</th><th>relative RMS error</th><th>net of the reference's "
                            "noise</th><th>R</th><th>G</th><th>B</th><th>frame (ms, GPU)</th><th>setup (ms, CPU)"
                            "</th><th>settings</th></tr>\n");
    for (int i = 0; i < sc->method_count; i++) {
        const lucent_compare_method *m = &sc->methods[i];
        lucent_strbuf_printf(b, "<tr%s><td>", i == best ? " class=\"best\"" : "");
        lucent_strbuf_xml(b, m->name);
        lucent_strbuf_printf(b,
                             "</td><td>%.2f%%</td><td>%.2f%%</td><td>%.2f%%</td><td>%.2f%%</td><td>%.2f%%</td>"
                             "<td>%.3f</td><td>%.0f</td><td>",
                             100 * m->rel_rms, 100 * lucent_compare_net_error(m->rel_rms, sc->reference_noise),
                             100 * m->rel_rms_rgb[0], 100 * m->rel_rms_rgb[1], 100 * m->rel_rms_rgb[2], m->frame_ms,
                             m->setup_ms);
        lucent_strbuf_xml(b, m->settings ? m->settings : "");
        lucent_strbuf_printf(b, "</td></tr>\n");
    }
    lucent_strbuf_printf(b, "</table>\n");
}

static void html_images(lucent_strbuf *b, const lucent_compare_scene *sc)
{
    char caption[256];
    lucent_strbuf_printf(b, "<div class=\"grid\">\n");
    snprintf(caption, sizeof caption, "reference: path tracer, %d spp", sc->reference_spp);
    html_figure(b, sc->reference_image, caption);
    for (int i = 0; i < sc->method_count; i++) {
        const lucent_compare_method *m = &sc->methods[i];
        snprintf(caption, sizeof caption, "%s: %.1f%%, %.2f ms", m->name, 100 * m->rel_rms, m->frame_ms);
        html_figure(b, m->image, caption);
    }
    lucent_strbuf_printf(b, "</div>\n<p class=\"note\">Per-pixel relative error |method - reference| / "
                            "(reference + 0.01), averaged over R, G, B (black 0, white at the scale of each map's "
                            "99th percentile):</p>\n<div class=\"grid\">\n");
    for (int i = 0; i < sc->method_count; i++) {
        snprintf(caption, sizeof caption, "%s: error", sc->methods[i].name);
        html_figure(b, sc->methods[i].error_image, caption);
    }
    lucent_strbuf_printf(b, "</div>\n");
}

static void html_scene(lucent_strbuf *b, const lucent_compare_scene *sc)
{
    lucent_strbuf_printf(b, "<section id=\"");
    lucent_strbuf_xml(b, sc->name);
    lucent_strbuf_printf(b, "\"><h2>");
    lucent_strbuf_xml(b, sc->name);
    lucent_strbuf_printf(b, "</h2>\n<p>");
    lucent_strbuf_xml(b, sc->description ? sc->description : "");
    lucent_strbuf_printf(b,
                         "</p>\n<p>%d x %d pixels. Reference: Lucent's path tracer, %d samples per pixel in "
                         "%.1f s; its own relative standard error over the object is %.2f%%, so smaller "
                         "differences are noise (the net column takes it out: sqrt(error^2 - noise^2)). "
                         "Real-time methods on: ",
                         sc->width, sc->height, sc->reference_spp, sc->reference_seconds, 100 * sc->reference_noise);
    lucent_strbuf_xml(b, sc->device ? sc->device : "unknown");
    lucent_strbuf_printf(b, ".</p>\n");
    html_table(b, sc);
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
    for (int i = 0; i < count; i++) {
        const lucent_compare_scene *sc = &scenes[i];
        lucent_strbuf_printf(&b,
                             "%s## %s\n\nReference: path tracer, %d spp, %.1f s (noise %.2f%%); %d x %d; GL: %s\n\n"
                             "| method | rel. RMS error | net of noise | R | G | B | frame ms | setup ms |\n"
                             "|---|---|---|---|---|---|---|---|\n",
                             i ? "\n" : "", sc->name, sc->reference_spp, sc->reference_seconds,
                             100 * sc->reference_noise, sc->width, sc->height, sc->device ? sc->device : "unknown");
        for (int k = 0; k < sc->method_count; k++) {
            const lucent_compare_method *m = &sc->methods[k];
            lucent_strbuf_printf(&b, "| %s | %.2f%% | %.2f%% | %.2f%% | %.2f%% | %.2f%% | %.3f | %.0f |\n", m->name,
                                 100 * m->rel_rms, 100 * lucent_compare_net_error(m->rel_rms, sc->reference_noise),
                                 100 * m->rel_rms_rgb[0], 100 * m->rel_rms_rgb[1], 100 * m->rel_rms_rgb[2], m->frame_ms,
                                 m->setup_ms);
        }
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
                             "reference_spp,reference_noise,rel_rms_net\n");
    for (int i = 0; i < count; i++)
        for (int k = 0; k < scenes[i].method_count; k++) {
            const lucent_compare_method *m = &scenes[i].methods[k];
            csv_field(&b, scenes[i].name);
            lucent_strbuf_printf(&b, ",");
            csv_field(&b, m->name);
            lucent_strbuf_printf(&b, ",%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%.6g,%.6g\n", m->rel_rms, m->rel_rms_rgb[0],
                                 m->rel_rms_rgb[1], m->rel_rms_rgb[2], m->frame_ms, m->setup_ms,
                                 scenes[i].reference_spp, scenes[i].reference_noise,
                                 lucent_compare_net_error(m->rel_rms, scenes[i].reference_noise));
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
    lucent_plot_series *series = calloc((size_t)(n > 0 ? n : 1), sizeof *series);
    double *xy = calloc(2 * (size_t)(n > 0 ? n : 1), sizeof *xy);
    if (!series || !xy) {
        free(series), free(xy);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    }
    for (int i = 0; i < n; i++) {
        xy[2 * i] = sc->methods[i].frame_ms, xy[2 * i + 1] = 100 * sc->methods[i].rel_rms;
        series[i] = (lucent_plot_series){
            .label = sc->methods[i].name, .x = &xy[2 * i], .y = &xy[2 * i + 1], .count = 1, .markers = true};
    }
    char title[160];
    snprintf(title, sizeof title, "%s: error against the reference and frame time", sc->name);
    lucent_plot_panel panel = {.title = title,
                               .x_label = "frame time (ms, GPU)",
                               .y_label = "relative RMS error (%)",
                               .series = series,
                               .series_count = n};
    lucent_status s = lucent_plot_write_svg(
        path, &(lucent_plot_desc){.panels = &panel, .panel_count = 1, .panel_width = 640, .panel_height = 400});
    free(series), free(xy);
    return s;
}
