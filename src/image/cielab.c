/* Linear sRGB to CIE XYZ and CIELAB, and the CIEDE2000 colour difference. */
#include <math.h>

#include "lucent/image.h"

/* IEC 61966-2-1:1999, the matrix from linear sRGB to XYZ (D65). */
void lucent_linear_srgb_to_xyz(const double rgb[3], double dest[3])
{
    static const double m[3][3] = {{0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}};
    for (int i = 0; i < 3; i++) dest[i] = m[i][0] * rgb[0] + m[i][1] * rgb[1] + m[i][2] * rgb[2];
}

/* CIE 15:2004, 8.2.1: f(t) = t^(1/3) above (6/29)^3, else t / (3 (6/29)^2) + 4/29. */
static double lab_f(double t)
{
    const double e = 216.0 / 24389.0, k = 24389.0 / 27.0;
    return t > e ? cbrt(t) : (k * t + 16.0) / 116.0;
}

void lucent_xyz_to_lab(const double xyz[3], const double white_xyz[3], double lab[3])
{
    double fx = lab_f(xyz[0] / white_xyz[0]), fy = lab_f(xyz[1] / white_xyz[1]), fz = lab_f(xyz[2] / white_xyz[2]);
    lab[0] = 116.0 * fy - 16.0;
    lab[1] = 500.0 * (fx - fy);
    lab[2] = 200.0 * (fy - fz);
}

void lucent_linear_srgb_to_lab(const double rgb[3], double dest[3])
{
    static const double white[3] = {0.95047, 1.0, 1.08883}; /* D65, 2 degree observer */
    double xyz[3];
    lucent_linear_srgb_to_xyz(rgb, xyz);
    lucent_xyz_to_lab(xyz, white, dest);
}

static double deg(double radians) { return radians * 180.0 / M_PI; }
static double rad(double degrees) { return degrees * M_PI / 180.0; }

/* The hue angle in degrees, [0, 360); 0 for a neutral colour (Sharma et al. eq. 7). */
static double hue(double b, double a)
{
    if (a == 0.0 && b == 0.0) return 0.0;
    double h = deg(atan2(b, a));
    return h < 0.0 ? h + 360.0 : h;
}

/* Sharma, Wu & Dalal 2005, "The CIEDE2000 color-difference formula: implementation notes,
 * supplementary test data, and mathematical observations", eqs. 1-22. */
double lucent_ciede2000(const double lab1[3], const double lab2[3])
{
    double c1 = hypot(lab1[1], lab1[2]), c2 = hypot(lab2[1], lab2[2]);
    double cbar7 = pow(0.5 * (c1 + c2), 7.0);
    double g = 0.5 * (1.0 - sqrt(cbar7 / (cbar7 + pow(25.0, 7.0)))); /* eq. 4 */
    double a1 = (1.0 + g) * lab1[1], a2 = (1.0 + g) * lab2[1];       /* eq. 5 */
    double cp1 = hypot(a1, lab1[2]), cp2 = hypot(a2, lab2[2]);       /* eq. 6 */
    double hp1 = hue(lab1[2], a1), hp2 = hue(lab2[2], a2);           /* eq. 7 */
    double dl = lab2[0] - lab1[0], dc = cp2 - cp1;                   /* eqs. 8, 9 */
    double dh = 0.0;                                                 /* eq. 10 */
    if (cp1 * cp2 != 0.0) {
        dh = hp2 - hp1;
        if (dh > 180.0)
            dh -= 360.0;
        else if (dh < -180.0)
            dh += 360.0;
    }
    double dhh = 2.0 * sqrt(cp1 * cp2) * sin(rad(dh / 2.0)); /* eq. 11 */
    double lbar = 0.5 * (lab1[0] + lab2[0]), cbar = 0.5 * (cp1 + cp2);
    double hbar = hp1 + hp2; /* eq. 14 */
    if (cp1 * cp2 != 0.0) {
        if (fabs(hp1 - hp2) <= 180.0)
            hbar *= 0.5;
        else
            hbar = hp1 + hp2 < 360.0 ? 0.5 * (hp1 + hp2 + 360.0) : 0.5 * (hp1 + hp2 - 360.0);
    }
    double t = 1.0 - 0.17 * cos(rad(hbar - 30.0)) + 0.24 * cos(rad(2.0 * hbar)) + 0.32 * cos(rad(3.0 * hbar + 6.0)) -
               0.20 * cos(rad(4.0 * hbar - 63.0));                /* eq. 15 */
    double dtheta = 30.0 * exp(-pow((hbar - 275.0) / 25.0, 2.0)); /* eq. 16 */
    double cbar7p = pow(cbar, 7.0);
    double rc = 2.0 * sqrt(cbar7p / (cbar7p + pow(25.0, 7.0))); /* eq. 17 */
    double l50 = (lbar - 50.0) * (lbar - 50.0);
    double sl = 1.0 + 0.015 * l50 / sqrt(20.0 + l50);            /* eq. 18 */
    double sc = 1.0 + 0.045 * cbar, sh = 1.0 + 0.015 * cbar * t; /* eqs. 19, 20 */
    double rt = -sin(rad(2.0 * dtheta)) * rc;                    /* eq. 21 */
    double x = dl / sl, y = dc / sc, z = dhh / sh;
    return sqrt(x * x + y * y + z * z + rt * y * z); /* eq. 22 */
}
