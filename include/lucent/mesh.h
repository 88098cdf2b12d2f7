/* Lucent mesh: triangle meshes, import (PLY, .ply.gz, OBJ, glTF through assimp), welding,
 * normals, analytic primitives (UV sphere, icosphere, torus, ellipsoid) and per-vertex
 * curvature (Rusinkiewicz 2004, Meyer et al. 2003, Garimella & Swartz 2003).
 *
 * Sign convention: with outward normals (counter-clockwise faces seen from outside), a sphere
 * of radius R has mean curvature H = +1/R and principal curvatures k1 = k2 = +1/R.
 * Curvatures are in inverse mesh units; pass mm_per_unit to get mm^-1. */
#ifndef LUCENT_MESH_H
#define LUCENT_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "lucent/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A triangle mesh. Arrays are owned by the mesh; positions and normals hold 3 doubles per
 * vertex, faces 3 vertex indices per triangle (counter-clockwise seen from outside). */
typedef struct lucent_mesh {
    size_t vertex_count;
    size_t face_count;
    double *positions;
    double *normals; /* unit, area-weighted; zero for vertices without a face of non-zero area */
    uint32_t *faces;
    /* Texture coordinates per face corner: (u, v) of corners 0, 1, 2 of face f at uvs[6 f ..
     * 6 f + 5]; NULL when the mesh has none. Per corner, so that a seam needs no split vertex: the
     * mesh stays welded (normals, curvature) and the GPU splits where corners differ. Imported
     * from OBJ / glTF / PLY texture coordinates, analytic on the UV sphere and ellipsoid, made by
     * lucent_mesh_uv_atlas otherwise. malloc'd; lucent_mesh_destroy frees it. */
    double *uvs;
} lucent_mesh;

/* Allocates a mesh with room for the given counts (contents zeroed). */
lucent_status lucent_mesh_create(size_t vertex_count, size_t face_count, lucent_mesh **dest);

/* Frees a mesh (NULL is accepted). */
void lucent_mesh_destroy(lucent_mesh *mesh);

/* ---- Import ---------------------------------------------------------------- */

/* How to load a mesh; a zero field means the default. */
typedef struct lucent_mesh_load_desc {
    const char *format;  /* "ply", "obj", "gltf", "glb"; default: from the extension (.gz inflated) */
    int keep_duplicates; /* non-zero: do not weld vertices at identical positions */
    int use_assimp;      /* non-zero: PLY and OBJ through assimp too (in its child process), for the
                            comparison in bench/bench_mesh_load.c */
} lucent_mesh_load_desc;

/* Loads a triangle mesh from a file: PLY (ASCII/binary, .ply.gz) and OBJ (.obj, .obj.gz) through
 * Lucent's own readers (lucent_ply_open below; OBJ: v and f lines, polygons fan-triangulated, mtllib
 * never opened), other formats (glTF/GLB, STL, OFF) through assimp, restricted to the named file and
 * run in a child process so that a crash there is an error. Vertices at
 * identical positions are welded, faces that collapse to a line or point after welding are
 * dropped, normals are computed (lucent_mesh_compute_normals). Empty, truncated or malformed
 * files fail with LUCENT_ERR_PARSE and a message naming the file. desc may be NULL. */
lucent_status lucent_mesh_load(const char *path, const lucent_mesh_load_desc *desc, lucent_mesh **dest);

/* The same from memory; name is used in messages, format is required ("ply", "obj", ...). */
lucent_status lucent_mesh_load_memory(const void *data, size_t size, const char *name,
                                      const lucent_mesh_load_desc *desc, lucent_mesh **dest);

/* ---- PLY reading: any vertex property by name ------------------------------
 * Lucent's own PLY reader (ASCII, binary little and big endian, gzip-compressed .ply.gz), written for
 * hostile input: only regular files are read (a FIFO or /dev/urandom is refused up front), the header is
 * bounded (1 MiB, 64 elements, 1024 properties each), every count is checked against the bytes the file
 * can still hold before anything is allocated (for .gz, against deflate's largest expansion of what is
 * left, and arrays then grow with the data actually read), every face index is checked, and a truncated
 * or malformed body is an error naming the file and the line (ASCII) or byte offset (binary).
 *
 * Usage (a point cloud, say 3D Gaussian splats):
 *     lucent_ply *ply;
 *     if (lucent_ply_open("points.ply", &ply) != LUCENT_OK) return fail();
 *     const char *names[] = {"x", "y", "z", "f_dc_0", "opacity"};
 *     lucent_ply_data d;
 *     s = lucent_ply_read(ply, &(lucent_ply_read_desc){.names = names, .count = 5}, &d);
 *     lucent_ply_close(ply);
 *     ... d.values[5 * i + k] is property names[k] of vertex i ...
 *     lucent_ply_data_free(&d);
 * lucent_ply_property_index tells which properties a file has before reading. */
typedef struct lucent_ply lucent_ply;

/* The read limit of the mesh and point-cloud readers (PLY and OBJ, plain or gzip), against files that
 * declare or hold more than memory allows (a decompression bomb: 117 KB of .ply.gz declaring 30 million
 * faces): the most elements (every element's rows: vertices, faces, ...) a file may declare, or hold as it
 * is read. lucent_mesh_set_read_limit(0) returns to the environment variable LUCENT_MESH_MAX_ELEMENTS, else
 * LUCENT_MESH_DEFAULT_READ_ELEMENTS (64 Mi: the largest Stanford scans, Lucy's 42 M, fit). gzip input is
 * also refused once it has inflated more than LUCENT_MESH_MAX_INFLATE_RATIO times the compressed bytes read
 * (plus 1 MiB): real meshes inflate 2 to 10 times; gunzip such a file to read it whole. */
#define LUCENT_MESH_DEFAULT_READ_ELEMENTS ((uint64_t)1 << 26)
#define LUCENT_MESH_MAX_INFLATE_RATIO 100
void lucent_mesh_set_read_limit(uint64_t elements);
uint64_t lucent_mesh_read_limit(void);

/* Opens a PLY file (plain or gzip, found by its first bytes) and reads its header. Close with
 * lucent_ply_close. */
lucent_status lucent_ply_open(const char *path, lucent_ply **dest);

/* The same from memory (data must outlive the lucent_ply); name is used in messages. */
lucent_status lucent_ply_open_memory(const void *data, size_t size, const char *name, lucent_ply **dest);

void lucent_ply_close(lucent_ply *ply);

/* The declared vertex count (0 when there is no vertex element) and face count (0 without a face
 * element). */
size_t lucent_ply_vertex_count(const lucent_ply *ply);
size_t lucent_ply_face_count(const lucent_ply *ply);

/* The vertex element's scalar properties in file order: their number, the i-th one's name, and the
 * index of a name (-1 when the file has no such vertex property). */
int lucent_ply_property_count(const lucent_ply *ply);
const char *lucent_ply_property_name(const lucent_ply *ply, int i);
int lucent_ply_property_index(const lucent_ply *ply, const char *name);

/* Whether the vertex element has a list property of that name (not readable as a value). */
bool lucent_ply_property_is_list(const lucent_ply *ply, const char *name);
/* The largest value of the i-th property's type when it is an integer type (uchar: 255, ushort: 65535,
 * char: 127, ...), 0 for float and double: the scale of colours stored as integers. */
double lucent_ply_property_integer_max(const lucent_ply *ply, int i);

/* Faces: not read, read when the file has them, or required (an error naming the file when the file
 * has no face element: "holds points only"). */
typedef enum lucent_ply_faces {
    LUCENT_PLY_FACES_SKIP = 0,
    LUCENT_PLY_FACES_OPTIONAL,
    LUCENT_PLY_FACES_REQUIRED
} lucent_ply_faces;

/* What to read. A name the file lacks is an error naming it, unless allow_missing is set: then its
 * values are NaN. single: values as float (values32) instead of double (values), half the memory. */
typedef struct lucent_ply_read_desc {
    const char *const *names; /* vertex properties, any PLY scalar type; converted to floating point */
    int count;
    int allow_missing;
    int single;
    lucent_ply_faces faces; /* faces are fan-triangulated: a polygon of n vertices gives n - 2 */
    /* Optional: called for each vertex as it is read, before it is stored, with its count values in double
     * (as read, before any rounding to float); a status other than LUCENT_OK stops the read with it. */
    lucent_status (*check)(void *user, uint64_t vertex, const double *values);
    void *user;
} lucent_ply_read_desc;

typedef struct lucent_ply_data {
    size_t vertex_count;
    int count;       /* values per vertex (desc->count) */
    double *values;  /* vertex_count x count, row-major (NULL when single) */
    float *values32; /* the same when single */
    size_t triangle_count;
    uint32_t *triangles;  /* 3 per triangle, each index < vertex_count */
    size_t polygon_count; /* faces in the file (before triangulation) */
} lucent_ply_data;

/* Reads the body once (a lucent_ply reads once); on failure dest is zeroed. */
lucent_status lucent_ply_read(lucent_ply *ply, const lucent_ply_read_desc *desc, lucent_ply_data *dest);

void lucent_ply_data_free(lucent_ply_data *data);

/* Writes the mesh as binary little-endian PLY, with per-vertex colours (3 bytes per vertex)
 * and per-vertex scalar properties when given (names[i] for values[i], vertex_count each). */
typedef struct lucent_mesh_ply_extra {
    const uint8_t *colors; /* 3 per vertex, may be NULL */
    int scalar_count;
    const char *const *names;
    const double *const *values;
} lucent_mesh_ply_extra;

lucent_status lucent_mesh_write_ply(const char *path, const lucent_mesh *mesh, const lucent_mesh_ply_extra *extra);

typedef struct lucent_image lucent_image; /* lucent/image.h */

/* Writes the mesh as Wavefront OBJ (v, vn, and vt per corner when it has texture coordinates). */
lucent_status lucent_mesh_write_obj(const char *path, const lucent_mesh *mesh);

/* Writes the mesh as glTF 2.0 (.gltf, one buffer embedded as a base64 data URI): positions,
 * normals, TEXCOORD_0 (vertices split where corners differ; v flipped to glTF's top-left origin). */
lucent_status lucent_mesh_write_gltf(const char *path, const lucent_mesh *mesh);

/* ---- Texture atlases (uv_atlas.c, docs/tsd.md) ------------------------------ */

enum { LUCENT_UV_ATLAS_TEXTURE = 1024 };
#define LUCENT_UV_ATLAS_ANGLE 40.0 /* degrees */
#define LUCENT_UV_ATLAS_GUTTER 4.0 /* texels at texture_size */

/* How to make an atlas; a zero field means the default. */
typedef struct lucent_uv_atlas_desc {
    double max_angle; /* a chart's faces lie within this angle of its seed face's normal (degrees) */
    int texture_size; /* texels along a side, for the gutter */
    double gutter;    /* texels between two charts at texture_size (half of it to the border) */
} lucent_uv_atlas_desc;

/* What a mesh's texture coordinates are like. */
typedef struct lucent_uv_stats {
    size_t chart_count; /* lucent_mesh_uv_atlas: charts made; else 0 */
    double stretch_l2;  /* Sander et al. 2001's L2 stretch, area-weighted, 1 = isometric up to scale */
    double stretch_max; /* the largest face's L-infinity stretch, on the same scale */
    double uv_area;     /* the faces' total area in texture space */
    double uv_min[2], uv_max[2];
    size_t flipped_faces;    /* faces mirrored in texture space */
    size_t degenerate_faces; /* faces of non-zero area with zero area in texture space */
} lucent_uv_stats;

/* Replaces mesh->uvs by an atlas: charts grown by normal cone, projected on their seed's plane
 * (overlap-free by construction), packed on shelves in [0, 1]^2 with gutters. stats may be NULL.
 * On failure the mesh is unchanged. */
lucent_status lucent_mesh_uv_atlas(lucent_mesh *mesh, const lucent_uv_atlas_desc *desc, lucent_uv_stats *stats);

/* Measures mesh->uvs (LUCENT_ERR_INVALID_ARGUMENT without them). */
lucent_status lucent_mesh_uv_stats_compute(const lucent_mesh *mesh, lucent_uv_stats *dest);

/* Rasterises every face into a size x size grid over [0, 1]^2 (texel centres strictly inside a
 * face, by a thousandth of a texel): overlapping = texels inside two or more faces, covered =
 * texels inside at least one. Either may be NULL. */
lucent_status lucent_mesh_uv_overlaps(const lucent_mesh *mesh, int size, size_t *overlapping, size_t *covered);

/* chart[f] (face_count entries): the chart of face f, charts being the components of faces joined
 * by edges whose two corners have the same coordinates on both sides; count: how many. */
lucent_status lucent_mesh_uv_charts(const lucent_mesh *mesh, uint32_t *chart, size_t *count);

/* A size x size picture of the charts in texture space (v up), each chart its own colour. */
lucent_status lucent_mesh_uv_paint(const lucent_mesh *mesh, int size, lucent_image **dest);

/* The mesh's vertices split where their corners' coordinates differ (for the GPU and glTF). */
typedef struct lucent_uv_split {
    size_t count;     /* split vertices */
    uint32_t *vertex; /* the mesh vertex of each */
    double *uv;       /* 2 each */
    uint32_t *faces;  /* 3 per face, into the split vertices */
} lucent_uv_split;

lucent_status lucent_mesh_uv_split(const lucent_mesh *mesh, lucent_uv_split *dest);
void lucent_uv_split_free(lucent_uv_split *split);

/* A texel near a texture seam (uv_seams.c, docs/tsd.md): the same surface point in the chart across
 * the seam, by unfolding the two faces of its nearest seam edge into one plane. Texel (x, y) has its
 * centre at (x + 0.5, y + 0.5) in texel coordinates, v up (row 0 at v = 0). */
typedef struct lucent_uv_seam_texel {
    uint32_t x, y;
    uint32_t chart;    /* the chart of the edge's face on this side (lucent_mesh_uv_charts) */
    uint32_t across;   /* the chart on the other side (may be the same chart) */
    float target[2];   /* the same surface point in texel coordinates */
    float jacobian[4]; /* d target / d texel, row major: a step (dx, dy) here is J (dx, dy) there */
} lucent_uv_seam_texel;

typedef struct lucent_uv_seams {
    size_t count;
    lucent_uv_seam_texel *texels; /* sorted by y, then x */
} lucent_uv_seams;

/* Every texel of a size x size texture whose centre lies within reach texels of a seam edge (an
 * edge whose faces give its corners different coordinates), mapped across its nearest seam edge.
 * Boundary edges map nothing. */
lucent_status lucent_mesh_uv_seams(const lucent_mesh *mesh, int size, double reach, lucent_uv_seams *dest);
void lucent_uv_seams_free(lucent_uv_seams *seams);

/* ---- A picture of a mesh (no GPU) ------------------------------------------ */

/* How to paint a mesh; zero fields take the defaults. */
typedef struct lucent_mesh_paint_desc {
    int width, height;         /* pixels (default 800 x 800) */
    double azimuth, elevation; /* degrees: 0, 0 looks along -z with +y up; azimuth turns the eye
                                  about +y toward +x, elevation raises it toward +y */
    const uint8_t *colors;     /* sRGB, 3 bytes per vertex (required) */
    float background[3];       /* linear RGB (default black) */
    int supersample;           /* samples per pixel and axis, 1..8 (default 3); fewer where the supersampled picture
                                  would pass 64 Mpixels */
} lucent_mesh_paint_desc;

/* Paints mesh with its vertex colours, seen orthographically with its bounding sphere filling 92% of
 * the shorter side, z-buffered, shaded by a head light (0.35 + 0.65 |n.v|); a new linear RGB image. */
lucent_status lucent_mesh_paint(const lucent_mesh *mesh, const lucent_mesh_paint_desc *desc, lucent_image **dest);

/* ---- Clean-up and queries -------------------------------------------------- */

/* Merges vertices at bitwise-identical positions, drops faces with a repeated index and
 * vertices no face uses; keeps the order of first use. Recomputes normals. */
lucent_status lucent_mesh_weld(lucent_mesh *mesh);

/* Replaces mesh by `levels` rounds of Loop subdivision (Loop 1987; boundaries as cubic B-splines;
 * corner texture coordinates interpolated linearly),
 * 0 <= levels <= 6: each round turns every triangle into four and smooths the surface toward Loop's
 * limit surface (which shrinks convex shapes slightly). Vertices on non-manifold edges or where
 * boundaries meet stay in place. Normals are recomputed. On failure mesh is unchanged. */
lucent_status lucent_mesh_subdivide(lucent_mesh *mesh, int levels);

/* Recomputes area-weighted vertex normals (sum of face cross products, normalised). */
void lucent_mesh_compute_normals(lucent_mesh *mesh);

/* What is dirty about a mesh. */
typedef struct lucent_mesh_stats {
    size_t boundary_edges;    /* edges with one face */
    size_t nonmanifold_edges; /* edges with three or more faces */
    size_t degenerate_faces;  /* faces of zero area */
    size_t unused_vertices;   /* vertices no face uses */
    double bbox_min[3], bbox_max[3];
} lucent_mesh_stats;

lucent_status lucent_mesh_stats_compute(const lucent_mesh *mesh, lucent_mesh_stats *dest);

/* ---- Primitives with analytic curvature ------------------------------------ */

typedef enum lucent_primitive_kind {
    LUCENT_PRIMITIVE_UV_SPHERE = 0, /* radius, u_count slices x v_count stacks */
    LUCENT_PRIMITIVE_ICOSPHERE,     /* radius, subdivisions */
    LUCENT_PRIMITIVE_TORUS,         /* major_radius R, radius r, u_count x v_count grid */
    LUCENT_PRIMITIVE_ELLIPSOID      /* axes a, b, c, u_count slices x v_count stacks */
} lucent_primitive_kind;

/* A primitive; a zero field means the default (radius 1, R 3, axes 1, 64 x 32, 3 subdivisions). */
typedef struct lucent_primitive_desc {
    lucent_primitive_kind kind;
    double radius;
    double major_radius;
    double axes[3];
    int u_count, v_count;
    int subdivisions;
    double jitter; /* vertices moved by up to jitter x a cell, kept on the surface (0: none) */
    uint64_t seed; /* for the jitter */
} lucent_primitive_desc;

/* Builds a primitive, centred at the origin, outward normals. */
lucent_status lucent_mesh_primitive(const lucent_primitive_desc *desc, lucent_mesh **dest);

/* The analytic curvature of a primitive at a point on it (mean, Gaussian, k1 >= k2). */
typedef struct lucent_curvature_value {
    double k1, k2, mean, gauss;
} lucent_curvature_value;

lucent_status lucent_primitive_curvature(const lucent_primitive_desc *desc, const double point[3],
                                         lucent_curvature_value *dest);

/* ---- Curvature ------------------------------------------------------------- */

typedef enum lucent_curvature_method {
    LUCENT_CURVATURE_RUSINKIEWICZ = 0, /* per-face tensors, Rusinkiewicz 2004 */
    LUCENT_CURVATURE_MEYER,            /* cotangent Laplacian + angle deficit, Meyer et al. 2003 */
    LUCENT_CURVATURE_GARIMELLA         /* area-weighted normal curvatures, Garimella & Swartz 2003 */
} lucent_curvature_method;

/* How to estimate curvature; a zero field means the default. */
typedef struct lucent_curvature_desc {
    lucent_curvature_method method;
    int smooth_rings;   /* average over the n-ring, weighted by vertex area (0: none) */
    double mm_per_unit; /* millimetres per mesh unit (default 1): curvatures come out in mm^-1 */
    lucent_pool *pool;  /* NULL: run on the caller */
    int fast;           /* Rusinkiewicz only, non-zero: skip the normal-correcting second pass
                           (about 1.7x faster; the same on regular meshes, less accurate on irregular
                           ones: 4.8% instead of 0.8% on the jittered acceptance torus) */
} lucent_curvature_desc;

/* Per-vertex curvature. dir1/dir2 (3 per vertex) are the principal directions for
 * Rusinkiewicz; zero for the other methods. flags[i] is LUCENT_CURVATURE_* bits. */
typedef struct lucent_curvature {
    size_t count;
    double *k1, *k2, *mean, *gauss;
    double *dir1, *dir2;
    uint8_t *flags;
    size_t invalid_count; /* vertices without a usable neighbourhood (values set to 0) */
} lucent_curvature;

enum {
    LUCENT_CURVATURE_BOUNDARY = 1, /* the vertex lies on a boundary edge */
    LUCENT_CURVATURE_INVALID = 2   /* no face of non-zero area: values are 0 */
};

/* Estimates curvature at every vertex. Never yields NaN or Inf: vertices without a usable
 * neighbourhood get 0 and the INVALID flag. Free dest with lucent_curvature_free. */
lucent_status lucent_mesh_curvature(const lucent_mesh *mesh, const lucent_curvature_desc *desc, lucent_curvature *dest);

void lucent_curvature_free(lucent_curvature *curv);

/* Writes the curvature as CSV, atomically: a header line "vertex,x,y,z,k1,k2,mean,gauss,flags",
 * then one row per vertex, the index and flags as integers and the seven values as printf's
 * "%.9g" gives them (9 significant digits: a float's positions read back exactly). */
lucent_status lucent_curvature_write_csv(const char *path, const lucent_mesh *mesh, const lucent_curvature *curv);

/* Returns the method's name ("rusinkiewicz", "meyer", "garimella"). */
const char *lucent_curvature_method_name(lucent_curvature_method method);

/* Parses a method name; LUCENT_ERR_INVALID_ARGUMENT for an unknown one. */
lucent_status lucent_curvature_method_parse(const char *name, lucent_curvature_method *dest);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_MESH_H */
