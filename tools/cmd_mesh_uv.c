/* `lucent mesh-uv`: a mesh's texture atlas (its own coordinates, or Lucent's charts for a mesh that
 * has none), written as OBJ or glTF with a picture of the charts and the atlas's measures. */
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli.h"
#include "lucent/image.h"
#include "lucent/mesh.h"

static const char k_usage[] =
    "usage: lucent mesh-uv IN --out OUT.obj|OUT.gltf [--png FILE] [--size N] [--angle DEG] [--gutter T] [--atlas]\n"
    "\n"
    "Writes the mesh IN (PLY, .ply.gz, OBJ, glTF) with texture coordinates to OUT (.obj: one vt per\n"
    "corner; .gltf: one file, the buffer embedded). A mesh with its own coordinates keeps them; one\n"
    "without (the Stanford scans) gets Lucent's atlas (docs/tsd.md): charts grown by normal cone,\n"
    "each projected on its seed's plane without overlap, packed on shelves with gutters. Prints the\n"
    "charts, Sander et al.'s area-weighted L2 stretch (1: no stretch) and the overlapping texels\n"
    "of a raster of the atlas (0: no two faces share a texel).\n"
    "\n"
    "options:\n"
    "  --out FILE     the mesh with its coordinates, .obj or .gltf (required; the form\n"
    "                 `lucent mesh-uv IN OUT` of Lucent 0.1 still works, with a note)\n"
    "  --png FILE     the picture of the charts (default: OUT with .png)\n"
    "  --size N       texels along a side: the picture, the overlap raster and the gutter (default 1024)\n"
    "  --angle DEG    a chart's normal cone, degrees (default 40)\n"
    "  --gutter T     texels between charts at --size (default 4)\n"
    "  --atlas        make the atlas even when the mesh has coordinates\n"
    "  -h, --help     show this help\n"
    "\n"
    "examples:\n"
    "  lucent mesh-uv data/meshes/bunny.ply --out out/bunny-uv.obj\n"
    "  lucent mesh-uv data/meshes/dragon_vrip_res2.ply.gz --out out/dragon-uv.gltf --size 2048\n";

typedef struct options {
    const char *in, *out, *png;
    int size, atlas;
    double angle, gutter;
    char default_png[1024];
} options;

static int parse_args(int argc, char **argv, options *o)
{
    for (int i = 1; i < argc; i++) {
        const char *v;
        if (cli_option(argc, argv, &i, "--out", &v)) {
            if (!v) return cli_usage_error("mesh-uv", "--out needs a file name");
            if (o->out) return cli_usage_error("mesh-uv", "two outputs: '%s' and '%s'", o->out, v);
            o->out = v;
        } else if (cli_option(argc, argv, &i, "--png", &v)) {
            if (!(o->png = v)) return cli_usage_error("mesh-uv", "--png needs a file name");
        } else if (cli_option(argc, argv, &i, "--size", &v)) {
            if (!cli_parse_int(v, &o->size) || o->size < 16 || o->size > 16384)
                return cli_usage_error("mesh-uv", "--size needs texels from 16 to 16384");
        } else if (cli_option(argc, argv, &i, "--angle", &v)) {
            if (!cli_parse_double(v, &o->angle) || !(o->angle > 0 && o->angle < 90))
                return cli_usage_error("mesh-uv", "--angle needs degrees in (0, 90)");
        } else if (cli_option(argc, argv, &i, "--gutter", &v)) {
            if (!cli_parse_double(v, &o->gutter) || !(o->gutter > 0))
                return cli_usage_error("mesh-uv", "--gutter needs texels > 0");
        } else if (!strcmp(argv[i], "--atlas")) {
            o->atlas = 1;
        } else if (argv[i][0] == '-' && argv[i][1]) {
            return cli_usage_error("mesh-uv", "unknown option '%s'", argv[i]);
        } else if (!o->in) {
            o->in = argv[i];
        } else if (!o->out) {
            o->out = argv[i];
            fprintf(stderr,
                    "lucent mesh-uv: note: the output as a second argument is Lucent 0.1's form; "
                    "write --out %s\n",
                    argv[i]);
        } else {
            return cli_usage_error("mesh-uv", "expected one mesh (got '%s' too)", argv[i]);
        }
    }
    if (!o->in) return cli_usage_error("mesh-uv", "expected a mesh");
    if (!o->out) return cli_usage_error("mesh-uv", "expected --out OUT.obj or OUT.gltf");
    size_t n = strlen(o->out);
    bool obj = n > 4 && !strcasecmp(o->out + n - 4, ".obj"), gltf = n > 5 && !strcasecmp(o->out + n - 5, ".gltf");
    if (!obj && !gltf) return cli_usage_error("mesh-uv", "OUT must end in .obj or .gltf");
    if (o->gutter * 4 >= o->size) return cli_usage_error("mesh-uv", "--gutter must be below a quarter of --size");
    if (!o->png) {
        snprintf(o->default_png, sizeof o->default_png, "%.*s.png", (int)(n - (obj ? 4 : 5)), o->out);
        o->png = o->default_png;
    }
    return CLI_OK;
}

int cmd_mesh_uv(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) return fputs(k_usage, stdout), CLI_OK;
    options o = {.size = LUCENT_UV_ATLAS_TEXTURE, .angle = LUCENT_UV_ATLAS_ANGLE, .gutter = LUCENT_UV_ATLAS_GUTTER};
    int rc = parse_args(argc, argv, &o);
    const char *ins[1] = {o.in}, *outs[2] = {o.out, o.png};
    static const char *const flags[2] = {"OUT", "--png"};
    if (rc == CLI_OK) rc = cli_check_outputs("mesh-uv", ins, 1, outs, flags, 2);
    if (rc != CLI_OK) return rc;
    lucent_mesh *m = NULL;
    lucent_image *img = NULL;
    lucent_uv_stats st = {0};
    size_t over = 0, covered = 0, charts = 0;
    bool own = false;
    lucent_status s = lucent_mesh_load(o.in, NULL, &m);
    if (s == LUCENT_OK && m->uvs && !o.atlas) {
        own = true;
        s = lucent_mesh_uv_stats_compute(m, &st);
    } else if (s == LUCENT_OK) {
        lucent_uv_atlas_desc d = {.max_angle = o.angle, .texture_size = o.size, .gutter = o.gutter};
        s = lucent_mesh_uv_atlas(m, &d, &st);
    }
    uint32_t *chart = s == LUCENT_OK ? malloc((m->face_count + 1) * sizeof *chart) : NULL;
    if (s == LUCENT_OK && !chart) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    if (s == LUCENT_OK) s = lucent_mesh_uv_charts(m, chart, &charts);
    free(chart);
    if (s == LUCENT_OK) s = lucent_mesh_uv_overlaps(m, o.size, &over, &covered);
    if (s == LUCENT_OK) s = lucent_mesh_uv_paint(m, o.size, &img);
    size_t n = strlen(o.out);
    if (s == LUCENT_OK)
        s = !strcasecmp(o.out + n - 4, ".obj") ? lucent_mesh_write_obj(o.out, m) : lucent_mesh_write_gltf(o.out, m);
    if (s == LUCENT_OK && (s = lucent_image_write(o.png, img, NULL)) != LUCENT_OK) remove(o.out); /* both or none */
    if (s == LUCENT_OK) {
        cli_info("%s: %zu faces, %s, %zu charts", o.in, m->face_count, own ? "its own coordinates" : "Lucent's atlas",
                 charts);
        cli_info("stretch L2 %.4f (max %.3f), %zu flipped, %zu texels of %zu covered in two faces at %d^2, %.1f%% "
                 "covered",
                 st.stretch_l2, st.stretch_max, st.flipped_faces, over, covered, o.size,
                 100.0 * (double)covered / ((double)o.size * o.size));
        cli_wrote("wrote %s", o.out);
        cli_wrote("wrote %s", o.png);
    }
    lucent_image_destroy(img);
    lucent_mesh_destroy(m);
    return s == LUCENT_OK ? CLI_OK : cli_fail();
}
