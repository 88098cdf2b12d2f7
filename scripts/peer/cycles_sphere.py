# The peer renderer's side of issue 12 section 5: Blender 3.4's Cycles renders the Skin1 sphere of
# bench/skin1-sphere.json (radius 10 mm, Glass BSDF GGX alpha 0.3 / IOR 1.3 on a homogeneous
# volume, a delta sun from +x, the camera at z = 60 with a 25 degree field of view, 128 x 128) and
# reduces the image to the equator bins that tests/test_trace.c compares `render.boundary_model =
# cycles3` against (tests/data/cycles_sphere.json). Needs Blender (Debian's `blender` 3.4), not at
# test time:
#
#   nice -n 10 blender -b --factory-startup -P scripts/peer/cycles_sphere.py -- OUT.json SAMPLES SEED [THREADS]
#
# Units: one Blender unit is one millimetre (Cycles' volume densities are per unit; the sun's
# strength is irradiance, unit-free in the comparison). The volume is Volume Scatter (colour
# sigma_s, density 1: sigma_s per unit) plus Volume Absorption (colour 1 - sigma_a, density 1:
# sigma_a per unit), anisotropy 0 (Skin1 of data/materials.json, g = 0). Cycles squares the Glass
# BSDF's roughness (svm node glass: alpha = roughness^2), so roughness = sqrt(0.3). The film's pixel
# filter is a box of one pixel (Lucent's), clamping, glossy blur, light threshold and denoising are
# off, bounces are at Cycles' maximum (1024). Only the band of rows the bins use is rendered.
#
# The bins (the C test computes the same): a pixel belongs to the equator band when its row is one of
# the BAND rows about the centre; its centre's camera ray meets the analytic sphere at normal n, and
# it counts when the rays through its four corners meet the sphere too (fully covered); its bin is
# floor(theta / 10 degrees), theta = acos(n . x) the angle from the sun. Each bin's value is the mean
# linear radiance of its pixels per channel.
import json
import math
import sys

import bpy

SIZE = 128
BAND = 16  # rows about the centre: 56 .. 71
RADIUS = 10.0
CAMERA_Z = 60.0
FOV_Y = math.radians(25.0)
BINS = 18
SIGMA_A = (0.032, 0.17, 0.48)  # Skin1, data/materials.json (mm^-1)
SIGMA_S = (0.74, 0.88, 1.01)
IOR = 1.3
ALPHA = 0.3


def build_scene(samples, seed, threads):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    sc.render.engine = 'CYCLES'
    cy = sc.cycles
    cy.device = 'CPU'
    cy.samples = samples
    cy.seed = seed
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    cy.max_bounces = cy.volume_bounces = cy.transmission_bounces = cy.glossy_bounces = 1024
    cy.diffuse_bounces = 0
    cy.transparent_max_bounces = 8
    cy.sample_clamp_direct = 0.0
    cy.sample_clamp_indirect = 0.0
    cy.blur_glossy = 0.0
    cy.caustics_reflective = True
    cy.caustics_refractive = True
    cy.light_sampling_threshold = 0.0
    cy.pixel_filter_type = 'BOX'
    cy.filter_width = 1.0
    sc.render.threads_mode = 'FIXED'
    sc.render.threads = threads
    sc.render.resolution_x = sc.render.resolution_y = SIZE
    sc.render.resolution_percentage = 100
    sc.render.use_border = True
    sc.render.use_crop_to_border = False
    sc.render.border_min_x, sc.render.border_max_x = 0.0, 1.0
    sc.render.border_min_y = (SIZE - BAND) / 2 / SIZE
    sc.render.border_max_y = (SIZE + BAND) / 2 / SIZE
    sc.render.image_settings.file_format = 'OPEN_EXR'
    sc.render.image_settings.color_depth = '32'
    sc.view_settings.view_transform = 'Standard'
    sc.view_settings.look = 'None'
    sc.view_settings.exposure = 0.0
    sc.view_settings.gamma = 1.0

    world = bpy.data.worlds.new('black')
    world.use_nodes = True
    world.node_tree.nodes['Background'].inputs['Strength'].default_value = 0.0
    sc.world = world

    cam = bpy.data.cameras.new('camera')
    cam.lens_unit = 'FOV'
    cam.sensor_fit = 'VERTICAL'
    cam.angle = FOV_Y
    cam.clip_start, cam.clip_end = 0.1, 1000.0
    cam_ob = bpy.data.objects.new('camera', cam)
    cam_ob.location = (0.0, 0.0, CAMERA_Z)  # looks down -z, up +y, right +x (Lucent's framing)
    sc.collection.objects.link(cam_ob)
    sc.camera = cam_ob

    sun = bpy.data.lights.new('sun', 'SUN')
    sun.energy = 1.0  # irradiance
    sun.angle = 0.0   # a delta light, as Lucent's angular_radius 0
    sun_ob = bpy.data.objects.new('sun', sun)
    sun_ob.rotation_euler = (0.0, math.pi / 2, 0.0)  # its -z onto -x: light travelling toward -x
    sc.collection.objects.link(sun_ob)

    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=7, radius=RADIUS, location=(0, 0, 0))
    sphere = bpy.context.active_object  # 81920 flat faces, as Lucent's icosphere of 6 subdivisions
    for poly in sphere.data.polygons:
        poly.use_smooth = False

    mat = bpy.data.materials.new('skin1')
    mat.use_nodes = True
    mat.cycles.homogeneous_volume = True
    nt = mat.node_tree
    for n in list(nt.nodes):
        nt.nodes.remove(n)
    out = nt.nodes.new('ShaderNodeOutputMaterial')
    glass = nt.nodes.new('ShaderNodeBsdfGlass')
    glass.distribution = 'GGX'
    glass.inputs['Color'].default_value = (1, 1, 1, 1)
    glass.inputs['Roughness'].default_value = math.sqrt(ALPHA)
    glass.inputs['IOR'].default_value = IOR
    scatter = nt.nodes.new('ShaderNodeVolumeScatter')
    scatter.inputs['Density'].default_value = 1.0
    scatter.inputs['Anisotropy'].default_value = 0.0
    s_rgb = nt.nodes.new('ShaderNodeCombineRGB')
    for k in range(3):
        s_rgb.inputs[k].default_value = SIGMA_S[k]
    nt.links.new(s_rgb.outputs[0], scatter.inputs['Color'])
    absorb = nt.nodes.new('ShaderNodeVolumeAbsorption')
    absorb.inputs['Density'].default_value = 1.0
    a_rgb = nt.nodes.new('ShaderNodeCombineRGB')
    for k in range(3):
        a_rgb.inputs[k].default_value = 1.0 - SIGMA_A[k]
    nt.links.new(a_rgb.outputs[0], absorb.inputs['Color'])
    add = nt.nodes.new('ShaderNodeAddShader')
    nt.links.new(scatter.outputs[0], add.inputs[0])
    nt.links.new(absorb.outputs[0], add.inputs[1])
    nt.links.new(glass.outputs[0], out.inputs['Surface'])
    nt.links.new(add.outputs[0], out.inputs['Volume'])
    sphere.data.materials.append(mat)


def ray_hit(px, py):
    """The unit normal where the camera ray through image point (px, py) (pixels, y down) meets the
    sphere, or None."""
    t = math.tan(FOV_Y / 2)
    d = ((2 * px / SIZE - 1) * t, (1 - 2 * py / SIZE) * t, -1.0)
    n = math.sqrt(sum(c * c for c in d))
    d = tuple(c / n for c in d)
    o = (0.0, 0.0, CAMERA_Z)
    b = sum(o[k] * d[k] for k in range(3))
    c = sum(v * v for v in o) - RADIUS * RADIUS
    disc = b * b - c
    if disc < 0:
        return None
    s = -b - math.sqrt(disc)
    return tuple((o[k] + s * d[k]) / RADIUS for k in range(3))


def pixel_bins():
    """(row from the top, column, bin) of every fully covered pixel of the band."""
    out = []
    for row in range((SIZE - BAND) // 2, (SIZE + BAND) // 2):
        for col in range(SIZE):
            corners = [ray_hit(col + a, row + b) for a in (0, 1) for b in (0, 1)]
            n = ray_hit(col + 0.5, row + 0.5)
            if n is None or any(c is None for c in corners):
                continue
            theta = math.degrees(math.acos(max(-1.0, min(1.0, n[0]))))
            out.append((row, col, min(BINS - 1, int(theta // 10))))
    return out


def main():
    argv = sys.argv[sys.argv.index('--') + 1:] if '--' in sys.argv else []
    if len(argv) < 3:
        sys.exit('usage: blender -b --factory-startup -P cycles_sphere.py -- OUT.json SAMPLES SEED [THREADS]')
    out_path, samples, seed = argv[0], int(argv[1]), int(argv[2])
    threads = int(argv[3]) if len(argv) > 3 else 2
    build_scene(samples, seed, threads)
    exr = out_path + '.exr'
    bpy.context.scene.render.filepath = exr
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(exr)
    img.colorspace_settings.name = 'Non-Color'  # the file's linear values as they are
    px = list(img.pixels)
    sums = [[0.0, 0.0, 0.0] for _ in range(BINS)]
    counts = [0] * BINS
    for row, col, b in pixel_bins():
        i = ((SIZE - 1 - row) * SIZE + col) * 4  # Blender stores the bottom row first
        for k in range(3):
            sums[b][k] += px[i + k]
        counts[b] += 1
    result = {
        'renderer': bpy.app.version_string,
        'samples': samples,
        'seed': seed,
        'size': SIZE,
        'band_rows': BAND,
        'pixels': counts,
        'mean': [[s / c if c else 0.0 for s in sums[b]] for b, c in enumerate(counts)],
    }
    with open(out_path, 'w') as f:
        json.dump(result, f, indent=1)
    print('cycles_sphere: wrote', out_path)


main()
