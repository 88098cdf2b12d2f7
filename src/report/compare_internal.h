/* Shared by the files of the comparison report (compare_report.c, compare_tables.c). */
#ifndef LUCENT_SRC_REPORT_COMPARE_INTERNAL_H
#define LUCENT_SRC_REPORT_COMPARE_INTERNAL_H

#include "base/strbuf.h"
#include "lucent/report.h"

/* Where and how the run was made: version, revision, command, date, machine, GL renderer. */
void report_html_provenance(lucent_strbuf *b, const lucent_compare_provenance *p);
void report_md_provenance(lucent_strbuf *b, const lucent_compare_provenance *p);

/* Each method's error per region, and per light alone (nothing when the scene has none). */
void report_html_regions(lucent_strbuf *b, const lucent_compare_scene *sc);
void report_html_lights(lucent_strbuf *b, const lucent_compare_scene *sc);
void report_md_regions(lucent_strbuf *b, const lucent_compare_scene *sc);
void report_md_lights(lucent_strbuf *b, const lucent_compare_scene *sc);

#endif
