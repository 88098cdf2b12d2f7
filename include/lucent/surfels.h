/* Lucent surfels: surface elements for point-based rendering (Pfister et al. 2000), a disk with a
 * centre, a normal, a radius and optionally a colour, made from a mesh (one per vertex) or from a
 * point cloud, with decimated levels for wide splats (Kim, Bickel, Gross & Choi, seed 001: "we can
 * reduce the number of surfels when the amplitude of the radius is large").
 *
 * Radius: where the input gives none, the distance to the k-th nearest other surfel (k = 8 by
 * default), so that neighbouring disks overlap: on a square grid of spacing s the 8th neighbour is a
 * diagonal one, r = s sqrt(2), twice the s / sqrt(2) that covering the plane needs.
 *
 * Levels: level 0 is the input. Level l + 1 clusters level l on a grid of cells `decimation` times
 * level l's spacing (cells split by the normal's dominant axis, so the two sides of a thin part stay
 * apart); each cluster becomes one surfel at the member nearest the cluster's centroid, with the
 * members' mean normal, and radii from the k nearest at the new level (grown to keep coverage).
 * Every surfel of level l < last has a parent in level l + 1; children[] lists, for every surfel of
 * level l >= 1, its members in level l - 1 (what a renderer averages to resample onto the coarse
 * level). Deterministic: the same result for any thread count. */
#ifndef LUCENT_SURFELS_H
#define LUCENT_SURFELS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lucent/base.h"
#include "lucent/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { LUCENT_SURFEL_MAX_LEVELS = 12, LUCENT_SURFEL_DEFAULT_K = 8 };

/* One level: surfels [first, first + count) of the arrays. */
typedef struct lucent_surfel_level {
    size_t first, count;
    double spacing; /* the median radius over sqrt(2): the grid spacing on a square grid, mm */
} lucent_surfel_level;

/* Surfels of every level, concatenated (level 0 first). Arrays hold 3 floats per surfel (positions,
 * normals: unit; colors: linear RGB, or NULL when the input had none) or one (radii, > 0). */
typedef struct lucent_surfels {
    size_t count; /* all levels */
    float *positions;
    float *normals;
    float *radii;
    float *colors;
    bool radii_given; /* level 0's radii came with the points (else from the k nearest) */
    int level_count;
    lucent_surfel_level levels[LUCENT_SURFEL_MAX_LEVELS];
    /* Per surfel: its parent in the next level (global index), UINT32_MAX on the last level. */
    uint32_t *parent;
    /* Per surfel s: its children in the previous level are children[child_start[s] ..
     * child_start[s + 1]) (global indices; empty on level 0). count + 1 entries. */
    uint32_t *child_start;
    uint32_t *children;
} lucent_surfels;

/* How to build surfels; a zero field means the default. */
typedef struct lucent_surfels_desc {
    int neighbours;    /* k of the radius; 0: LUCENT_SURFEL_DEFAULT_K */
    int max_levels;    /* 1: level 0 only; 0: until a level has fewer than min_count surfels */
    double decimation; /* spacing ratio of consecutive levels, > 1; 0: 2 */
    size_t min_count;  /* 0: 64 */
    lucent_pool *pool; /* NULL: serial */
} lucent_surfels_desc;

/* Surfels from count points: positions and normals (3 each, normals need not be unit but must not be
 * zero), radii (NULL or all > 0; NULL: from the k nearest), colors (NULL or 3 each). Non-finite
 * values, zero normals, non-positive radii and fewer than two points fail (LUCENT_ERR_INVALID_ARGUMENT,
 * naming the first bad point). */
lucent_status lucent_surfels_from_points(size_t count, const float *positions, const float *normals, const float *radii,
                                         const float *colors, const lucent_surfels_desc *desc, lucent_surfels **dest);

/* Surfels from a mesh: one per vertex with a non-zero normal (vertices without a face are left out). */
lucent_status lucent_surfels_from_mesh(const lucent_mesh *mesh, const lucent_surfels_desc *desc, lucent_surfels **dest);

/* Surfels from a point cloud in a PLY file (ASCII, binary, .ply.gz; faces, if any, are ignored), read
 * by Lucent's PLY reader (lucent_ply_open):
 *   - a plain cloud: vertex properties x y z nx ny nz, optionally red green blue (integer types scaled
 *     by their largest value, floats taken as [0, 1]; sRGB-encoded, decoded to linear) and radius
 *     (in the file's units; without it radii come from the k nearest, desc->neighbours);
 *   - a 3D Gaussian splatting file (Kerbl et al. 2023: x y z nx ny nz f_dc_0..2 f_rest_* opacity
 *     scale_0..2 rot_0..3, the normals written as zeros): the normal is the axis of the smallest scale
 *     (the rotation's column; turned away from the cloud's centroid, since a splat has no side), the
 *     radius twice the geometric mean of the two other scales (scales are stored as logs: two standard
 *     deviations, the method's default cutoff), the colour 0.5 + 0.28209479 f_dc (the band-0 spherical
 *     harmonic 1 / (2 sqrt(pi))), clamped to [0, 1] and decoded from sRGB. opacity and f_rest are not
 *     used.
 * Fails with LUCENT_ERR_PARSE and a message naming the file and, for bad values, the vertex and the
 * property: no positions or no normals, fewer than two points, a value that is not finite, a zero
 * normal, a radius <= 0, a truncated or malformed file. */
lucent_status lucent_surfels_load(const char *path, const lucent_surfels_desc *desc, lucent_surfels **dest);

/* Moves surfels by the affine column-major m: positions by m, normals by its inverse transpose
 * (renormalised; turned with a mirroring map's sign so they keep their side), radii and spacings by
 * the cube root of |det| (exact for uniform scales). */
void lucent_surfels_transform(lucent_surfels *surfels, const double m[16]);

/* Frees surfels (NULL is accepted). */
void lucent_surfels_destroy(lucent_surfels *surfels);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_SURFELS_H */
