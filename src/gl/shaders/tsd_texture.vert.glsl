// tsd: the mesh rasterised at its texture coordinates (d'Eon & Luebke 2007, GPU Gems 3 14.4.1): the
// texture's texels are the fragments; position and normal in world mm go along.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 3) in vec2 a_uv;
layout(location = 4) in float a_chart; // the chart + 1

out vec3 v_position;
out vec3 v_normal;
flat out float v_chart;

void main()
{
    v_chart = a_chart;
    v_position = a_position;
    v_normal = a_normal;
    gl_Position = vec4(a_uv * 2.0 - 1.0, 0.0, 1.0);
}
