# Procedural Blender scenes (no external assets) for validating Glint against Cycles.
#
# Every material is a Principled BSDF restricted to a diffuse lobe and a GGX specular lobe
# (no sheen, clearcoat, transmission, subsurface or specular tint), because those are the
# only two lobes Glint's buffers separate. Every material also writes the Shader AOVs
# "roughness" and "f0" so the G-buffers come from the same inputs the BSDF uses.
import math

import bmesh
import bpy
from mathutils import Vector

ROOM_MIN = Vector((-3.0, -3.0, 0.0))
ROOM_MAX = Vector((3.0, 3.0, 2.8))
WORLD_COLOUR = (0.03, 0.03, 0.035)  # dim: in a closed room it is only seen through no gap
LIGHT_STRENGTH = 18.0               # emitter radiance well above 1, so lights are HDR


def clear_scene():
    """Starts from an empty scene (factory startup holds a cube, a light and a camera)."""
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for mesh in list(bpy.data.meshes):
        bpy.data.meshes.remove(mesh)
    for mat in list(bpy.data.materials):
        bpy.data.materials.remove(mat)
    scene = bpy.context.scene
    world = scene.world or bpy.data.worlds.new("World")
    scene.world = world
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (*WORLD_COLOUR, 1.0)
    background.inputs["Strength"].default_value = 1.0
    # Glint's buffers are read through these two AOVs; each material writes both.
    view_layer = scene.view_layers[0]
    for name, kind in (("roughness", "VALUE"), ("f0", "COLOR")):
        if name not in view_layer.aovs:
            aov = view_layer.aovs.add()
            aov.name, aov.type = name, kind


# ---------------------------------------------------------------- materials

def _texture(nodes, links, kind, colour_a, colour_b, scale):
    """A procedural colour texture on the object's generated coordinates; returns its colour socket."""
    coords = nodes.new("ShaderNodeTexCoord")
    mapping = nodes.new("ShaderNodeMapping")
    links.new(coords.outputs["Object"], mapping.inputs["Vector"])
    mapping.inputs["Scale"].default_value = (scale, scale, scale)
    if kind == "checker":
        tex = nodes.new("ShaderNodeTexChecker")
        tex.inputs["Color1"].default_value = (*colour_a, 1.0)
        tex.inputs["Color2"].default_value = (*colour_b, 1.0)
        tex.inputs["Scale"].default_value = 1.0
    elif kind == "brick":
        tex = nodes.new("ShaderNodeTexBrick")
        tex.inputs["Color1"].default_value = (*colour_a, 1.0)
        tex.inputs["Color2"].default_value = (*colour_b, 1.0)
        tex.inputs["Mortar"].default_value = (0.75, 0.74, 0.7, 1.0)
        tex.inputs["Scale"].default_value = 1.0
    elif kind == "noise":
        noise = nodes.new("ShaderNodeTexNoise")
        noise.inputs["Scale"].default_value = 1.0
        noise.inputs["Detail"].default_value = 4.0
        links.new(mapping.outputs["Vector"], noise.inputs["Vector"])
        tex = nodes.new("ShaderNodeMixRGB")
        tex.inputs["Color1"].default_value = (*colour_a, 1.0)
        tex.inputs["Color2"].default_value = (*colour_b, 1.0)
        links.new(noise.outputs["Fac"], tex.inputs["Fac"])
        return tex.outputs["Color"]
    else:
        raise ValueError(f"unknown texture {kind}")
    links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
    return tex.outputs["Color"]


def principled(name, base=(0.8, 0.8, 0.8), roughness=0.5, metallic=0.0, specular=0.5,
               texture=None):
    """A two-lobe Principled material that also writes the roughness and f0 AOVs.

    texture = (kind, colour_a, colour_b, scale) replaces the constant base colour.
    """
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes["Principled BSDF"]
    bsdf.distribution = "GGX"
    bsdf.subsurface_method = "BURLEY"
    for socket, value in (("Metallic", metallic), ("Specular", specular),
                          ("Roughness", roughness), ("Specular Tint", 0.0),
                          ("Sheen", 0.0), ("Clearcoat", 0.0), ("Transmission", 0.0),
                          ("Subsurface", 0.0), ("Anisotropic", 0.0),
                          ("Emission Strength", 0.0)):
        bsdf.inputs[socket].default_value = value
    if texture is not None:
        base_socket = _texture(nodes, links, *texture)
        links.new(base_socket, bsdf.inputs["Base Color"])
    else:
        bsdf.inputs["Base Color"].default_value = (*base, 1.0)
        base_socket = None

    # f0 = (1 - metallic) * 0.08 * specular + metallic * base: a linear mix by metallic.
    f0_mix = nodes.new("ShaderNodeMixRGB")
    f0_mix.blend_type = "MIX"
    f0_mix.inputs["Fac"].default_value = metallic
    dielectric = 0.08 * specular
    f0_mix.inputs["Color1"].default_value = (dielectric, dielectric, dielectric, 1.0)
    if base_socket is not None:
        links.new(base_socket, f0_mix.inputs["Color2"])
    else:
        f0_mix.inputs["Color2"].default_value = (*base, 1.0)
    _write_aovs(nodes, links, roughness, f0_mix.outputs["Color"])
    return mat


def emitter(name, colour=(1.0, 0.95, 0.88), strength=LIGHT_STRENGTH):
    """An emissive surface; it has no specular lobe, so it writes roughness 1 and f0 0."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (*colour, 1.0)
    emission.inputs["Strength"].default_value = strength
    links.new(emission.outputs["Emission"], nodes["Material Output"].inputs["Surface"])
    black = nodes.new("ShaderNodeRGB")
    black.outputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    _write_aovs(nodes, links, 1.0, black.outputs["Color"])
    return mat


def _write_aovs(nodes, links, roughness, f0_socket):
    # In Blender 3.4 an AOV Output node's `name` is the AOV it writes to.
    rough_out = nodes.new("ShaderNodeOutputAOV")
    rough_out.name = "roughness"
    rough_out.inputs["Value"].default_value = roughness
    f0_out = nodes.new("ShaderNodeOutputAOV")
    f0_out.name = "f0"
    links.new(f0_socket, f0_out.inputs["Color"])


# ---------------------------------------------------------------- geometry

def mesh_object(name, verts, faces, material, smooth=False):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(v) for v in verts], [], faces)
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    mesh.materials.append(material)
    for poly in mesh.polygons:
        poly.use_smooth = smooth
    return obj


def quad(name, corner, edge_u, edge_v, material):
    """A rectangle corner, corner+u, corner+u+v, corner+v; its normal is u x v."""
    c, u, v = Vector(corner), Vector(edge_u), Vector(edge_v)
    return mesh_object(name, [c, c + u, c + u + v, c + v], [(0, 1, 2, 3)], material)


def box(name, lo, hi, material):
    """An axis-aligned box with outward faces (flat shaded: its edges are sharp)."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    verts = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
             (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    faces = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    return mesh_object(name, verts, faces, material)


def sphere(name, centre, radius, material):
    mesh = bpy.data.meshes.new(name)
    bm = bmesh.new()
    bmesh.ops.create_uvsphere(bm, u_segments=64, v_segments=32, radius=radius)
    bm.to_mesh(mesh)
    bm.free()
    obj = bpy.data.objects.new(name, mesh)
    obj.location = centre
    bpy.context.scene.collection.objects.link(obj)
    mesh.materials.append(material)
    for poly in mesh.polygons:
        poly.use_smooth = True
    return obj


def lathe(name, profile, centre, material, segments=64, cap_bottom=True):
    """Revolves a (radius, height) profile about the vertical axis through centre."""
    verts, faces = [], []
    rings = len(profile)
    for s in range(segments):
        angle = 2.0 * math.pi * s / segments
        for r, z in profile:
            verts.append((centre[0] + r * math.cos(angle), centre[1] + r * math.sin(angle),
                          centre[2] + z))
    for s in range(segments):
        s1 = (s + 1) % segments
        for k in range(rings - 1):
            faces.append((s * rings + k, s1 * rings + k, s1 * rings + k + 1, s * rings + k + 1))
    if cap_bottom:
        faces.append(tuple(s * rings for s in reversed(range(segments))))
    return mesh_object(name, verts, faces, material, smooth=True)


def room(floor, ceiling, walls):
    """Six inward-facing rectangles; walls = materials for -x, +x, -y, +y."""
    (x0, y0, z0), (x1, y1, z1) = ROOM_MIN, ROOM_MAX
    w, d, h = x1 - x0, y1 - y0, z1 - z0
    quad("floor", (x0, y0, z0), (w, 0, 0), (0, d, 0), floor)
    quad("ceiling", (x0, y0, z1), (0, d, 0), (w, 0, 0), ceiling)
    quad("wall_-x", (x0, y0, z0), (0, 0, h), (0, d, 0), walls[0])
    quad("wall_+x", (x1, y0, z0), (0, d, 0), (0, 0, h), walls[1])
    quad("wall_-y", (x0, y0, z0), (w, 0, 0), (0, 0, h), walls[2])
    quad("wall_+y", (x0, y1, z0), (0, 0, h), (w, 0, 0), walls[3])


def ceiling_light(name, centre, size, material):
    """A downward-facing emissive quad just under the ceiling."""
    cx, cy, cz = centre
    sx, sy = size
    return quad(name, (cx - sx / 2, cy - sy / 2, cz), (0, sy, 0), (sx, 0, 0), material)


# ---------------------------------------------------------------- scenes

def spheres_room():
    """Curved mirrors, rough gold and red plastic spheres in a textured, quad-lit room."""
    clear_scene()
    floor = principled("floor_checker", roughness=0.35,
                       texture=("checker", (0.65, 0.62, 0.58), (0.12, 0.12, 0.14), 2.0))
    brick = principled("wall_brick", roughness=0.8,
                       texture=("brick", (0.55, 0.22, 0.14), (0.42, 0.18, 0.12), 1.5))
    plaster = principled("wall_plaster", roughness=0.6,
                         texture=("noise", (0.55, 0.6, 0.65), (0.35, 0.42, 0.5), 2.5))
    ceiling = principled("ceiling", base=(0.7, 0.7, 0.68), roughness=0.9)
    room(floor, ceiling, [brick, plaster, plaster, brick])

    light = emitter("light")
    ceiling_light("light_a", (-1.2, -0.8, 2.79), (1.0, 0.6), light)
    ceiling_light("light_b", (1.3, 0.9, 2.79), (0.8, 0.8), light)
    # A vertical panel on the +x wall: seen directly and in the mirrors at eye height.
    quad("light_wall", (2.99, -0.6, 0.9), (0, 0, 0.9), (0, 1.2, 0), emitter("light_cool", (0.85, 0.92, 1.0), 12.0))

    sphere("chrome", (-0.9, 0.3, 0.5), 0.5,
           principled("chrome", base=(0.9, 0.9, 0.9), roughness=0.02, metallic=1.0))
    sphere("tinted_chrome", (0.95, 0.55, 0.4), 0.4,
           principled("tinted_chrome", base=(0.45, 0.65, 0.95), roughness=0.02, metallic=1.0))
    sphere("gold", (0.15, -0.7, 0.45), 0.45,
           principled("gold", base=(1.0, 0.766, 0.336), roughness=0.35, metallic=1.0))
    sphere("red_plastic", (0.1, 1.3, 0.35), 0.35,
           principled("red_plastic", base=(0.7, 0.04, 0.03), roughness=0.1))
    box("pedestal", (-1.9, -1.5, 0.0), (-1.3, -0.9, 0.6),
        principled("pedestal", base=(0.2, 0.45, 0.3), roughness=0.5))
    # Flat mirror on the +y wall.
    quad("wall_mirror", (-1.2, 2.98, 0.5), (0, 0, 1.5), (2.4, 0, 0),
         principled("mirror", base=(0.92, 0.92, 0.92), roughness=0.0, metallic=1.0))
    return {
        "cam_region": ((-2.5, -2.5, 0.9), (2.5, 2.5, 1.9)),
        "cam_keep_out": ((0.0, 0.3), 1.9),   # (centre xy, radius): stay clear of the spheres
        "look_at": (0.0, 0.2, 0.45),
        "look_jitter": 0.35,
        "mirror_only": None,
    }


def mirror_room():
    """A mirror wall reflecting a glossy table, a copper pot and an object behind the cameras."""
    clear_scene()
    floor = principled("floor_wood", roughness=0.45,
                       texture=("noise", (0.42, 0.27, 0.15), (0.25, 0.15, 0.08), 3.0))
    tiles = principled("wall_tiles", roughness=0.3,
                       texture=("checker", (0.85, 0.85, 0.8), (0.3, 0.45, 0.55), 3.0))
    brick = principled("wall_brick", roughness=0.85,
                       texture=("brick", (0.6, 0.55, 0.48), (0.45, 0.4, 0.35), 1.8))
    ceiling = principled("ceiling", base=(0.75, 0.75, 0.72), roughness=0.9)
    room(floor, ceiling, [tiles, tiles, brick, brick])

    light = emitter("light")
    ceiling_light("light_a", (0.0, 1.2, 2.79), (1.4, 0.6), light)
    ceiling_light("light_b", (0.0, -1.4, 2.79), (1.0, 0.8), light)
    quad("light_wall", (-2.99, -1.2, 1.0), (0, 1.0, 0), (0, 0, 0.8), emitter("light_warm", (1.0, 0.8, 0.6), 12.0))

    # The mirror covers most of the +y wall; training cameras face it.
    quad("wall_mirror", (-2.2, 2.98, 0.35), (0, 0, 2.1), (4.4, 0, 0),
         principled("mirror", base=(0.93, 0.93, 0.93), roughness=0.0, metallic=1.0))

    table = principled("table_glossy", roughness=0.15,
                       texture=("noise", (0.35, 0.12, 0.05), (0.22, 0.07, 0.03), 4.0))
    box("table_top", (-0.9, 0.8, 0.72), (0.9, 1.8, 0.78), table)
    for x in (-0.82, 0.76):
        for y in (0.88, 1.66):
            box(f"table_leg_{x}_{y}", (x, y, 0.0), (x + 0.06, y + 0.06, 0.72), table)

    copper = principled("copper", base=(0.955, 0.638, 0.538), roughness=0.25, metallic=1.0)
    pot = [(0.0, 0.0), (0.22, 0.0), (0.28, 0.04), (0.3, 0.12), (0.29, 0.24), (0.26, 0.3),
           (0.27, 0.33), (0.25, 0.33)]
    lathe("copper_pot", pot, (0.25, 1.3, 0.78), copper)
    sphere("blue_plastic", (-0.45, 1.25, 0.93), 0.15,
           principled("blue_plastic", base=(0.05, 0.15, 0.6), roughness=0.2))

    # Seen only in the mirror: near the -y wall, behind every training camera.
    vase = [(0.0, 0.0), (0.18, 0.0), (0.3, 0.2), (0.32, 0.45), (0.2, 0.8), (0.12, 1.0),
            (0.16, 1.15), (0.14, 1.2)]
    hidden = lathe("mirror_only_vase", vase, (0.5, -2.45, 0.0),
                   principled("vase_green", base=(0.05, 0.75, 0.2), roughness=0.3))
    return {
        "cam_region": ((-1.8, -1.2, 1.0), (1.8, -0.2, 1.8)),
        "cam_keep_out": None,
        "look_at": (0.0, 2.4, 1.0),
        "look_jitter": 0.4,
        "mirror_only": hidden,
        # Test views that face the hidden object directly.
        "face_region": ((-1.5, -0.3, 1.0), (1.5, 1.0, 1.7)),
        "face_look_at": (0.5, -2.45, 0.6),
        "face_jitter": 0.25,
    }


SCENES = {"spheres_room": spheres_room, "mirror_room": mirror_room}
