// The scene pass: meshes are in world millimetres already (scaled and placed when the scene loads).
#include "common.glsl"

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in float a_curvature; // mean curvature, mm^-1 (a constant 0 when unused)
layout(location = 3) in vec2 a_uv;

out vec3 v_position;
out vec3 v_normal;
out float v_curvature;
out vec2 v_uv;

void main()
{
    v_position = a_position;
    v_normal = a_normal;
    v_curvature = a_curvature;
    v_uv = a_uv;
    gl_Position = u_view_proj * vec4(a_position, 1.0);
}
