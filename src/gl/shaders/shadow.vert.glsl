// Shadow maps: depth from a light (one layer of the shadow array per light).
layout(location = 0) in vec3 a_position;
uniform mat4 u_light_mvp;

void main()
{
    gl_Position = u_light_mvp * vec4(a_position, 1.0);
}
