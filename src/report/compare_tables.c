/* The comparison report's further tables: the run's provenance, each method's error per region of
 * the image, and per light alone; as HTML and as Markdown. */
#include <math.h>
#include <stdio.h>

#include "report/compare_internal.h"

static const char *text_or(const char *s, const char *fallback) { return s && *s ? s : fallback; }

void report_html_provenance(lucent_strbuf *b, const lucent_compare_provenance *p)
{
    if (!p) return;
    lucent_strbuf_printf(b, "<p class=\"note\" id=\"provenance\">Made by Lucent ");
    lucent_strbuf_xml(b, text_or(p->version, "unknown"));
    lucent_strbuf_printf(b, " (revision ");
    lucent_strbuf_xml(b, text_or(p->revision, "unknown"));
    lucent_strbuf_printf(b, ") on ");
    lucent_strbuf_xml(b, text_or(p->date, "an unknown date"));
    lucent_strbuf_printf(b, "; machine: ");
    lucent_strbuf_xml(b, text_or(p->machine, "unknown"));
    lucent_strbuf_printf(b, ", %d cores; GL renderer: ", p->cores);
    lucent_strbuf_xml(b, text_or(p->renderer, "unknown"));
    lucent_strbuf_printf(b, ".<br>Command: <code>");
    lucent_strbuf_xml(b, text_or(p->command, "(not recorded)"));
    lucent_strbuf_printf(b, "</code></p>\n");
}

void report_md_provenance(lucent_strbuf *b, const lucent_compare_provenance *p)
{
    if (!p) return;
    lucent_strbuf_printf(b,
                         "Made by Lucent %s (revision %s) on %s; machine: %s, %d cores; GL renderer: %s.\n\n"
                         "Command: `%s`\n\n",
                         text_or(p->version, "unknown"), text_or(p->revision, "unknown"),
                         text_or(p->date, "an unknown date"), text_or(p->machine, "unknown"), p->cores,
                         text_or(p->renderer, "unknown"), text_or(p->command, "(not recorded)"));
}

static void html_pct(lucent_strbuf *b, double v)
{
    if (isfinite(v))
        lucent_strbuf_printf(b, "<td>%.1f%%</td>", 100 * v);
    else
        lucent_strbuf_printf(b, "<td>&ndash;</td>");
}

/* A header cell per method: its name, then what its cells hold; the row's end. */
static void html_method_headers(lucent_strbuf *b, const lucent_compare_scene *sc, const char *holds)
{
    for (int m = 0; m < sc->method_count; m++) {
        lucent_strbuf_printf(b, "<th>");
        lucent_strbuf_xml(b, sc->methods[m].name);
        lucent_strbuf_printf(b, ": %s</th>", holds);
    }
    lucent_strbuf_printf(b, "</tr>\n");
}

/* One table: a row per region, per method its error and its brightness against the reference. */
static void html_region_table(lucent_strbuf *b, const lucent_compare_scene *sc, const lucent_compare_region *regions,
                              int count)
{
    lucent_strbuf_printf(b, "<table><tr><th>region</th><th>pixels</th><th>share of the reference</th>"
                            "<th>reference noise</th>");
    html_method_headers(b, sc, "error, m / r, share");
    for (int r = 0; r < count; r++) {
        const lucent_compare_region *g = &regions[r];
        lucent_strbuf_printf(b, "<tr><td>");
        lucent_strbuf_xml(b, g->name);
        lucent_strbuf_printf(b, "</td><td>%llu</td>", (unsigned long long)g->pixels);
        html_pct(b, g->energy);
        html_pct(b, g->reference_noise);
        for (int m = 0; m < sc->method_count; m++) {
            if (!g->pixels || !isfinite(g->rel_rms[m]) || !isfinite(g->ratio[m])) {
                lucent_strbuf_printf(b, "<td>&ndash;</td>");
                continue;
            }
            lucent_strbuf_printf(b, "<td>%.1f%%, %.2f, %.0f%%</td>", 100 * g->rel_rms[m], g->ratio[m],
                                 100 * g->error_share[m]);
        }
        lucent_strbuf_printf(b, "</tr>\n");
    }
    lucent_strbuf_printf(b, "</table>\n");
}

void report_html_regions(lucent_strbuf *b, const lucent_compare_scene *sc)
{
    if (!sc->regions || sc->region_count <= 0) return;
    lucent_strbuf_printf(b, "<h3>Each method's error by region</h3>\n<p class=\"note\">Regions of the object's "
                            "pixels, from the surface seen through each pixel's centre (they overlap): lit (some "
                            "light within 75 degrees of the normal, unoccluded), terminator (the normal 75 to 105 "
                            "degrees from a light, none lit), attached shadow (every light beyond 105 degrees), cast "
                            "shadow (a light within 75 degrees but occluded, none lit), grazing view (the normal "
                            "beyond 75 degrees from the view), convex (mean curvature radius of 20 mm or less), "
                            "silhouette band (within 3 pixels of the object's outline). Per method: the relative RMS "
                            "error over the region, its brightness against the reference (sum m / sum r), and the "
                            "region's share of the method's squared error.</p>\n");
    html_region_table(b, sc, sc->regions, sc->region_count);
}

void report_html_lights(lucent_strbuf *b, const lucent_compare_scene *sc)
{
    if (!sc->lights || sc->light_count <= 0) return;
    lucent_strbuf_printf(b, "<h3>Each light alone</h3>\n<p class=\"note\">Rendering is linear in the lights: the "
                            "reference and every method again with one light on, the others off. Per light its "
                            "reference's samples and noise, per method the relative RMS error and the brightness "
                            "against the reference.</p>\n<table><tr><th>light</th><th>reference spp</th>"
                            "<th>reference noise</th>");
    html_method_headers(b, sc, "error, m / r");
    for (int l = 0; l < sc->light_count; l++) {
        const lucent_compare_light *li = &sc->lights[l];
        lucent_strbuf_printf(b, "<tr><td>");
        lucent_strbuf_xml(b, li->name);
        lucent_strbuf_printf(b, "</td><td>%d</td>", li->reference_spp);
        html_pct(b, li->reference_noise);
        for (int m = 0; m < sc->method_count; m++) {
            if (isfinite(li->rel_rms[m]) && isfinite(li->ratio[m]))
                lucent_strbuf_printf(b, "<td>%.1f%%, %.2f</td>", 100 * li->rel_rms[m], li->ratio[m]);
            else
                lucent_strbuf_printf(b, "<td>&ndash;</td>");
        }
        lucent_strbuf_printf(b, "</tr>\n");
    }
    lucent_strbuf_printf(b, "</table>\n");
    for (int l = 0; l < sc->light_count; l++) {
        if (!sc->lights[l].regions || sc->lights[l].region_count <= 0) continue;
        lucent_strbuf_printf(b, "<details><summary>");
        lucent_strbuf_xml(b, sc->lights[l].name);
        lucent_strbuf_printf(b, " alone, by region</summary>\n");
        html_region_table(b, sc, sc->lights[l].regions, sc->lights[l].region_count);
        lucent_strbuf_printf(b, "</details>\n");
    }
}

static void md_region_table(lucent_strbuf *b, const lucent_compare_scene *sc, const lucent_compare_region *regions,
                            int count)
{
    lucent_strbuf_printf(b, "| region | pixels | share | noise |");
    for (int m = 0; m < sc->method_count; m++) lucent_strbuf_printf(b, " %s |", sc->methods[m].name);
    lucent_strbuf_printf(b, "\n|---|---|---|---|");
    for (int m = 0; m < sc->method_count; m++) lucent_strbuf_printf(b, "---|");
    lucent_strbuf_printf(b, "\n");
    for (int r = 0; r < count; r++) {
        const lucent_compare_region *g = &regions[r];
        char energy[24] = "-", noise[24] = "-";
        if (isfinite(g->energy)) snprintf(energy, sizeof energy, "%.1f%%", 100 * g->energy);
        if (isfinite(g->reference_noise)) snprintf(noise, sizeof noise, "%.1f%%", 100 * g->reference_noise);
        lucent_strbuf_printf(b, "| %s | %llu | %s | %s |", g->name, (unsigned long long)g->pixels, energy, noise);
        for (int m = 0; m < sc->method_count; m++) {
            if (g->pixels && isfinite(g->rel_rms[m]) && isfinite(g->ratio[m]))
                lucent_strbuf_printf(b, " %.1f%%, %.2f, %.0f%% |", 100 * g->rel_rms[m], g->ratio[m],
                                     100 * g->error_share[m]);
            else
                lucent_strbuf_printf(b, " - |");
        }
        lucent_strbuf_printf(b, "\n");
    }
}

void report_md_regions(lucent_strbuf *b, const lucent_compare_scene *sc)
{
    if (!sc->regions || sc->region_count <= 0) return;
    lucent_strbuf_printf(b, "\nBy region (per method: relative RMS error, sum m / sum r, share of its squared "
                            "error):\n\n");
    md_region_table(b, sc, sc->regions, sc->region_count);
}

void report_md_lights(lucent_strbuf *b, const lucent_compare_scene *sc)
{
    if (!sc->lights || sc->light_count <= 0) return;
    lucent_strbuf_printf(b, "\nEach light alone (per method: relative RMS error, sum m / sum r):\n\n| light | spp | "
                            "noise |");
    for (int m = 0; m < sc->method_count; m++) lucent_strbuf_printf(b, " %s |", sc->methods[m].name);
    lucent_strbuf_printf(b, "\n|---|---|---|");
    for (int m = 0; m < sc->method_count; m++) lucent_strbuf_printf(b, "---|");
    lucent_strbuf_printf(b, "\n");
    for (int l = 0; l < sc->light_count; l++) {
        const lucent_compare_light *li = &sc->lights[l];
        char noise[24] = "unknown";
        if (isfinite(li->reference_noise)) snprintf(noise, sizeof noise, "%.1f%%", 100 * li->reference_noise);
        lucent_strbuf_printf(b, "| %s | %d | %s |", li->name, li->reference_spp, noise);
        for (int m = 0; m < sc->method_count; m++)
            if (isfinite(li->rel_rms[m]) && isfinite(li->ratio[m]))
                lucent_strbuf_printf(b, " %.1f%%, %.2f |", 100 * li->rel_rms[m], li->ratio[m]);
            else
                lucent_strbuf_printf(b, " - |");
        lucent_strbuf_printf(b, "\n");
    }
    for (int l = 0; l < sc->light_count; l++) {
        if (!sc->lights[l].regions || sc->lights[l].region_count <= 0) continue;
        lucent_strbuf_printf(b, "\n%s alone, by region:\n\n", sc->lights[l].name);
        md_region_table(b, sc, sc->lights[l].regions, sc->lights[l].region_count);
    }
}
