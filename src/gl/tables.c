/* The scene's distinct materials, their bakes and the transmittance texture (tables.h). */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "gl/tables.h"

static bool same_material(const lucent_material *a, const lucent_material *b)
{
    return !strcmp(a->name, b->name) && !memcmp(a->sigma_a, b->sigma_a, sizeof a->sigma_a) &&
           !memcmp(a->sigma_s, b->sigma_s, sizeof a->sigma_s) && !memcmp(a->g, b->g, sizeof a->g) && a->eta == b->eta;
}

static bool same_entry(const gl_tables *t, int k, const lucent_material *m, double roughness)
{
    return same_material(&t->material[k], m) && t->roughness[k] == roughness;
}

lucent_status gl_tables_collect(gl_tables *t, const lucent_scene *scene)
{
    t->object_material = calloc((size_t)scene->object_count, sizeof *t->object_material);
    if (!t->object_material) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (int i = 0; i < scene->object_count; i++) {
        const lucent_material *m = &scene->objects[i].material;
        double rough = scene->objects[i].roughness;
        int k = 0;
        while (k < t->count && !same_entry(t, k, m, rough)) k++;
        if (k == GLR_MAX_MATERIALS)
            return lucent_error(LUCENT_ERR_UNSUPPORTED, "%s: more than %d distinct materials (with their roughness)",
                                scene->name, GLR_MAX_MATERIALS);
        if (k == t->count) {
            memset(&t->baked[k], 0, sizeof t->baked[k]);
            t->material[k] = *m, t->roughness[k] = rough;
            t->count++;
        }
        t->object_material[i] = k;
    }
    return LUCENT_OK;
}

lucent_status gl_tables_recollect(gl_tables *t, const lucent_scene *scene)
{
    gl_tables old = *t;
    memset(t, 0, sizeof *t);
    lucent_status s = gl_tables_collect(t, scene);
    bool kept[GLR_MAX_MATERIALS] = {false};
    for (int k = 0; s == LUCENT_OK && k < t->count; k++)
        for (int j = 0; j < old.count; j++)
            if (!kept[j] && same_entry(t, k, &old.material[j], old.roughness[j])) {
                t->baked[k] = old.baked[j], kept[j] = true;
                break;
            }
    for (int j = 0; j < old.count; j++)
        if (!kept[j]) lucent_baked_free(&old.baked[j]);
    if (old.transmit_tex) glDeleteTextures(1, &old.transmit_tex);
    if (old.boundary_tex) glDeleteTextures(1, &old.boundary_tex);
    if (old.spheres_tex) glDeleteTextures(1, &old.spheres_tex);
    if (old.sheet_tex) glDeleteTextures(1, &old.sheet_tex);
    free(old.object_material);
    return s;
}

lucent_status gl_tables_adopt(gl_tables *t, const lucent_material *m, const lucent_baked *baked)
{
    bool found = false;
    for (int k = 0; k < t->count; k++)
        if (same_material(&t->material[k], m)) {
            t->transmit_key[0] = t->boundary_key[0] = t->spheres_key[0] = t->sheet_key[0] = '\0'; /* rows may
                                                                                                change under a key */
            lucent_status s = lucent_baked_copy(baked, &t->baked[k]);
            if (s != LUCENT_OK) return s;
            found = true;
        }
    return found ? LUCENT_OK : lucent_error(LUCENT_ERR_NOT_FOUND, "no object has the material %s", m->name);
}

lucent_status gl_tables_bake(gl_tables *t, const lucent_bake_desc *desc, lucent_cache *cache)
{
    lucent_status s = LUCENT_OK;
    for (int i = 0; i < t->count && s == LUCENT_OK; i++) {
        lucent_bake_desc d = *desc;
        d.roughness = t->roughness[i];
        s = lucent_material_bake(&t->material[i], &d, cache, &t->baked[i]);
    }
    return s;
}

lucent_status gl_tables_upload_transmittance(gl_tables *t)
{
    char key[sizeof t->transmit_key] = "";
    for (int m = 0; m < t->count; m++)
        snprintf(key + strlen(key), sizeof key - strlen(key), "%s|", t->baked[m].transmit_key);
    if (t->transmit_tex && !strcmp(t->transmit_key, key)) return LUCENT_OK;
    enum { N = LUCENT_BAKE_TRANSMIT_SIZE };
    float rows[GLR_MAX_MATERIALS][N * 3];
    for (int m = 0; m < t->count; m++) memcpy(rows[m], t->baked[m].transmittance, sizeof rows[m]);
    if (t->transmit_tex) glDeleteTextures(1, &t->transmit_tex);
    t->transmit_tex = gl_texture(GL_RGB32F, N, t->count, GL_LINEAR);
    glTextureSubImage2D(t->transmit_tex, 0, 0, 0, N, t->count, GL_RGB, GL_FLOAT, rows);
    snprintf(t->transmit_key, sizeof t->transmit_key, "%s", key);
    return gl_check("uploading the transmittance tables");
}

lucent_status gl_tables_upload_boundary(gl_tables *t)
{
    char key[sizeof t->boundary_key] = "";
    for (int m = 0; m < t->count; m++)
        snprintf(key + strlen(key), sizeof key - strlen(key), "%s|", t->baked[m].boundary_key);
    if (t->boundary_tex && !strcmp(t->boundary_key, key)) return LUCENT_OK;
    enum { N = LUCENT_BOUNDARY_BINS };
    if (t->boundary_tex) glDeleteTextures(1, &t->boundary_tex);
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &t->boundary_tex);
    glTextureStorage3D(t->boundary_tex, 1, GL_RGB32F, N, N + 1, t->count > 0 ? t->count : 1);
    for (int m = 0; m < t->count; m++)
        glTextureSubImage3D(t->boundary_tex, 0, 0, 0, m, N, N + 1, 1, GL_RGB, GL_FLOAT, t->baked[m].boundary);
    glTextureParameteri(t->boundary_tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(t->boundary_tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t->boundary_tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t->boundary_tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    snprintf(t->boundary_key, sizeof t->boundary_key, "%s", key);
    return gl_check("uploading the boundary's tables");
}

/* One RGB32F array texture layer per material of a baked table (an array inside lucent_baked at data_off,
 * w x h texels, keyed by the string at key_off), uploaded again only when a material's key changed. */
static lucent_status upload_layers(gl_tables *t, GLuint *tex, char *cur, size_t cur_size, size_t key_off,
                                   size_t data_off, int w, int h, const char *what)
{
    char key[GLR_MAX_MATERIALS * LUCENT_BAKE_KEY_SIZE] = ""; /* the size of spheres_key and sheet_key */
    for (int m = 0; m < t->count; m++)
        snprintf(key + strlen(key), sizeof key - strlen(key), "%s|", (const char *)&t->baked[m] + key_off);
    if (*tex && !strcmp(cur, key)) return LUCENT_OK;
    if (*tex) glDeleteTextures(1, tex);
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, tex);
    glTextureStorage3D(*tex, 1, GL_RGB32F, w, h, t->count > 0 ? t->count : 1);
    for (int m = 0; m < t->count; m++)
        glTextureSubImage3D(*tex, 0, 0, 0, m, w, h, 1, GL_RGB, GL_FLOAT, (const char *)&t->baked[m] + data_off);
    glTextureParameteri(*tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(*tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(*tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(*tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    snprintf(cur, cur_size, "%s", key);
    return gl_check(what);
}

lucent_status gl_tables_upload_spheres(gl_tables *t)
{
    return upload_layers(t, &t->spheres_tex, t->spheres_key, sizeof t->spheres_key, offsetof(lucent_baked, spheres_key),
                         offsetof(lucent_baked, spheres), LUCENT_BAKE_SPHERE_BINS, 2 * (LUCENT_BAKE_SPHERE_RADII + 1),
                         "uploading the curved parts' tables");
}

lucent_status gl_tables_upload_sheet(gl_tables *t)
{
    return upload_layers(t, &t->sheet_tex, t->sheet_key, sizeof t->sheet_key, offsetof(lucent_baked, sheet_key),
                         offsetof(lucent_baked, sheet), LUCENT_SHEET_BINS, 2 * LUCENT_BAKE_SHEET_ROWS,
                         "uploading the thin parts' sheet tables");
}

const lucent_baked *gl_tables_of(const gl_tables *t, int object) { return &t->baked[t->object_material[object]]; }

void gl_tables_free(gl_tables *t)
{
    for (int i = 0; i < t->count; i++) lucent_baked_free(&t->baked[i]);
    if (t->transmit_tex) glDeleteTextures(1, &t->transmit_tex);
    if (t->boundary_tex) glDeleteTextures(1, &t->boundary_tex);
    if (t->spheres_tex) glDeleteTextures(1, &t->spheres_tex);
    if (t->sheet_tex) glDeleteTextures(1, &t->sheet_tex);
    free(t->object_material);
    memset(t, 0, sizeof *t);
}
