"""A Blender scene as a Caligo scene file: camera, meshes (PLY through Blender's own exporter),
lights, world, materials, mesh volumes and VDB volume objects.

    warnings = export_scene(depsgraph, "/tmp/shot/scene.json")

writes scene.json and one PLY per mesh object beside it, and returns the list of what could not
be carried over. Blender's Z-up frame becomes Caligo's
Y-up one (convert.py), so world HDRIs keep their orientation.
"""
import json
import math
import os
import re

import bpy

from . import convert, materials


class ExportError(Exception):
    """The scene cannot be exported at all (no camera, an unsupported camera type)."""


def export_scene(depsgraph, path, spp=None):
    exporter = _Exporter(depsgraph, os.path.dirname(os.path.abspath(path)))
    doc = exporter.run(spp)
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(doc, f, indent=1)
    os.replace(tmp, path)
    return exporter.warnings


def _safe(name):
    return re.sub(r"[^A-Za-z0-9_.-]", "_", name) or "object"


class _Exporter:
    def __init__(self, depsgraph, directory):
        self.depsgraph = depsgraph
        self.scene = depsgraph.scene
        self.directory = directory
        self.warnings = []
        self.doc = {"materials": {}, "media": {}, "shapes": [], "lights": [], "volumes": []}

    def warn(self, text):
        if text not in self.warnings:
            self.warnings.append(text)

    def run(self, spp):
        w, h = self.resolution()
        self.doc["camera"] = self.camera(w, h)
        self.doc["render"] = self.render_settings(spp)
        for inst in self.depsgraph.object_instances:
            obj = inst.object
            if inst.is_instance:
                self.warn(f"object \"{obj.name}\": instances (particles, collections) are not exported")
                continue
            if obj.type == 'MESH':
                self.mesh(obj)
            elif obj.type == 'LIGHT':
                self.light(obj)
            elif obj.type == 'VOLUME':
                self.vdb(obj)
            elif obj.type not in ('CAMERA', 'EMPTY'):
                self.warn(f"object \"{obj.name}\" of type {obj.type} is not exported")
        self.world()
        for key in ("materials", "media", "shapes", "lights", "volumes"):
            if not self.doc[key]:
                del self.doc[key]
        return self.doc

    # ---- camera and settings ----

    def resolution(self):
        r = self.scene.render
        scale = r.resolution_percentage / 100.0
        return max(1, int(r.resolution_x * scale)), max(1, int(r.resolution_y * scale))

    def camera(self, w, h):
        obj = self.scene.camera
        if obj is None:
            raise ExportError("the scene has no camera")
        cam, m = obj.data, obj.matrix_world
        rot = m.to_3x3().normalized()
        eye = m.translation
        forward = rot.col[2] * -1.0
        out = {"position": convert.point(eye), "look_at": convert.point(eye + forward),
               "up": convert.point(rot.col[1]), "resolution": [w, h]}
        if abs(cam.shift_x) > 1e-6 or abs(cam.shift_y) > 1e-6:
            self.warn(f"camera \"{obj.name}\": lens shift is not exported")
        if cam.type == 'PERSP':
            out["fov"] = convert.vertical_fov(cam.sensor_fit, cam.sensor_width, cam.sensor_height, cam.lens, w, h)
            if cam.dof.use_dof:
                focus = cam.dof.focus_distance
                if cam.dof.focus_object is not None:
                    to = cam.dof.focus_object.matrix_world.translation - eye
                    focus = max(1e-4, to.dot(forward))
                out["aperture_radius"] = convert.aperture_radius(cam.lens, cam.dof.aperture_fstop)
                out["focus_distance"] = focus
                if cam.dof.aperture_blades >= 3:
                    self.warn(f"camera \"{obj.name}\": a polygonal aperture is exported round")
        elif cam.type == 'ORTHO':
            out["projection"] = "orthographic"
            out["ortho_width"] = convert.ortho_width(cam.sensor_fit, cam.ortho_scale, w, h)
        else:
            raise ExportError(f"camera \"{obj.name}\": {cam.type} cameras are not supported")
        return out

    def render_settings(self, spp):
        out = {"spp": int(spp or 64)}
        cycles = getattr(self.scene, "cycles", None)
        if cycles is not None:
            if spp is None:
                out["spp"] = int(cycles.samples)
            # Cycles counts bounces after the first hit (0: direct light), Caligo counts the
            # first (1: direct light); likewise for scattering events in volumes.
            out["max_bounces"] = int(cycles.max_bounces) + 1
            out["max_volume_bounces"] = int(cycles.volume_bounces) + 1
            out["seed"] = int(cycles.seed)
        return out

    # ---- meshes, their materials and mesh volumes ----

    def mesh(self, obj):
        slots = [s.material for s in obj.material_slots if s.material is not None]
        if len(slots) > 1:
            self.warn(f"object \"{obj.name}\": {len(slots)} materials; only the first is exported")
        mat = slots[0] if slots else None
        surface, medium = self.material(mat)
        if surface is False and medium is None:
            return  # nothing to render: a transparent surface with nothing inside
        ply = self.write_ply(obj)
        if medium is not None and surface is False:
            self.doc["volumes"].append({"type": "mesh", "file": ply, "medium": medium})
            return
        shape = {"type": "mesh", "file": ply, "material": surface}
        self.doc["shapes"].append(shape)

    def write_ply(self, obj):
        name = _safe(obj.name) + ".ply"
        path = os.path.join(self.directory, name)
        original = bpy.data.objects[obj.name]
        view_layer = bpy.context.view_layer
        selected = [o for o in view_layer.objects if o.select_get()]
        active = view_layer.objects.active
        for o in selected:
            o.select_set(False)
        original.select_set(True)
        view_layer.objects.active = original
        try:
            # World space, in Caligo's frame: -Z forward, Y up is convert.FRAME.
            bpy.ops.export_mesh.ply(filepath=path, check_existing=False, use_selection=True,
                                    use_mesh_modifiers=True, use_normals=True, use_uv_coords=False,
                                    use_colors=False, axis_forward='-Z', axis_up='Y', global_scale=1.0)
        finally:
            original.select_set(False)
            for o in selected:
                o.select_set(True)
            view_layer.objects.active = active
        return name

    def material(self, mat):
        """(surface material name, or False for none; interior medium name or None)."""
        if mat is None or not mat.use_nodes:
            name = "default_grey"
            self.doc["materials"].setdefault(name, {"type": "diffuse", "reflectance": 0.8})
            return name, None
        name = _safe(mat.name)
        if name in self.doc["materials"]:
            return name, self.doc["materials"][name].get("interior")
        out = materials.output_node(mat.node_tree)
        surface_node = materials.linked_node(out.inputs["Surface"]) if out else None
        volume_node = materials.linked_node(out.inputs["Volume"]) if out else None
        medium = None
        if volume_node is not None:
            converted = materials.volume(f"material \"{mat.name}\"", volume_node, self.warn)
            if converted is not None:
                medium = "medium_" + name
                self.doc["media"][medium] = converted[0]
        desc = materials.surface(mat.name, surface_node, self.warn) if surface_node is not None else None
        if desc is None:
            if medium is None:
                return False, None
            return False, medium  # a volume bounded by nothing visible: a mesh volume
        if medium is not None:
            if desc["type"] == "dielectric":
                desc["interior"] = medium
            else:
                self.warn(f"material \"{mat.name}\": a volume inside an opaque surface is not exported")
        self.doc["materials"][name] = desc
        return name, None

    # ---- lights ----

    def light(self, obj):
        light, m = obj.data, obj.matrix_world
        color = list(light.color)
        where = f"light \"{obj.name}\""
        position = convert.point(m.translation)
        direction = convert.point(m.to_3x3().normalized().col[2] * -1.0)
        if light.use_nodes:
            self.warn(f"{where}: light node trees are not exported")
        if light.type == 'POINT':
            out = self.point_like(where, light, position, color)
        elif light.type == 'SPOT':
            out = self.point_like(where, light, position, color)
            inner, outer = convert.spot_angles(light.spot_size, light.spot_blend)
            out.update({"type": "spot", "direction": direction, "inner_angle": inner, "outer_angle": outer})
            if any(abs(s - 1.0) > 1e-4 for s in m.to_scale()):
                self.warn(f"{where}: a scaled (elliptical) spot cone is exported round")
        elif light.type == 'SUN':
            out = {"type": "directional", "direction": direction,
                   "irradiance": convert.rgb(color, convert.sun_irradiance(light.energy)),
                   "angular_radius": min(45.0, math.degrees(light.angle) / 2.0)}
        else:
            out = self.area(where, light, m, color)
        if out is not None:
            self.doc["lights"].append(out)

    def point_like(self, where, light, position, color):
        if light.shadow_soft_size > 0.0 and light.type == 'POINT':
            # Cycles' soft point light keeps the intensity P / (4 pi); so does a Caligo sphere of power P.
            return {"type": "sphere", "center": position, "radius": light.shadow_soft_size,
                    "power": convert.rgb(color, light.energy)}
        if light.shadow_soft_size > 0.0:
            self.warn(f"{where}: a soft spot (radius {light.shadow_soft_size:g}) is exported as a point spot")
        return {"type": "point", "position": position,
                "intensity": convert.rgb(color, convert.point_intensity(light.energy))}

    def area(self, where, light, m, color):
        sx = light.size
        sy = light.size_y if light.shape in ('RECTANGLE', 'ELLIPSE') else light.size
        ex = (m.to_3x3() @ _vec((sx, 0.0, 0.0)))
        ey = (m.to_3x3() @ _vec((0.0, sy, 0.0)))
        centre = m.translation
        if getattr(light, "spread", math.pi) < math.pi - 1e-4:
            self.warn(f"{where}: an area light's spread is not exported (it emits into the hemisphere)")
        if light.shape in ('SQUARE', 'RECTANGLE'):
            area = ex.cross(ey).length
            corner = centre - 0.5 * ex - 0.5 * ey
            # Blender's area light emits along its local -Z: cross(ey, ex) points there.
            return {"type": "quad", "corner": convert.point(corner), "edge1": convert.point(ey),
                    "edge2": convert.point(ex), "radiance": convert.rgb(color, convert.area_radiance(light.energy, area))}
        rx, ry = 0.5 * ex.length, 0.5 * ey.length
        if abs(rx - ry) > 1e-4 * max(rx, ry):
            self.warn(f"{where}: an elliptical area light is exported as a disk of the same area")
        radius = math.sqrt(rx * ry)
        normal = convert.point(ex.cross(ey).normalized() * -1.0)
        # Cycles' disk light of power P has radiance P / (pi * pi r^2); Caligo's disk (a 64-gon
        # 0.16 % smaller) is given that radiance, not the power, to keep Cycles' brightness.
        return {"type": "disk", "center": convert.point(centre), "normal": normal, "radius": radius,
                "radiance": convert.rgb(color, convert.area_radiance(light.energy, math.pi * radius * radius))}

    # ---- world ----

    def world(self):
        world = self.scene.world
        if world is None:
            return
        if not world.use_nodes:
            self.doc["lights"].append({"type": "environment", "color": list(world.color), "radiance": 1.0})
            return
        out = materials.output_node(world.node_tree)
        if out is None:
            return
        bg = materials.linked_node(out.inputs["Surface"])
        if bg is not None:
            self.background(world, bg)
        vol = materials.linked_node(out.inputs["Volume"])
        if vol is not None:
            converted = materials.volume(f"world \"{world.name}\"", vol, self.warn)
            if converted is not None:
                self.doc["media"]["world_volume"] = converted[0]
                # Cycles' world volume fills all space; a box 100 km across is all of it here.
                self.doc["volumes"].append({"type": "box", "min": [-5e4] * 3, "max": [5e4] * 3,
                                            "medium": "world_volume"})

    def background(self, world, bg):
        where = f"world \"{world.name}\""
        if bg.type != 'BACKGROUND':
            self.warn(f"{where}: surface node {bg.bl_idname} is not exported")
            return
        strength = float(bg.inputs["Strength"].default_value)
        source = materials.linked_node(bg.inputs["Color"])
        if source is None:
            color = list(bg.inputs["Color"].default_value)[:3]
            if strength > 0.0 and any(c > 0.0 for c in color):
                self.doc["lights"].append({"type": "environment", "color": color, "radiance": strength})
            return
        if source.type != 'TEX_ENVIRONMENT' or source.image is None:
            self.warn(f"{where}: the background colour is driven by {source.bl_idname}; not exported")
            return
        if source.projection != 'EQUIRECTANGULAR':
            self.warn(f"{where}: {source.projection} environment images are not supported")
            return
        rotation = 0.0
        mapping = materials.linked_node(source.inputs["Vector"])
        if mapping is not None and mapping.type == 'MAPPING':
            rotation = math.degrees(mapping.inputs["Rotation"].default_value[2])
        elif mapping is not None:
            self.warn(f"{where}: the environment's vector input {mapping.bl_idname} is not exported")
        # Blender's lat-long image centre looks along -X; Caligo's along -Z, turned by 90
        # degrees about +Y to -X (convert.FRAME keeps Blender's +Z rotation as Caligo's +Y).
        self.doc["lights"].append({"type": "environment", "map": bpy.path.abspath(source.image.filepath),
                                   "strength": strength, "rotation": 90.0 + rotation})

    # ---- VDB volumes ----

    def vdb(self, obj):
        volume = obj.data
        where = f"volume \"{obj.name}\""
        mat = volume.materials[0] if len(volume.materials) and volume.materials[0] else None
        if mat is None or not mat.use_nodes:
            self.warn(f"{where}: no material with a volume shader; not exported")
            return
        out = materials.output_node(mat.node_tree)
        node = materials.linked_node(out.inputs["Volume"]) if out else None
        converted = materials.volume(where, node, self.warn, on_grid=True) if node else None
        if converted is None:
            return
        medium = "medium_" + _safe(obj.name)
        self.doc["media"][medium] = converted[0]
        volume.grids.load()
        available = {g.name for g in volume.grids}
        grids = {k: v for k, v in converted[1].items() if v in available}
        if "density" not in grids:
            self.warn(f"{where}: no grid \"{converted[1]['density']}\" in {volume.filepath}; not exported")
            return
        if volume.sequence_mode != 'REPEAT' or volume.is_sequence:
            self.warn(f"{where}: a VDB sequence is exported at its current frame only")
        self.doc["volumes"].append({"type": "vdb", "file": bpy.path.abspath(volume.grids.frame_filepath),
                                    "medium": medium, "grids": grids,
                                    "transform": [{"matrix": convert.matrix(obj.matrix_world)}]})


def _vec(v):
    from mathutils import Vector
    return Vector(v)
