// The path tracer's boundary on a half-space of the object's material (docs/render.md, "One boundary";
// lucent/bake.h, the boundary part, baked through the tracer's rough dielectric): a layer per material
// table row (the material index of the depth target), exit cosine bins across (32, bin b centred at
// (b + 1/2) / 32), incidence bins down, then one row more, the exit curve. Every method multiplies the
// light that enters by the entry factor A(mu_i, mu_o) and the light that leaves toward the viewer, after
// any blur, by the exit curve E(mu_o); with the albedo (the half-space's hemispherical albedo) a flat
// surface shows the tracer's radiance, albedo A E E_light mu_i / pi. Needs no other file.
layout(binding = 9) uniform sampler2DArray u_boundary;
const float BOUNDARY_BINS = 32.0;

// The exit curve E(mu_o) of table row `layer`: the diffuse light's way out toward the viewer.
vec3 boundary_exit(float mu_o, float layer)
{
    return texture(u_boundary, vec3(clamp(mu_o, 0.0, 1.0), (BOUNDARY_BINS + 0.5) / (BOUNDARY_BINS + 1.0), layer)).rgb;
}

// The entry factor A(mu_i, mu_o) of table row `layer` for light entering at cosine mu_i, seen at mu_o.
vec3 boundary_entry(float mu_i, float mu_o, float layer)
{
    float y = clamp(mu_i * BOUNDARY_BINS, 0.5, BOUNDARY_BINS - 0.5) / (BOUNDARY_BINS + 1.0);
    return texture(u_boundary, vec3(clamp(mu_o, 0.0, 1.0), y, layer)).rgb;
}
