// Window output: exposure, the tonemap of lucent_tonemap_value, sRGB encoding (the image module's
// curve), the frame scaled to the window.
layout(binding = 0) uniform sampler2D u_image;
uniform int u_tonemap;     // 0 none, 1 clamp, 2 reinhard, 3 filmic (lucent_tonemap_op)
uniform float u_exposure;  // 2^stops
uniform vec2 u_scale;      // image texels per window pixel
uniform vec2 u_origin;     // the window pixel (bottom-left) where the image starts

layout(location = 0) out vec4 o_color;

vec3 tonemap(vec3 x)
{
    if (u_tonemap == 2) return x / (1.0 + x);
    if (u_tonemap == 3) return x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
    return x;
}

vec3 srgb(vec3 x)
{
    x = clamp(x, 0.0, 1.0);
    return mix(12.92 * x, 1.055 * pow(x, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), x));
}

void main()
{
    vec3 c = texture(u_image, (gl_FragCoord.xy - u_origin) * u_scale / vec2(textureSize(u_image, 0))).rgb;
    o_color = vec4(srgb(tonemap(max(c, 0.0) * u_exposure)), 1.0);
}
