// tsd, the stretch map (GPU Gems 3 14.4.2): texels per mm along u and v, 1 / |dP/du| per texel,
// from the screen-space derivatives of the world position while the mesh is rasterised in texture
// space (one texel = one pixel there); z: the texel's chart + 1 (0: none), for the blurs.
in vec3 v_position;
in vec3 v_normal;
flat in float v_chart;

layout(location = 0) out vec4 o_stretch;

void main()
{
    float du = length(dFdx(v_position)), dv = length(dFdy(v_position));
    o_stretch = vec4(du > 0.0 ? 1.0 / du : 0.0, dv > 0.0 ? 1.0 / dv : 0.0, v_chart, 1.0);
}
