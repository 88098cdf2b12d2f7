/* A program an engine would write against an installed Lucent (tests/install_test.sh builds it with
 * pkg-config, statically and shared, and with CMake's find_package(Lucent)). It checks the library
 * against Jensen et al. 2001 in closed form, computed here independently:
 *   Fdr = -1.440/eta^2 + 0.710/eta + 0.668 + 0.0636 eta,  A = (1 + Fdr)/(1 - Fdr),
 *   Rd  = (a'/2) (1 + exp(-(4/3) A sqrt(3 (1 - a')))) exp(-sqrt(3 (1 - a'))),
 * with a' the Skin1 preset's reduced albedo (Jensen's Figure 5: sigma_s', sigma_a). */
#include <lucent/lucent.h>
#include <math.h>
#include <stdio.h>

int main(void)
{
    lucent_material m;
    if (lucent_material_preset_find("skin1", &m) != LUCENT_OK) {
        fprintf(stderr, "consumer: %s\n", lucent_last_error());
        return 1;
    }
    lucent_material_derived d;
    lucent_material_derive(&m, &d);
    double eta = m.eta, fdr = -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
    double a = (1 + fdr) / (1 - fdr);
    int bad = 0;
    for (int c = 0; c < 3; c++) {
        double sp = m.sigma_s[c] * (1 - m.g[c]), ap = sp / (sp + m.sigma_a[c]);
        double s = sqrt(3 * (1 - ap)), rd = 0.5 * ap * (1 + exp(-4.0 / 3.0 * a * s)) * exp(-s);
        if (fabs(rd - d.rd[c]) > 1e-12) bad = 1;
        printf("%s Rd[%d] = %.6f (closed form %.6f)\n", m.name, c, d.rd[c], rd);
    }
    /* A failure comes back as a status and a message naming the field. */
    if (lucent_material_preset_find("no-such-material", &m) == LUCENT_OK || !lucent_last_error()[0]) bad = 1;
    printf("lucent %s: %s\n", LUCENT_VERSION_STRING, bad ? "FAIL" : "ok");
    return bad;
}
