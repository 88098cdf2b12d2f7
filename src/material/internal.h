/* Shared with other modules that embed materials in their own files (scenes). Not public. */
#ifndef LUCENT_MATERIAL_INTERNAL_H
#define LUCENT_MATERIAL_INTERNAL_H

#include "base/json.h"
#include "lucent/material.h"

/* Reads one material object at node n (errors carry n's file and JSON path); def_name names it
 * when it has no "name" (NULL: "name" is required). */
lucent_status material_read_json(const lucent_json_node *n, const char *def_name, lucent_material *m);

#endif
