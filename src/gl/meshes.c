/* The scene's meshes on the GPU: positions and normals (world mm), texture coordinates and albedo
 * maps, and the per-vertex mean curvature the CDRF reads (computed when first needed). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/meshes.h"
#include "lucent/mesh.h"

/* Vertex-buffer bindings. */
enum { BIND_VERTICES = 0, BIND_CURVATURE = 1, BIND_UV = 2 };

static GLuint buffer(const void *data, size_t size)
{
    GLuint b;
    glCreateBuffers(1, &b);
    glNamedBufferData(b, (GLsizeiptr)size, data, GL_STATIC_DRAW);
    return b;
}

static void attribute(GLuint vao, GLuint attr, GLuint binding, int size, GLuint offset)
{
    glEnableVertexArrayAttrib(vao, attr);
    glVertexArrayAttribFormat(vao, attr, size, GL_FLOAT, GL_FALSE, offset);
    glVertexArrayAttribBinding(vao, attr, binding);
}

/* Interleaved position + normal as floats. */
static lucent_status upload_vertices(const lucent_mesh *m, gl_mesh *g)
{
    float *v = malloc(m->vertex_count * 6 * sizeof *v);
    if (!v) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory uploading a mesh");
    for (size_t i = 0; i < m->vertex_count; i++)
        for (int c = 0; c < 3; c++)
            v[6 * i + c] = (float)m->positions[3 * i + c], v[6 * i + 3 + c] = (float)m->normals[3 * i + c];
    g->vertices = buffer(v, m->vertex_count * 6 * sizeof *v);
    free(v);
    g->indices = buffer(m->faces, m->face_count * 3 * sizeof *m->faces);
    g->index_count = (GLsizei)(m->face_count * 3);
    glCreateVertexArrays(1, &g->vao);
    glVertexArrayVertexBuffer(g->vao, BIND_VERTICES, g->vertices, 0, 6 * sizeof(float));
    glVertexArrayElementBuffer(g->vao, g->indices);
    attribute(g->vao, GL_ATTR_POSITION, BIND_VERTICES, 3, 0);
    attribute(g->vao, GL_ATTR_NORMAL, BIND_VERTICES, 3, 3 * sizeof(float));
    return LUCENT_OK;
}

static lucent_status upload_texture(const lucent_scene_object *o, gl_mesh *g)
{
    size_t n = o->mesh->vertex_count;
    float *uv = malloc(n * 2 * sizeof *uv);
    if (!uv) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory uploading texture coordinates");
    for (size_t i = 0; i < 2 * n; i++) uv[i] = (float)o->texcoords[i];
    g->uvs = buffer(uv, n * 2 * sizeof *uv);
    free(uv);
    glVertexArrayVertexBuffer(g->vao, BIND_UV, g->uvs, 0, 2 * sizeof(float));
    attribute(g->vao, GL_ATTR_UV, BIND_UV, 2, 0);
    lucent_status s = gl_texture_from_image(o->albedo_texture, GL_LINEAR, &g->albedo_map);
    if (s == LUCENT_OK) {
        glTextureParameteri(g->albedo_map, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTextureParameteri(g->albedo_map, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    }
    return s == LUCENT_OK ? LUCENT_OK : lucent_error_context(s, "object \"%s\": albedo_texture", o->name);
}

lucent_status gl_meshes_upload(gl_meshes *m, const lucent_scene *sc)
{
    m->mesh = calloc((size_t)sc->object_count, sizeof *m->mesh);
    if (!m->mesh) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    m->count = sc->object_count;
    lucent_status s = LUCENT_OK;
    for (int i = 0; i < sc->object_count && s == LUCENT_OK; i++) {
        const lucent_scene_object *o = &sc->objects[i];
        gl_mesh *g = &m->mesh[i];
        g->curvature_smooth = -1;
        if (!o->mesh) {
            s = lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "object \"%s\" has no mesh (scene loaded with skip_meshes?)",
                             o->name);
            break;
        }
        s = upload_vertices(o->mesh, g);
        if (s == LUCENT_OK && o->albedo_texture && o->texcoords) s = upload_texture(o, g);
    }
    return s == LUCENT_OK ? gl_check("uploading the meshes") : s;
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void percentiles(const double *v, size_t n, double dest[2])
{
    double *copy = malloc(n * sizeof *copy);
    dest[0] = dest[1] = 0;
    if (!copy || n == 0) return free(copy);
    memcpy(copy, v, n * sizeof *copy);
    qsort(copy, n, sizeof *copy, compare_doubles);
    dest[0] = copy[(size_t)(0.05 * (double)(n - 1))], dest[1] = copy[(size_t)(0.95 * (double)(n - 1))];
    free(copy);
}

/* Rusinkiewicz's estimator on the mesh in world mm, so the mean curvature is in mm^-1. */
static lucent_status one_curvature(const lucent_scene_object *o, gl_mesh *g, int rings, lucent_pool *pool)
{
    lucent_curvature c;
    lucent_curvature_desc d = {.method = LUCENT_CURVATURE_RUSINKIEWICZ, .smooth_rings = rings, .pool = pool};
    lucent_status s = lucent_mesh_curvature(o->mesh, &d, &c);
    if (s != LUCENT_OK) return lucent_error_context(s, "object \"%s\": curvature", o->name);
    float *k = malloc(c.count * sizeof *k);
    if (!k) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (size_t i = 0; k && i < c.count; i++) k[i] = (float)c.mean[i];
    if (k) {
        if (!g->curvature) glCreateBuffers(1, &g->curvature);
        glNamedBufferData(g->curvature, (GLsizeiptr)(c.count * sizeof *k), k, GL_STATIC_DRAW);
        glVertexArrayVertexBuffer(g->vao, BIND_CURVATURE, g->curvature, 0, sizeof(float));
        attribute(g->vao, GL_ATTR_CURVATURE, BIND_CURVATURE, 1, 0);
        percentiles(c.mean, c.count, g->curvature_range);
        g->curvature_smooth = rings;
    }
    free(k);
    lucent_curvature_free(&c);
    return s;
}

lucent_status gl_meshes_curvature(gl_meshes *m, const lucent_scene *scene, int smooth_rings, lucent_pool *pool)
{
    lucent_status s = LUCENT_OK;
    for (int i = 0; i < m->count && s == LUCENT_OK; i++)
        if (m->mesh[i].curvature_smooth != smooth_rings && scene->objects[i].visible &&
            scene->objects[i].mesh->face_count > 0) /* a point cloud has no curvature to upload */
            s = one_curvature(&scene->objects[i], &m->mesh[i], smooth_rings, pool);
    return s == LUCENT_OK ? gl_check("uploading curvature") : s;
}

void gl_meshes_draw(const gl_meshes *m, int i)
{
    glBindVertexArray(m->mesh[i].vao);
    glDrawElements(GL_TRIANGLES, m->mesh[i].index_count, GL_UNSIGNED_INT, NULL);
}

void gl_meshes_free(gl_meshes *m)
{
    for (int i = 0; m->mesh && i < m->count; i++) {
        gl_mesh *g = &m->mesh[i];
        GLuint buffers[4] = {g->vertices, g->indices, g->curvature, g->uvs};
        glDeleteBuffers(4, buffers);
        if (g->vao) glDeleteVertexArrays(1, &g->vao);
        if (g->albedo_map) glDeleteTextures(1, &g->albedo_map);
    }
    free(m->mesh);
    m->mesh = NULL, m->count = 0;
}
