/* Translucency: light through thin parts (Jimenez 2010; docs/render.md, "Translucency"), added by
 * ssss and cdrf+translucency. Light reaching the back of a part, whose thickness s the shadow map
 * gives, leaves the front attenuated by the material's transmittance T(s): the Monte Carlo slab's or
 * the profile's (lucent/profile.h), baked per material (lucent/bake.h) into a texture row. */
#include <math.h>

#include "base/settings_table.h"
#include "gl/methods/surface.h"

/* The names are the bake room's (lucent_transmittance_name), the model being a part of the bake. */
static const char *transmittance_names(int i)
{
    return i >= 0 && i <= LUCENT_TRANSMIT_PROFILE ? lucent_transmittance_name((lucent_transmittance_model)i) : NULL;
}

static const lucent_setting k_translucency[] = {
    SETTING_BOOL("translucency", translucency.enabled, true, "ssss: light through thin parts (shadow-map thickness)"),
    SETTING_CHOICE("transmittance", translucency.transmittance, "slab", transmittance_names,
                   "how much light passes a thickness of a thin part: the Monte Carlo slab, or the profile's tail "
                   "(Jimenez); through a convex body always the profile's tail"),
    SETTING_BOOL(
        "thin_sheet", translucency.sheet, false,
        "thin parts (transmittance slab; ssss, cdrf+translucency, burley, tsd, points): the light of sheets "
        "of the material behind the tracer's boundary lit from behind, the forward lobe through both faces "
        "and the diffuse rest, in place of T(s) / pi (off by default: worse on the default scenes, docs/render.md)"),
    SETTING_REAL("translucency_curvature", translucency.curvature, 1, -100, 100,
                 "cdrf+translucency: transmitted light times 1 + this x sigma0 x curvature (the CDRF blog)"),
};

const lucent_settings_group gl_translucency_settings =
    SETTINGS_GROUP("translucency", "light through thin parts", k_translucency);

/* The convex body's transmittance (surface.glsl, transmitted): the profile's power outside radius s,
 * for the profile as a sum of Gaussians sum_k w_k exp(-s^2 / (2 v_k)) / sum_k w_k (Jimenez et al.
 * 2010's transmittance function with the material's own fit, lucent_sog_fit), needs the vertex
 * curvature and the material's Gaussians. */
enum { TRANSLUCENCY_SOG = 6 };

/* The sheet tables replace T(s) / pi on thin parts (docs/render.md, "Thin parts"). */
static bool uses_sheet(const lucent_render_settings *s)
{
    return s->translucency.sheet && s->translucency.transmittance == LUCENT_TRANSMIT_SLAB;
}

unsigned gl_translucency_bakes(const lucent_render_settings *s, bool enabled)
{
    return enabled ? LUCENT_BAKE_TRANSMITTANCE | (uses_sheet(s) ? LUCENT_BAKE_SHEET : 0u) : 0u;
}

lucent_status gl_translucency_prepare(lucent_renderer *r, const lucent_render_settings *s)
{
    lucent_bake_desc d = gl_renderer_bake_desc(
        r, s, LUCENT_BAKE_TRANSMITTANCE | LUCENT_BAKE_SOG | (uses_sheet(s) ? LUCENT_BAKE_SHEET : 0u));
    d.sog_count = TRANSLUCENCY_SOG;
    lucent_status st = gl_meshes_curvature(&r->meshes, r->scene, s->cdrf.curvature_smooth, r->desc.pool);
    if (st == LUCENT_OK) st = gl_tables_bake(&r->tables, &d, r->cache);
    if (st == LUCENT_OK && uses_sheet(s)) st = gl_tables_upload_sheet(&r->tables);
    return st == LUCENT_OK ? gl_tables_upload_transmittance(&r->tables) : st;
}

void gl_translucency_uniforms(const lucent_renderer *r, const lucent_render_settings *s, int i, GLuint p, bool enabled)
{
    const lucent_baked *b = gl_tables_of(&r->tables, i);
    glUniform1i(glGetUniformLocation(p, "u_translucency"), enabled);
    glUniform1f(glGetUniformLocation(p, "u_transmit_range"), (float)fmax(b->transmit_range, 1e-6));
    glUniform1f(glGetUniformLocation(p, "u_transmit_v"),
                (float)((r->tables.object_material[i] + 0.5) / r->tables.count));
    glUniform1i(glGetUniformLocation(p, "u_transmit_albedo"), s->translucency.transmittance == LUCENT_TRANSMIT_PROFILE);
    glUniform1i(glGetUniformLocation(p, "u_sheet"), uses_sheet(s) && (b->have & LUCENT_BAKE_SHEET));
    glUniform1f(glGetUniformLocation(p, "u_sheet_range"), (float)fmax(b->sheet_range, 1e-6));
    glUniform1f(glGetUniformLocation(p, "u_curvature_gain"), (float)s->translucency.curvature);
    float var[TRANSLUCENCY_SOG][3] = {{0}}, w[TRANSLUCENCY_SOG][3] = {{0}};
    int n = b->sog.count < TRANSLUCENCY_SOG ? b->sog.count : TRANSLUCENCY_SOG;
    for (int c = 0; c < 3; c++) {
        double total = 0;
        for (int k = 0; k < n; k++) total += b->sog.weight[c][k];
        for (int k = 0; k < n; k++)
            var[k][c] = (float)b->sog.variance[c][k], w[k][c] = (float)(total > 0 ? b->sog.weight[c][k] / total : 0);
    }
    glUniform1i(glGetUniformLocation(p, "u_tr_sog_count"), n);
    if (n) {
        glUniform3fv(glGetUniformLocation(p, "u_tr_sog_var"), n, &var[0][0]);
        glUniform3fv(glGetUniformLocation(p, "u_tr_sog_w"), n, &w[0][0]);
    }
}

double gl_translucency_range(const lucent_renderer *r, int i) { return gl_tables_of(&r->tables, i)->transmit_range; }

/* ---- curved parts (docs/render.md, "Curved parts") ---- */

lucent_status gl_curved_prepare(lucent_renderer *r, const lucent_render_settings *s)
{
    lucent_bake_desc d = gl_renderer_bake_desc(r, s, LUCENT_BAKE_SPHERES);
    lucent_status st = gl_meshes_curvature(&r->meshes, r->scene, s->cdrf.curvature_smooth, r->desc.pool);
    if (st == LUCENT_OK) st = gl_tables_bake(&r->tables, &d, r->cache);
    return st == LUCENT_OK ? gl_tables_upload_spheres(&r->tables) : st;
}

void gl_curved_uniforms(const lucent_renderer *r, int i, GLuint p)
{
    const lucent_baked *b = gl_tables_of(&r->tables, i);
    lucent_material_derived md;
    lucent_material_derive(&r->scene->objects[i].material, &md);
    double tr = fmin(md.sigma_tr[0], fmin(md.sigma_tr[1], md.sigma_tr[2]));
    glUniform1f(glGetUniformLocation(p, "u_sphere_r0"), (float)b->sphere_r0);
    /* light past the terminator enters up to three of the longest diffusion lengths toward the light */
    glUniform1f(glGetUniformLocation(p, "u_sphere_reach"), (float)(3.0 / fmax(tr, 1e-3)));
    /* the spheres hold the light through convex bodies: translucency's convex branch adds none */
    glUniform1f(glGetUniformLocation(p, "u_convex_carried"), 1.0f);
}
