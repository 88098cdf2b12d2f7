/* SVG line charts: panels side by side, linear or logarithmic axes, legends placed off the data,
 * point labels placed apart, error bands. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/strbuf.h"
#include "lucent/report.h"

enum { MARGIN_LEFT = 72, MARGIN_RIGHT = 16, MARGIN_TOP = 36, MARGIN_BOTTOM = 48, MAX_TICKS = 8 };
enum { LOG_MAX_DECADES = 12 };

/* Twelve hues that stay apart (Paul Tol's bright and muted schemes, mixed; no two reds or greens). */
enum { PALETTE = 12, MARKERS = 8 };
static const char *const k_palette[PALETTE] = {"#c0392b", "#27ae60", "#2e64c8", "#8e44ad", "#d68910", "#17a5a5",
                                               "#5d6d7e", "#e377c2", "#000000", "#8c564b", "#bcbd22", "#1f3a93"};

int lucent_plot_marker_count(void) { return MARKERS; }

/* The data rectangle of one panel, in SVG pixels, and its value ranges. */
typedef struct frame {
    double left, top, width, height;
    double x0, x1, y0, y1; /* x, y in log10 units when log */
    bool log_x, log_y;
} frame;

/* A rectangle in SVG pixels. */
typedef struct box {
    double x0, y0, x1, y1;
} box;

static double overlap(box a, box b)
{
    double w = fmin(a.x1, b.x1) - fmax(a.x0, b.x0), h = fmin(a.y1, b.y1) - fmax(a.y0, b.y0);
    return w > 0 && h > 0 ? w * h : 0;
}

void lucent_plot_text_box(int n, double *width, double *height) { *width = 7.0 * (n > 0 ? n : 0), *height = 14; }

int lucent_plot_nice_ticks(double lo, double hi, int max_ticks, double *dest)
{
    if (!(hi > lo) || max_ticks < 2) return 0;
    double raw = (hi - lo) / (max_ticks - 1), mag = pow(10, floor(log10(raw)));
    double step = mag * (raw / mag <= 1 ? 1 : raw / mag <= 2 ? 2 : raw / mag <= 5 ? 5 : 10);
    int n = 0;
    for (double t = ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step && n < max_ticks; t += step)
        dest[n++] = fabs(t) < 1e-12 * step ? 0 : t;
    return n;
}

static bool usable(const lucent_plot_panel *p, double x, double y)
{
    if (!isfinite(x) || !isfinite(y) || (p->log_y && y <= 0) || (p->log_x && x <= 0)) return false;
    bool fixed_x = p->x_min != 0 || p->x_max != 0;
    return !fixed_x || (x >= p->x_min && x <= p->x_max);
}

/* Fits the ranges to the data where the panel leaves them open. */
static void fit_ranges(const lucent_plot_panel *p, frame *f)
{
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    for (int s = 0; s < p->series_count; s++)
        for (int i = 0; i < p->series[s].count; i++) {
            double x = p->series[s].x[i], y = p->series[s].y[i];
            if (!usable(p, x, y)) continue;
            xmin = fmin(xmin, x), xmax = fmax(xmax, x);
            ymin = fmin(ymin, y), ymax = fmax(ymax, y);
        }
    if (!(xmax >= xmin)) xmin = 0, xmax = 1, ymin = p->log_y ? 0.1 : 0, ymax = 1;
    if (p->band_y0 != 0 || p->band_y1 != 0) /* the band shows whole */
        ymin = fmin(ymin, fmin(p->band_y0, p->band_y1)), ymax = fmax(ymax, fmax(p->band_y0, p->band_y1));
    if (p->x_min != 0 || p->x_max != 0) {
        xmin = p->x_min, xmax = p->x_max;
    } else if (p->log_x) { /* open log x: whole decades */
        if (!(xmin > 0)) xmin = 0.1, xmax = fmax(xmax, 1);
        xmin = pow(10, floor(log10(xmin))), xmax = pow(10, ceil(log10(xmax)));
    } else if (xmax > xmin) { /* open x: widen to whole ticks */
        double t[MAX_TICKS];
        int n = lucent_plot_nice_ticks(xmin, xmax, 7, t);
        double step = n > 1 ? t[1] - t[0] : xmax - xmin;
        xmin = floor(xmin / step + 1e-9) * step, xmax = ceil(xmax / step - 1e-9) * step;
    }
    if (p->y_min != 0 || p->y_max != 0) ymin = p->y_min, ymax = p->y_max;
    if (xmax <= xmin) xmax = xmin + 1;
    f->log_y = p->log_y;
    if (p->log_y) {
        f->y1 = ceil(log10(ymax));
        f->y0 = fmax(floor(log10(fmax(ymin, 1e-300))), f->y1 - LOG_MAX_DECADES);
        if (f->y1 <= f->y0) f->y1 = f->y0 + 1;
    } else {
        double t[MAX_TICKS];
        if (ymax <= ymin) ymax = ymin + (ymin == 0 ? 1 : fabs(ymin));
        int n = lucent_plot_nice_ticks(ymin, ymax, 6, t);
        double step = n > 1 ? t[1] - t[0] : ymax - ymin;
        f->y0 = floor(ymin / step + 1e-9) * step, f->y1 = ceil(ymax / step - 1e-9) * step;
    }
    f->log_x = p->log_x;
    if (p->log_x) {
        f->x0 = log10(fmax(xmin, 1e-300)), f->x1 = log10(fmax(xmax, 1e-300));
        if (f->x1 - f->x0 > LOG_MAX_DECADES) f->x0 = f->x1 - LOG_MAX_DECADES;
        if (f->x1 <= f->x0) f->x1 = f->x0 + 1;
        return;
    }
    f->x0 = xmin, f->x1 = xmax;
}

static double px(const frame *f, double x)
{
    double v = f->log_x ? log10(x) : x;
    return f->left + (v - f->x0) / (f->x1 - f->x0) * f->width;
}

static double py(const frame *f, double y)
{
    double v = f->log_y ? log10(y) : y;
    return f->top + f->height - (v - f->y0) / (f->y1 - f->y0) * f->height;
}

static void axis_label(lucent_strbuf *b, double x, double y, const char *anchor, double rotate, const char *text)
{
    lucent_strbuf_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"%s\"", x, y, anchor);
    if (rotate != 0) lucent_strbuf_printf(b, " transform=\"rotate(%g %.1f %.1f)\"", rotate, x, y);
    lucent_strbuf_printf(b, ">");
    lucent_strbuf_xml(b, text);
    lucent_strbuf_printf(b, "</text>\n");
}

static void draw_x_ticks(lucent_strbuf *b, const frame *f)
{
    double t[LOG_MAX_DECADES + 2];
    int n = 0;
    if (f->log_x) { /* a tick per decade (every other one past 7), labelled with its value */
        int stride = (int)ceil((f->x1 - f->x0) / 7);
        for (double e = ceil(f->x0 - 1e-9); e <= f->x1 + 1e-9 && n < LOG_MAX_DECADES + 2; e += stride)
            t[n++] = pow(10, e);
    } else {
        n = lucent_plot_nice_ticks(f->x0, f->x1, 7, t);
    }
    for (int i = 0; i < n; i++) {
        double x = px(f, t[i]);
        lucent_strbuf_printf(b, "<line class=\"grid\" x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/>\n", x, f->top,
                             x, f->top + f->height);
        lucent_strbuf_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%g</text>\n", x,
                             f->top + f->height + 16, t[i]);
    }
}

static void draw_y_ticks(lucent_strbuf *b, const frame *f)
{
    double t[LOG_MAX_DECADES + 2];
    int n = 0;
    if (f->log_y) {
        int stride = (int)ceil((f->y1 - f->y0) / 7);
        for (double e = f->y0; e <= f->y1 + 1e-9; e += stride) t[n++] = e;
    } else {
        n = lucent_plot_nice_ticks(f->y0, f->y1, 7, t);
    }
    for (int i = 0; i < n; i++) {
        double y = f->log_y ? f->top + f->height - (t[i] - f->y0) / (f->y1 - f->y0) * f->height : py(f, t[i]);
        lucent_strbuf_printf(b, "<line class=\"grid\" x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/>\n", f->left, y,
                             f->left + f->width, y);
        if (f->log_y)
            lucent_strbuf_printf(b,
                                 "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">10<tspan dy=\"-6\" "
                                 "font-size=\"9\">%d</tspan></text>\n",
                                 f->left - 6, y + 4, (int)t[i]);
        else
            lucent_strbuf_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%g</text>\n", f->left - 6, y + 4,
                                 t[i]);
    }
}

static bool band_point(const lucent_plot_panel *p, const lucent_plot_series *s, int i)
{
    return usable(p, s->x[i], s->y[i]) && isfinite(s->err[i]);
}

/* Error band over points [begin, end): y + err forward, y - err backward (on a log axis a
 * lower edge at or below zero sits on the bottom of the panel). */
static void draw_band_run(lucent_strbuf *b, const frame *f, const lucent_plot_panel *p, const lucent_plot_series *s,
                          int begin, int end, const char *color)
{
    lucent_strbuf_printf(b, "<polygon fill=\"%s\" fill-opacity=\"0.18\" stroke=\"none\" points=\"", color);
    for (int i = begin; i < end; i++)
        lucent_strbuf_printf(b, "%.2f,%.2f ", px(f, s->x[i]), py(f, s->y[i] + fabs(s->err[i])));
    for (int i = end - 1; i >= begin; i--) {
        double lo = s->y[i] - fabs(s->err[i]);
        if (p->log_y && lo <= 0) lo = pow(10, f->y0);
        lucent_strbuf_printf(b, "%.2f,%.2f ", px(f, s->x[i]), py(f, lo));
    }
    lucent_strbuf_printf(b, "\"/>\n");
}

/* One band polygon per run of drawable points, so gaps stay gaps. */
static void draw_band(lucent_strbuf *b, const frame *f, const lucent_plot_panel *p, const lucent_plot_series *s,
                      const char *color)
{
    for (int i = 0; i < s->count;) {
        if (!band_point(p, s, i)) {
            i++;
            continue;
        }
        int end = i;
        while (end < s->count && band_point(p, s, end)) end++;
        if (end - i > 1) draw_band_run(b, f, p, s, i, end, color);
        i = end;
    }
}

/* Marker shape k (lucent_plot_series.marker) centred at (x, y). */
static void draw_marker(lucent_strbuf *b, int k, double x, double y, const char *color)
{
    const double r = 4.5;
    switch (((k % MARKERS) + MARKERS) % MARKERS) {
    case 1:
        lucent_strbuf_printf(b, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"%s\"/>\n",
                             x - r * 0.8, y - r * 0.8, 1.6 * r, 1.6 * r, color);
        return;
    case 2:
    case 4: {
        double d = k % MARKERS == 2 ? 1 : -1;
        lucent_strbuf_printf(b, "<polygon points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f\" fill=\"%s\"/>\n", x, y - d * r,
                             x - r, y + d * 0.8 * r, x + r, y + d * 0.8 * r, color);
        return;
    }
    case 3:
        lucent_strbuf_printf(b, "<polygon points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f %.2f,%.2f\" fill=\"%s\"/>\n", x, y - r,
                             x + r, y, x, y + r, x - r, y, color);
        return;
    case 5:
    case 6: {
        double a = k % MARKERS == 5 ? 0.75 * r : 0, c = k % MARKERS == 5 ? 0.75 * r : r;
        lucent_strbuf_printf(b,
                             "<path d=\"M%.2f %.2fL%.2f %.2fM%.2f %.2fL%.2f %.2f\" stroke=\"%s\" "
                             "stroke-width=\"2.2\" fill=\"none\"/>\n",
                             x - c, y - a, x + c, y + a, x - a, y + c, x + a, y - c, color);
        return;
    }
    case 7:
        lucent_strbuf_printf(b, "<polygon points=\"");
        for (int i = 0; i < 10; i++) {
            double rr = i % 2 ? 0.45 * r : 1.15 * r, t = M_PI * i / 5;
            lucent_strbuf_printf(b, "%.2f,%.2f ", x + rr * sin(t), y - rr * cos(t));
        }
        lucent_strbuf_printf(b, "\" fill=\"%s\"/>\n", color);
        return;
    default:
        lucent_strbuf_printf(b, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"%s\"/>\n", x, y, k ? r : 2.2, color);
    }
}

/* The curve as polylines, broken where points cannot be drawn. */
static void draw_series(lucent_strbuf *b, const frame *f, const lucent_plot_panel *p, const lucent_plot_series *s,
                        const char *color)
{
    if (s->err) draw_band(b, f, p, s, color);
    bool open = false;
    for (int i = 0; i < s->count; i++) {
        bool ok = usable(p, s->x[i], s->y[i]);
        if (ok && !open)
            lucent_strbuf_printf(b, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"1.6\"%s points=\"", color,
                                 s->dashed ? " stroke-dasharray=\"6 4\"" : "");
        else if (!ok && open)
            lucent_strbuf_printf(b, "\"/>\n");
        if (ok) lucent_strbuf_printf(b, "%.2f,%.2f ", px(f, s->x[i]), py(f, s->y[i]));
        open = ok;
    }
    if (open) lucent_strbuf_printf(b, "\"/>\n");
    for (int i = 0; s->markers && i < s->count; i++)
        if (usable(p, s->x[i], s->y[i])) draw_marker(b, s->marker, px(f, s->x[i]), py(f, s->y[i]), color);
}

/* The boxes of every drawable point of the panel (markers, or the points of labelled series), 10 px
 * wide; returns how many (at most max). */
static int point_boxes(const frame *f, const lucent_plot_panel *p, box *dest, int max)
{
    int n = 0;
    for (int s = 0; s < p->series_count; s++) {
        const lucent_plot_series *ser = &p->series[s];
        if (!ser->markers && !ser->point_labels) continue;
        for (int i = 0; i < ser->count && n < max; i++)
            if (usable(p, ser->x[i], ser->y[i])) {
                double x = px(f, ser->x[i]), y = py(f, ser->y[i]);
                dest[n++] = (box){x - 5, y - 5, x + 5, y + 5};
            }
    }
    return n;
}

enum { MAX_PLACED = 256 };

/* Writes every point label where it overlaps least what is placed already (the points, the legend,
 * the labels before it): the first of the places around its point (up right first, then the other
 * sides, then farther out, ring after ring up to 12 rings of 8 px) that overlaps nothing and stays
 * inside the panel, else the least overlapping of them; a label set away from its point gets a thin
 * line to it. */
static void place_labels(lucent_strbuf *b, const frame *f, const lucent_plot_panel *p, box legend)
{
    box taken[MAX_PLACED];
    int n = point_boxes(f, p, taken, MAX_PLACED - 1);
    taken[n++] = legend;
    static const double dir[8][2] = {{1, -1}, {1, 1}, {-1, -1}, {-1, 1}, {0, -1}, {0, 1}, {1, 0}, {-1, 0}};
    for (int s = 0; s < p->series_count; s++) {
        const lucent_plot_series *ser = &p->series[s];
        for (int i = 0; ser->point_labels && i < ser->count; i++) {
            if (!usable(p, ser->x[i], ser->y[i]) || !ser->point_labels[i]) continue;
            double x = px(f, ser->x[i]), y = py(f, ser->y[i]), w, h, best = INFINITY;
            lucent_plot_text_box((int)strlen(ser->point_labels[i]), &w, &h);
            box pick = {x + 7, y - 5 - h, x + 7 + w, y - 5};
            int placed_ring = 1;
            for (int ring = 1; ring <= 12 && best > 0; ring++)
                for (int k = 0; k < 8 && best > 0; k++) {
                    double gap = 8 * ring - 1, cx = x + dir[k][0] * gap, cy = y + dir[k][1] * gap;
                    double bx = dir[k][0] > 0 ? cx : dir[k][0] < 0 ? cx - w : cx - w / 2;
                    double by = dir[k][1] > 0 ? cy : dir[k][1] < 0 ? cy - h : cy - h / 2;
                    box c = {bx, by, bx + w, by + h};
                    double cost = 0;
                    for (int t = 0; t < n; t++) cost += overlap(c, taken[t]);
                    if (c.x0 < f->left || c.x1 > f->left + f->width || c.y0 < f->top || c.y1 > f->top + f->height)
                        cost += w * h; /* outside the panel: as bad as covering a label */
                    if (cost < best) best = cost, pick = c, placed_ring = ring;
                }
            if (n < MAX_PLACED) taken[n++] = pick;
            if (placed_ring > 1) { /* a leader from the point to the label's nearest edge */
                double lx = fmin(fmax(x, pick.x0), pick.x1), ly = fmin(fmax(y, pick.y0), pick.y1);
                lucent_strbuf_printf(b,
                                     "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#999\" "
                                     "stroke-width=\"0.8\"/>\n",
                                     x, y, lx, ly);
            }
            axis_label(b, pick.x0, pick.y1 - 3, "start", 0, ser->point_labels[i]);
        }
    }
}

/* The legend's box: rows of 16 px, a 28 px key and the longest text. */
static box legend_size(const lucent_plot_panel *p)
{
    int rows = 0, chars = 0;
    for (int s = 0; s < p->series_count; s++)
        if (p->series[s].label) rows++, chars = fmax(chars, (int)strlen(p->series[s].label));
    if (p->band_label && (p->band_y0 != 0 || p->band_y1 != 0)) rows++, chars = fmax(chars, (int)strlen(p->band_label));
    double w, h;
    lucent_plot_text_box(chars, &w, &h);
    return (box){0, 0, rows ? w + 36 : 0, rows ? 16.0 * rows + 6 : 0};
}

/* The corner of the panel where the legend covers no point (top right, top left, bottom right,
 * bottom left), else the one covering fewest. */
static box legend_box(const frame *f, const lucent_plot_panel *p)
{
    box size = legend_size(p), pts[MAX_PLACED], best = {0};
    int n = point_boxes(f, p, pts, MAX_PLACED), fewest = 1 << 30;
    double w = size.x1, h = size.y1;
    const double corner[4][2] = {{f->left + f->width - w - 4, f->top + 4},
                                 {f->left + 4, f->top + 4},
                                 {f->left + f->width - w - 4, f->top + f->height - h - 4},
                                 {f->left + 4, f->top + f->height - h - 4}};
    for (int c = 0; c < 4 && fewest > 0; c++) {
        box cand = {corner[c][0], corner[c][1], corner[c][0] + w, corner[c][1] + h};
        int covered = 0;
        for (int i = 0; i < n; i++) covered += overlap(cand, pts[i]) > 0;
        if (covered < fewest) fewest = covered, best = cand;
    }
    return best;
}

static void draw_legend(lucent_strbuf *b, const lucent_plot_panel *p, box at)
{
    int row = 0;
    if (at.x1 > at.x0)
        lucent_strbuf_printf(b,
                             "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"white\" "
                             "fill-opacity=\"0.85\" stroke=\"#ccc\"/>\n",
                             at.x0, at.y0, at.x1 - at.x0, at.y1 - at.y0);
    for (int s = 0; s < p->series_count; s++) {
        const lucent_plot_series *ser = &p->series[s];
        if (!ser->label) continue;
        const char *color = ser->color ? ser->color : k_palette[s % PALETTE];
        double x = at.x0 + 4, y = at.y0 + 16 + 16 * row++;
        if (ser->markers && ser->count == 1) /* a lone point: its marker stands for it */
            draw_marker(b, ser->marker ? ser->marker : 0, x + 11, y - 4, color);
        else
            lucent_strbuf_printf(b,
                                 "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" "
                                 "stroke-width=\"2\"%s/>\n",
                                 x, y - 4, x + 22, y - 4, color, ser->dashed ? " stroke-dasharray=\"6 4\"" : "");
        axis_label(b, x + 28, y, "start", 0, ser->label);
    }
    if (p->band_label && (p->band_y0 != 0 || p->band_y1 != 0)) {
        double x = at.x0 + 4, y = at.y0 + 16 + 16 * row;
        lucent_strbuf_printf(b,
                             "<rect x=\"%.1f\" y=\"%.1f\" width=\"22\" height=\"9\" fill=\"#888\" "
                             "fill-opacity=\"0.25\"/>\n",
                             x, y - 9);
        axis_label(b, x + 28, y, "start", 0, p->band_label);
    }
}

/* The panel's horizontal band (below the series). */
static void draw_hband(lucent_strbuf *b, const frame *f, const lucent_plot_panel *p)
{
    if (p->band_y0 == 0 && p->band_y1 == 0) return;
    double lo = fmin(p->band_y0, p->band_y1), hi = fmax(p->band_y0, p->band_y1);
    if (p->log_y && lo <= 0) lo = pow(10, f->y0);
    double y0 = py(f, hi), y1 = py(f, lo);
    y0 = fmax(y0, f->top), y1 = fmin(y1, f->top + f->height);
    if (y1 > y0)
        lucent_strbuf_printf(b,
                             "<rect x=\"%.1f\" y=\"%.2f\" width=\"%.1f\" height=\"%.2f\" fill=\"#888\" "
                             "fill-opacity=\"0.25\"/>\n",
                             f->left, y0, f->width, y1 - y0);
}

static void draw_panel(lucent_strbuf *b, const lucent_plot_desc *d, int index, double top)
{
    const lucent_plot_panel *p = &d->panels[index];
    int w = d->panel_width ? d->panel_width : 480, h = d->panel_height ? d->panel_height : 360;
    frame f = {.left = index * w + MARGIN_LEFT,
               .top = top + MARGIN_TOP,
               .width = w - MARGIN_LEFT - MARGIN_RIGHT,
               .height = h - MARGIN_TOP - MARGIN_BOTTOM};
    box legend = legend_size(p);
    if (p->legend_outside && legend.x1 > 0) f.width = fmax(f.width - legend.x1 - 12, 0.25 * f.width);
    fit_ranges(p, &f);
    lucent_strbuf_printf(b,
                         "<clipPath id=\"clip%d\"><rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" "
                         "height=\"%.1f\"/></clipPath>\n",
                         index, f.left, f.top, f.width, f.height);
    draw_x_ticks(b, &f);
    draw_y_ticks(b, &f);
    lucent_strbuf_printf(b, "<rect class=\"frame\" x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\"/>\n", f.left,
                         f.top, f.width, f.height);
    lucent_strbuf_printf(b, "<g clip-path=\"url(#clip%d)\">\n", index);
    draw_hband(b, &f, p);
    for (int s = 0; s < p->series_count; s++)
        draw_series(b, &f, p, &p->series[s], p->series[s].color ? p->series[s].color : k_palette[s % PALETTE]);
    lucent_strbuf_printf(b, "</g>\n");
    if (p->legend_outside)
        legend = (box){f.left + f.width + 12, f.top, f.left + f.width + 12 + legend.x1, f.top + legend.y1};
    else
        legend = legend_box(&f, p);
    draw_legend(b, p, legend);
    place_labels(b, &f, p, legend);
    if (p->title) axis_label(b, f.left + f.width / 2, f.top - 12, "middle", 0, p->title);
    if (p->x_label) axis_label(b, f.left + f.width / 2, f.top + f.height + 38, "middle", 0, p->x_label);
    if (p->y_label) axis_label(b, f.left - 52, f.top + f.height / 2, "middle", -90, p->y_label);
}

static lucent_status check_desc(const lucent_plot_desc *d)
{
    if (!d || d->panel_count < 1 || !d->panels) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "plot: no panels");
    for (int i = 0; i < d->panel_count; i++)
        for (int s = 0; s < d->panels[i].series_count; s++) {
            const lucent_plot_series *ser = &d->panels[i].series[s];
            if (ser->count < 0 || (ser->count > 0 && (!ser->x || !ser->y)))
                return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "plot: panel %d, series %d: no data", i, s);
        }
    return LUCENT_OK;
}

lucent_status lucent_plot_svg(const lucent_plot_desc *d, char **dest)
{
    *dest = NULL;
    lucent_status s = check_desc(d);
    if (s != LUCENT_OK) return s;
    int w = d->panel_width ? d->panel_width : 480, h = d->panel_height ? d->panel_height : 360;
    double top = d->title ? 28 : 0;
    lucent_strbuf b = {0};
    lucent_strbuf_printf(&b,
                         "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" "
                         "version=\"1.1\" width=\"%d\" height=\"%.0f\" viewBox=\"0 0 %d %.0f\" "
                         "font-family=\"sans-serif\" font-size=\"12\">\n",
                         w * d->panel_count, h + top, w * d->panel_count, h + top);
    lucent_strbuf_printf(&b, "<style>.grid{stroke:#e3e3e3;stroke-width:1}.frame{fill:none;stroke:#444}</style>\n"
                             "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n");
    if (d->title) axis_label(&b, w * d->panel_count / 2.0, 20, "middle", 0, d->title);
    for (int i = 0; i < d->panel_count; i++) draw_panel(&b, d, i, top);
    lucent_strbuf_printf(&b, "</svg>\n");
    return lucent_strbuf_finish(&b, dest);
}

lucent_status lucent_plot_write_svg(const char *path, const lucent_plot_desc *desc)
{
    char *text;
    lucent_status s = lucent_plot_svg(desc, &text);
    if (s != LUCENT_OK) return s;
    s = lucent_write_file(path, text, strlen(text));
    free(text);
    return s;
}
