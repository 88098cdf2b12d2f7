// burley's blur (src/gl/methods/burley.c): Burley's profile sampled on a disk as Unity HDRP samples its
// Diffusion Profiles (Golubev 2018): per pixel, u_samples radii at the CDF values (i + 0.5) / N of the
// widest channel's profile, golden-angle azimuths rotated per pixel by interleaved gradient noise
// (Jimenez 2014), each sample weighted per channel by the profile at the 3-D distance sqrt(r^2 + dz^2)
// over the sampling density, the sums normalised per channel. Background samples and samples of another
// material take no weight; a pixel with none keeps its own light.
layout(binding = 0) uniform sampler2D u_diffuse; // rgb: irradiance x albedo before the blur; a: strength
layout(binding = 1) uniform sampler2D u_depth;   // x: linear depth (mm, 0 = background); y: material

uniform vec3 u_d[8];   // per material: d = 1 / s per channel, mm (GLR_MAX_MATERIALS)
uniform int u_samples; // disk samples per pixel
uniform float u_scale; // pixels per mm at a depth of 1 mm

layout(location = 0) out vec4 o_color;

const float PI = 3.14159265358979;
const float GOLDEN_ANGLE = 2.39996322972865332; // pi (3 - sqrt(5))

// Burley's R(r) / A with s = 1 / d (Christensen & Burley 2015, eq. 2).
vec3 burley(vec3 d, float r)
{
    vec3 s = 1.0 / d;
    return s * (exp(-s * r) + exp(-s * r / 3.0)) / (8.0 * PI * max(r, 1e-6));
}

// The radius where the profile's CDF, 1 - e^(-x) / 4 - 3 e^(-x/3) / 4 with x = r / d, reaches c: with
// y = e^(-x/3) it is the cubic y^3 + 3 y = 4 (1 - c), solved by Cardano's formula.
float sample_radius(float d, float c)
{
    float q = 2.0 * (1.0 - c), h = sqrt(q * q + 1.0);
    float y = pow(q + h, 1.0 / 3.0) - pow(h - q, 1.0 / 3.0);
    return -3.0 * d * log(max(y, 1e-30));
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy), size = textureSize(u_diffuse, 0);
    vec2 zm = texelFetch(u_depth, p, 0).xy;
    vec3 centre = texelFetch(u_diffuse, p, 0).rgb;
    if (zm.x <= 0.0) {
        o_color = vec4(centre, 1.0);
        return;
    }
    int m = int(zm.y + 0.5);
    vec3 d = u_d[m];
    float dmax = max(d.r, max(d.g, d.b)), px_per_mm = u_scale / zm.x;
    float rotation = 2.0 * PI * fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
    vec3 sum = vec3(0.0), weights = vec3(0.0);
    for (int i = 0; i < u_samples; i++) {
        float r = sample_radius(dmax, (float(i) + 0.5) / float(u_samples));
        float pdf = (exp(-r / dmax) + exp(-r / (3.0 * dmax))) / (4.0 * dmax); // per unit radius
        float phi = rotation + float(i) * GOLDEN_ANGLE;
        ivec2 q = ivec2(floor(gl_FragCoord.xy + r * px_per_mm * vec2(cos(phi), sin(phi))));
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
        vec2 zq = texelFetch(u_depth, q, 0).xy;
        if (zq.x <= 0.0 || int(zq.y + 0.5) != m) continue;
        float dz = zq.x - zm.x;
        vec3 w = burley(d, sqrt(r * r + dz * dz)) * 2.0 * PI * r / pdf;
        sum += w * texelFetch(u_diffuse, q, 0).rgb;
        weights += w;
    }
    o_color = vec4(mix(centre, sum / max(weights, vec3(1e-30)), greaterThan(weights, vec3(0.0))), 1.0);
}
