# The Blender side of stage_to_blender.py: turns the resolved stage (a JSON
# document, SCENE_JSON, written above this code by stage_to_blender.py) into
# Blender data and Cycles settings. Runs inside Blender 3.4 (bpy, mathutils).
# Every unit conversion is done in stage_to_blender.py and derived in
# README.md; this file only builds what the document says.
import json
import math
import os

import bpy
from mathutils import Matrix, Vector

# Blender's glTF importer turns glTF's +Y up into Blender's +Z up, a +90
# degree turn about X; sdgbehave (assimp) uses the file's coordinates as
# they are, so imported glTF objects are turned back.
GLTF_TO_FILE = Matrix.Rotation(-math.pi / 2, 4, "X")


def _clear():
    for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.lights, bpy.data.cameras, bpy.data.materials,
                       bpy.data.images, bpy.data.worlds):
        for item in list(collection):
            collection.remove(item)


def _mesh(name, data):
    """A Blender mesh with exactly these triangles, per-vertex normals and uvs."""
    me = bpy.data.meshes.new(name)
    positions, indices = data["positions"], data["indices"]
    triangles = len(indices) // 3
    me.vertices.add(len(positions))
    me.vertices.foreach_set("co", [c for p in positions for c in p])
    me.loops.add(len(indices))
    me.loops.foreach_set("vertex_index", indices)
    me.polygons.add(triangles)
    me.polygons.foreach_set("loop_start", list(range(0, len(indices), 3)))
    me.polygons.foreach_set("loop_total", [3] * triangles)
    me.update(calc_edges=True)
    uvs = data.get("uvs")
    if uvs:
        layer = me.uv_layers.new(name="UVMap")
        layer.data.foreach_set("uv", [c for i in indices for c in uvs[i]])
    # sdgbehave interpolates the generator's vertex normals; custom split
    # normals make Cycles shade with the same ones.
    me.polygons.foreach_set("use_smooth", [True] * triangles)
    me.use_auto_smooth = True
    me.normals_split_custom_set_from_vertices([tuple(n) for n in data["normals"]])
    return me


def _sheared(m):
    """True when a matrix is not rotation x scale: Blender objects keep
    location, rotation and scale only, so a shear (a non-uniform scale above
    a rotation) would be lost on assignment to matrix_world."""
    cols = [m.col[i].xyz for i in range(3)]
    if min(c.length for c in cols) == 0:
        return False
    return any(abs(cols[i].normalized().dot(cols[j].normalized())) > 1e-6 for i, j in ((0, 1), (0, 2), (1, 2)))


def _baked(name, data, m):
    """The mesh with a sheared matrix baked in: positions by m, normals by
    its inverse transpose, as sdgbehave's normal matrix does."""
    normal_matrix = m.to_3x3().inverted_safe().transposed()
    positions = [list(m @ Vector(p)) for p in data["positions"]]
    normals = [list((normal_matrix @ Vector(nrm)).normalized()) for nrm in data["normals"]]
    return _mesh(name, dict(data, positions=positions, normals=normals))


def _link(obj):
    bpy.context.scene.collection.objects.link(obj)
    return obj


# ---------------------------------------------------------------- materials

class _Nodes:
    """Small helpers over a node tree."""

    def __init__(self, tree):
        self.tree = tree

    def new(self, kind, **inputs):
        node = self.tree.nodes.new(kind)
        for name, value in inputs.items():
            node.inputs[name].default_value = value
        return node

    def link(self, out, into):
        self.tree.links.new(out, into)

    def math(self, op, a, b):
        node = self.new("ShaderNodeMath")
        node.operation = op
        for i, v in enumerate((a, b)):
            if isinstance(v, (int, float)):
                node.inputs[i].default_value = v
            else:
                self.link(v, node.inputs[i])
        return node.outputs[0]


def _image(path, colorspace):
    image = bpy.data.images.load(path, check_existing=True)
    image.colorspace_settings.name = colorspace
    image.alpha_mode = "CHANNEL_PACKED"  # colour is used as stored, never premultiplied
    return image


def _uv_in_sdg_convention(n, desc, uv_socket):
    """sdgbehave's transformUv(): scale, then rotate about the origin; then
    its textures are stored top row first (t = 0 is the image's top), while
    Blender's v = 0 is the bottom, so v is flipped."""
    scale = desc.get("texture_scale", [1.0, 1.0])
    transform = n.new("ShaderNodeMapping")
    transform.vector_type = "POINT"
    transform.inputs["Scale"].default_value = (scale[0], scale[1], 1.0)
    transform.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(desc.get("texture_rotate", 0.0)))
    n.link(uv_socket, transform.inputs["Vector"])
    flip = n.new("ShaderNodeMapping")
    flip.vector_type = "POINT"
    flip.inputs["Scale"].default_value = (1.0, -1.0, 1.0)
    flip.inputs["Location"].default_value = (0.0, 1.0, 0.0)
    n.link(transform.outputs[0], flip.inputs["Vector"])
    return flip.outputs[0]


class _Sampler:
    """Samples a material's maps the way sdgbehave addresses them: the mesh's
    uvs, or world-space triplanar (project_uvw) blended by the normal."""

    def __init__(self, n, desc):
        self.n, self.desc = n, desc
        self.coords = []
        if desc.get("project_uvw"):
            geometry = n.new("ShaderNodeNewGeometry")
            position = n.new("ShaderNodeSeparateXYZ")
            n.link(geometry.outputs["Position"], position.inputs[0])
            normal = n.new("ShaderNodeSeparateXYZ")
            n.link(geometry.outputs["Normal"], normal.inputs[0])
            w = [n.math("ABSOLUTE", normal.outputs[i], 0.0) for i in range(3)]
            total = n.math("ADD", n.math("ADD", w[0], w[1]), w[2])
            # x projects (y, z), y projects (x, z), z projects (x, y), as in the shader.
            for axis, (a, b) in enumerate(((1, 2), (0, 2), (0, 1))):
                plane = n.new("ShaderNodeCombineXYZ")
                n.link(position.outputs[a], plane.inputs[0])
                n.link(position.outputs[b], plane.inputs[1])
                self.coords.append((_uv_in_sdg_convention(n, desc, plane.outputs[0]),
                                    n.math("DIVIDE", w[axis], total)))
        else:
            uv = n.new("ShaderNodeUVMap")
            uv.uv_map = "UVMap"
            self.coords.append((_uv_in_sdg_convention(n, desc, uv.outputs[0]), None))

    def color(self, path, colorspace):
        """The map's colour (a socket), weighted over the projections."""
        total = None
        for coord, weight in self.coords:
            tex = self.n.new("ShaderNodeTexImage")
            tex.image = _image(path, colorspace)
            tex.interpolation = "Linear"
            tex.extension = "REPEAT"
            self.n.link(coord, tex.inputs["Vector"])
            out = tex.outputs["Color"]
            if weight is not None:
                scaled = self.n.new("ShaderNodeVectorMath")
                scaled.operation = "SCALE"
                self.n.link(out, scaled.inputs[0])
                self.n.link(weight, scaled.inputs["Scale"])
                out = scaled.outputs[0]
                if total is not None:
                    add = self.n.new("ShaderNodeVectorMath")
                    add.operation = "ADD"
                    self.n.link(total, add.inputs[0])
                    self.n.link(out, add.inputs[1])
                    out = add.outputs[0]
            total = out
        return total

    def channel(self, path, index):
        split = self.n.new("ShaderNodeSeparateXYZ")
        self.n.link(self.color(path, "Non-Color"), split.inputs[0])
        return split.outputs[index]


def _principled(n):
    bsdf = n.new("ShaderNodeBsdfPrincipled")
    # Single-scattering GGX with F0 = 0.04 for dielectrics (Specular 0.5), as
    # sdgbehave's GGX + Schlick; no sheen, clearcoat or subsurface.
    bsdf.distribution = "GGX"
    for name, value in (("Specular", 0.5), ("Specular Tint", 0.0), ("Sheen", 0.0), ("Clearcoat", 0.0),
                        ("Subsurface", 0.0), ("Transmission", 0.0)):
        bsdf.inputs[name].default_value = value
    return bsdf


def make_material(name, desc, bsdf_kind="principled"):
    """sdgbehave's RenderMaterial as a Principled BSDF (README.md lists what
    differs), or with bsdf_kind "lambert" as a pure Lambert surface of albedo
    base colour x (1 - metallic), which the unit checks use."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    n = _Nodes(mat.node_tree)
    n.tree.nodes.clear()
    out = n.new("ShaderNodeOutputMaterial")
    # A coat-less dielectric (specular_level 0, metallic 0) is Lambert in
    # sdgbehave: a Diffuse BSDF, not Principled's Disney diffuse, whose
    # retro-reflection differs from Lambert's at rough, grazing angles.
    plain = not desc.get("maps") and desc.get("specular_level", 0.5) == 0 and desc.get("metallic", 0) == 0
    if bsdf_kind == "lambert" or plain:
        bsdf = n.new("ShaderNodeBsdfDiffuse", Roughness=0.0)
        bsdf.inputs["Color"].default_value = (*[c * (1 - desc["metallic"]) for c in desc["base_color"]], 1.0)
        n.link(bsdf.outputs[0], out.inputs["Surface"])
        return mat
    bsdf = _principled(n)
    bsdf.inputs["Specular"].default_value = desc.get("specular_level", 0.5)  # F0 = 0.08 x it, as OmniPBR
    maps = desc.get("maps", {})
    sampler = _Sampler(n, desc) if maps else None
    if "base_color" in maps:
        n.link(sampler.color(maps["base_color"], "sRGB"), bsdf.inputs["Base Color"])  # the texture replaces the constant
    else:
        bsdf.inputs["Base Color"].default_value = (*desc["base_color"], 1.0)
    for key, channel_in_orm, socket in (("roughness", 1, "Roughness"), ("metallic", 2, "Metallic")):
        constant = desc[key]
        source = None
        if "orm" in maps:
            source = sampler.channel(maps["orm"], channel_in_orm)
        elif key in maps:
            source = sampler.channel(maps[key], 0)
        influence = desc.get(f"{key}_influence", 0.0)
        if source is not None and influence > 0:
            # OmniPBR: value = mix(constant, map, influence)
            n.link(n.math("ADD", n.math("MULTIPLY", source, influence), constant * (1 - influence)), bsdf.inputs[socket])
        else:
            bsdf.inputs[socket].default_value = constant
    if "normal" in maps and not desc.get("project_uvw"):
        normal = n.new("ShaderNodeNormalMap", Strength=desc.get("normal_scale", 1.0))
        normal.space = "TANGENT"
        normal.uv_map = "UVMap"
        n.link(sampler.color(maps["normal"], "Non-Color"), normal.inputs["Color"])
        n.link(normal.outputs[0], bsdf.inputs["Normal"])
    surface = bsdf.outputs[0]
    if "opacity_cutoff" in desc:
        # Cut out, not blended: drawn where opacity >= the cut-off.
        opacity = desc["opacity_constant"]
        if "opacity" in maps:
            opacity = n.math("MULTIPLY", sampler.channel(maps["opacity"], 0), opacity)
        keep = n.math("SUBTRACT", 1.0, n.math("LESS_THAN", opacity, desc["opacity_cutoff"]))
        mix = n.new("ShaderNodeMixShader")
        n.link(keep, mix.inputs[0])
        n.link(n.new("ShaderNodeBsdfTransparent").outputs[0], mix.inputs[1])
        n.link(surface, mix.inputs[2])
        surface = mix.outputs[0]
    n.link(surface, out.inputs["Surface"])
    return mat


def _normalize_file_materials(objects, mtl_values):
    """Mesh files keep their own materials, made to read as sdgbehave reads them
    through assimp: GGX with F0 = 0.04 (OBJ's Ks/illum and Ns are not used),
    no emission, an OBJ material's roughness 0.5 and metallic 0 unless its
    MTL has Pr/Pm."""
    for obj in objects:
        for slot in obj.material_slots:
            mat = slot.material
            if mat is None or not mat.use_nodes:
                continue
            for node in mat.node_tree.nodes:
                if node.type != "BSDF_PRINCIPLED":
                    continue
                node.distribution = "GGX"
                node.inputs["Specular"].default_value = 0.5
                node.inputs["Specular Tint"].default_value = 0.0
                # sdgbehave reads no emission from mesh files.
                for link in list(node.inputs["Emission"].links):
                    mat.node_tree.links.remove(link)
                node.inputs["Emission"].default_value = (0.0, 0.0, 0.0, 1.0)
                if mtl_values is not None:
                    pr, pm = mtl_values.get(mat.name, (None, None))
                    node.inputs["Roughness"].default_value = 0.5 if pr is None else pr
                    node.inputs["Metallic"].default_value = 0.0 if pm is None else pm
                    for socket in ("Roughness", "Metallic", "Specular"):
                        for link in list(node.inputs[socket].links):
                            mat.node_tree.links.remove(link)


def _mtl_values(obj_path):
    """Pr and Pm of each material in an OBJ's MTL files (assimp reads these)."""
    values = {}
    folder = os.path.dirname(obj_path)
    with open(obj_path, errors="replace") as f:
        libs = [line.split(None, 1)[1].strip() for line in f if line.startswith("mtllib ")]
    for lib in libs:
        path = os.path.join(folder, lib)
        if not os.path.exists(path):
            continue
        current = None
        with open(path, errors="replace") as f:
            for line in f:
                parts = line.split()
                if not parts:
                    continue
                if parts[0] == "newmtl":
                    current = " ".join(parts[1:])
                    values[current] = [None, None]
                elif current and parts[0] in ("Pr", "Pm"):
                    values[current][0 if parts[0] == "Pr" else 1] = float(parts[1])
    return values


# ---------------------------------------------------------------- mesh files

_library = {}


def _import_file(path, submesh):
    """The file's mesh objects (imported once, kept out of the scene) and the
    matrix that maps Blender's world of the import back to the file's own
    coordinates, which sdgbehave uses as they are."""
    key = (path, submesh)
    if key in _library:
        return _library[key]
    before = set(bpy.data.objects)
    ext = os.path.splitext(path)[1].lower()
    fix = Matrix.Identity(4)
    mtl = None
    if ext in (".glb", ".gltf"):
        # Debian's Blender 3.4 runs on the system's numpy 1.24, which dropped
        # the np.bool alias its glTF importer still uses.
        import numpy
        if not hasattr(numpy, "bool"):
            numpy.bool = bool
        bpy.ops.import_scene.gltf(filepath=path)
        fix = GLTF_TO_FILE
    elif ext == ".obj":
        # Forward +Y, up +Z: the file's axes are Blender's, no conversion.
        bpy.ops.wm.obj_import(filepath=path, forward_axis="Y", up_axis="Z")
        mtl = _mtl_values(path)
    elif ext == ".fbx":
        bpy.ops.import_scene.fbx(filepath=path)  # unverified against assimp: README.md
    elif ext == ".ply":
        bpy.ops.import_mesh.ply(filepath=path)
    elif ext == ".stl":
        bpy.ops.import_mesh.stl(filepath=path)
    elif ext == ".dae":
        bpy.ops.wm.collada_import(filepath=path)  # unverified against assimp: README.md
    else:
        raise RuntimeError(f"{path}: no Blender importer for {ext}")
    new = [o for o in bpy.data.objects if o not in before]
    for o in new:
        for c in list(o.users_collection):
            c.objects.unlink(o)
    bpy.context.view_layer.update()
    meshes = [o for o in new if o.type == "MESH"]
    if submesh:
        meshes = [o for o in meshes if submesh in (o.name, o.data.name)]
        if not meshes:
            raise RuntimeError(f"{path}: no mesh named {submesh!r} (Blender names: "
                               f"{', '.join(sorted(o.name for o in new))})")
    _normalize_file_materials(meshes, mtl)
    result = [(o, fix @ o.matrix_world) for o in meshes]
    _library[key] = result
    return result


# ---------------------------------------------------------------- the scene

def build_scene(scene):
    _clear()
    bscene = bpy.context.scene
    materials = {}

    def material_for(desc, name):
        key = json.dumps(desc, sort_keys=True)
        if key not in materials:
            materials[key] = make_material(name, desc, scene.get("bsdf", "principled"))
        return materials[key]

    meshes = {key: _mesh(f"mesh{i}", data) for i, (key, data) in enumerate(scene["meshes"].items())}
    for obj in scene["objects"]:
        world = Matrix(obj["matrix"])
        name = obj["path"]
        desc = obj["material"]
        own = material_for(desc, desc.get("path", name + ".displayColor"))
        if "mesh" in obj:
            if _sheared(world):
                me = _baked(name, scene["meshes"][obj["mesh"]], world)
                world = Matrix.Identity(4)
            else:
                me = meshes[obj["mesh"]]
            if not me.materials:
                me.materials.append(None)
            o = _link(bpy.data.objects.new(name, me))
            o.matrix_world = world
            o.material_slots[0].link = "OBJECT"
            o.material_slots[0].material = own
            continue
        for source, file_world in _import_file(obj["file"], obj["submesh"]):
            m = world @ file_world
            data = source.data
            if _sheared(m):
                # Baked into a copy; the custom normals follow the faces
                # rather than the exact inverse transpose (README.md).
                data = source.data.copy()
                data.transform(m)
                m = Matrix.Identity(4)
            o = _link(bpy.data.objects.new(f"{name}/{source.name}", data))
            o.matrix_world = m
            if not o.material_slots:
                o.data.materials.append(None)
            for slot in o.material_slots:
                file_material = slot.material
                slot.link = "OBJECT"
                # The prim's bound Material wins; else the file's; else displayColor.
                slot.material = own if desc["from_prim"] or file_material is None else file_material

    _lights(scene)
    _camera(scene)
    _settings(bscene, scene)


def _lights(scene):
    domes = []
    for light in scene["lights"]:
        kind = light["type"]
        if kind == "DOME":
            domes.append(light)
            continue
        if kind == "EMISSIVE_MESH":
            me = _mesh(light["path"], light["mesh"])
            mat = bpy.data.materials.new(light["path"] + ".emission")
            mat.use_nodes = True
            n = _Nodes(mat.node_tree)
            n.tree.nodes.clear()
            peak = max(light["radiance"]) or 1.0
            # A mesh's Emission of strength S and colour c has radiance S * c.
            emission = n.new("ShaderNodeEmission", Strength=peak)
            emission.inputs["Color"].default_value = (*[c / peak for c in light["radiance"]], 1.0)
            n.link(emission.outputs[0], n.new("ShaderNodeOutputMaterial").inputs["Surface"])
            me.materials.append(mat)
            o = _link(bpy.data.objects.new(light["path"], me))
        else:
            data = bpy.data.lights.new(light["path"], kind)
            data.energy = light["energy"]
            data.color = light["color"]
            if kind == "SUN":
                data.angle = light["angle"]
            elif kind == "POINT":
                data.shadow_soft_size = light["radius"]
            else:
                data.shape = light["shape"]
                data.size = light["size"]
                data.size_y = light["size_y"]
            data.cycles.cast_shadow = True
            o = _link(bpy.data.objects.new(light["path"], data))
        o.matrix_world = Matrix(light["matrix"])
        # sdgbehave never draws an emitter itself, only what it lights.
        o.visible_camera = False
    _world(scene, domes)


def _world(scene, domes):
    world = bpy.data.worlds.new("World")
    bpy.context.scene.world = world
    world.use_nodes = True
    n = _Nodes(world.node_tree)
    n.tree.nodes.clear()
    out = n.new("ShaderNodeOutputWorld")
    # As the rasterizer: the first dome with a texture lights through it, the
    # others add up as a uniform colour.
    textured = next((d for d in domes if d["texture"]), None)
    uniform = [0.0, 0.0, 0.0]
    for d in domes:
        if d is not textured:
            uniform = [u + c for u, c in zip(uniform, d["radiance"])]
    background = n.new("ShaderNodeBackground", Strength=1.0)
    background.inputs["Color"].default_value = (*uniform, 1.0)
    surface = background.outputs[0]
    if textured:
        surface = _textured_dome(n, textured, surface)
    n.link(surface, out.inputs["Surface"])


def _textured_dome(n, dome, uniform_surface):
    """The lat-long dome as Blender's equirectangular environment.

    sdgbehave looks the texture up with the world direction d turned into
    the dome's frame, d' = F^T d (F: the dome's frame, stage_to_blender.py),
    in render/latlong.h's convention (OpenEXR's, which the GLSL shares):
    u = 0.5 - atan2(d'.x, d'.z) / 2pi, v = acos(d'.y) / pi from the top.
    Blender's equirectangular lookup of a vector b has u = 0.5 - atan2(b.y,
    b.x) / 2pi and v = acos(b.z) / pi from the top, so b = (d'.z, d'.x,
    d'.y) = P F^T d.
    """
    P = Matrix(((0, 0, 1), (1, 0, 0), (0, 1, 0)))
    A = P @ Matrix(dome["frame"]).transposed()
    coords = n.new("ShaderNodeTexCoord")
    direction = coords.outputs["Generated"]  # the ray's world direction for the world shader
    b = n.new("ShaderNodeCombineXYZ")
    for row in range(3):
        dot = n.new("ShaderNodeVectorMath")
        dot.operation = "DOT_PRODUCT"
        n.link(direction, dot.inputs[0])
        dot.inputs[1].default_value = tuple(A[row])
        n.link(dot.outputs["Value"], b.inputs[row])
    env = n.new("ShaderNodeTexEnvironment")
    env.image = _image(dome["texture"], "sRGB")
    env.projection = "EQUIRECTANGULAR"
    env.interpolation = "Linear"
    n.link(b.outputs[0], env.inputs["Vector"])
    scaled = n.new("ShaderNodeVectorMath")
    scaled.operation = "MULTIPLY"
    n.link(env.outputs["Color"], scaled.inputs[0])
    scaled.inputs[1].default_value = tuple(dome["radiance"])
    background = n.new("ShaderNodeBackground", Strength=1.0)
    n.link(scaled.outputs[0], background.inputs["Color"])
    add = n.new("ShaderNodeAddShader")
    n.link(background.outputs[0], add.inputs[0])
    n.link(uniform_surface, add.inputs[1])
    return add.outputs[0]


def _camera(scene):
    c = scene["camera"]
    cam = bpy.data.cameras.new(c["path"])
    # As Replicator and sdgbehave do: the horizontal aperture and the image's
    # aspect ratio set the field of view (camera_math.cpp).
    cam.sensor_fit = "HORIZONTAL"
    cam.sensor_width = c["horizontal_aperture"]
    if c["orthographic"]:
        cam.type = "ORTHO"
        cam.ortho_scale = c["horizontal_aperture"] / 10.0  # tenths of a scene unit
    else:
        cam.lens = c["focal_length"]
    # sdgbehave moves the image content by +2 offset / aperture in NDC (x right,
    # y up); Blender's shift moves the view window by shift * width, the other
    # way, in units of the image width for both axes.
    cam.shift_x = -c["horizontal_aperture_offset"] / c["horizontal_aperture"]
    cam.shift_y = -c["vertical_aperture_offset"] / c["horizontal_aperture"]
    cam.clip_start = c["near"]
    cam.clip_end = c["far"]
    o = _link(bpy.data.objects.new(c["path"], cam))
    o.matrix_world = Matrix(c["matrix"])  # both look down local -Z with +Y up
    bpy.context.scene.camera = o


def _settings(bscene, scene):
    r = bscene.render
    r.engine = "CYCLES"
    r.resolution_x, r.resolution_y = scene["resolution"]
    r.resolution_percentage = 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.film_transparent = False
    # Linear radiance out: no Filmic, no look, no exposure.
    bscene.view_settings.view_transform = "Standard"
    bscene.view_settings.look = "None"
    bscene.view_settings.exposure = 0.0
    bscene.view_settings.gamma = 1.0
    cy = bscene.cycles
    cy.device = "CPU"
    cy.film_exposure = 1.0
    # Each pixel the average of its own square, as averaging sub-pixel samples gives.
    cy.pixel_filter_type = "BOX"
    cy.filter_width = 1.0
    # An unbiased reference: no clamping, no glossy blur, no light threshold,
    # no adaptive stopping; bounces deep enough for white walls (albedo 0.73:
    # 0.73^32 < 1e-4 of the light is lost).
    cy.sample_clamp_direct = 0.0
    cy.sample_clamp_indirect = 0.0
    cy.blur_glossy = 0.0
    cy.light_sampling_threshold = 0.0
    cy.use_adaptive_sampling = False
    cy.max_bounces = 32
    cy.diffuse_bounces = 32
    cy.glossy_bounces = 32
    cy.transmission_bounces = 32
    cy.volume_bounces = 0
    cy.transparent_max_bounces = 32
    cy.caustics_reflective = True
    cy.caustics_refractive = True
    cy.use_denoising = False
    cy.seed = 0
    cy.use_animated_seed = False
