/* Internal helpers shared by the mesh module: small vector math, vertex-to-face adjacency,
 * per-corner (mixed Voronoi) areas. */
#ifndef LUCENT_MESH_INTERNAL_H
#define LUCENT_MESH_INTERNAL_H

#include <math.h>
#include <stdint.h>

#include "lucent/mesh.h"

static inline void v3_sub(const double *a, const double *b, double *dest)
{
    dest[0] = a[0] - b[0], dest[1] = a[1] - b[1], dest[2] = a[2] - b[2];
}
static inline double v3_dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static inline void v3_cross(const double *a, const double *b, double *dest)
{
    double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2], z = a[0] * b[1] - a[1] * b[0];
    dest[0] = x, dest[1] = y, dest[2] = z;
}
static inline double v3_len(const double *a) { return sqrt(v3_dot(a, a)); }
/* Normalises in place; a zero (or non-finite) vector becomes zero. Returns the old length. */
static inline double v3_normalize(double *a)
{
    double l = v3_len(a);
    if (!(l > 0) || !isfinite(l)) {
        a[0] = a[1] = a[2] = 0;
        return 0;
    }
    double inv = 1 / l; /* one division, not three */
    a[0] *= inv, a[1] *= inv, a[2] *= inv;
    return l;
}

/* Vertex -> incident faces, in CSR form: faces of vertex v are face[start[v] .. start[v+1]),
 * corner[] says which corner (0..2) of that face v is. */
typedef struct mesh_adjacency {
    uint32_t *start; /* vertex_count + 1 */
    uint32_t *face;
    uint8_t *corner;
} mesh_adjacency;

lucent_status mesh_adjacency_build(const lucent_mesh *mesh, mesh_adjacency *dest);
void mesh_adjacency_free(mesh_adjacency *adj);

/* Mixed Voronoi areas of the three corners of face f (Meyer et al. 2003, Fig. 4; the same
 * split as trimesh2's compute_pointareas). Zero for a degenerate face. */
void mesh_corner_areas(const lucent_mesh *mesh, size_t f, double dest[3]);

/* Unit vertex normals with Max 1999 weights (sin angle / (|e1| |e2|), exact on a sphere),
 * used by the curvature estimators. dest holds 3 doubles per vertex. */
lucent_status mesh_max_normals(const lucent_mesh *mesh, const mesh_adjacency *adj, lucent_pool *pool,
                               double *dest);

/* True when the edge (v, other) has exactly one face among v's incident faces. */
int mesh_vertex_on_boundary(const lucent_mesh *mesh, const mesh_adjacency *adj, uint32_t v);

/* Per-method estimators: fill k1, k2, mean, gauss (and dir1/dir2 for Rusinkiewicz). */
lucent_status mesh_curvature_rusinkiewicz(const lucent_mesh *mesh, const mesh_adjacency *adj,
                                          lucent_pool *pool, int fast, lucent_curvature *dest);

/* What a per-vertex estimator that works from Max's vertex normals sees (Meyer, Garimella). */
typedef struct mesh_vertex_job {
    const lucent_mesh *mesh;
    const mesh_adjacency *adj;
    const double *normals; /* 3 per vertex */
    lucent_curvature *out;
} mesh_vertex_job;

typedef void (*mesh_vertex_fn)(const mesh_vertex_job *job, uint32_t v);

/* Computes Max's normals, then runs fn for every vertex in fixed chunks. */
lucent_status mesh_curvature_per_vertex(const lucent_mesh *mesh, const mesh_adjacency *adj,
                                        lucent_pool *pool, mesh_vertex_fn fn, lucent_curvature *dest);

/* The per-vertex estimators: Meyer et al. 2003 and Garimella & Swartz 2003. */
void mesh_meyer_vertex(const mesh_vertex_job *job, uint32_t v);
void mesh_garimella_vertex(const mesh_vertex_job *job, uint32_t v);

/* Angle-deficit Gaussian curvature of vertex v over its mixed area (Meyer et al. 2003, eq. 9);
 * pi instead of 2 pi at a boundary vertex. *area receives the mixed area. */
double mesh_angle_deficit_gauss(const lucent_mesh *mesh, const mesh_adjacency *adj, uint32_t v,
                                int boundary, double *area);

/* Builds an icosphere (desc resolved: radius > 0, subdivisions >= 1). */
lucent_status mesh_icosphere(const lucent_primitive_desc *d, lucent_mesh **dest);

/* Averages values over the 1-ring, `rings` times, weighted by vertex area. */
lucent_status mesh_smooth(const lucent_mesh *mesh, const mesh_adjacency *adj, int rings,
                          lucent_curvature *curv);

#endif
