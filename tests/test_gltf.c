/* glTF: the material mapping of lucent/gltf.h against its definitions (Beer-Lambert for
 * KHR_materials_volume's attenuation, the draft KHR_materials_volume_scatter's albedo formula, the
 * inverse), the scene reader on a hand-made asset (values from the glTF 2.0 specification's own
 * definitions: metres, column-major matrices, T R S, quaternions, -z as the view and light direction)
 * and on malformed ones (each error named), and the pack's round trip: pack -> material.gltf -> scene
 * gives the material back exactly, and its sphere traces to the pixels of the same sphere in a JSON
 * scene (whose mesh assimp reads from the same file). Peer checks (Khronos' validator, Blender,
 * glslang) are in tests/pack_peer_test.sh. */
#include <stdint.h>

#include "lucent/gltf.h"
#include "lucent/material.h"
#include "lucent/pack.h"
#include "lucent/scene.h"
#include "lucent/skin.h"
#include "lucent/trace.h"
#include "test.h"

/* ---- the mapping ---- */

TEST(draft_albedo_formula_meets_its_ends_and_inverts)
{
    /* The draft's formula at m = 0 and 1: 1 - (4.09712 - sqrt(9.59217))^2 and
     * 1 - (8.30575 - sqrt(68.98557))^2, which the published constants make ~0 and ~1. */
    CHECK_NEAR(lucent_gltf_single_albedo(0), 1 - pow(4.09712 - sqrt(9.59217), 2), 1e-15);
    CHECK_NEAR(lucent_gltf_single_albedo(0), 0, 1e-5);
    CHECK_NEAR(lucent_gltf_single_albedo(1), 1, 1e-9);
    double last = -1;
    for (int i = 0; i <= 100; i++) {
        double m = i / 100.0, a = lucent_gltf_single_albedo(m);
        CHECK_MSG(a >= last, "not increasing at m = %g", m);
        last = a;
        if (i > 0 && i < 100) CHECK_NEAR(lucent_gltf_multiscatter_albedo(a), m, 1e-12);
    }
}

static lucent_material marble(void)
{
    lucent_material m;
    lucent_status s = lucent_material_preset_find("marble", &m);
    if (s != LUCENT_OK) TEST_FAIL_("marble: %s", lucent_last_error());
    return m;
}

TEST(volume_attenuation_is_the_absorption)
{
    /* Jensen et al. 2001, Figure 5: Marble sigma_a = (0.0021, 0.0041, 0.0071) /mm, sigma_s' = (2.19, 2.62,
     * 3.00) /mm, eta 1.5 (g = 0). KHR_materials_volume: light through x metres keeps
     * attenuationColor^(x / attenuationDistance); that must be exp(-sigma_a x). */
    lucent_material m = marble();
    lucent_gltf_material g;
    CHECK_OK(lucent_gltf_material_from_lucent(&m, 0.3, 0.02, &g));
    const double sa[3] = {0.0021, 0.0041, 0.0071}, ss[3] = {2.19, 2.62, 3.00};
    for (int c = 0; c < 3; c++)
        for (double x_mm = 1; x_mm <= 1000; x_mm *= 10)
            CHECK_NEAR(pow(g.attenuation_color[c], x_mm / 1000 / g.attenuation_distance), exp(-sa[c] * x_mm), 1e-12);
    /* a tenth of the shortest absorption length: colours at least e^-0.1, so (1 - c) / d is within 5% */
    CHECK_NEAR(g.attenuation_distance, 0.1 / 0.0071 / 1000, 1e-15);
    for (int c = 0; c < 3; c++) {
        CHECK((1 - g.attenuation_color[c]) / (g.attenuation_distance * 1000) >= 0.95 * sa[c]);
        CHECK_NEAR(lucent_gltf_single_albedo(g.multiscatter_color[c]), ss[c] / (sa[c] + ss[c]), 1e-12);
    }
    CHECK(g.ior == 1.5 && g.transmission == 1 && g.diffuse_transmission == 1 && g.has_scatter);
    CHECK_NEAR(g.roughness * g.roughness, 0.3, 1e-15);
    CHECK(g.scatter_anisotropy == 0 && g.thickness == 0.02);
    CHECK(g.base_color[0] == 1 && g.base_color[1] == 1 && g.base_color[2] == 1);
}

TEST(inverse_mapping_recovers_every_preset)
{
    for (int i = 0; i < lucent_material_preset_count(); i++) {
        lucent_material m, back;
        lucent_gltf_material g;
        double alpha;
        CHECK_OK(lucent_material_preset(i, &m));
        CHECK_OK(lucent_skin_resolve(&m)); /* a spectral skin as its equivalent medium, as the pack maps it */
        CHECK_OK(lucent_gltf_material_from_lucent(&m, 0.25, 0.05, &g));
        CHECK_OK(lucent_gltf_material_to_lucent(&g, &back, &alpha));
        for (int c = 0; c < 3; c++) {
            CHECK_MSG(fabs(back.sigma_a[c] / m.sigma_a[c] - 1) < 1e-9, "%s sigma_a[%d]: %.9g vs %.9g", m.name, c,
                      back.sigma_a[c], m.sigma_a[c]);
            CHECK_MSG(fabs(back.sigma_s[c] / m.sigma_s[c] - 1) < 1e-6, "%s sigma_s[%d]: %.9g vs %.9g", m.name, c,
                      back.sigma_s[c], m.sigma_s[c]);
        }
        CHECK(back.eta == m.eta);
        CHECK_NEAR(alpha, 0.25, 1e-15);
    }
}

TEST(surface_material_reads_as_a_dense_medium_of_its_colour)
{
    lucent_gltf_material g = {.base_color = {0.5, 0.2, 0.95}, .roughness = 0.5, .ior = 1.4};
    lucent_material m;
    CHECK_OK(lucent_gltf_material_to_lucent(&g, &m, NULL));
    const double want[3] = {0.5, 0.2, LUCENT_GLTF_SURFACE_MAX_ALBEDO};
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(m.sigma_a[c] + m.sigma_s[c], 1 / LUCENT_GLTF_SURFACE_MFP_MM, 1e-15);
        CHECK_NEAR(m.sigma_s[c], lucent_gltf_single_albedo(want[c]), 1e-15);
    }
    CHECK(m.eta == 1.4);
}

TEST(mapping_refuses_what_is_not_a_medium)
{
    lucent_gltf_material g = {.name = "glass", .ior = 0.5, .roughness = 0.1};
    lucent_material m;
    CHECK_ERR(lucent_gltf_material_to_lucent(&g, &m, NULL), LUCENT_ERR_INVALID_ARGUMENT, "glass", "ior 0.5");
    g.ior = 1.5, g.has_volume = true, g.thickness = 1, g.attenuation_distance = 1;
    for (int c = 0; c < 3; c++) g.attenuation_color[c] = 0.5;
    g.attenuation_color[1] = 0;
    CHECK_ERR(lucent_gltf_material_to_lucent(&g, &m, NULL), LUCENT_ERR_INVALID_ARGUMENT, "attenuationColor[1] is 0");
    g.attenuation_color[1] = 1; /* green neither absorbs nor scatters */
    CHECK_ERR(lucent_gltf_material_to_lucent(&g, &m, NULL), LUCENT_ERR_INVALID_ARGUMENT, "channel 1 neither");
    g.attenuation_color[1] = 0.5, g.has_scatter = true, g.multiscatter_color[2] = 1;
    CHECK_ERR(lucent_gltf_material_to_lucent(&g, &m, NULL), LUCENT_ERR_INVALID_ARGUMENT, "multiscatterColor[2]");
    lucent_material bad = marble();
    lucent_gltf_material out;
    CHECK_ERR(lucent_gltf_material_from_lucent(&bad, 1.5, 0.1, &out), LUCENT_ERR_INVALID_ARGUMENT, "roughness 1.5");
    bad.sigma_a[0] = -1;
    CHECK_ERR(lucent_gltf_material_from_lucent(&bad, 0.3, 0.1, &out), LUCENT_ERR_INVALID_ARGUMENT, "sigma_a");
}

/* ---- a hand-made asset ---- */

static void base64(const unsigned char *data, size_t n, char *out)
{
    static const char k[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (size_t i = 0; i < n; i += 3) {
        uint32_t w =
            (uint32_t)data[i] << 16 | (i + 1 < n ? (uint32_t)data[i + 1] << 8 : 0) | (i + 2 < n ? data[i + 2] : 0);
        *out++ = k[w >> 18 & 63], *out++ = k[w >> 12 & 63];
        *out++ = i + 1 < n ? k[w >> 6 & 63] : '=', *out++ = i + 2 < n ? k[w & 63] : '=';
    }
    *out = '\0';
}

/* A tetrahedron with a 1 cm edge along each axis: 48 bytes of positions, 24 of uint16 indices. */
static void tetra_buffer(unsigned char buf[72], uint16_t bad_index)
{
    const float p[12] = {0, 0, 0, 0.01f, 0, 0, 0, 0.01f, 0, 0, 0, 0.01f};
    const uint16_t f[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, bad_index ? bad_index : 3};
    memcpy(buf, p, sizeof p);
    memcpy(buf + 48, f, sizeof f);
}

static const char k_asset[] =
    "{\"asset\": {\"version\": \"2.0\"}, \"scene\": 0, \"scenes\": [{\"nodes\": [0, 1, 2]}],\n"
    " \"nodes\": [{\"name\": \"tet\", \"mesh\": 0, \"translation\": [0.005, 0, 0]},\n"
    "  {\"camera\": 0, \"translation\": [0, 0, 0.1]},\n"
    "  {\"rotation\": [0, 0, 0, 1], \"extensions\": {\"KHR_lights_punctual\": {\"light\": 0}}}],\n"
    " \"cameras\": [{\"type\": \"perspective\", \"perspective\": {\"yfov\": 0.5, \"znear\": 0.001, \"aspectRatio\": "
    "2}}],\n"
    " \"extensions\": {\"KHR_lights_punctual\": {\"lights\": [{\"type\": \"directional\", \"intensity\": 2}]}},\n"
    " \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0}, \"indices\": 1, \"material\": 0}]}],\n"
    " \"materials\": [{\"name\": \"jelly\", \"extensions\": {\"KHR_materials_volume\": {\"thicknessFactor\": 0.01,\n"
    "   \"attenuationDistance\": 0.01, \"attenuationColor\": [0.5, 0.6, 0.7]}, \"KHR_materials_ior\": {\"ior\": 1.4},\n"
    "   \"KHR_materials_volume_scatter\": {\"multiscatterColor\": [0.8, 0.7, 0.6], \"scatterAnisotropy\": 0.2}}}],\n"
    " \"buffers\": [{\"byteLength\": 72, \"uri\": \"%s\"}],\n"
    " \"bufferViews\": [{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": 48}, {\"buffer\": 0, \"byteOffset\": 48, "
    "\"byteLength\": 24}],\n"
    " \"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\", \"min\": [0, 0, "
    "0],"
    " \"max\": [0.01, 0.01, 0.01]},\n"
    "  {\"bufferView\": 1, \"componentType\": 5123, \"count\": 12, \"type\": \"SCALAR\"}]}\n";

static char g_text[8192];

/* The asset with its buffer as a data URI (uri NULL) or as uri. */
static const char *asset(const char *uri, uint16_t bad_index)
{
    unsigned char buf[72];
    char data[200] = "data:application/octet-stream;base64,";
    tetra_buffer(buf, bad_index);
    base64(buf, sizeof buf, data + strlen(data));
    snprintf(g_text, sizeof g_text, k_asset, uri ? uri : data);
    return g_text;
}

/* text with the first `from` replaced by `to` (static buffer). */
static const char *edit(const char *text, const char *from, const char *to)
{
    static char out[8192];
    const char *at = strstr(text, from);
    if (!at) {
        TEST_FAIL_("no \"%s\" in the asset", from);
        return text;
    }
    snprintf(out, sizeof out, "%.*s%s%s", (int)(at - text), text, to, at + strlen(from));
    return out;
}

static lucent_status parse(const char *text, lucent_scene **sc)
{
    return lucent_scene_parse_gltf(text, strlen(text), "tet.gltf", NULL, NULL, sc);
}

TEST(gltf_scene_reads_meshes_cameras_lights_and_materials)
{
    lucent_scene *sc = NULL;
    CHECK_OK(parse(asset(NULL, 0), &sc));
    if (!sc) return;
    CHECK(sc->object_count == 1 && sc->light_count == 1);
    const lucent_mesh *m = sc->objects[0].mesh;
    CHECK(m && m->vertex_count == 4 && m->face_count == 4);
    /* metres to mm, moved by the node's translation of 5 mm along x */
    double lo[3], hi[3];
    lucent_scene_bounds(sc, lo, hi);
    CHECK_NEAR(lo[0], 5, 1e-6);
    CHECK_NEAR(hi[0], 15, 1e-6);
    CHECK_NEAR(hi[1], 10, 1e-6);
    CHECK_NEAR(hi[2], 10, 1e-6);
    /* outward faces: the normal at the vertex on +z points away from the centre */
    for (size_t v = 0; m && v < m->vertex_count; v++)
        if (m->positions[3 * v + 2] > 9) CHECK(m->normals[3 * v + 2] > 0.5);
    /* the camera: 0.1 m on +z looking down -z, yfov 0.5 rad */
    CHECK_NEAR(sc->camera.position[2], 100, 1e-9);
    CHECK(sc->camera.target[2] < 100 && sc->camera.target[0] == 0 && sc->camera.target[1] == 0);
    CHECK_NEAR(sc->camera.fov_y, 0.5 * 180 / M_PI, 1e-12);
    CHECK_NEAR(sc->camera.near_plane, 1, 1e-12);
    CHECK(sc->render.view.width == 1024 && sc->render.view.height == 512); /* aspectRatio 2 */
    /* the light travels along its node's -z, 2 lux */
    CHECK(sc->lights[0].type == LUCENT_LIGHT_DIRECTIONAL && sc->lights[0].intensity == 2);
    CHECK_NEAR(sc->lights[0].direction[2], -1, 1e-12);
    /* the material: sigma_a = -ln(colour) / distance (10 mm), sigma_s from the draft's albedo */
    const lucent_material *mat = &sc->objects[0].material;
    const double col[3] = {0.5, 0.6, 0.7}, ms[3] = {0.8, 0.7, 0.6};
    for (int c = 0; c < 3; c++) {
        double sa = -log(col[c]) / 10, a = lucent_gltf_single_albedo(ms[c]);
        CHECK_NEAR(mat->sigma_a[c], sa, 1e-12);
        CHECK_NEAR(mat->sigma_s[c], sa * a / (1 - a), 1e-9);
        CHECK(mat->g[c] == 0.2);
    }
    CHECK(mat->eta == 1.4 && !strcmp(mat->name, "jelly"));
    CHECK_NEAR(sc->objects[0].roughness, 1, 0); /* roughnessFactor's default 1 */
    CHECK(strstr(sc->json, "\"gltf\"") != NULL);
    lucent_scene_destroy(sc);
}

TEST(gltf_node_transforms_compose_parent_times_child)
{
    /* the mesh under a parent turned 90 degrees about z (quaternion (0, 0, sin 45, cos 45)), itself
     * scaled by 2: x -> 2x -> y. */
    char text[8192];
    snprintf(text, sizeof text, "%s",
             edit(asset(NULL, 0), "{\"name\": \"tet\", \"mesh\": 0, \"translation\": [0.005, 0, 0]}",
                  "{\"children\": [3], \"rotation\": [0, 0, 0.70710678118654752, 0.70710678118654752]}"));
    const char *t = edit(text, "{\"light\": 0}}}]", "{\"light\": 0}}}, {\"mesh\": 0, \"scale\": [2, 2, 2]}]");
    lucent_scene *sc = NULL;
    CHECK_OK(parse(t, &sc));
    if (!sc) return;
    double lo[3], hi[3];
    lucent_scene_bounds(sc, lo, hi);
    CHECK_NEAR(lo[0], -20, 1e-6); /* the y edge (10 mm, x 2) turned onto -x */
    CHECK_NEAR(hi[0], 0, 1e-6);
    CHECK_NEAR(hi[1], 20, 1e-6); /* the x edge onto +y */
    CHECK_NEAR(hi[2], 20, 1e-6);
    lucent_scene_destroy(sc);
}

TEST(gltf_external_buffer_and_glb)
{
    unsigned char buf[72];
    tetra_buffer(buf, 0);
    FILE *f = fopen(test_path("tet ra.bin"), "wb");
    CHECK(f && fwrite(buf, 1, sizeof buf, f) == sizeof buf);
    if (f) fclose(f);
    f = fopen(test_path("ext.gltf"), "w");
    CHECK(f && fputs(asset("tet%20ra.bin", 0), f) >= 0); /* a space, %-encoded as URIs have it */
    if (f) fclose(f);
    lucent_scene *sc = NULL;
    CHECK_OK(lucent_scene_load(test_path("ext.gltf"), NULL, &sc));
    CHECK(sc && sc->objects[0].mesh && sc->objects[0].mesh->face_count == 4);
    lucent_scene_destroy(sc);
    /* the same as GLB: the JSON chunk (padded with spaces) and the BIN chunk */
    const char *json = edit(asset(NULL, 0), "\"uri\": \"", "\"extras\": \"");
    size_t jn = (strlen(json) + 3) / 4 * 4, total = 12 + 8 + jn + 8 + 72;
    unsigned char *glb = calloc(1, total);
    uint32_t head[5] = {0x46546C67, 2, (uint32_t)total, (uint32_t)jn, 0x4E4F534A};
    memcpy(glb, head, sizeof head);
    memset(glb + 20, ' ', jn);
    memcpy(glb + 20, json, strlen(json));
    uint32_t bin[2] = {72, 0x004E4942};
    memcpy(glb + 20 + jn, bin, 8);
    memcpy(glb + 28 + jn, buf, 72);
    CHECK_OK(lucent_scene_parse_gltf(glb, total, "tet.glb", NULL, NULL, &sc));
    CHECK(sc && sc->objects[0].mesh && sc->objects[0].mesh->vertex_count == 4);
    lucent_scene_destroy(sc);
    /* malformed GLB: version 1, a length past the end, no JSON chunk first */
    uint32_t v1 = 1;
    memcpy(glb + 4, &v1, 4);
    CHECK_ERR(lucent_scene_parse_gltf(glb, total, "tet.glb", NULL, NULL, &sc), LUCENT_ERR_UNSUPPORTED, "tet.glb",
              "GLB version 1");
    memcpy(glb + 4, head + 1, 4);
    CHECK_ERR(lucent_scene_parse_gltf(glb, total - 1, "tet.glb", NULL, NULL, &sc), LUCENT_ERR_PARSE, "tet.glb",
              "the header says");
    memcpy(glb + 16, bin + 1, 4);
    CHECK_ERR(lucent_scene_parse_gltf(glb, total, "tet.glb", NULL, NULL, &sc), LUCENT_ERR_PARSE,
              "the first chunk is not JSON");
    CHECK_ERR(lucent_scene_parse_gltf(glb, 15, "tet.glb", NULL, NULL, &sc), LUCENT_ERR_PARSE,
              "shorter than its header");
    free(glb);
}

typedef struct bad_case {
    const char *from, *to, *message;
} bad_case;

TEST(malformed_gltf_fails_naming_the_file_and_the_member)
{
    static const bad_case cases[] = {
        {"\"count\": 4,", "\"count\": 5,", "accessors[0].count: 5 elements of 12 bytes"},
        {"\"count\": 12,", "\"count\": 13,", "accessors[1].count: 13 elements"},
        {"\"byteOffset\": 0, \"byteLength\": 48}", "\"byteOffset\": 0, \"byteLength\": 4800}",
         "past the end of buffers[0]"},
        {"\"byteLength\": 72,", "\"byteLength\": 720,", "buffers[0].byteLength: 720 bytes, the data holds 72"},
        {"base64,", "base64,*", "buffers[0].uri: not base64"},
        {"\"POSITION\": 0", "\"POSITION\": 9", "POSITION: 9: no such accessor"},
        {"\"componentType\": 5126", "\"componentType\": 5121", "not what POSITION takes"},
        {"\"type\": \"VEC3\"", "\"type\": \"VEC2\"", "\"VEC2\": POSITION takes VEC3"},
        {"\"bufferView\": 1,", "\"bufferView\": 7,", "7: no such buffer view"},
        {"\"bufferView\": 1,", "\"sparse\": {}, \"bufferView\": 1,", "sparse accessors are not read"},
        {"\"min\": [0, 0, 0],", "", "accessors[0].min: missing field"},
        {"\"nodes\": [0, 1, 2]", "\"nodes\": [0, 1, 2, 9]", "scenes[0].nodes[3]: 9: no such node"},
        {"\"translation\": [0, 0, 0.1]}", "\"translation\": [0, 0, 0.1], \"children\": [1]}", "reached twice"},
        {"\"translation\": [0.005, 0, 0]", "\"matrix\": [1,0,0,1, 0,1,0,0, 0,0,1,0, 0,0,0,1]", "not affine"},
        {"\"rotation\": [0, 0, 0, 1]", "\"rotation\": [0, 0, 0, 0]", "not a unit quaternion"},
        {"\"yfov\": 0.5", "\"yfov\": 0", "cameras[0].perspective.yfov"},
        {"\"type\": \"directional\"", "\"type\": \"area\"", "\"area\": expected directional, point or spot"},
        {"\"ior\": 1.4", "\"ior\": 0.5", "materials[0]: jelly: ior 0.5"},
        {"[0.5, 0.6, 0.7]", "[0, 0.6, 0.7]", "attenuationColor[0] is 0"},
        {"[0.5, 0.6, 0.7]", "[1.5, 0.6, 0.7]", "attenuationColor[0]: must be in [0, 1]"},
        {"\"material\": 0", "\"material\": 3", "3: no such material"},
        {"\"indices\": 1,", "\"indices\": 1, \"mode\": 1,", "no mesh of triangles"},
        {"\"indices\": 1,", "\"indices\": 1, \"mode\": 1e300,", "mode: must be 0 to 6"},
        {"\"material\": 0", "\"material\": 1e300", "must be a material index"},
        {"\"version\": \"2.0\"", "\"version\": \"1.0\"", "glTF 1.0 (only 2.x is read)"},
        {"\"uri\": \"data:", "\"uri\": \"../x.bin\", \"x\": \"", "only files in the asset's folder"},
    };
    const char *base = asset(NULL, 0);
    char copy[8192];
    snprintf(copy, sizeof copy, "%s", base);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        lucent_scene *sc = NULL;
        lucent_status s = parse(edit(copy, cases[i].from, cases[i].to), &sc);
        CHECK_MSG(s != LUCENT_OK && strstr(lucent_last_error(), cases[i].message) &&
                      strstr(lucent_last_error(), "tet.gltf"),
                  "case %zu: %s -> %s", i, lucent_status_string(s), lucent_last_error());
        lucent_scene_destroy(sc);
    }
    /* absolute paths and schemes, a file from memory, an index past the vertices, a NaN position */
    lucent_scene *sc = NULL;
    CHECK_ERR(parse(asset("/etc/passwd", 0), &sc), LUCENT_ERR_UNSUPPORTED, "only files in the asset's folder");
    CHECK_ERR(parse(asset("http://example.com/x.bin", 0), &sc), LUCENT_ERR_UNSUPPORTED, "no scheme");
    CHECK_ERR(parse(asset("x.bin", 0), &sc), LUCENT_ERR_UNSUPPORTED, "given from memory");
    CHECK_ERR(parse(asset(NULL, 9), &sc), LUCENT_ERR_PARSE, "accessors[1]: index 11 is 9, past the 4 vertices");
    unsigned char buf[72];
    char text[8192], data[200] = "data:application/octet-stream;base64,";
    tetra_buffer(buf, 0);
    const uint32_t nan = 0x7fc00000;
    memcpy(buf + 16, &nan, 4);
    base64(buf, sizeof buf, data + strlen(data));
    snprintf(text, sizeof text, k_asset, data);
    CHECK_ERR(parse(text, &sc), LUCENT_ERR_PARSE, "accessors[0]: vertex 1 is not finite");
    CHECK_ERR(lucent_scene_parse_gltf("glTF", 4, "x.glb", NULL, NULL, &sc), LUCENT_ERR_PARSE, "x.glb");
    CHECK_ERR(lucent_scene_parse_gltf("{", 1, "x.gltf", NULL, NULL, &sc), LUCENT_ERR_PARSE, "x.gltf");
    CHECK_ERR(lucent_scene_parse_gltf("[]", 2, "x.gltf", NULL, NULL, &sc), LUCENT_ERR_PARSE, "expected a glTF object");
    /* 300 nested nodes */
    char *deep = malloc(20000);
    int n = snprintf(deep, 20000, "{\"asset\": {\"version\": \"2.0\"}, \"scenes\": [{\"nodes\": [0]}], \"nodes\": [");
    for (int i = 0; i < 300; i++) n += snprintf(deep + n, 20000 - n, "%s{\"children\": [%d]}", i ? "," : "", i + 1);
    snprintf(deep + n, 20000 - n, ",{}]}");
    CHECK_ERR(parse(deep, &sc), LUCENT_ERR_UNSUPPORTED, "nested deeper than 256");
    free(deep);
}

/* ---- the pack's round trip ---- */

static lucent_status trace(lucent_scene *sc, lucent_trace_result *r)
{
    lucent_tracer *tr = NULL;
    lucent_status s = lucent_tracer_create(sc, NULL, &tr);
    if (s == LUCENT_OK) s = lucent_tracer_render(tr, &(lucent_trace_desc){.spp = 2, .seed = 7}, r);
    lucent_tracer_destroy(tr);
    return s;
}

TEST(pack_gltf_round_trip_gives_the_material_and_the_pixels)
{
    lucent_material m = marble();
    const char *dir = test_path("pack");
    char out[1024], gltf[1100];
    snprintf(out, sizeof out, "%s", dir);
    lucent_pack_desc d = {.engine = LUCENT_PACK_JSON,
                          .out = out,
                          .object_height_mm = 20,
                          .sigma0_photons = 500,
                          .transmit_photons = 100,
                          .lut_width = 8,
                          .lut_height = 8,
                          .no_fit = true};
    lucent_pack_result r;
    CHECK_OK(lucent_pack(&m, &d, &r));
    snprintf(gltf, sizeof gltf, "%s/material.gltf", out);
    static const char *const small[] = {"render.width=20", "render.height=16"};
    lucent_scene *sc = NULL;
    CHECK_OK(lucent_scene_load(gltf, &(lucent_scene_load_desc){.overrides = small, .override_count = 2}, &sc));
    if (!sc) return;
    /* the exact medium, from extras.lucent */
    const lucent_material *back = &sc->objects[0].material;
    CHECK(!memcmp(back->sigma_a, m.sigma_a, sizeof m.sigma_a) && !memcmp(back->sigma_s, m.sigma_s, sizeof m.sigma_s));
    CHECK(!memcmp(back->g, m.g, sizeof m.g) && back->eta == m.eta && sc->objects[0].roughness == 0.3);
    /* the sphere, 20 mm across; the camera at the depth where it fills the screen's height (Freude's
     * pinhole: h / (2 tan(fov / 2))), looking down -z; the key light along (0.55, -0.45, -0.7) */
    double lo[3], hi[3], depth = 20 / (2 * tan(22.5 * M_PI / 180)), dir3[3] = {0.55, -0.45, -0.7};
    lucent_scene_bounds(sc, lo, hi);
    CHECK_NEAR(hi[1] - lo[1], 20, 1e-4);
    CHECK_NEAR(sc->camera.position[2], depth, 1e-9);
    CHECK_NEAR(sc->camera.fov_y, 45, 1e-12);
    double len = sqrt(0.55 * 0.55 + 0.45 * 0.45 + 0.7 * 0.7);
    for (int k = 0; k < 3; k++) CHECK_NEAR(sc->lights[0].direction[k], dir3[k] / len, 1e-12);
    CHECK_NEAR(r.thickness_m, 0.02 * 2 / 3, 2e-4); /* a sphere's mean chord 4 V / A = 4 r / 3 */
    /* the same sphere in a JSON scene, its mesh read by assimp from the same file */
    char json[4096];
    const lucent_camera *c = &sc->camera;
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [%.17g, %.17g, %.17g], \"target\": [%.17g, %.17g, %.17g], \"fov_y\": %.17g, "
             "\"near\": %.17g},\n \"lights\": [{\"type\": \"directional\", \"intensity\": 3, \"direction\": [%.17g, "
             "%.17g, %.17g]}],\n \"objects\": [{\"mesh\": \"material.gltf\", \"mm_per_unit\": 1000, \"material\": "
             "\"marble\", \"roughness\": 0.3}],\n \"render\": {\"width\": 20, \"height\": 16}}\n",
             c->position[0], c->position[1], c->position[2], c->target[0], c->target[1], c->target[2], c->fov_y,
             c->near_plane, sc->lights[0].direction[0], sc->lights[0].direction[1], sc->lights[0].direction[2]);
    lucent_scene *js = NULL;
    CHECK_OK(lucent_scene_parse(json, "sphere.json", out, NULL, &js));
    lucent_trace_result a = {0}, b = {0};
    if (js) CHECK_OK(trace(sc, &a));
    if (js) CHECK_OK(trace(js, &b));
    if (a.image && b.image) {
        double diff = 0, sum = 0;
        for (int y = 0; y < 16; y++)
            for (int x = 0; x < 20; x++)
                for (int k = 0; k < 3; k++) {
                    diff = fmax(diff, fabs(lucent_image_get(a.image, x, y, k) - lucent_image_get(b.image, x, y, k)));
                    sum += lucent_image_get(a.image, x, y, k);
                }
        CHECK_MSG(diff == 0 && sum > 0, "glTF and JSON spheres differ by %g (sum %g)", diff, sum);
    }
    lucent_trace_result_free(&a);
    lucent_trace_result_free(&b);
    lucent_scene_destroy(js);
    lucent_scene_destroy(sc);
}

TEST_MAIN(TEST_ENTRY(draft_albedo_formula_meets_its_ends_and_inverts), TEST_ENTRY(volume_attenuation_is_the_absorption),
          TEST_ENTRY(inverse_mapping_recovers_every_preset),
          TEST_ENTRY(surface_material_reads_as_a_dense_medium_of_its_colour),
          TEST_ENTRY(mapping_refuses_what_is_not_a_medium),
          TEST_ENTRY(gltf_scene_reads_meshes_cameras_lights_and_materials),
          TEST_ENTRY(gltf_node_transforms_compose_parent_times_child), TEST_ENTRY(gltf_external_buffer_and_glb),
          TEST_ENTRY(malformed_gltf_fails_naming_the_file_and_the_member),
          TEST_ENTRY(pack_gltf_round_trip_gives_the_material_and_the_pixels))
