// Shared by the scene shaders: constants and the per-frame uniform block (std140, binding 0),
// mirrored by gl_frame_block in src/gl/renderer_internal.h.
#define PI 3.14159265358979
#define MAX_LIGHTS 8

layout(std140, binding = 0) uniform Frame {
    mat4 u_view_proj;                 // world mm -> clip
    vec4 u_eye;                       // xyz: camera position (mm)
    vec4 u_forward;                   // xyz: unit view direction; linear depth = dot(P - eye, forward)
    vec4 u_ambient;                   // rgb: uniform environment radiance
    ivec4 u_counts;                   // x: lights
    vec4 u_light_vec[MAX_LIGHTS];     // xyz: direction of travel (w = 0, directional) or position (w = 1)
    vec4 u_light_rgb[MAX_LIGHTS];     // rgb: colour x intensity (irradiance, or intensity per sr)
    vec4 u_light_shadow[MAX_LIGHTS];  // x: shadow layer (-1: none), y: near, z: far (mm), w: 1 ortho
    vec4 u_light_texel[MAX_LIGHTS];   // x: shadow texel size at the scene centre (mm)
    mat4 u_light_matrix[MAX_LIGHTS];  // world mm -> the light's clip space
};
