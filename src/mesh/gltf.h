/* glTF 2.0 documents (.gltf with external or data-URI buffers, .glb), read for hostile input, and the
 * mesh part of writing one. Shared with the scene reader (src/scene/gltf.c) and the pack
 * (src/engine/pack_gltf.c). Not public: cJSON types stay inside. docs/scenes.md#gltf-scenes. */
#ifndef LUCENT_MESH_GLTF_H
#define LUCENT_MESH_GLTF_H

#include "base/json.h"
#include "lucent/mesh.h"

typedef struct gltf_doc gltf_doc;

/* Opens a .gltf or a .glb (told apart by the first bytes): the JSON parsed, nothing else read yet.
 * Buffers are read when a primitive needs them: the GLB's BIN chunk, a base64 data URI, or a file in
 * the document's folder or below (an absolute path, "..", or another scheme is refused). */
lucent_status gltf_open(const char *path, gltf_doc **dest);

/* The same from memory (copied); name stands for the file in messages; base_dir resolves external
 * buffers (NULL: they are refused). */
lucent_status gltf_open_memory(const void *data, size_t size, const char *name, const char *base_dir, gltf_doc **dest);

void gltf_close(gltf_doc *doc);

/* The document's root (an object; checked by gltf_open), named by the file in messages. */
lucent_json_node gltf_root(const gltf_doc *doc);

/* The file it came from (as given to gltf_open). */
const char *gltf_path(const gltf_doc *doc);

/* Reads primitive `primitive` of mesh `mesh`: POSITION (float VEC3), the indices (unsigned byte,
 * short or int; absent: the vertices in order), triangles, strips or fans as triangles; vertices at
 * identical positions welded and normals computed as lucent_mesh_load does. In the file's units, not
 * moved by any node. Errors name the file and the JSON path of the bad member. */
lucent_status gltf_read_primitive(gltf_doc *doc, int mesh, int primitive, lucent_mesh **dest);

/* True for modes 4, 5 and 6 (triangles, strip, fan): what gltf_read_primitive reads. */
bool gltf_mode_is_surface(int mode);

/* Adds the mesh to a glTF document: one buffer (a base64 data URI) with positions and normals (float
 * VEC3, scaled by scale: 0.001 turns mm into glTF's metres), TEXCOORD_0 when the mesh has texture
 * coordinates (vertices split where corners differ; v flipped to glTF's top-left origin) and uint32
 * indices, its views and accessors (POSITION with min and max), and meshes[*index], one primitive of
 * triangles using material (-1: none). root must be an object without buffers yet. */
lucent_status gltf_add_mesh(cJSON *root, const lucent_mesh *mesh, double scale, int material, int *index);

#endif
