/* Primitives with analytic curvature, for tests: UV sphere / ellipsoid (one generator),
 * icosphere, torus. Jitter moves vertices in parameter space (or tangentially, then back onto
 * the sphere), so they stay exactly on the surface. */
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/internal.h"

static lucent_primitive_desc resolve(const lucent_primitive_desc *d)
{
    lucent_primitive_desc r = *d;
    if (!(r.radius > 0)) r.radius = 1;
    if (!(r.major_radius > 0)) r.major_radius = 3;
    for (int k = 0; k < 3; k++)
        if (!(r.axes[k] > 0)) r.axes[k] = r.kind == LUCENT_PRIMITIVE_UV_SPHERE ? r.radius : 1;
    if (r.kind == LUCENT_PRIMITIVE_UV_SPHERE) r.axes[0] = r.axes[1] = r.axes[2] = r.radius;
    if (r.u_count <= 0) r.u_count = 64;
    if (r.v_count <= 0) r.v_count = 32;
    if (r.subdivisions <= 0) r.subdivisions = 3;
    return r;
}

/* A symmetric random offset in [-amount, amount). */
static double jitter(lucent_rng *rng, double amount)
{
    return amount == 0 ? 0 : amount * (2 * lucent_rng_uniform(rng) - 1);
}

static void quad(uint32_t *f, uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
    f[0] = a, f[1] = b, f[2] = c, f[3] = a, f[4] = c, f[5] = d;
}

/* Per-corner texture coordinates from per-vertex ones that wrap at 1 (wrap[i]: coordinate i is
 * periodic): a face across the seam gets 1 added to the corners below one half, so that it spans
 * the seam instead of the whole texture. A corner at a pole (pole[v]) takes the mean u of the
 * other two. */
static lucent_status corner_uvs(lucent_mesh *m, const double *vertex_uv, const bool wrap[2], const uint8_t *pole)
{
    m->uvs = malloc(6 * m->face_count * sizeof *m->uvs + 1);
    if (!m->uvs) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory for texture coordinates");
    for (size_t f = 0; f < m->face_count; f++) {
        double *c = m->uvs + 6 * f;
        for (int k = 0; k < 3; k++) memcpy(c + 2 * k, vertex_uv + 2 * m->faces[3 * f + k], 2 * sizeof *c);
        for (int i = 0; i < 2; i++) {
            double lo = fmin(c[i], fmin(c[2 + i], c[4 + i])), hi = fmax(c[i], fmax(c[2 + i], c[4 + i]));
            for (int k = 0; wrap[i] && hi - lo > 0.5 && k < 3; k++)
                if (c[2 * k + i] < 0.5 && !(pole && pole[m->faces[3 * f + k]])) c[2 * k + i] += 1;
        }
        for (int k = 0; pole && k < 3; k++)
            if (pole[m->faces[3 * f + k]]) c[2 * k] = 0.5 * (c[2 * ((k + 1) % 3)] + c[2 * ((k + 2) % 3)]);
    }
    return LUCENT_OK;
}

/* The ellipsoid's analytic coordinates: u = phi / 2 pi about z, v = 1 - theta / pi (v = 1 at the
 * north pole +z), from each vertex's position (jittered ones included). */
static lucent_status ellipsoid_uvs(lucent_mesh *m, const double axes[3])
{
    double *uv = malloc(2 * m->vertex_count * sizeof *uv);
    uint8_t *pole = calloc(m->vertex_count, 1);
    lucent_status s = uv && pole ? LUCENT_OK : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (size_t v = 0; s == LUCENT_OK && v < m->vertex_count; v++) {
        const double *p = m->positions + 3 * v;
        double x = p[0] / axes[0], y = p[1] / axes[1], z = fmax(-1, fmin(1, p[2] / axes[2]));
        double phi = atan2(y, x);
        uv[2 * v] = (phi < 0 ? phi + 2 * M_PI : phi) / (2 * M_PI);
        uv[2 * v + 1] = 1 - acos(z) / M_PI;
        pole[v] = v == 0 || v == m->vertex_count - 1;
    }
    if (s == LUCENT_OK) s = corner_uvs(m, uv, (const bool[2]){true, false}, pole);
    free(uv), free(pole);
    return s;
}

/* Ellipsoid (a UV sphere when the axes are equal): poles on z, u_count slices, v_count stacks. */
static lucent_status make_ellipsoid(const lucent_primitive_desc *d, lucent_mesh **dest)
{
    int nu = d->u_count, nv = d->v_count < 2 ? 2 : d->v_count;
    size_t rings = (size_t)nv - 1;
    lucent_status s = lucent_mesh_create(2 + rings * (size_t)nu, 2 * (size_t)nu * rings, dest);
    if (s != LUCENT_OK) return s;
    lucent_mesh *m = *dest;
    double du = 2 * M_PI / nu, dv = M_PI / nv;
    for (size_t j = 0; j < rings; j++)
        for (int i = 0; i < nu; i++) {
            size_t v = 1 + j * (size_t)nu + (size_t)i;
            lucent_rng rng;
            lucent_rng_init(d->seed, v, &rng);
            double phi = i * du + jitter(&rng, d->jitter * du),
                   th = (double)(j + 1) * dv + jitter(&rng, d->jitter * dv);
            double *p = m->positions + 3 * v;
            p[0] = d->axes[0] * sin(th) * cos(phi), p[1] = d->axes[1] * sin(th) * sin(phi), p[2] = d->axes[2] * cos(th);
        }
    m->positions[2] = d->axes[2];
    m->positions[3 * (m->vertex_count - 1) + 2] = -d->axes[2];
    uint32_t *f = m->faces, south = (uint32_t)(m->vertex_count - 1);
    for (int i = 0; i < nu; i++) {
        uint32_t a = 1 + (uint32_t)i, b = 1 + (uint32_t)((i + 1) % nu);
        f[0] = 0, f[1] = a, f[2] = b, f += 3;
        for (size_t j = 0; j + 1 < rings; j++) {
            uint32_t r0 = (uint32_t)(1 + j * (size_t)nu), r1 = r0 + (uint32_t)nu;
            quad(f, r0 + (uint32_t)i, r1 + (uint32_t)i, r1 + (b - 1), r0 + (b - 1)), f += 6;
        }
        uint32_t last = (uint32_t)(1 + (rings - 1) * (size_t)nu);
        f[0] = last + (uint32_t)i, f[1] = south, f[2] = last + (b - 1), f += 3;
    }
    lucent_mesh_compute_normals(m);
    s = ellipsoid_uvs(m, d->axes);
    if (s != LUCENT_OK) lucent_mesh_destroy(m), *dest = NULL;
    return s;
}

/* Torus around z: major radius R, tube radius r; u around z, v around the tube. */
static lucent_status make_torus(const lucent_primitive_desc *d, lucent_mesh **dest)
{
    int nu = d->u_count, nv = d->v_count;
    lucent_status s = lucent_mesh_create((size_t)nu * (size_t)nv, 2 * (size_t)nu * (size_t)nv, dest);
    if (s != LUCENT_OK) return s;
    lucent_mesh *m = *dest;
    double du = 2 * M_PI / nu, dv = 2 * M_PI / nv, R = d->major_radius, r = d->radius;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            size_t v = (size_t)i * (size_t)nv + (size_t)j;
            lucent_rng rng;
            lucent_rng_init(d->seed, v, &rng);
            double u = i * du + jitter(&rng, d->jitter * du), w = j * dv + jitter(&rng, d->jitter * dv);
            double *p = m->positions + 3 * v;
            p[0] = (R + r * cos(w)) * cos(u), p[1] = (R + r * cos(w)) * sin(u), p[2] = r * sin(w);
            uint32_t a = (uint32_t)v, b = (uint32_t)(((i + 1) % nu) * nv + j);
            uint32_t c = (uint32_t)(((i + 1) % nu) * nv + (j + 1) % nv), e = (uint32_t)(i * nv + (j + 1) % nv);
            quad(m->faces + 6 * v, a, b, c, e);
        }
    lucent_mesh_compute_normals(m);
    /* u = the angle about z, v = the angle about the tube, both over 2 pi */
    double *uv = malloc(2 * m->vertex_count * sizeof *uv);
    if (!uv) {
        lucent_mesh_destroy(m), *dest = NULL;
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    }
    for (size_t v = 0; v < m->vertex_count; v++) {
        const double *p = m->positions + 3 * v;
        double a = atan2(p[1], p[0]), w = atan2(p[2], hypot(p[0], p[1]) - R);
        uv[2 * v] = (a < 0 ? a + 2 * M_PI : a) / (2 * M_PI), uv[2 * v + 1] = (w < 0 ? w + 2 * M_PI : w) / (2 * M_PI);
    }
    s = corner_uvs(m, uv, (const bool[2]){true, true}, NULL);
    free(uv);
    if (s != LUCENT_OK) lucent_mesh_destroy(m), *dest = NULL;
    return s;
}

lucent_status lucent_mesh_primitive(const lucent_primitive_desc *desc, lucent_mesh **dest)
{
    *dest = NULL;
    lucent_primitive_desc d = resolve(desc);
    if (d.u_count < 3 || d.v_count < 2 || d.u_count > 1 << 14 || d.v_count > 1 << 14 || d.subdivisions > 9 ||
        !(d.jitter >= 0 && d.jitter < 0.5))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "primitive: grid 3..16384 x 2..16384, "
                                                         "subdivisions <= 9, jitter in [0, 0.5)");
    switch (d.kind) {
    case LUCENT_PRIMITIVE_UV_SPHERE:
    case LUCENT_PRIMITIVE_ELLIPSOID: return make_ellipsoid(&d, dest);
    case LUCENT_PRIMITIVE_TORUS:
        if (d.v_count < 3) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "torus: v_count >= 3");
        return d.major_radius > d.radius
                   ? make_torus(&d, dest)
                   : lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "torus: major radius must exceed the tube radius");
    case LUCENT_PRIMITIVE_ICOSPHERE: return mesh_icosphere(&d, dest);
    }
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "unknown primitive kind %d", (int)d.kind);
}

/* Ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 with outward normal: with
 * W = x^2/a^4 + y^2/b^4 + z^2/c^4, K = 1 / (a^2 b^2 c^2 W^2) and
 * H = (a^2 + b^2 + c^2 - |p|^2) / (2 a^2 b^2 c^2 W^(3/2)) (e.g. Weisstein, MathWorld "Ellipsoid"). */
static void ellipsoid_curvature(const double *ax, const double *p, lucent_curvature_value *dest)
{
    double a2 = ax[0] * ax[0], b2 = ax[1] * ax[1], c2 = ax[2] * ax[2];
    double w = p[0] * p[0] / (a2 * a2) + p[1] * p[1] / (b2 * b2) + p[2] * p[2] / (c2 * c2);
    dest->gauss = 1 / (a2 * b2 * c2 * w * w);
    dest->mean = (a2 + b2 + c2 - v3_dot(v3_load(p), v3_load(p))) / (2 * a2 * b2 * c2 * pow(w, 1.5));
}

lucent_status lucent_primitive_curvature(const lucent_primitive_desc *desc, const double point[3],
                                         lucent_curvature_value *dest)
{
    lucent_primitive_desc d = resolve(desc);
    if (d.kind == LUCENT_PRIMITIVE_TORUS) {
        /* Torus: k1 = 1/r (around the tube), k2 = cos v / (R + r cos v) (do Carmo 1976, 3-3). */
        double rho = hypot(point[0], point[1]), cv = (rho - d.major_radius) / d.radius;
        dest->k1 = 1 / d.radius, dest->k2 = cv / rho;
        dest->mean = 0.5 * (dest->k1 + dest->k2), dest->gauss = dest->k1 * dest->k2;
        return LUCENT_OK;
    }
    if (d.kind == LUCENT_PRIMITIVE_ICOSPHERE) d.axes[0] = d.axes[1] = d.axes[2] = d.radius;
    ellipsoid_curvature(d.axes, point, dest);
    double disc = sqrt(fmax(0, dest->mean * dest->mean - dest->gauss));
    dest->k1 = dest->mean + disc, dest->k2 = dest->mean - disc;
    return LUCENT_OK;
}
