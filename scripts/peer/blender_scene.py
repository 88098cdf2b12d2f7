# Lucent's engine peer (src/eval/compare_peers.c, `lucent compare --peers ...`): Blender 3.4 (Debian's
# `blender`) renders a Lucent scene with the Principled BSDF that `lucent fit` gives each material, with
# Cycles (Random Walk or Christensen-Burley) or EEVEE, and writes a linear EXR of the same framing.
# Lucent embeds this script and runs it headless:
#
#   blender -b --factory-startup -noaudio -P blender_scene.py -- SCENE.json
#
# (EEVEE needs an OpenGL context: Debian's Blender 3.4 gets one under -b without a display here;
# tests/peer_blender_test.sh renders with it headless.)
#
# SCENE.json, written by Lucent (all lengths in mm: one Blender unit is one millimetre):
#   {"width", "height", "output": EXR path,
#    "engine": "CYCLES" | "BLENDER_EEVEE", "samples", "seed", "threads",
#    "camera": {"position", "target", "up", "fov_y" (degrees, vertical)},
#    "lights": [{"type": "directional", "direction" (travel), "irradiance" [r, g, b], "angular_radius" (rad)},
#               {"type": "environment", "radiance" [r, g, b]}],
#    "objects": [{"name", "mesh": raw mesh path, "vertices", "triangles", "principled": {input name: value},
#                 "subsurface_method": "BURLEY" | "RANDOM_WALK"}]}
# A raw mesh: vertices x (x, y, z) float32, vertices x (nx, ny, nz) float32, triangles x 3 uint32, little
# endian, in world mm (Lucent's scene after its transforms and subdivision).
#
# Conventions (the same as scripts/peer/cycles_sphere.py, validated there against Lucent's tracer): a sun's
# strength is the irradiance on a surface facing it and the world's colour the environment's radiance,
# as Lucent's lights; the film is a one-pixel box filter, the view transform Standard (the EXR holds the
# scene's linear values); no denoising, no clamping, no adaptive sampling.
import array
import json
import math
import sys

import bpy
from mathutils import Matrix, Vector


def read_mesh(path, nv, nt):
    with open(path, 'rb') as f:
        data = f.read()
    want = nv * 24 + nt * 12
    if len(data) != want:
        sys.exit('blender_scene: %s: %d bytes, expected %d' % (path, len(data), want))
    pos = array.array('f', data[:nv * 12])
    nrm = array.array('f', data[nv * 12:nv * 24])
    tri = array.array('I', data[nv * 24:])
    if sys.byteorder != 'little':
        pos.byteswap(), nrm.byteswap(), tri.byteswap()
    verts = [(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]) for i in range(nv)]
    normals = [(nrm[3 * i], nrm[3 * i + 1], nrm[3 * i + 2]) for i in range(nv)]
    faces = [(tri[3 * i], tri[3 * i + 1], tri[3 * i + 2]) for i in range(nt)]
    return verts, normals, faces


def look_at(position, target, up):
    """The camera's world matrix: it looks down its -z toward target, its +y toward up."""
    p, t, u = Vector(position), Vector(target), Vector(up)
    f = (t - p).normalized()
    r = f.cross(u).normalized()
    u = r.cross(f)
    m = Matrix.Identity(4)
    for k in range(3):
        m[k][0], m[k][1], m[k][2], m[k][3] = r[k], u[k], -f[k], p[k]
    return m


def material(o):
    mat = bpy.data.materials.new(o['name'])
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes['Principled BSDF']
    bsdf.subsurface_method = o['subsurface_method']
    for name, value in o['principled'].items():
        socket = bsdf.inputs[name]
        if isinstance(value, list):
            socket.default_value = tuple(value) + ((1.0,) if len(socket.default_value) == 4 else ())
        else:
            socket.default_value = value
    mat.use_sss_translucency = True  # EEVEE: light through thin parts, as Cycles' walk gives it
    return mat


def build(sc_json):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    sc.render.engine = sc_json['engine']
    sc.render.resolution_x, sc.render.resolution_y = sc_json['width'], sc_json['height']
    sc.render.resolution_percentage = 100
    sc.render.threads_mode = 'FIXED'
    sc.render.threads = max(1, sc_json.get('threads', 2))
    sc.render.image_settings.file_format = 'OPEN_EXR'
    sc.render.image_settings.color_mode = 'RGBA'
    sc.render.image_settings.color_depth = '32'
    sc.render.filepath = sc_json['output']
    sc.view_settings.view_transform = 'Standard'
    sc.view_settings.look = 'None'
    sc.view_settings.exposure = 0.0
    sc.view_settings.gamma = 1.0
    samples = sc_json['samples']
    if sc_json['engine'] == 'CYCLES':
        cy = sc.cycles
        cy.device = 'CPU'
        cy.samples = samples
        cy.seed = sc_json.get('seed', 0)
        cy.use_adaptive_sampling = False
        cy.use_denoising = False
        cy.max_bounces = 32
        cy.diffuse_bounces = cy.glossy_bounces = 8
        cy.transmission_bounces = 16
        cy.volume_bounces = 0
        cy.sample_clamp_direct = cy.sample_clamp_indirect = 0.0
        cy.light_sampling_threshold = 0.0
        cy.caustics_reflective = cy.caustics_refractive = True
        cy.pixel_filter_type = 'BOX'
        cy.filter_width = 1.0
    else:
        ee = sc.eevee
        ee.taa_render_samples = samples
        ee.use_ssr = False
        ee.use_soft_shadows = True
        ee.shadow_cube_size = '2048'
        ee.shadow_cascade_size = '4096'
        ee.sss_samples = 25
        sc.render.filter_size = 1.0

    world = bpy.data.worlds.new('environment')
    world.use_nodes = True
    bg = world.node_tree.nodes['Background']
    env = [0.0, 0.0, 0.0]
    for light in sc_json['lights']:
        if light['type'] == 'environment':
            env = [env[k] + light['radiance'][k] for k in range(3)]
    strength = max(env)
    bg.inputs['Color'].default_value = tuple(c / strength if strength > 0 else 0.0 for c in env) + (1.0,)
    bg.inputs['Strength'].default_value = strength
    sc.world = world

    cam_json = sc_json['camera']
    cam = bpy.data.cameras.new('camera')
    cam.lens_unit = 'FOV'
    cam.sensor_fit = 'VERTICAL'
    cam.angle = math.radians(cam_json['fov_y'])
    cam.clip_start, cam.clip_end = cam_json.get('near', 0.1), cam_json.get('far', 1e5)
    cam_ob = bpy.data.objects.new('camera', cam)
    cam_ob.matrix_world = look_at(cam_json['position'], cam_json['target'], cam_json['up'])
    sc.collection.objects.link(cam_ob)
    sc.camera = cam_ob

    for i, light in enumerate(sc_json['lights']):
        if light['type'] != 'directional':
            continue
        irr = light['irradiance']
        energy = max(irr)
        sun = bpy.data.lights.new('sun%d' % i, 'SUN')
        sun.energy = energy
        sun.color = tuple(c / energy if energy > 0 else 0.0 for c in irr)
        sun.angle = 2.0 * light.get('angular_radius', 0.0)
        sun_ob = bpy.data.objects.new('sun%d' % i, sun)
        d = Vector(light['direction']).normalized()  # the sun emits along its -z
        sun_ob.matrix_world = look_at((0, 0, 0), tuple(d), (0, 0, 1) if abs(d.z) < 0.9 else (0, 1, 0))
        sc.collection.objects.link(sun_ob)

    for o in sc_json['objects']:
        verts, normals, faces = read_mesh(o['mesh'], o['vertices'], o['triangles'])
        me = bpy.data.meshes.new(o['name'])
        me.from_pydata(verts, [], faces)
        me.update()
        for poly in me.polygons:
            poly.use_smooth = True
        me.use_auto_smooth = True
        me.normals_split_custom_set_from_vertices(normals)
        ob = bpy.data.objects.new(o['name'], me)
        ob.data.materials.append(material(o))
        sc.collection.objects.link(ob)


def main():
    argv = sys.argv[sys.argv.index('--') + 1:] if '--' in sys.argv else []
    if len(argv) != 1:
        sys.exit('usage: blender -b --factory-startup -P blender_scene.py -- SCENE.json')
    with open(argv[0]) as f:
        sc_json = json.load(f)
    build(sc_json)
    bpy.ops.render.render(write_still=True)
    print('blender_scene: wrote', sc_json['output'])


main()
