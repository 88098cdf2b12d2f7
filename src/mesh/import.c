/* Mesh import through assimp's C API (PLY ASCII/binary, OBJ, glTF); .gz inflated with zlib
 * first, then handed to assimp from memory with a format hint. */
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <zlib.h>

#include "mesh/internal.h"

static int has_suffix(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    return n >= k && strcasecmp(s + n - k, suffix) == 0;
}

/* The format hint from a file name: "ply" for x.ply and x.ply.gz, etc. */
static lucent_status format_from_path(const char *path, char *dest, size_t size)
{
    char name[4096];
    snprintf(name, sizeof name, "%s", path);
    if (has_suffix(name, ".gz")) name[strlen(name) - 3] = '\0';
    const char *dot = strrchr(name, '.');
    static const char *const known[] = {"ply", "obj", "gltf", "glb", "stl", "off"};
    for (size_t i = 0; dot && i < sizeof known / sizeof known[0]; i++)
        if (strcasecmp(dot + 1, known[i]) == 0) {
            snprintf(dest, size, "%s", known[i]);
            return LUCENT_OK;
        }
    return lucent_error(LUCENT_ERR_UNSUPPORTED,
                        "%s: unknown mesh format (expected .ply, .ply.gz, "
                        ".obj, .gltf or .glb)",
                        path);
}

/* Reads a file, inflating it when gzip-compressed (gzread passes plain files through). */
static lucent_status read_maybe_gz(const char *path, char **dest, size_t *size)
{
    gzFile gz = gzopen(path, "rb");
    if (!gz) return lucent_error(LUCENT_ERR_IO, "%s: cannot open", path);
    size_t cap = 1 << 20, n = 0;
    char *buf = malloc(cap);
    int got = 1;
    while (buf && got > 0) {
        if (cap - n < (1u << 20)) {
            char *grown = cap < ((size_t)1 << 31) ? realloc(buf, cap * 2) : NULL;
            if (!grown) free(buf);
            buf = grown, cap *= 2;
            if (!buf) break;
        }
        got = gzread(gz, buf + n, 1u << 20);
        if (got > 0) n += (size_t)got;
    }
    int err = 0;
    const char *msg = buf ? gzerror(gz, &err) : "";
    lucent_status s = !buf      ? lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path)
                      : got < 0 ? lucent_error(LUCENT_ERR_PARSE, "%s: truncated or corrupt gzip data (%s)", path, msg)
                                : LUCENT_OK;
    gzclose(gz);
    if (s != LUCENT_OK) {
        free(buf);
        return s;
    }
    *dest = buf, *size = n;
    return LUCENT_OK;
}

/* Copies the triangles of every assimp mesh into one lucent_mesh. */
static lucent_status copy_scene(const struct aiScene *sc, const char *name, lucent_mesh **dest)
{
    size_t nv = 0, nf = 0;
    for (unsigned i = 0; i < sc->mNumMeshes; i++) {
        nv += sc->mMeshes[i]->mNumVertices;
        for (unsigned f = 0; f < sc->mMeshes[i]->mNumFaces; f++) nf += sc->mMeshes[i]->mFaces[f].mNumIndices == 3;
    }
    if (nf == 0) return lucent_error(LUCENT_ERR_PARSE, "%s: no triangles in the file", name);
    lucent_status s = lucent_mesh_create(nv, nf, dest);
    if (s != LUCENT_OK) return lucent_error_context(s, "%s", name);
    size_t v0 = 0, fi = 0;
    for (unsigned i = 0; i < sc->mNumMeshes; i++) {
        const struct aiMesh *am = sc->mMeshes[i];
        for (unsigned v = 0; v < am->mNumVertices; v++) {
            double *p = (*dest)->positions + 3 * (v0 + v);
            p[0] = am->mVertices[v].x, p[1] = am->mVertices[v].y, p[2] = am->mVertices[v].z;
            if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
                lucent_mesh_destroy(*dest), *dest = NULL;
                return lucent_error(LUCENT_ERR_PARSE, "%s: vertex %zu is not finite", name, v0 + v);
            }
        }
        for (unsigned f = 0; f < am->mNumFaces; f++) {
            const struct aiFace *face = &am->mFaces[f];
            if (face->mNumIndices != 3) continue;
            for (int j = 0; j < 3; j++) (*dest)->faces[3 * fi + j] = (uint32_t)(v0 + face->mIndices[j]);
            fi++;
        }
        v0 += am->mNumVertices;
    }
    return LUCENT_OK;
}

/* True when every face index of every mesh names one of its vertices. */
static int scene_indices_valid(const struct aiScene *sc)
{
    for (unsigned i = 0; i < sc->mNumMeshes; i++) {
        const struct aiMesh *am = sc->mMeshes[i];
        if (!am || (am->mNumFaces && !am->mFaces) || (am->mNumVertices && !am->mVertices)) return 0;
        for (unsigned f = 0; f < am->mNumFaces; f++) {
            const struct aiFace *face = &am->mFaces[f];
            if (face->mNumIndices && !face->mIndices) return 0;
            for (unsigned j = 0; j < face->mNumIndices; j++)
                if (face->mIndices[j] >= am->mNumVertices) return 0;
        }
    }
    return 1;
}

lucent_status lucent_mesh_load_memory(const void *data, size_t size, const char *name,
                                      const lucent_mesh_load_desc *desc, lucent_mesh **dest)
{
    *dest = NULL;
    const char *format = desc && desc->format ? desc->format : NULL;
    if (!format) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: no mesh format given", name);
    if (size == 0) return lucent_error(LUCENT_ERR_PARSE, "%s: empty file", name);
    if (size > UINT32_MAX) return lucent_error(LUCENT_ERR_UNSUPPORTED, "%s: file larger than 4 GiB", name);
    /* Import raw, check indices ourselves (assimp's post-processing crashes on the faces of a
     * truncated binary PLY, which point past the vertices read), then post-process. */
    unsigned flags = aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_SortByPType;
    const struct aiScene *sc = aiImportFileFromMemory(data, (unsigned)size, 0, format);
    if (sc && sc->mNumMeshes && !scene_indices_valid(sc)) {
        aiReleaseImport(sc);
        return lucent_error(LUCENT_ERR_PARSE,
                            "%s: truncated or malformed %s mesh (a face refers to a "
                            "missing vertex)",
                            name, format);
    }
    if (sc && sc->mNumMeshes) sc = aiApplyPostProcessing(sc, flags);
    if (!sc || !sc->mNumMeshes) {
        lucent_status s = lucent_error(LUCENT_ERR_PARSE, "%s: not a readable %s mesh (%s)", name, format,
                                       sc ? "no meshes" : aiGetErrorString());
        aiReleaseImport(sc);
        return s;
    }
    lucent_status s = copy_scene(sc, name, dest);
    aiReleaseImport(sc);
    if (s == LUCENT_OK && !(desc && desc->keep_duplicates))
        s = lucent_mesh_weld(*dest);
    else if (s == LUCENT_OK)
        lucent_mesh_compute_normals(*dest);
    if (s == LUCENT_OK && (*dest)->face_count == 0)
        s = lucent_error(LUCENT_ERR_PARSE, "%s: every face is degenerate", name);
    if (s != LUCENT_OK) lucent_mesh_destroy(*dest), *dest = NULL;
    return s;
}

lucent_status lucent_mesh_load(const char *path, const lucent_mesh_load_desc *desc, lucent_mesh **dest)
{
    *dest = NULL;
    char format[16];
    lucent_mesh_load_desc d = desc ? *desc : (lucent_mesh_load_desc){0};
    lucent_status s = LUCENT_OK;
    if (!d.format) s = format_from_path(path, format, sizeof format), d.format = format;
    char *data = NULL;
    size_t size = 0;
    if (s == LUCENT_OK) s = read_maybe_gz(path, &data, &size);
    if (s == LUCENT_OK) s = lucent_mesh_load_memory(data, size, path, &d, dest);
    free(data);
    return s;
}
