// Kubo, Dobashi & Morishima's curvature-dependent reflectance (seed 000): the LUT of section V, or
// the function itself. Defines CDRF_LUT (1: the table) and CDRF_VARIANT (0: Kubo, 1: Collomb).
layout(binding = 3) uniform sampler2D u_cdrf_lut; // cos theta across [-1, 1], sigma down [0, max]
uniform float u_lut_sigma_max;

// The LUT's samples sit on its end points (lucent_cdrf_lut_build): column i is
// cos = -1 + 2 i / (w - 1), row j is sigma = max j / (h - 1), row 0 uploaded first (t = 0).
float cdrf_table(float cos_theta, float sigma)
{
    vec2 size = vec2(textureSize(u_cdrf_lut, 0));
    vec2 f = vec2((clamp(cos_theta, -1.0, 1.0) + 1.0) * 0.5, clamp(sigma / u_lut_sigma_max, 0.0, 1.0));
    return textureLod(u_cdrf_lut, (0.5 + f * (size - 1.0)) / size, 0.0).r; // no mip chain: skip the LOD
}

// 16-point Gauss-Legendre on [-1, 1] (nodes +-x_i, weights w_i).
const float GL_X[8] = float[8](0.98940093499165, 0.94457502307323, 0.86563120238783, 0.75540440835500,
                               0.61787624440264, 0.45801677765723, 0.28160355077926, 0.09501250983764);
const float GL_W[8] = float[8](0.02715245941175, 0.06225352393865, 0.09515851168249, 0.12462897125553,
                               0.14959598881658, 0.16915651939500, 0.18260341504492, 0.18945061045507);

// integral over [a, b] of cos(u) g(theta - u; sigma) du.
float kubo_segment(float theta, float sigma, float a, float b)
{
    if (b <= a) return 0.0;
    float c = 0.5 * (a + b), h = 0.5 * (b - a), sum = 0.0;
    for (int i = 0; i < 8; i++)
        for (int s = -1; s <= 1; s += 2) {
            float u = c + float(s) * h * GL_X[i], d = (theta - u) / sigma;
            sum += GL_W[i] * cos(u) * exp(-0.5 * d * d);
        }
    return sum * h / (sigma * 2.50662827463100); // sqrt(2 pi)
}

// Kubo Eq. 1-3 without a table: (E * g)(theta) with E = max(cos, 0), 2 pi-periodic (as
// lucent_cdrf_kubo). For sigma >= 0.5 the Fourier series of E, whose modes m the Gaussian damps by
// exp(-m^2 sigma^2 / 2): E = 1/pi + cos/2 + (2/pi) sum_n (-1)^(n+1) cos(2 n x) / (4 n^2 - 1); for
// smaller sigma the integral over the lit arcs within 6 sigma of theta, by Gauss-Legendre.
float cdrf_kubo(float theta, float sigma)
{
    theta = abs(mod(theta + PI, 2.0 * PI) - PI);
    if (sigma <= 0.0) return max(cos(theta), 0.0);
    if (sigma >= 0.5) {
        float f = 1.0 / PI + 0.5 * exp(-0.5 * sigma * sigma) * cos(theta);
        for (int n = 1; n <= 8; n++)
            f += (2.0 / PI) * ((n & 1) == 1 ? 1.0 : -1.0) * exp(-2.0 * float(n * n) * sigma * sigma) *
                 cos(2.0 * float(n) * theta) / float(4 * n * n - 1);
        return f;
    }
    float lo = theta - 6.0 * sigma, hi = theta + 6.0 * sigma;
    return kubo_segment(theta, sigma, max(lo, -0.5 * PI), min(hi, 0.5 * PI)) +
           kubo_segment(theta, sigma, max(lo, 1.5 * PI), hi);
}

// Collomb's fit from the CDRF blog (seed 003), its kappa read as sigma (lucent_cdrf_collomb).
float cdrf_collomb(float theta, float k)
{
    theta = abs(mod(theta + PI, 2.0 * PI) - PI);
    float a = (1.0 + k) / 4.0 * (cos(min((5.0 + k) * theta / 4.0, PI)) + 1.0);
    float b = 1.0 + pow(log(1.0 + 1.7 * k) * theta / 1.45, 10.0);
    return max(a / b + 0.075 * (1.0 - k), 0.0);
}

// The CDRF at cos theta = n . l for sigma = sigma0 kappa (Kubo Eq. 4), clamped to [0, the LUT's max].
float cdrf(float cos_theta, float sigma)
{
    sigma = clamp(sigma, 0.0, u_lut_sigma_max);
#if CDRF_LUT
    return cdrf_table(cos_theta, sigma);
#elif CDRF_VARIANT == 1
    return cdrf_collomb(acos(clamp(cos_theta, -1.0, 1.0)), sigma);
#else
    return cdrf_kubo(acos(clamp(cos_theta, -1.0, 1.0)), sigma);
#endif
}

vec3 cdrf3(float cos_theta, vec3 sigma)
{
    return vec3(cdrf(cos_theta, sigma.r), cdrf(cos_theta, sigma.g), cdrf(cos_theta, sigma.b));
}
