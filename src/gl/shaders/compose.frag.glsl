// Final pass (Freude 4.2, pass 4): the blurred diffuse blended with the unblurred one by the
// per-pixel strength, times the boundary's exit curve toward the viewer (where the light leaves;
// boundary.glsl), then the specular added after the blur; background where nothing was drawn.
#include "boundary.glsl"
layout(binding = 0) uniform sampler2D u_diffuse;  // rgb diffuse, a: strength
layout(binding = 1) uniform sampler2D u_blurred;  // the blur's sum over kernel passes
layout(binding = 2) uniform sampler2D u_specular;
layout(binding = 3) uniform sampler2D u_depth;    // x: linear depth, 0 = background; y: material

uniform int u_blurred_valid;
uniform vec3 u_background;

layout(location = 0) out vec4 o_color; // rgb: radiance; a: coverage

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    if (texelFetch(u_depth, p, 0).x <= 0.0) {
        o_color = vec4(u_background, 0.0);
        return;
    }
    vec2 z = texelFetch(u_depth, p, 0).xy;
    vec4 d = texelFetch(u_diffuse, p, 0);
    vec3 diffuse = u_blurred_valid != 0 ? mix(d.rgb, texelFetch(u_blurred, p, 0).rgb, d.a) : d.rgb;
    vec4 s = texelFetch(u_specular, p, 0); // a: the view cosine
    o_color = vec4(diffuse * boundary_exit(s.a, z.y) + s.rgb, 1.0);
}
