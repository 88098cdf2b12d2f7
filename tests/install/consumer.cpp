// The C++ side of tests/install/consumer.c: the same check through the C headers from C++.
#include <lucent/lucent.h>

#include <cmath>
#include <iostream>
#include <string>

int main()
{
    lucent_material m;
    if (lucent_material_preset_find("marble", &m) != LUCENT_OK) {
        std::cerr << "consumer++: " << lucent_last_error() << "\n";
        return 1;
    }
    lucent_material_derived d;
    lucent_material_derive(&m, &d);
    // Jensen et al. 2001's dipole Rd in closed form (see consumer.c), against the library's.
    double eta = m.eta, fdr = -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
    double a = (1 + fdr) / (1 - fdr);
    bool ok = true;
    for (int c = 0; c < 3; c++) {
        double sp = m.sigma_s[c] * (1 - m.g[c]), ap = sp / (sp + m.sigma_a[c]);
        double s = std::sqrt(3 * (1 - ap)), rd = 0.5 * ap * (1 + std::exp(-4.0 / 3.0 * a * s)) * std::exp(-s);
        ok = ok && std::fabs(rd - d.rd[c]) < 1e-12;
        std::cout << std::string(m.name) << " Rd[" << c << "] = " << d.rd[c] << "\n";
    }
    std::cout << "lucent " << LUCENT_VERSION_STRING << " (C++): " << (ok ? "ok" : "FAIL") << "\n";
    return ok ? 0 : 1;
}
