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

/* Two scenes with two methods each; one name needs escaping. */
static const lucent_compare_method k_methods[2][2] = {
    {{"lambert", "a/lambert.png", "a/lambert-err.png", 0.25, {0.3, 0.2, 0.1}, 1.5, 10, "Blinn-Phong"},
     {"ssss:preint", "a/ssss.png", "a/ssss-err.png", 0.05, {0.06, 0.05, 0.04}, 2.25, 300, "17 taps"}},
    {{"cdrf", "b/cdrf.png", "b/cdrf-err.png", 0.125, {0.1, 0.1, 0.2}, 1.75, 900, "LUT"},
     {"x<y&\"z\"", "b/x.png", "b/x-err.png", 0.5, {0.5, 0.5, 0.5}, 3, 1, "a, b"}}};

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
    const char *path = test_path("report.html");
    CHECK_OK(lucent_compare_write_html(path, "Lucent <test>", sc, 2));
    char *html;
    size_t size;
    CHECK_OK(lucent_read_file(path, &html, &size));
    if (!html) return;
    CHECK(strstr(html, "<title>Lucent &lt;test&gt;</title>") != NULL);
    CHECK(count_of(html, "<section id=") == 2);
    CHECK(count_of(html, "<tr") == 2 * 3); /* a header row and two method rows per scene */
    CHECK(count_of(html, "class=\"best\"") == 2);
    /* the best row of the first scene is ssss:preint (5% < 25%) */
    const char *best = strstr(html, "class=\"best\"");
    static const char want[] = "class=\"best\"><td>ssss:preint<";
    CHECK(best && strncmp(best, want, strlen(want)) == 0);
    CHECK(strstr(html, "x&lt;y&amp;&quot;z&quot;") != NULL && strstr(html, "x<y") == NULL);
    CHECK(count_of(html, "<img src=") == 2 * (1 + 2 + 2));                     /* reference, methods, error maps */
    CHECK(strstr(html, "<td>5.00%</td><td>4.90%</td><td>6.00%</td>") != NULL); /* net: sqrt(5^2 - 1^2) */
    CHECK(strstr(html, "256 samples per pixel in 12.5 s") != NULL);
    free(html);
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
        /* net of noise: sqrt(0.125^2 - 0.01^2) = 12.46% */
        CHECK(strstr(text, "| cdrf | 12.50% | 12.46% | 10.00% | 10.00% | 20.00% | 1.750 | 900 |") != NULL);
        free(text);
    }
    const char *csv = test_path("report.csv");
    CHECK_OK(lucent_compare_write_csv(csv, sc, 2));
    CHECK_OK(lucent_read_file(csv, &text, &size));
    if (!text) return;
    CHECK(count_of(text, "\n") == 1 + 4);
    CHECK(strstr(text, "\"dragon\",\"lambert\",0.25,0.3,0.2,0.1,1.5,10,256,0.01,0.2498\n") != NULL);
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
    CHECK(count_of(svg, "<circle") >= 2);
    CHECK(strstr(svg, "ssss:preint") != NULL);
    free(svg);
}

TEST_MAIN(TEST_ENTRY(nice_ticks_are_1_2_5_steps), TEST_ENTRY(svg_has_a_curve_per_series_and_log_decades),
          TEST_ENTRY(svg_rejects_empty_figures), TEST_ENTRY(compare_html_has_every_scene_method_and_image),
          TEST_ENTRY(compare_markdown_and_csv_tables), TEST_ENTRY(net_error_takes_the_noise_out_in_quadrature),
          TEST_ENTRY(compare_chart_has_a_marker_per_method))
