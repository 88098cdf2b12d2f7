/* Tests of src/report: SVG charts and the comparison report (HTML, Markdown, CSV). */
#include <math.h>

#include "lucent/report.h"
#include "test.h"

static int count_of(const char *text, const char *needle)
{
    int n = 0;
    for (const char *p = strstr(text, needle); p; p = strstr(p + 1, needle)) n++;
    return n;
}

TEST(nice_ticks_are_1_2_5_steps)
{
    double t[8];
    int n = lucent_plot_nice_ticks(0, 1, 6, t); /* range 1 over 5 gaps: step 0.2 */
    CHECK(n == 6);
    CHECK_NEAR(t[1] - t[0], 0.2, 1e-12);
    CHECK_NEAR(t[5], 1.0, 1e-12);
    n = lucent_plot_nice_ticks(-3, 7.5, 7, t); /* 10.5 over 6 gaps = 1.75 -> step 2 */
    CHECK(n == 5);
    CHECK(t[0] == -2 && t[4] == 6);
    CHECK(lucent_plot_nice_ticks(1, 1, 6, t) == 0);
}

TEST(svg_has_a_curve_per_series_and_log_decades)
{
    enum { N = 50 };
    double x[N], y[N], z[N], e[N];
    for (int i = 0; i < N; i++) {
        x[i] = 0.1 * (i + 1);
        y[i] = exp(-x[i]) / x[i];         /* spans about 2.5 decades */
        z[i] = i == 20 ? -1 : y[i] * 0.5; /* one point that a log axis cannot show */
        e[i] = 0.1 * y[i];
    }
    lucent_plot_series series[2] = {{.label = "R <red> & co", .x = x, .y = y, .err = e, .count = N},
                                    {.label = "half", .x = x, .y = z, .count = N, .dashed = true}};
    lucent_plot_panel panels[2] = {
        {.title = "linear", .x_label = "r (mm)", .series = series, .series_count = 2, .x_max = 1, .x_min = 0},
        {.title = "log", .log_y = true, .series = series, .series_count = 2}};
    lucent_plot_desc d = {.title = "Profile", .panels = panels, .panel_count = 2};
    char *svg;
    CHECK_OK(lucent_plot_svg(&d, &svg));
    CHECK(strncmp(svg, "<?xml", 5) == 0 && strstr(svg, "</svg>\n"));
    CHECK(strstr(svg, "R &lt;red&gt; &amp; co") != NULL); /* labels are escaped */
    CHECK(!strstr(svg, "<red>"));
    /* Panel 1 draws the dashed series whole (its negative point is a valid linear value) but
     * only x <= 1; panel 2 breaks it at the negative point: 1 + 1 + 1 + 2 polylines. */
    CHECK_MSG(count_of(svg, "<polyline") == 5, "%d polylines", count_of(svg, "<polyline"));
    CHECK(count_of(svg, "<polygon") == 2); /* one error band per panel */
    /* y from min 0.5*e^-5/5 = 6.7e-4 to e^-0.1/0.1 = 9.05: decades 10^-4 .. 10^1 */
    CHECK(strstr(svg, ">-4</tspan>") && strstr(svg, ">1</tspan>"));
    CHECK(!strstr(svg, ">-5</tspan>") && !strstr(svg, ">2</tspan>"));
    CHECK(!strstr(svg, "nan") && !strstr(svg, "inf"));
    free(svg);
    CHECK_OK(lucent_plot_write_svg(test_path("p.svg"), &d));
    CHECK_ERR(lucent_plot_write_svg(test_path("none/p.svg"), &d), LUCENT_ERR_IO, "none/p.svg");
}

TEST(svg_rejects_empty_figures)
{
    char *svg;
    lucent_plot_desc d = {0};
    CHECK_ERR(lucent_plot_svg(&d, &svg), LUCENT_ERR_INVALID_ARGUMENT, "no panels");
    lucent_plot_series s = {.count = 3};
    lucent_plot_panel p = {.series = &s, .series_count = 1};
    d = (lucent_plot_desc){.panels = &p, .panel_count = 1};
    CHECK_ERR(lucent_plot_svg(&d, &svg), LUCENT_ERR_INVALID_ARGUMENT, "panel 0, series 0: no data");
    p.series_count = 0; /* axes alone are fine */
    CHECK_OK(lucent_plot_svg(&d, &svg));
    free(svg);
}

/* Two scenes with two methods each; one name needs escaping. The first scene's errors, net of its
 * 1% noise: lambert sqrt(25^2 - 1) = 24.98%, ssss 4.90%; the second's: cdrf 12.46%, x<y 49.99%. */
static const lucent_compare_method k_methods[2][2] = {
    {{"lambert",
      "a/lambert.png",
      "a/lambert-err.png",
      0.25,
      {0.3, 0.2, 0.1},
      1.5,
      10,
      "Blinn-Phong",
      NULL,
      {0},
      false,
      0,
      NULL,
      false,
      0},
     {"ssss:preint",
      "a/ssss.png",
      "a/ssss-err.png",
      0.05,
      {0.06, 0.05, 0.04},
      2.25,
      300,
      "17 taps",
      "a/ssss-worst.png",
      {8, 4, 16},
      false,
      0,
      NULL,
      true,
      0.25}},
    {{"cdrf",
      "b/cdrf.png",
      "b/cdrf-err.png",
      0.125,
      {0.1, 0.1, 0.2},
      1.75,
      900,
      "LUT",
      NULL,
      {0},
      false,
      0,
      NULL,
      false,
      0},
     {"x<y&\"z\"", "b/x.png", "b/x-err.png", 0.5, {0.5, 0.5, 0.5}, 3, 1, "a, b", NULL, {0}, false, 0, NULL, false, 0}}};

static void make_scenes(lucent_compare_scene sc[2])
{
    for (int i = 0; i < 2; i++)
        sc[i] = (lucent_compare_scene){.name = i ? "bunny" : "dragon",
                                       .description = "test",
                                       .width = 64,
                                       .height = 32,
                                       .reference_image = i ? "b/ref.png" : "a/ref.png",
                                       .reference_spp = 256,
                                       .reference_seconds = 12.5,
                                       .reference_noise = 0.01,
                                       .device = "llvmpipe",
                                       .scene_json = "{\"camera\": {}}",
                                       .methods = k_methods[i],
                                       .method_count = 2};
}

TEST(compare_html_has_every_scene_method_and_image)
{
    lucent_compare_scene sc[2];
    make_scenes(sc);
    sc[0].error_scale_image = "error-scale.png";
    const char *path = test_path("report.html");
    CHECK_OK(lucent_compare_write_html(path, "Lucent <test>", sc, 2));
    char *html;
    size_t size;
    CHECK_OK(lucent_read_file(path, &html, &size));
    if (!html) return;
    CHECK(strstr(html, "<title>Lucent &lt;test&gt;</title>") != NULL);
    CHECK(count_of(html, "<section id=") == 2);
    /* the summary (a header, the noise and spread rows, a row per method name) and per scene a header and
     * two rows */
    CHECK(count_of(html, "<tr") == (3 + 4) + 2 * 3);
    CHECK(strstr(html, "Summary across scenes") < strstr(html, "<section id="));
    CHECK(count_of(html, "class=\"best\"") == 2);
    /* the ranked table: ssss:preint (5% < 25%) first, bold, rank 1 */
    const char *best = strstr(html, "class=\"best\"");
    static const char want[] = "class=\"best\"><td>1</td><td>ssss:preint<";
    CHECK(best && strncmp(best, want, strlen(want)) == 0);
    CHECK(strstr(html, "x&lt;y&amp;&quot;z&quot;") != NULL && strstr(html, "x<y") == NULL);
    /* reference, methods, error maps (each also a link), the colour bar, one crop */
    CHECK(count_of(html, "<img src=") == 2 * (1 + 2 + 2) + 1 + 1);
    CHECK(count_of(html, "<a href=\"a/") == 1 + 2 + 2 + 1);
    CHECK(strstr(html, "<img src=\"a/ref.png\" width=\"64\" height=\"32\"") != NULL); /* native size */
    /* net: sqrt(5^2 - 1^2); the worst 1% column where a method has it (ssss:preint 0.25), a dash elsewhere */
    CHECK(strstr(html, "<td>5.00%</td><td>4.90%</td><td>25.0%</td><td>6.00%</td>") != NULL);
    CHECK(strstr(html, "<th>worst 1% of pixels' share</th>") != NULL && strstr(html, "<td>&ndash;</td><td>") != NULL);
    CHECK(strstr(html, "<td>1.500</td><td>1.00x</td>") != NULL && strstr(html, "<td>2.250</td><td>1.50x</td>"));
    CHECK(strstr(html, "256 samples per pixel in 12.5 s") != NULL);
    CHECK(strstr(html, "full at 50%") != NULL && strstr(html, "too dark") != NULL);
    CHECK(strstr(html, "Warning") == NULL);
    free(html);
}

/* Errors within the noise of each other share a rank: with 3% noise, nets 4.00% (5% raw) and 6.71%
 * (7.35% raw: sqrt(7.35^2 - 9) = 6.71) differ by 2.71 < 3, so both are rank 1, tied; a third at 20%
 * (net 19.77%) is rank 3. */
TEST(compare_rank_ties_methods_within_the_noise)
{
    lucent_compare_method m[3] = {
        {.name = "c", .rel_rms = 0.20}, {.name = "a", .rel_rms = 0.05}, {.name = "b", .rel_rms = 0.0735}};
    lucent_compare_scene sc = {
        .name = "s", .reference_spp = 64, .reference_noise = 0.03, .methods = m, .method_count = 3};
    int order[3], rank[3];
    CHECK(lucent_compare_rank(&sc, order, rank));
    CHECK(order[0] == 1 && order[1] == 2 && order[2] == 0);
    CHECK(rank[1] == 1 && rank[2] == 1 && rank[0] == 3);
    sc.reference_noise = 0.02; /* 2.71 > 2: no tie */
    CHECK(lucent_compare_rank(&sc, order, rank) && rank[1] == 1 && rank[2] == 2 && rank[0] == 3);
    sc.reference_spp = LUCENT_COMPARE_MIN_SPP - 1; /* too few samples: no ranking */
    CHECK(!lucent_compare_rank(&sc, order, rank) && rank[0] == 0 && rank[1] == 0 && order[0] == 0);
    CHECK(!lucent_compare_noise_known(&sc));
}

/* A 1-spp reference: its variance cannot be estimated, so the noise is unknown, nothing is ranked or
 * bolded, and every report says so. */
TEST(compare_reports_of_a_one_spp_reference_warn_and_rank_nothing)
{
    lucent_compare_scene sc[2];
    make_scenes(sc);
    sc[0].reference_spp = 1, sc[0].reference_noise = NAN;
    const char *path = test_path("report1.html");
    CHECK_OK(lucent_compare_write_html(path, "one spp", sc, 2));
    char *text;
    size_t size;
    CHECK_OK(lucent_read_file(path, &text, &size));
    if (text) {
        CHECK(count_of(text, "class=\"warn\"") == 2); /* at the head and in the scene */
        CHECK(strstr(text, "the reference has 1 sample per pixel, fewer than the 8") != NULL);
        CHECK(count_of(text, "class=\"best\"") == 1); /* the other scene only */
        CHECK(strstr(text, "object is unknown,") != NULL);
        CHECK(strstr(text, ">0.00%") == NULL && strstr(text, " 0.00%") == NULL); /* no zero noise claimed */
        free(text);
    }
    const char *md = test_path("report1.md");
    CHECK_OK(lucent_compare_write_markdown(md, sc, 2));
    CHECK_OK(lucent_read_file(md, &text, &size));
    if (text) {
        CHECK(strstr(text, "(noise unknown)") != NULL && strstr(text, "**Warning:**") != NULL);
        CHECK(strstr(text, "| - | lambert | 25.00% | unknown |") != NULL);
        free(text);
    }
    const char *csv = test_path("report1.csv");
    CHECK_OK(lucent_compare_write_csv(csv, sc, 2));
    CHECK_OK(lucent_read_file(csv, &text, &size));
    if (text) {
        CHECK(strstr(text, "\"dragon\",\"lambert\",0.25,0.3,0.2,0.1,1.5,10,1,,,,1\n") != NULL);
        free(text);
    }
}

TEST(compare_markdown_and_csv_tables)
{
    lucent_compare_scene sc[2];
    make_scenes(sc);
    const char *md = test_path("report.md");
    CHECK_OK(lucent_compare_write_markdown(md, sc, 2));
    char *text;
    size_t size;
    CHECK_OK(lucent_read_file(md, &text, &size));
    if (text) {
        CHECK(count_of(text, "\n## ") + (strncmp(text, "## ", 3) == 0) == 2);
        /* net of noise: sqrt(0.125^2 - 0.01^2) = 12.46%; ranked first, bold */
        CHECK(strstr(text, "| 1 | **cdrf** | 12.50% | 12.46% | 10.00% | 10.00% | 20.00% | 1.750 | - | 900 |") != NULL);
        /* the first scene's ssss:preint has its worst 1% share (0.25), lambert a dash */
        CHECK(strstr(text, "| 900 |\n") != NULL && strstr(text, " worst 1% |\n") != NULL &&
              strstr(text, " 25.0% |\n") != NULL && strstr(text, " - |\n") != NULL);
        free(text);
    }
    const char *csv = test_path("report.csv");
    CHECK_OK(lucent_compare_write_csv(csv, sc, 2));
    CHECK_OK(lucent_read_file(csv, &text, &size));
    if (!text) return;
    CHECK(count_of(text, "\n") == 1 + 4);
    CHECK(strstr(text, "\"dragon\",\"lambert\",0.25,0.3,0.2,0.1,1.5,10,256,0.01,0.2498,2,1\n") != NULL);
    CHECK(strstr(text, "\"x<y&\"\"z\"\"\"") != NULL); /* quotes doubled */
    free(text);
}

/* The reference's noise adds in quadrature to a method's distance from the truth: a 3-4-5 triangle
 * (error 5%, noise 3% -> 4%), no noise (unchanged), and an error within the noise (0, not NaN). */
TEST(net_error_takes_the_noise_out_in_quadrature)
{
    CHECK_NEAR(lucent_compare_net_error(0.05, 0.03), 0.04, 1e-15);
    CHECK_NEAR(lucent_compare_net_error(0.2, 0), 0.2, 0);
    CHECK(lucent_compare_net_error(0.02, 0.03) == 0);
}

TEST(compare_chart_has_a_marker_per_method)
{
    lucent_compare_scene sc[2];
    make_scenes(sc);
    const char *path = test_path("chart.svg");
    CHECK_OK(lucent_compare_write_chart(path, &sc[0]));
    char *svg;
    size_t size;
    CHECK_OK(lucent_read_file(path, &svg, &size));
    if (!svg) return;
    /* two methods: two shapes (a square and a triangle, in the data and the legend), their labels at the
     * points and in the legend, the noise band and its legend entry */
    CHECK(count_of(svg, "<rect x=") >= 2 + 2);
    CHECK(count_of(svg, ">ssss:preint<") == 2 && count_of(svg, ">lambert<") == 2);
    CHECK(strstr(svg, "reference noise (1.00%)") != NULL && strstr(svg, "fill-opacity=\"0.25\"") != NULL);
    CHECK(strstr(svg, "net of the reference") != NULL);
    free(svg);
}

/* ---- the error-against-time chart ---- */

typedef struct pt {
    double x, y;
} pt;

/* The centres of the data markers: the shapes drawn inside the clipped group (squares, triangles,
 * diamonds, stars as polygons or rects, crosses as paths); the centre of a polygon is the mean of its
 * vertices (a triangle's is 0.1 of its size off the point, well inside its 9 px). */
static int marker_centres(const char *svg, pt *dest, int max)
{
    const char *g = strstr(svg, "<g clip-path"), *end = g ? strstr(g, "</g>") : NULL;
    int n = 0;
    for (const char *p = g; p && p < end && n < max; p++) {
        double x, y, w;
        if (sscanf(p, "<rect x=\"%lf\" y=\"%lf\" width=\"%lf\"", &x, &y, &w) == 3 && w < 10) {
            dest[n++] = (pt){x + w / 2, y + w / 2};
        } else if (!strncmp(p, "<polygon points=\"", 17) || !strncmp(p, "<path d=\"M", 10)) {
            const char *q = p + (p[1] == 'p' && p[2] == 'o' ? 17 : 10);
            double sx = 0, sy = 0;
            int k = 0;
            while (k < 12 && sscanf(q, "%lf%*[, ]%lf", &x, &y) == 2) {
                sx += x, sy += y, k++;
                while (*q && *q != ' ' && *q != 'L' && *q != 'M' && *q != '"') q++;
                if (*q == ' ' || *q == 'L' || *q == 'M') q++;
                if (*q == '"') break;
                while (*q && *q != ' ' && *q != 'L' && *q != 'M' && *q != '"') q++;
                if (*q == '"') break;
                q++;
            }
            if (k) dest[n++] = (pt){sx / k, sy / k};
        }
    }
    return n;
}

/* Eleven methods as compare runs them on llvmpipe, six of them within a few percent and 0.2 ms of each
 * other, two a thousand times slower: the time axis is logarithmic (whole decades from 0.1 to 100000
 * ms), every label (at the points and in the legend) lies clear of every other and of every data
 * marker, and the legend covers no marker. Text boxes as the plots measure them (7 px a character,
 * 14 px high). */
TEST(compare_chart_has_a_log_time_axis_and_labels_apart)
{
    static const char *names[11] = {"lambert",   "cdrf",        "cdrf+translucency", "ssss:preint",  "ssss:svd1",
                                    "ssss:svd3", "ssss:guided", "ssss:manual",       "ssss:jimenez", "tsd",
                                    "points"};
    static const double ms[11] = {0.4, 0.45, 0.46, 0.9, 0.85, 0.95, 0.92, 0.88, 0.9, 33000, 13000};
    static const double err[11] = {0.36, 0.20, 0.205, 0.203, 0.208, 0.201, 0.204, 0.22, 0.21, 0.19, 0.25};
    lucent_compare_method m[11];
    for (int i = 0; i < 11; i++) m[i] = (lucent_compare_method){.name = names[i], .rel_rms = err[i], .frame_ms = ms[i]};
    lucent_compare_scene sc = {
        .name = "bunny", .reference_spp = 256, .reference_noise = 0.05, .methods = m, .method_count = 11};
    const char *path = test_path("chart-log.svg");
    CHECK_OK(lucent_compare_write_chart(path, &sc));
    char *svg;
    size_t size;
    CHECK_OK(lucent_read_file(path, &svg, &size));
    if (!svg) return;
    for (int e = -1; e <= 5; e++) { /* a labelled tick per decade */
        char want[64];
        snprintf(want, sizeof want, "text-anchor=\"middle\">%g</text>", pow(10, e));
        CHECK_MSG(strstr(svg, want) != NULL, "no tick %s", want);
    }
    CHECK(strstr(svg, "logarithmic") != NULL);
    pt markers[64];
    int nm = marker_centres(svg, markers, 64);
    CHECK_MSG(nm == 11, "%d markers", nm);
    const char *legend = strstr(svg, "fill-opacity=\"0.85\"");
    double lx = 0, ly = 0, lw = 0, lh = 0;
    while (legend && legend > svg && strncmp(legend, "<rect", 5)) legend--;
    CHECK(legend && sscanf(legend, "<rect x=\"%lf\" y=\"%lf\" width=\"%lf\" height=\"%lf\"", &lx, &ly, &lw, &lh) == 4);
    for (int i = 0; i < nm; i++)
        CHECK_MSG(!(markers[i].x > lx && markers[i].x < lx + lw && markers[i].y > ly && markers[i].y < ly + lh),
                  "the legend covers a marker at (%g, %g)", markers[i].x, markers[i].y);
    /* every start-anchored text after the data: the legend's and the points' labels */
    double box[64][4];
    int nb = 0;
    for (const char *p = strstr(svg, "</g>"); p && (p = strstr(p, "<text x=\"")) && nb < 64; p++) {
        double x, y;
        char anchor[16], text[64];
        if (sscanf(p, "<text x=\"%lf\" y=\"%lf\" text-anchor=\"%15[a-z]\">%63[^<]", &x, &y, anchor, text) != 4 ||
            strcmp(anchor, "start"))
            continue;
        box[nb][0] = x, box[nb][1] = y - 11, box[nb][2] = x + 7.0 * strlen(text), box[nb][3] = y + 3, nb++;
    }
    CHECK_MSG(nb == 2 * 11 + 1, "%d labels", nb); /* each name twice, and the noise band's */
    int overlaps = 0, covered = 0;
    for (int i = 0; i < nb; i++) {
        for (int j = i + 1; j < nb; j++)
            overlaps +=
                box[i][0] < box[j][2] && box[j][0] < box[i][2] && box[i][1] < box[j][3] && box[j][1] < box[i][3];
        for (int k = 0; k < nm; k++)
            covered += markers[k].x > box[i][0] && markers[k].x < box[i][2] && markers[k].y > box[i][1] &&
                       markers[k].y < box[i][3];
    }
    CHECK_MSG(overlaps == 0, "%d pairs of labels overlap", overlaps);
    CHECK_MSG(covered == 0, "%d markers under a label", covered);
    free(svg);
}

/* The summary (issue 35): what a tie means said once, the spread per scene, the methods ranked best
 * first, bold only for a best rank that is apart from some other method; no "(=1)" cells. Scene 1:
 * three methods the paired test separates (z 10 and 20); scene 2: two it cannot (z 1). */
TEST(compare_summary_says_once_what_a_tie_is_and_puts_the_distinguishable_first)
{
    lucent_compare_method m1[3] = {
        {.name = "lambert", .rel_rms = 0.30}, {.name = "svd3", .rel_rms = 0.12}, {.name = "cdrf", .rel_rms = 0.20}};
    lucent_compare_method m2[2] = {{.name = "lambert", .rel_rms = 0.105}, {.name = "svd3", .rel_rms = 0.10}};
    /* se of e_i^2 - e_j^2 chosen for z: svd3-cdrf (0.0144 - 0.04) / se = -10, cdrf-lambert -20 */
    double se1[9] = {0, 0.0756 / 20, 0.05 / 20, 0.0756 / 20, 0, 0.0256 / 10, 0.05 / 20, 0.0256 / 10, 0};
    double se2[4] = {0, 0.001025, 0.001025, 0};
    lucent_compare_scene sc[2] = {
        {.name = "one", .reference_spp = 64, .reference_noise = 0.01, .methods = m1, .method_count = 3, .pair_se = se1},
        {.name = "two",
         .reference_spp = 64,
         .reference_noise = 0.01,
         .methods = m2,
         .method_count = 2,
         .pair_se = se2}};
    const char *path = test_path("summary.html");
    CHECK_OK(lucent_compare_write_html(path, "summary", sc, 2));
    char *html;
    size_t size;
    CHECK_OK(lucent_read_file(path, &html, &size));
    if (!html) return;
    const char *sum = strstr(html, "Summary across scenes"), *end = sum ? strstr(sum, "</table>") : NULL;
    CHECK(sum && end);
    if (!sum || !end) return;
    CHECK(count_of(sum, "cannot be told apart") >= 1 && strstr(sum, "(=") == NULL);
    const char *svd3 = strstr(sum, "<tr><td>svd3"), *cdrf = strstr(sum, "<tr><td>cdrf"),
               *lambert = strstr(sum, "<tr><td>lambert");
    /* mean ranks: svd3 1, lambert (3 + 1) / 2 = 2, cdrf 2; then the mean net error: cdrf 19.97%, lambert
     * (29.98 + 10.45) / 2 = 20.22% */
    CHECK(svd3 && cdrf && lambert && svd3 < cdrf && cdrf < lambert);
    /* scene one's spread: net sqrt(0.12^2 - 0.01^2) = 11.96% to sqrt(0.3^2 - 0.01^2) = 29.98%, 3 ranks */
    CHECK(strstr(sum, "<td>11.96% to 29.98% (3)</td>") != NULL);
    CHECK(strstr(sum, "<td><b>11.96% (1)</b></td>") != NULL); /* svd3 in one: apart from the rest */
    CHECK(strstr(sum, "<td>9.95% (1)</td>") != NULL);         /* svd3 in two: tied, not bold */
    CHECK(strstr(sum, "<td>10.45% (1)</td>") != NULL);        /* lambert in two: the same rank */
    free(html);
}

TEST_MAIN(TEST_ENTRY(nice_ticks_are_1_2_5_steps), TEST_ENTRY(svg_has_a_curve_per_series_and_log_decades),
          TEST_ENTRY(svg_rejects_empty_figures), TEST_ENTRY(compare_html_has_every_scene_method_and_image),
          TEST_ENTRY(compare_markdown_and_csv_tables), TEST_ENTRY(compare_rank_ties_methods_within_the_noise),
          TEST_ENTRY(compare_reports_of_a_one_spp_reference_warn_and_rank_nothing),
          TEST_ENTRY(net_error_takes_the_noise_out_in_quadrature), TEST_ENTRY(compare_chart_has_a_marker_per_method),
          TEST_ENTRY(compare_chart_has_a_log_time_axis_and_labels_apart),
          TEST_ENTRY(compare_summary_says_once_what_a_tie_is_and_puts_the_distinguishable_first))
