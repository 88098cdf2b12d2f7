/* The MCML output file (.mco, format A1) read back (the MCML manual, chapter on the output
 * file; the sections MCML 1.2's WriteResult writes, in cm). Hostile input: every count is
 * checked against InParm, every value must be a finite number >= 0, and errors name the file,
 * the line and the section. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/mcml.h"
#include "mcml_internal.h"

enum { RAT, A_L, A_Z, RD_R, RD_A, TT_R, TT_A, A_RZ, RD_RA, TT_RA, SECTIONS };

static const char *const k_section[SECTIONS] = {"RAT",  "A_l",  "A_z",  "Rd_r",  "Rd_a",
                                                "Tt_r", "Tt_a", "A_rz", "Rd_ra", "Tt_ra"};

/* What one section holds: where its values go, how many, and the factor from cm to mm. */
typedef struct section_spec {
    double **dest;
    size_t count;
    double per_mm; /* divide the file's value by this (cm^-k -> mm^-k: 10^k) */
    const char *count_name;
    bool required;
} section_spec;

static void section_specs(lucent_mco *m, section_spec *spec)
{
    const lucent_mc_grid *g = &m->run.desc.grid;
    size_t nr = (size_t)g->nr, nz = (size_t)g->nz, na = (size_t)g->na;
    const double cm = MCML_CM;
    spec[RAT] = (section_spec){NULL, 4, 1.0, "Rsp, Rd, A, Tt", true};
    spec[A_L] = (section_spec){&m->a_l, (size_t)m->run.desc.layer_count, 1.0, "layers", true};
    spec[A_Z] = (section_spec){&m->a_z, nz, cm, "nz", true};
    spec[RD_R] = (section_spec){&m->rd_r, nr, cm * cm, "nr", true};
    spec[RD_A] = (section_spec){&m->rd_a, na, 1.0, "na", true};
    spec[TT_R] = (section_spec){&m->tt_r, nr, cm * cm, "nr", true};
    spec[TT_A] = (section_spec){&m->tt_a, na, 1.0, "na", true};
    spec[A_RZ] = (section_spec){&m->a_rz, nr * nz, cm * cm * cm, "nr x nz", false};
    spec[RD_RA] = (section_spec){&m->rd_ra, nr * na, cm * cm, "nr x na", false};
    spec[TT_RA] = (section_spec){&m->tt_ra, nr * na, cm * cm, "nr x na", false};
}

static bool is_number(const char *word)
{
    char *end;
    strtod(word, &end);
    return end != word && *end == '\0';
}

static int section_of(const char *word)
{
    for (int i = 0; i < SECTIONS; i++)
        if (strcmp(word, k_section[i]) == 0) return i;
    return -1;
}

/* The first word of the current data line, and whether anything follows it. */
static void first_word(const mcml_reader *r, char *word, size_t size, bool *more)
{
    const char *p = r->buf;
    while (isspace((unsigned char)*p)) p++;
    size_t n = strcspn(p, " \t\r\n");
    snprintf(word, size, "%.*s", (int)(n < size ? n : size - 1), p);
    p += n;
    while (isspace((unsigned char)*p)) p++;
    *more = *p != '\0';
}

/* One value of a section: a finite number >= 0. */
static lucent_status parse_value(const mcml_reader *r, const char *name, size_t index, const char **p, double *dest)
{
    char *end;
    errno = 0;
    double v = strtod(*p, &end);
    int len = (int)strcspn(*p, " \t\r");
    if (end == *p || (*end && !isspace((unsigned char)*end)))
        return mcml_fail(r, "%s: value %zu: expected a number, got '%.*s'", name, index + 1, len, *p);
    if (!isfinite(v) || errno == ERANGE)
        return mcml_fail(r, "%s: value %zu: not a usable number: '%.*s'", name, index + 1, len, *p);
    if (v < 0) return mcml_fail(r, "%s: value %zu: must be >= 0, got %g", name, index + 1, v);
    *dest = v;
    *p = end;
    return LUCENT_OK;
}

/* Reads `count` values after a section's header, over as many lines as they take. */
static lucent_status read_values(mcml_reader *r, int id, const section_spec *spec, double *dest)
{
    const char *name = k_section[id];
    char what[96];
    snprintf(what, sizeof what, "%s: %zu values (%s)", name, spec->count, spec->count_name);
    size_t i = 0;
    while (i < spec->count) {
        lucent_status s = mcml_next_line(r, what);
        if (s != LUCENT_OK) return s;
        char word[32];
        bool more;
        first_word(r, word, sizeof word, &more);
        if (section_of(word) >= 0)
            return mcml_fail(r, "%s: expected %zu values (%s), got %zu before section %s", name, spec->count,
                             spec->count_name, i, word);
        const char *p = r->buf;
        while (1) {
            while (isspace((unsigned char)*p)) p++;
            if (!*p) break;
            if (i == spec->count)
                return mcml_fail(r, "%s: more than %zu values (%s)", name, spec->count, spec->count_name);
            if ((s = parse_value(r, name, i, &p, &dest[i])) != LUCENT_OK) return s;
            i++;
        }
    }
    for (size_t k = 0; k < spec->count; k++) dest[k] /= spec->per_mm;
    return LUCENT_OK;
}

static lucent_status read_section(mcml_reader *r, lucent_mco *m, int id, const section_spec *spec)
{
    if (id == RAT) {
        double v[4];
        lucent_status s = read_values(r, id, spec, v);
        if (s == LUCENT_OK) m->rsp = v[0], m->rd = v[1], m->a = v[2], m->tt = v[3];
        return s;
    }
    /* each value takes two characters at least: a short file cannot make us allocate much */
    if (spec->count > strlen(r->p) / 2 + 1)
        return mcml_fail(r, "%s: the rest of the file is too short for %zu values (%s)", k_section[id], spec->count,
                         spec->count_name);
    double *v = malloc((spec->count ? spec->count : 1) * sizeof *v);
    if (!v) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    *spec->dest = v;
    return read_values(r, id, spec, v);
}

/* The header line: the format version. MCML writes A1 (ASCII) or B1 (binary, never used). */
static lucent_status read_version(mcml_reader *r)
{
    lucent_status s = mcml_next_line(r, "the format version (A1)");
    if (s != LUCENT_OK) return s;
    char word[32];
    bool more;
    first_word(r, word, sizeof word, &more);
    if (strcmp(word, "A1") == 0 && !more) return LUCENT_OK;
    if (strcmp(word, "B1") == 0) return mcml_fail(r, "binary .mco files (B1) are not supported");
    return mcml_fail(r, "expected the format version A1 of an MCML output file, got '%s'", word);
}

static lucent_status read_inparm(mcml_reader *r, lucent_mco *m)
{
    lucent_status s = mcml_next_line(r, "the section InParm");
    if (s != LUCENT_OK) return s;
    char word[32];
    bool more;
    first_word(r, word, sizeof word, &more);
    if (strcmp(word, "InParm") != 0 || more) return mcml_fail(r, "expected the section InParm, got '%s'", word);
    return mcml_read_run(r, &m->run);
}

/* Sections after InParm, in any order, each at most once; the required ones must all come. */
static lucent_status read_sections(mcml_reader *r, lucent_mco *m)
{
    section_spec spec[SECTIONS];
    section_specs(m, spec);
    int seen[SECTIONS] = {0}, last = -1;
    while (1) {
        mcml_reader probe = *r;
        if (mcml_next_line(&probe, "") != LUCENT_OK) { /* the end of the file */
            lucent_clear_error();
            r->line = probe.line;
            break;
        }
        *r = probe;
        char word[32];
        bool more;
        first_word(r, word, sizeof word, &more);
        int id = section_of(word);
        if (id < 0 && last >= 0 && is_number(word))
            return mcml_fail(r, "%s: more than %zu values (%s)", k_section[last], spec[last].count,
                             spec[last].count_name);
        if (id < 0) return mcml_fail(r, "expected a section name (RAT, A_l, A_z, ...), got '%s'", word);
        if (more) return mcml_fail(r, "unexpected data after the section name %s", word);
        if (seen[id]) return mcml_fail(r, "section %s appears twice (first at line %d)", word, seen[id]);
        seen[id] = r->at;
        last = id;
        lucent_status s = read_section(r, m, id, &spec[id]);
        if (s != LUCENT_OK) return s;
    }
    for (int id = 0; id < SECTIONS; id++)
        if (spec[id].required && !seen[id]) {
            r->at = r->line + 1;
            return mcml_fail(r, "unexpected end of file: missing the section %s", k_section[id]);
        }
    return LUCENT_OK;
}

/* The file's angular normalisations to Lucent's (mcml_internal.h). */
static void to_lucent_angles(lucent_mco *m)
{
    int nr = m->run.desc.grid.nr, na = m->run.desc.grid.na;
    double k = mcml_1d_per_lucent(na);
    for (int j = 0; j < na; j++) {
        m->rd_a[j] /= k;
        m->tt_a[j] /= k;
        double c = mcml_2d_per_lucent(j, na);
        for (int i = 0; i < nr; i++) {
            if (m->rd_ra) m->rd_ra[(size_t)i * na + j] /= c;
            if (m->tt_ra) m->tt_ra[(size_t)i * na + j] /= c;
        }
    }
}

lucent_status lucent_mco_parse(const char *text, const char *name, lucent_mco *dest)
{
    memset(dest, 0, sizeof *dest);
    mcml_reader r = {.name = name, .p = text};
    lucent_status s = read_version(&r);
    if (s == LUCENT_OK) s = read_inparm(&r, dest);
    if (s == LUCENT_OK) s = read_sections(&r, dest);
    if (s == LUCENT_OK) to_lucent_angles(dest);
    if (s != LUCENT_OK) lucent_mco_free(dest);
    return s;
}

lucent_status lucent_mco_load(const char *path, lucent_mco *dest)
{
    memset(dest, 0, sizeof *dest);
    char *text;
    lucent_status s = lucent_read_text_file(path, &text);
    if (s != LUCENT_OK) return s;
    s = lucent_mco_parse(text, path, dest);
    free(text);
    return s;
}

void lucent_mco_free(lucent_mco *m)
{
    free(m->run.output);
    free(m->run.layers);
    double *arrays[] = {m->a_l, m->a_z, m->rd_r, m->tt_r, m->rd_a, m->tt_a, m->a_rz, m->rd_ra, m->tt_ra};
    for (size_t i = 0; i < sizeof arrays / sizeof *arrays; i++) free(arrays[i]);
    memset(m, 0, sizeof *m);
}
