"""build_scene.py: renders a `restir scene export --mesh` file with Blender Cycles so that Cycles
computes the same integral as restir's `pt`.

    blender -b --factory-startup -t THREADS -P build_scene.py -- MESH_JSON OUT_EXR SPP SEED \
        [--res WxH] [--max-bounces N] [--blend FILE.blend] [--light-mis on|off]

--max-bounces N is pt.max_bounces (scattering events, default 8, as `restir render`); Cycles counts
bounces after the first hit, so it gets max_bounces = N - 1. --blend also saves the built scene.
--light-mis off (a diagnosis, not the comparison) turns off the emitters' "Multiple Importance"
(sample_as_light): Cycles then finds them only by BSDF sampling, which is unbiased but noisier.
Prints one line "cycles_render: ..." with the render's own wall and CPU seconds (the CPU time of
this process around the render call: Cycles' scene sync, BVH build and sampling).

What makes the integrals equal (see /work/shared/notes/cycles-comparison.md and docs/BENCHMARKS.md):
- geometry: the exported world-space triangles, flat shaded (restir refuses to export shading
  normals), y-up turned z-up by (x, y, z) -> (x, -z, y), a rotation, so windings keep their sides;
- materials: Diffuse BSDF (roughness 0: Lambert) of the exported albedo, and for emitters an
  Emission shader of strength 1 and the exported radiance, emitting from the front only (restir's
  emitters are one-sided; Cycles' mesh emission is two-sided, so the strength is 1 - Backfacing);
- world: the exported constant radiance at strength 1, or black (and not sampled) without one;
- camera: a pinhole with the exported basis and vertical field of view (sensor fit vertical), no
  clipping in practice (clip_start 1e-6 of the scene size, clip_end 1e3 times it);
- integrator: the bounce limits (every type), no clamping, no glossy blur, no light threshold, no
  adaptive sampling, no denoising; film: 1-pixel box filter, Standard view transform, exposure 0,
  gamma 1; output: linear float OpenEXR (RGB, uncompressed).
"""
import json
import math
import os
import sys
import time

import bpy
from mathutils import Matrix, Vector


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) < 4:
        sys.exit("usage: blender -b --factory-startup -t THREADS -P build_scene.py -- MESH_JSON OUT_EXR SPP SEED "
                 "[--res WxH] [--max-bounces N] [--blend FILE] [--light-mis on|off]")
    a = {"mesh": argv[0], "out": argv[1], "spp": int(argv[2]), "seed": int(argv[3]), "res": (640, 360),
         "max_bounces": 8, "blend": None, "light_mis": True}
    rest = argv[4:]
    while rest:
        key = rest.pop(0)
        if not rest:
            sys.exit(f"build_scene.py: {key} needs a value")
        val = rest.pop(0)
        if key == "--res":
            w, h = val.lower().split("x")
            a["res"] = (int(w), int(h))
        elif key == "--max-bounces":
            a["max_bounces"] = int(val)
        elif key == "--blend":
            a["blend"] = val
        elif key == "--light-mis" and val in ("on", "off"):
            a["light_mis"] = val == "on"
        else:
            sys.exit(f"build_scene.py: unknown option {key}")
    if a["max_bounces"] < 1 or a["spp"] < 1:
        sys.exit("build_scene.py: --max-bounces and SPP must be at least 1")
    return a


def to_blender(x, y, z):
    """restir's y-up point as Blender's z-up one (a +90 degree rotation about x)."""
    return (x, -z, y)


def clear_scene():
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.cameras, bpy.data.lights):
        for item in list(coll):
            coll.remove(item)


def make_material(index, m, light_mis):
    mat = bpy.data.materials.new(f"restir_{index}")
    if hasattr(mat.cycles, "sample_as_light"):  # Cycles 3.4's "Multiple Importance" of emitters (default on)
        mat.cycles.sample_as_light = light_mis
    elif not light_mis:
        sys.exit("build_scene.py: this Blender has no sample_as_light (3.5 renamed it emission_sampling)")
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    diffuse = nt.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (*m["diffuse"], 1.0)
    diffuse.inputs["Roughness"].default_value = 0.0  # Lambert (non-zero is Oren-Nayar)
    shader = diffuse.outputs["BSDF"]
    if max(m["emission"]) > 0.0:
        emission = nt.nodes.new("ShaderNodeEmission")
        emission.inputs["Color"].default_value = (*m["emission"], 1.0)
        # One-sided: strength 1 on the front, 0 seen from the back.
        geometry = nt.nodes.new("ShaderNodeNewGeometry")
        front = nt.nodes.new("ShaderNodeMath")
        front.operation = "SUBTRACT"
        front.inputs[0].default_value = 1.0
        nt.links.new(geometry.outputs["Backfacing"], front.inputs[1])
        nt.links.new(front.outputs["Value"], emission.inputs["Strength"])
        if max(m["diffuse"]) > 0.0:
            add = nt.nodes.new("ShaderNodeAddShader")
            nt.links.new(diffuse.outputs["BSDF"], add.inputs[0])
            nt.links.new(emission.outputs["Emission"], add.inputs[1])
            shader = add.outputs["Shader"]
        else:
            shader = emission.outputs["Emission"]
    nt.links.new(shader, out.inputs["Surface"])
    return mat


def build_mesh(d, light_mis):
    nv = len(d["vertices"]) // 3
    nt = len(d["indices"]) // 3
    v = d["vertices"]
    co = [0.0] * (3 * nv)
    for i in range(nv):
        co[3 * i], co[3 * i + 1], co[3 * i + 2] = to_blender(v[3 * i], v[3 * i + 1], v[3 * i + 2])
    me = bpy.data.meshes.new(d["scene"])
    me.vertices.add(nv)
    me.vertices.foreach_set("co", co)
    me.loops.add(3 * nt)
    me.loops.foreach_set("vertex_index", d["indices"])
    me.polygons.add(nt)
    me.polygons.foreach_set("loop_start", range(0, 3 * nt, 3))
    me.polygons.foreach_set("loop_total", [3] * nt)
    me.polygons.foreach_set("use_smooth", [False] * nt)
    for i, m in enumerate(d["materials"]):
        me.materials.append(make_material(i, m, light_mis))
    me.polygons.foreach_set("material_index", d["triangle_material"])
    me.update(calc_edges=True)  # no validate(): it could drop or merge triangles
    if len(me.polygons) != d["triangles"]:
        sys.exit(f"build_scene.py: {len(me.polygons)} triangles built, {d['triangles']} exported")
    obj = bpy.data.objects.new(d["scene"], me)
    bpy.context.scene.collection.objects.link(obj)
    if hasattr(obj, "cycles"):
        # Cycles' shadow terminator fixes move shadow rays of smooth-shaded triangles; ours are flat,
        # and these keep them from changing anything.
        for attr in ("shadow_terminator_offset", "shadow_terminator_geometry_offset"):
            if hasattr(obj.cycles, attr):
                setattr(obj.cycles, attr, 0.0)
    lo = [min(co[k::3]) for k in range(3)]
    hi = [max(co[k::3]) for k in range(3)]
    return math.dist(lo, hi)


def build_camera(d, diag):
    c = d["camera"]
    cam = bpy.data.cameras.new("restir_camera")
    cam.type = "PERSP"
    cam.sensor_fit = "VERTICAL"
    cam.angle_y = math.radians(c["vfov_deg"])
    cam.shift_x = cam.shift_y = 0.0
    cam.clip_start = max(1e-6, 1e-6 * diag)
    cam.clip_end = max(1e3, 1e3 * diag)
    cam.dof.use_dof = False
    obj = bpy.data.objects.new("restir_camera", cam)
    bpy.context.scene.collection.objects.link(obj)
    right = Vector(to_blender(*c["right"]))
    up = Vector(to_blender(*c["up"]))
    back = -Vector(to_blender(*c["direction"]))  # Blender cameras look down their local -z
    pos = Vector(to_blender(*c["position"]))
    m = Matrix.Identity(4)
    for row in range(3):
        m[row][0], m[row][1], m[row][2], m[row][3] = right[row], up[row], back[row], pos[row]
    obj.matrix_world = m
    bpy.context.scene.camera = obj
    return cam


def build_world(d):
    world = bpy.data.worlds.new("restir_world")
    bpy.context.scene.world = world
    world.use_nodes = True
    nt = world.node_tree
    nt.nodes.clear()
    bg = nt.nodes.new("ShaderNodeBackground")
    out = nt.nodes.new("ShaderNodeOutputWorld")
    env = d.get("environment")
    color = env["color"] if env else [0.0, 0.0, 0.0]
    bg.inputs["Color"].default_value = (*color, 1.0)
    bg.inputs["Strength"].default_value = 1.0 if env else 0.0
    nt.links.new(bg.outputs["Background"], out.inputs["Surface"])
    # A black world is not sampled as a light (it gives nothing); a constant one is (MIS).
    world.cycles.sampling_method = "AUTOMATIC" if env else "NONE"


def set_render(a):
    scene = bpy.context.scene
    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x, r.resolution_y = a["res"]
    r.resolution_percentage = 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.use_border = False
    r.use_motion_blur = False
    r.film_transparent = False
    r.dither_intensity = 0.0
    r.use_persistent_data = False
    cy = scene.cycles
    cy.device = "CPU"
    cy.samples = a["spp"]
    cy.seed = a["seed"]
    cy.use_animated_seed = False
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    if hasattr(cy, "use_preview_denoising"):
        cy.use_preview_denoising = False
    bounces = a["max_bounces"] - 1  # restir pt.max_bounces N is Cycles max_bounces N - 1
    cy.max_bounces = bounces
    cy.diffuse_bounces = bounces
    cy.glossy_bounces = bounces
    cy.transmission_bounces = bounces
    cy.transparent_max_bounces = bounces
    cy.volume_bounces = bounces
    cy.min_light_bounces = 0
    cy.min_transparent_bounces = 0
    cy.sample_clamp_direct = 0.0
    cy.sample_clamp_indirect = 0.0
    cy.blur_glossy = 0.0
    cy.light_sampling_threshold = 0.0
    cy.caustics_reflective = True
    cy.caustics_refractive = True
    if hasattr(cy, "use_fast_gi"):
        cy.use_fast_gi = False
    cy.pixel_filter_type = "BOX"
    cy.filter_width = 1.0
    cy.film_exposure = 1.0
    scene.display_settings.display_device = "sRGB"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    im = r.image_settings
    im.file_format = "OPEN_EXR"
    im.color_mode = "RGB"
    im.color_depth = "32"
    im.exr_codec = "NONE"
    r.use_file_extension = False
    r.filepath = os.path.abspath(a["out"])


def main():
    a = parse_args()
    with open(a["mesh"]) as f:
        d = json.load(f)
    if d.get("format") != "restir-mesh 1":
        sys.exit(f"build_scene.py: {a['mesh']} is not a restir-mesh 1 file")
    clear_scene()
    diag = build_mesh(d, a["light_mis"])
    build_camera(d, diag)
    build_world(d)
    set_render(a)
    if a["blend"]:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(a["blend"]))
    w0, c0 = time.perf_counter(), time.process_time()
    bpy.ops.render.render(write_still=True)
    w1, c1 = time.perf_counter(), time.process_time()
    cy = bpy.context.scene.cycles
    print(f"cycles_render: blender {bpy.app.version_string} spp {a['spp']} seed {a['seed']} "
          f"res {a['res'][0]}x{a['res'][1]} max_bounces {cy.max_bounces} pattern {cy.sampling_pattern} "
          f"light_mis {'on' if a['light_mis'] else 'off'} "
          f"wall_s {w1 - w0:.3f} cpu_s {c1 - c0:.3f} out {a['out']}", flush=True)
    if not os.path.exists(a["out"]):
        sys.exit(f"build_scene.py: Blender wrote no {a['out']}")


if __name__ == "__main__":
    main()
