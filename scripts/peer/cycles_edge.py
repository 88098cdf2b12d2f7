# The peer's side of the engine models' test (tests/test_engine.c, cycles_edge_*): Blender 3.4's Cycles
# renders the edge of a shadow on a half-space of one Principled BSDF, so that the engine's own profile
# can be compared with Lucent's model of it (src/engine/burley.c, cycles_walk.c) without running Blender
# at test time. Needs Blender (Debian's `blender` 3.4):
#
#   blender -b --factory-startup -noaudio -P scripts/peer/cycles_edge.py -- OUT.json SAMPLES SEED
#
# The scene, one Blender unit a millimetre: a box 4 m wide and 2 m deep (a half-space for these radii), its
# top at z = 0, Specular 0; a black plate 1 mm above it over x > 0 (invisible to the camera) casts a sharp
# shadow from a delta sun straight down (strength 1: irradiance 1); an orthographic camera looks down on
# 40 mm x 2 mm, 160 x 8 pixels (one-pixel box filter, Standard view, no denoising). Each column's mean
# times pi is the radiance of a Lambertian exit in units of the irradiance: T P(x), P the share of the
# profile over the lit half-plane at x mm from the edge. Two materials:
#   burley: Christensen-Burley, colour 0.5, radius 8 mm;
#   walk:   Random Walk, colour 0.5, radius 3 mm, Subsurface IOR 1.3, anisotropy 0.
import json
import math
import sys

import bpy

WIDTH, HEIGHT, SPAN = 160, 8, 40.0
CASES = {'burley': ('BURLEY', 0.5, 8.0), 'walk': ('RANDOM_WALK', 0.5, 3.0)}


def render(method, color, radius, samples, seed, exr):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    sc.render.engine = 'CYCLES'
    cy = sc.cycles
    cy.device = 'CPU'
    cy.samples = samples
    cy.seed = seed
    cy.use_denoising = False
    cy.use_adaptive_sampling = False
    cy.max_bounces = 32
    cy.diffuse_bounces = 8
    cy.pixel_filter_type = 'BOX'
    cy.filter_width = 1.0
    sc.render.resolution_x, sc.render.resolution_y = WIDTH, HEIGHT
    sc.render.image_settings.file_format = 'OPEN_EXR'
    sc.render.image_settings.color_depth = '32'
    sc.view_settings.view_transform = 'Standard'
    world = bpy.data.worlds.new('black')
    world.use_nodes = True
    world.node_tree.nodes['Background'].inputs['Strength'].default_value = 0.0
    sc.world = world
    bpy.ops.mesh.primitive_cube_add(size=1.0)
    box = bpy.context.active_object
    box.scale, box.location = (4000, 4000, 2000), (0, 0, -1000)
    mat = bpy.data.materials.new('m')
    mat.use_nodes = True
    b = mat.node_tree.nodes['Principled BSDF']
    b.subsurface_method = method
    b.inputs['Base Color'].default_value = (color, color, color, 1)
    b.inputs['Subsurface'].default_value = 1.0
    b.inputs['Subsurface Color'].default_value = (color, color, color, 1)
    b.inputs['Subsurface Radius'].default_value = (radius, radius, radius)
    b.inputs['Subsurface IOR'].default_value = 1.3
    b.inputs['Subsurface Anisotropy'].default_value = 0.0
    b.inputs['Specular'].default_value = 0.0
    box.data.materials.append(mat)
    bpy.ops.mesh.primitive_plane_add(size=1.0)
    plate = bpy.context.active_object
    plate.scale, plate.location = (4000, 4000, 1), (2000, 0, 1.0)
    plate.visible_camera = False
    black = bpy.data.materials.new('black')
    black.use_nodes = True
    black.node_tree.nodes['Principled BSDF'].inputs['Base Color'].default_value = (0, 0, 0, 1)
    plate.data.materials.append(black)
    cam = bpy.data.cameras.new('camera')
    cam.type, cam.ortho_scale = 'ORTHO', SPAN
    cam_ob = bpy.data.objects.new('camera', cam)
    cam_ob.location = (0, 0, 100)
    sc.collection.objects.link(cam_ob)
    sc.camera = cam_ob
    sun = bpy.data.lights.new('sun', 'SUN')
    sun.energy, sun.angle = 1.0, 0.0
    sc.collection.objects.link(bpy.data.objects.new('sun', sun))
    sc.render.filepath = exr
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(exr)
    img.colorspace_settings.name = 'Non-Color'
    px = list(img.pixels)
    return [sum(px[4 * (y * WIDTH + x)] for y in range(HEIGHT)) / HEIGHT * math.pi for x in range(WIDTH)]


def main():
    argv = sys.argv[sys.argv.index('--') + 1:] if '--' in sys.argv else []
    if len(argv) != 3:
        sys.exit('usage: blender -b --factory-startup -P cycles_edge.py -- OUT.json SAMPLES SEED')
    out, samples, seed = argv[0], int(argv[1]), int(argv[2])
    result = {'renderer': bpy.app.version_string, 'samples': samples, 'seed': seed,
              'x_mm': [((x + 0.5) / WIDTH - 0.5) * SPAN for x in range(WIDTH)]}
    for name, (method, color, radius) in CASES.items():
        result[name] = {'method': method, 'color': color, 'radius': radius, 'ior': 1.3,
                        'value': render(method, color, radius, samples, seed, out + '.' + name + '.exr')}
    with open(out, 'w') as f:
        json.dump(result, f, indent=1)
    print('cycles_edge: wrote', out)


main()
