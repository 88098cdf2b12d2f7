/* Internal helpers shared by the mesh module (vectors: base/vec3.h): vertex-to-face adjacency,
 * per-corner (mixed Voronoi) areas. */
#ifndef LUCENT_MESH_INTERNAL_H
#define LUCENT_MESH_INTERNAL_H

#include <math.h>
#include <stdint.h>

#include "base/vec3.h"
#include "lucent/mesh.h"

/* Vertex -> incident faces, in CSR form: the faces of vertex v are given by the slots
 * corner[start[v] .. start[v+1]), each the index 3 f + k into mesh->faces where v sits (face f,
 * corner k), in face order. Built with a counting sort. */
typedef struct mesh_adjacency {
    uint32_t *start;  /* vertex_count + 1 */
    uint32_t *corner; /* 3 face_count, then MESH_SLOT_PAD zeros (slot 0 of face 0) to read ahead */
} mesh_adjacency;

enum { MESH_SLOT_PAD = 64 };

lucent_status mesh_adjacency_build(const lucent_mesh *mesh, lucent_pool *pool, mesh_adjacency *dest);
void mesh_adjacency_free(mesh_adjacency *adj);

/* The vertices after and before the one in face slot i (counter-clockwise). Offsets from a
 * table: the corner is random, so a branch on it would be mispredicted a third of the time. */
static inline void mesh_slot_others(const uint32_t *faces, uint32_t i, uint32_t *next, uint32_t *prev)
{
    static const int8_t step_next[3] = {1, 1, -2}, step_prev[3] = {2, -1, -1};
    const uint32_t *at = faces + i;
    *next = at[step_next[i % 3]];
    *prev = at[step_prev[i % 3]];
}

/* Per-vertex passes read faces and vertices at random within a window too wide for the L2
 * cache (on the res1 dragon neighbours are thousands of indices apart): at slot a, a pass fetches
 * the face of slot a + 2 d and returns the next vertex of slot a + d, whose face should have
 * arrived by then, for the caller to fetch that vertex's data. d <= MESH_SLOT_PAD / 2. */
static inline uint32_t mesh_prefetch_slot(const mesh_adjacency *adj, const uint32_t *faces, uint32_t a, uint32_t d)
{
    uint32_t next, prev;
    __builtin_prefetch(faces + adj->corner[a + 2 * d]);
    mesh_slot_others(faces, adj->corner[a + d], &next, &prev);
    return next;
}

/* next[3 f + k]: the face across the edge from corner k to k + 1 of face f (UINT32_MAX: boundary or
 * non-manifold); next holds 3 face_count entries (uv_atlas.c). */
lucent_status mesh_face_neighbours(const lucent_mesh *mesh, uint32_t *next);

/* A 2 MiB-aligned block advised as transparent huge pages when large (alloc.c); free(). */
void *mesh_alloc_large(size_t bytes);

/* Advises the whole 2 MiB pages inside a block from malloc, calloc or realloc (of at least
 * 256 KiB, not yet touched there) as huge pages, so that its first touch faults 2 MiB at a time. */
void mesh_advise_large(void *p, size_t bytes);

/* Mixed Voronoi areas of the three corners of face f (Meyer et al. 2003, Fig. 4; the same
 * split as trimesh2's compute_pointareas). Zero for a degenerate face. */
void mesh_corner_areas(const lucent_mesh *mesh, size_t f, double dest[3]);
/* The same from the face's edges, e[j] opposite corner j (e[j] = p[j+2] - p[j+1]). */
void mesh_corner_areas_edges(const double e[3][3], double dest[3]);
/* The same from the squared edge lengths l[j], xl = |e0 x e1| > 0 (twice the area) and
 * inv_x = 1/xl (inline: the per-face passes call it for every face). Each corner gets the part of the triangle nearer to it than to the other corners (Meyer et al.
 * 2003, Fig. 4): s (ew of the other two corners), ew_j = l_j (l_j+1 + l_j+2 - l_j), where
 * s = area / (2 sum ew) and sum ew = 16 area^2 = 4 xl^2 (Heron), so s = 1/(16 xl); when a corner
 * is obtuse (its ew <= 0), it gets half and the others a quarter. Without branches: which corner
 * is obtuse is as random as the mesh. */
static inline void mesh_mixed_areas(const double l[3], double xl, double inv_x, double dest[3])
{
    double ew0 = l[0] * (l[1] + l[2] - l[0]), ew1 = l[1] * (l[2] + l[0] - l[1]), ew2 = l[2] * (l[0] + l[1] - l[2]);
    int o0 = ew0 <= 0, o1 = ew1 <= 0, o2 = ew2 <= 0, any = o0 | o1 | o2;
    double q = 0.125 * xl * any, s = (1 - any) * inv_x * (1.0 / 16);
    dest[0] = q * (1 + o0) + s * (ew1 + ew2), dest[1] = q * (1 + o1) + s * (ew2 + ew0);
    dest[2] = q * (1 + o2) + s * (ew0 + ew1);
}

/* Per face, for Meyer's and Garimella's estimators: corner areas and the cotangents of the
 * corner angles (zero for a face of zero area, whose corner areas are zero). */
typedef struct mesh_face_geometry {
    float corner[3], cot[3];
} mesh_face_geometry;

lucent_status mesh_face_geometry_compute(const lucent_mesh *mesh, lucent_pool *pool, mesh_face_geometry *dest);

/* Sum of v's corner angles, from the cotangents (faces of zero area count 0). */
double mesh_angle_sum(const mesh_face_geometry *geometry, const uint32_t *slot, uint32_t count);

/* One walk around every vertex's fan (fan.c) gives what all estimators need:
 * - normals: unit vertex normals with Max 1999 weights (sin angle / (|e1| |e2|), exact on a
 *   sphere), 3 floats per vertex; zero where no face has area;
 * - flags: LUCENT_CURVATURE_BOUNDARY on vertices of an edge with one face;
 * - pair (optional, one per adjacency slot): the offset within v's slots of the slot whose
 *   next vertex is this slot's previous one (a closed, consistently oriented fan pairs every
 *   slot), or MESH_UNPAIRED. Lets a per-vertex pass visit each neighbour once. */
enum { MESH_FAN_MAX = 32, MESH_UNPAIRED = 0xff };
typedef struct mesh_fan {
    float *normals;
    uint8_t *flags;
    uint8_t *pair;
} mesh_fan;

lucent_status mesh_fan_compute(const lucent_mesh *mesh, const mesh_adjacency *adj, lucent_pool *pool,
                               const mesh_fan *dest);

/* Per-method estimators: fill k1, k2, mean, gauss (and dir1/dir2 for Rusinkiewicz).
 * Rusinkiewicz writes values already scaled (curvature times scale, K times scale^2) and
 * flags non-finite ones invalid, as lucent_mesh_curvature's last pass would. */
lucent_status mesh_curvature_rusinkiewicz(const lucent_mesh *mesh, const mesh_adjacency *adj, const mesh_fan *fan,
                                          lucent_pool *pool, int fast, double scale, lucent_curvature *dest);

/* The first Rusinkiewicz pass at one vertex: principal directions and curvatures (floats,
 * 32 bytes), read by the normal correction. */
typedef struct mesh_principal {
    float d1[3], k1, d2[3], k2;
} mesh_principal;

/* The second pass's normal correction (curvature_refine.c): from the first pass's principal
 * frames (vertices flagged INVALID in fan->flags are skipped), writes 3 floats per vertex. */
lucent_status mesh_refine_normals(const lucent_mesh *mesh, const mesh_adjacency *adj, const mesh_fan *fan,
                                  const mesh_principal *principal, lucent_pool *pool, float *dest);

/* What a per-vertex estimator that works from Max's vertex normals sees (Meyer, Garimella). */
typedef struct mesh_vertex_job {
    const lucent_mesh *mesh;
    const mesh_adjacency *adj;
    const float *normals; /* 3 per vertex */
    const mesh_face_geometry *geometry;
    lucent_curvature *out;
} mesh_vertex_job;

typedef void (*mesh_vertex_fn)(const mesh_vertex_job *job, uint32_t v);

/* Runs fn for every vertex in fixed chunks. */
lucent_status mesh_curvature_per_vertex(const lucent_mesh *mesh, const mesh_adjacency *adj, const mesh_fan *fan,
                                        lucent_pool *pool, mesh_vertex_fn fn, lucent_curvature *dest);

/* The per-vertex estimators: Meyer et al. 2003 and Garimella & Swartz 2003. */
void mesh_meyer_vertex(const mesh_vertex_job *job, uint32_t v);
void mesh_garimella_vertex(const mesh_vertex_job *job, uint32_t v);

/* Angle-deficit Gaussian curvature of vertex v over its mixed area (Meyer et al. 2003, eq. 9);
 * pi instead of 2 pi at a boundary vertex. *area receives the mixed area. */
double mesh_angle_deficit_gauss(const mesh_vertex_job *job, uint32_t v, int boundary, double *area);

/* Builds an icosphere (desc resolved: radius > 0, subdivisions >= 1). */
lucent_status mesh_icosphere(const lucent_primitive_desc *d, lucent_mesh **dest);

/* Averages values over the 1-ring, `rings` times, weighted by vertex area. */
lucent_status mesh_smooth(const lucent_mesh *mesh, const mesh_adjacency *adj, int rings, lucent_curvature *curv);

#endif
