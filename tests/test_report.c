/* Tests of src/report: SVG charts. */
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
        y[i] = exp(-x[i]) / x[i];  /* spans about 2.5 decades */
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

TEST_MAIN(TEST_ENTRY(nice_ticks_are_1_2_5_steps), TEST_ENTRY(svg_has_a_curve_per_series_and_log_decades),
          TEST_ENTRY(svg_rejects_empty_figures))
