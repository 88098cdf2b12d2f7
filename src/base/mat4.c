/* 4x4 matrices (base/mat4.h). */
#include <string.h>

#include "base/mat4.h"

void lucent_mat4_mul(const double a[16], const double b[16], double dest[16])
{
    double t[16];
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            double s = 0;
            for (int k = 0; k < 4; k++) s += a[4 * k + r] * b[4 * c + k];
            t[4 * c + r] = s;
        }
    memcpy(dest, t, sizeof t);
}

void lucent_mat4_to_float(const double m[16], float dest[16])
{
    for (int i = 0; i < 16; i++) dest[i] = (float)m[i];
}
