# Blender 3.4's glTF importer (the io_scene_gltf2 add-on Debian's `blender` ships) on a glTF, and the
# values it leaves in the materials' nodes, as JSON, for tests/pack_peer_test.sh (issue 30 section 3:
# the pack's material.gltf must import as a material with transmission and volume):
#
#   blender -b --factory-startup -P scripts/peer/gltf_import.py -- IN.gltf OUT.json
#
# OUT.json: {"objects": [{"name", "type", "materials"}], "materials": {NAME: {"principled": {input:
# value}, "volume_absorption": {"Color", "Density"}, "volume_linked": bool, "thickness": value or
# null}}}. Colours are RGBA lists as Blender holds them (float32). The importer needs numpy (Debian:
# python3-numpy).
import json
import sys

import bpy
import numpy

# Debian 12 ships Blender 3.4 with numpy 1.24, which removed the alias np.bool that the importer's
# mesh code still uses (io_scene_gltf2/blender/imp/gltf2_blender_mesh.py); put the alias back.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

argv = sys.argv[sys.argv.index("--") + 1:]
src, out = argv[0], argv[1]

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=src)


def value(socket):
    v = socket.default_value
    try:
        return [float(x) for x in v]
    except TypeError:
        return float(v)


PRINCIPLED = ["Base Color", "Metallic", "Roughness", "IOR", "Transmission", "Subsurface"]

result = {"objects": [], "materials": {}}
for ob in bpy.data.objects:
    mats = [s.material.name for s in ob.material_slots if s.material] if ob.type == "MESH" else []
    result["objects"].append({"name": ob.name, "type": ob.type, "materials": mats})
for mat in bpy.data.materials:
    if not mat.use_nodes:
        continue
    nodes = mat.node_tree.nodes
    d = {"principled": None, "volume_absorption": None, "volume_linked": False, "thickness": None}
    for n in nodes:
        if n.type == "BSDF_PRINCIPLED":
            d["principled"] = {k: value(n.inputs[k]) for k in PRINCIPLED}
        elif n.type == "VOLUME_ABSORPTION":
            d["volume_absorption"] = {"Color": value(n.inputs["Color"]), "Density": value(n.inputs["Density"])}
        elif n.type == "OUTPUT_MATERIAL":
            d["volume_linked"] = d["volume_linked"] or n.inputs["Volume"].is_linked
        elif n.type == "GROUP" and n.node_tree and "Thickness" in n.inputs:
            d["thickness"] = value(n.inputs["Thickness"])
    result["materials"][mat.name] = d

with open(out, "w") as f:
    json.dump(result, f, indent=1)
