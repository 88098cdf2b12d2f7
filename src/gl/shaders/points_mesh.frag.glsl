// The points method's meshes (objects not splatted): their depth in the visibility pass and their
// attributes with weight 1 in the attribute pass, so splats and triangles mix in one image.
#include "common.glsl"

in vec3 v_position;
in vec3 v_normal;
in float v_curvature;
in vec2 v_uv;

uniform vec3 u_albedo;
uniform float u_f0;
uniform float u_roughness;
uniform float u_object;
uniform float u_material; // the renderer's material row (the shade pass's eta)

layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_albedo;
layout(location = 3) out vec4 o_object; // object + 1, 1 (a mesh), material, 1

void main()
{
    vec3 n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;
    o_position = vec4(v_position, 1.0);
    o_normal = vec4(n, u_f0);
    o_albedo = vec4(u_albedo, u_roughness);
    o_object = vec4(u_object + 1.0, 1.0, u_material, 1.0);
}
