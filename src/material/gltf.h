/* The glTF material mapping's JSON side (lucent/gltf.h), shared with the scene reader and the pack.
 * Not public: cJSON types stay inside. */
#ifndef LUCENT_MATERIAL_GLTF_H
#define LUCENT_MATERIAL_GLTF_H

#include "base/json.h"
#include "lucent/gltf.h"

/* The glTF material object of g, with extras.lucent holding exact (m's coefficients) and
 * roughness_alpha when exact is non-NULL. NULL when out of memory. */
cJSON *material_gltf_object(const lucent_gltf_material *g, const lucent_material *exact, double roughness_alpha);

/* What a glTF material object says. has_exact: extras.lucent was there and is read into exact and
 * *exact_roughness (checked like a material file's); otherwise those are untouched. Errors name the
 * file and the JSON path ("a.gltf: materials[2].extensions.KHR_materials_volume.attenuationColor[1]:
 * must be in (0, 1], got 0"). n->json must be an object. */
lucent_status material_gltf_read(const lucent_json_node *n, lucent_gltf_material *g, bool *has_exact,
                                 lucent_material *exact, double *exact_roughness);

#endif
