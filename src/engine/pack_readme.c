/* The pack's README.md: what a programmer needs to wire the pack into an engine, with this pack's
 * numbers: the files, the passes in order and the buffers each reads and writes, the kernel width from
 * the camera, thickness and curvature at run time, the composition with the specular, the engine's
 * bindings, the glTF mapping, and the engine parameters fitted to the material (readme_fitted). */
#include <stdlib.h>
#include <string.h>

#include "engine/internal.h"
#include "lucent/gltf.h"

static void files(FILE *f, const pack_ctx *p)
{
    lucent_pack_engine e = p->d.engine;
    bool hlsl = e == LUCENT_PACK_HLSL, shaders = e != LUCENT_PACK_JSON;
    const char *x = hlsl ? "hlsl" : "glsl";
    fputs("## Files\n\n| file | what |\n|---|---|\n", f);
    fprintf(f, "| `taps.%s` | the separable kernel's taps: %d per 1-D pass, %d pass(es), offsets in mm |\n",
            e == LUCENT_PACK_JSON ? "json" : x, p->b->taps->count, p->b->taps->rank);
    if (shaders) {
        fprintf(f, "| `%s` | one 1-D pass of the blur, a complete %s |\n", hlsl ? "blur.hlsl" : "blur.frag.glsl",
                hlsl                      ? "pixel shader (entry point `main`, ps_5_0)"
                : e == LUCENT_PACK_GLES   ? "GLSL ES 3.00 fragment shader (WebGL2)"
                : e == LUCENT_PACK_VULKAN ? "Vulkan GLSL fragment shader (compile to SPIR-V)"
                                          : "GLSL 4.50 fragment shader");
        fprintf(f, "| `cdrf.%s` | `lucent_cdrf(lut, n_dot_l, kappa)`: the CDRF in place of Lambert (snippet) |\n", x);
        fprintf(f,
                "| `translucency.%s` | `lucent_transmittance(s_mm)`: T(s) for light through thin parts (snippet) |\n",
                x);
    }
    fprintf(f,
            "| `cdrf-lut.exr`, `cdrf-lut.png` | the CDRF look-up table, %d x %d RGB: float, and 16-bit linear PNG of "
            "value / %g |\n"
            "| `transmittance.csv`, `transmittance.png` | T(s) per channel: a table, and a %d x 1 16-bit linear PNG |\n"
            "| `constants.json` | every number of the pack |\n"
            "| `material.gltf` | a glTF 2.0 scene: a mesh in this material, the pack's camera and a key light |\n\n",
            p->d.lut_width, p->d.lut_height, p->lut_png_scale, LUCENT_BAKE_TRANSMIT_SIZE);
}

static void passes(FILE *f, const pack_ctx *p)
{
    int rank = p->b->taps->rank;
    fprintf(f,
            "## The passes, in order\n\n"
            "| # | pass | reads | writes |\n|---|---|---|---|\n"
            "| 1 | shadow maps, per light (for translucency) | the scene | a depth map per light |\n"
            "| 2 | surface | the scene, the shadow maps, `translucency` | **diffuse** (RGB: albedo x (E max(n.l, 0) "
            "visibility / pi + ambient) + the light through thin parts; A: the blur's strength, 0 to 1), "
            "**specular** (RGB: the boundary's reflection; A: the diffuse light's way out, see below), **depth** "
            "(R: linear view depth in scene units, 0 for the background) |\n"
            "| 3 | blur, horizontal: `axis = (1, 0)`, `vertical = 0`, `pass = k` | diffuse, depth | a temporary |\n"
            "| 4 | blur, vertical: `axis = (0, 1)`, `vertical = 1`, `pass = k` | the temporary, depth | **blurred**, "
            "added (blend ONE, ONE) |\n"
            "| 5 | compose | diffuse, blurred, specular, depth | the image: `mix(diffuse, blurred, diffuse.a) * "
            "specular.a + specular.rgb` |\n\n"
            "Passes 3 and 4 run once per kernel pass k = 0 .. %d (`LUCENT_SSS_RANK` = %d); clear **blurred** to 0 "
            "first. The targets want 16-bit float RGBA (the depth: 32-bit float R). The diffuse is the irradiance "
            "times the albedo, before the blur; the albedo is the material's total diffuse reflectance "
            "(`constants.json` `diffuse_rd`, the dipole's; `lucent render` uses the Monte Carlo value). Instead "
            "of the blur, the CDRF (`lucent_cdrf` in place of `max(n.l, 0)` in pass 2, curvature below) gives "
            "the diffusion round curved parts without passes 3 and 4.\n\n",
            rank - 1, rank);
}

static void width(FILE *f, const pack_ctx *p)
{
    fprintf(f,
            "## The kernel's width from the camera\n\n"
            "A tap at offset o (mm) lands `o * pixels_per_mm_at_1mm * width_scale / z` pixels from the centre, z "
            "the linear depth in mm (`depth * mm_per_unit`), with\n\n"
            "    pixels_per_mm_at_1mm = height_px / (2 tan(fov_y / 2))\n\n"
            "for a perspective camera (square pixels). This pack's screen, %d x %d at fov_y %g degrees, gives "
            "%.9g; recompute it when the resolution or the field of view changes. The kernel's half-width is "
            "R = %.9g mm, so an object at %.6g mm gets a kernel %.4g px wide (`lucent pack` prints it). The "
            "follow-surface test moves a tap's sample toward the centre by min(|dz| / R, 1) (Jimenez; Freude "
            "Eq. 4.12), so the blur does not cross silhouettes. Scene units: `mm_per_unit` is 1000 for metres "
            "(glTF, Unreal's cm: 10, Unity's m: 1000). For an orthographic camera use `step = height_px / "
            "view_height_mm` in place of `pixels_per_mm_at_1mm / z`.\n\n",
            p->d.screen_width, p->d.screen_height, p->d.fov_y, p->r.pixels_per_mm_at_1mm, p->r.radius_mm, p->r.depth_mm,
            p->r.width_px);
}

static void thickness(FILE *f, const pack_ctx *p)
{
    fprintf(f,
            "## Thickness at run time (translucency)\n\n"
            "Light through thin parts (ears, fingers, leaves: Jimenez et al. 2010) reaches the back of a part and "
            "leaves at the front: in pass 2, for each light with n.l < 0,\n\n"
            "    s = max(d_light(P - n * offset) - d_shadow(uv), 0)   // mm, along the light\n"
            "    diffuse.rgb += E * max(-n.l, 0) * lucent_transmittance(s) / pi%s\n\n"
            "where d_light is the point's linear depth in the light's view, d_shadow the depth the shadow map "
            "holds there (where the light entered), and P moved a shadow texel inward along the normal. "
            "`lucent_transmittance` interpolates T(s), tabulated to %.6g mm (`transmittance.csv`, `.png`). "
            "Without shadow maps, a constant thickness serves: the glTF's `thicknessFactor`, %.6g m, the mesh's "
            "mean chord 4 V / A.\n\n",
            p->rs->translucency.transmittance == LUCENT_TRANSMIT_SLAB ? "" : " * albedo", p->b->transmit_range,
            p->r.thickness_m);
}

static void curvature(FILE *f, const pack_ctx *p)
{
    fprintf(f,
            "## Curvature at run time (CDRF)\n\n"
            "`lucent_cdrf` takes the mean curvature kappa in 1/mm (> 0 on convex parts; a sphere of radius r has "
            "1/r). Either bake it per vertex (`lucent curvature MESH --mm-per-unit N --out curvature.csv`, in 1/mm) "
            "and pass it as a vertex attribute, or estimate it per pixel from screen-space "
            "derivatives,\n\n"
            "    kappa = length(fwidth(N)) / length(fwidth(P_mm))\n\n"
            "(the estimate of pre-integrated skin shading, Penner & Borshukov 2011), which is noisy at silhouettes "
            "and zero on flat parts. The table covers 0 to %g 1/mm; larger curvatures read its last row.\n\n",
            p->d.kappa_max);
}

static void compose(FILE *f)
{
    fputs("## Composing with the specular\n\n"
          "The specular is not blurred. The boundary's reflection (a GGX lobe with the material's roughness and "
          "Fresnel at its index of refraction) goes to its own target in pass 2; the compose pass adds it after "
          "the blur. The diffuse light leaves through the boundary, so the blurred diffuse is multiplied by the "
          "way out toward the eye, `(1 - F(n.v, eta)) / mean_Ft(eta)` (F the dielectric Fresnel reflectance, "
          "mean_Ft its hemispherical transmittance), kept in the specular target's alpha. In an engine with its "
          "own lighting (Unreal, Unity, Godot), blur only the diffuse lighting buffer and let the engine add "
          "the specular afterwards.\n\n",
          f);
}

static void bindings(FILE *f, const pack_ctx *p)
{
    fputs("## Bindings\n\n", f);
    switch (p->d.engine) {
    case LUCENT_PACK_GLSL:
        fputs("OpenGL 4.5: `u_irradiance` at texture unit 0, `u_depth` at 1 (`binding` qualifiers); the uniforms have "
              "default values (this pack's screen), so a pass sets only `u_axis`, `u_pass` and `u_vertical`.\n\n",
              f);
        break;
    case LUCENT_PACK_GLES:
        fputs("GLSL ES 3.00 (WebGL2, three.js `ShaderMaterial` with `glslVersion: THREE.GLSL3`, Babylon.js): no "
              "binding qualifiers and no default values, so set every uniform: the samplers' texture units with "
              "`uniform1i`, `u_mm_per_unit` (1000 for metres), `u_pixels_per_mm_at_1mm` (above), `u_width_scale` "
              "(1) and, per pass, `u_axis`, `u_pass`, `u_vertical`. Rendering to float targets needs "
              "`EXT_color_buffer_float` in WebGL2. Include `cdrf.glsl` and `translucency.glsl` after the "
              "`#version 300 es` and precision lines.\n\n",
              f);
        break;
    case LUCENT_PACK_VULKAN:
        fputs("Vulkan: `glslangValidator -V -S frag blur.frag.glsl -o blur.spv`. Set 0: binding 0 `u_irradiance`, "
              "binding 1 `u_depth`, combined image samplers (nearest filtering: the pass reads texels); one "
              "push-constant range of 28 bytes, fragment stage: `u_axis` (vec2, offset 0), `u_pass` (int, 8), "
              "`u_vertical` (int, 12), `u_mm_per_unit` (16), `u_pixels_per_mm_at_1mm` (20), `u_width_scale` (24). "
              "Samplers passed to `lucent_cdrf` are combined image samplers too.\n\n",
              f);
        break;
    case LUCENT_PACK_HLSL:
        fputs("Direct3D 11/12: `irradiance` at t0, `depth` at t1, the constants in cbuffer b0 (`axis`, "
              "`pass_index`, `vertical`, `mm_per_unit`, `pixels_per_mm_at_1mm`, `width_scale`); compile with "
              "`dxc -T ps_6_0 -E main blur.hlsl` or `fxc /T ps_5_0 /E main blur.hlsl`. `lucent_cdrf` takes the "
              "LUT and a linear clamp sampler.\n\n",
              f);
        break;
    default:
        fputs("The json engine writes the data only: write the passes in your engine's language from the taps "
              "(`taps.json`) and the tables.\n\n",
              f);
    }
}

static void lut(FILE *f, const pack_ctx *p)
{
    fprintf(f,
            "## The CDRF look-up table\n\n"
            "Column i holds cos theta = -1 + 2 i / (width - 1) (left: light from behind); row j, counted from the "
            "top row of the file, holds kappa = %g j / (height - 1) 1/mm; channel c is Kubo's CDRF at sigma = "
            "sigma0_c kappa with sigma0 = (%.6g, %.6g, %.6g) mm. Upload the rows in file order so that t = 0 is "
            "kappa = 0, and read with linear filtering at the texel centres (as `lucent_cdrf` does). "
            "`cdrf-lut.png` is 16-bit and linear (gAMA 1.0): multiply by %g (`LUCENT_CDRF_LUT_PNG_SCALE`). The "
            "radiance is `k_d * CDRF * E` with k_d = (%.6g, %.6g, %.6g).\n\n",
            p->d.kappa_max, p->b->sigma0[0], p->b->sigma0[1], p->b->sigma0[2], p->lut_png_scale, p->b->kd[0],
            p->b->kd[1], p->b->kd[2]);
}

static void gltf(FILE *f, const pack_ctx *p)
{
    lucent_gltf_material g;
    if (lucent_gltf_material_from_lucent(p->m, p->d.roughness, p->r.thickness_m, &g) != LUCENT_OK) return;
    fprintf(f,
            "## material.gltf\n\n"
            "A mesh %.6g m tall in the material, the pack's camera and a directional key light "
            "(`KHR_lights_punctual`), in metres. The material (docs/pack.md in Lucent):\n\n"
            "| extension | values |\n|---|---|\n"
            "| `KHR_materials_ior` | ior %.6g |\n"
            "| `KHR_materials_transmission` | transmissionFactor 1, base colour white: a clear boundary |\n"
            "| `KHR_materials_volume` | the absorption: attenuationDistance %.6g m, attenuationColor (%.6g, %.6g, "
            "%.6g), thicknessFactor %.6g |\n"
            "| `KHR_materials_diffuse_transmission` | factor 1: the cue for a dense medium |\n"
            "| `KHR_materials_volume_scatter` (draft) | multiscatterColor (%.6g, %.6g, %.6g), scatterAnisotropy "
            "%.6g |\n"
            "| `extras.lucent` | the exact medium: sigma_a, sigma_s, g per channel (mm^-1), eta, roughness |\n\n"
            "The draft reads attenuationColor and attenuationDistance as the extinction; ratified "
            "`KHR_materials_volume` (and every released importer) as the absorption, which is what they hold here. "
            "A renderer without volume scattering should draw the total diffuse reflectance (%.6g, %.6g, %.6g) "
            "(`extras.lucent.rd`). `lucent render material.gltf` draws this scene.\n\n",
            p->d.object_height_mm / 1000, g.ior, g.attenuation_distance, g.attenuation_color[0], g.attenuation_color[1],
            g.attenuation_color[2], g.thickness, g.multiscatter_color[0], g.multiscatter_color[1],
            g.multiscatter_color[2], g.scatter_anisotropy, p->derived.rd[0], p->derived.rd[1], p->derived.rd[2]);
}

/* The engine parameters fitted to the material: the report of lucent/engine.h (what `lucent fit` writes
 * as PREFIX.md), its title left out and its engines' headings one level down. */
static void readme_fitted(FILE *f, const pack_ctx *p)
{
    fputs("## Engine parameters fitted to this material\n\n", f);
    char *md = NULL;
    if (!p->fit) {
        fprintf(f,
                "Left out when this pack was made (`--no-fit`): `lucent fit %s` gives each engine's parameters "
                "(Unreal, Unity HDRP, Blender, OpenPBR, Godot, glTF) with their error against Lucent's Monte Carlo "
                "reference.\n",
                p->m->name);
        return;
    }
    if (lucent_engine_report_markdown(p->fit, &md) != LUCENT_OK) {
        fputs("(out of memory writing the fitted parameters)\n", f);
        return;
    }
    fprintf(
        f,
        "What to type into each engine so that it draws %s, fitted by Lucent's library (`lucent_engine_report_run`, "
        "the numbers of `lucent fit %s --no-hand` with the same photons; docs/engines.md in Lucent says how). ",
        p->m->name, p->m->name);
    const char *line = strchr(md, '\n'); /* past the report's title */
    for (line = line ? line + 1 : md; *line == '\n'; line++) {
    }
    while (*line) {
        const char *end = strchr(line, '\n');
        size_t n = end ? (size_t)(end - line + 1) : strlen(line);
        if (!strncmp(line, "## ", 3)) fputc('#', f);
        fwrite(line, 1, n, f);
        line += n;
    }
    free(md);
}

void pack_readme(FILE *f, const pack_ctx *p)
{
    fprintf(f,
            "# %s for %s: a Lucent engine pack\n\n"
            "Made by Lucent %s: the separable subsurface-scattering blur, the curvature-dependent reflectance "
            "(CDRF) and the translucency of thin parts for the material %s (sigma_a %.6g %.6g %.6g, sigma_s "
            "%.6g %.6g %.6g /mm, g %.6g, eta %.6g), baked with the renderer's settings (kernel %s, %d taps, "
            "profile %s), so that the engine draws what `lucent render` draws.\n\n",
            p->m->name, lucent_pack_engine_name(p->d.engine), LUCENT_VERSION_STRING, p->m->name, p->m->sigma_a[0],
            p->m->sigma_a[1], p->m->sigma_a[2], p->m->sigma_s[0], p->m->sigma_s[1], p->m->sigma_s[2], p->m->g[0],
            p->m->eta, lucent_kernel_model_name((lucent_kernel_model)p->rs->ssss.kernel), p->b->taps->count,
            p->rs->ssss.profile);
    files(f, p);
    passes(f, p);
    width(f, p);
    thickness(f, p);
    curvature(f, p);
    compose(f);
    bindings(f, p);
    lut(f, p);
    gltf(f, p);
    readme_fitted(f, p);
}
