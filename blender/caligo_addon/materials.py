"""Blender materials and world shaders reduced to Caligo's materials and media.

Each function reads the node linked to an output and returns the Caligo description; whatever
it cannot carry over goes to `warn(text)`, one message per input, naming the material and the
input, and the input's default is used.
"""
from . import convert

# Principled BSDF inputs Caligo's diffuse and dielectric cannot honour, with the value at which
# ignoring them is exact.
_PRINCIPLED_EXACT_AT = {
    "Subsurface": 0.0, "Metallic": 0.0, "Specular": 0.0, "Anisotropic": 0.0, "Sheen": 0.0,
    "Clearcoat": 0.0,
}


def linked_node(socket):
    """The node feeding `socket`, skipping reroutes; None when nothing is linked."""
    while socket is not None and socket.is_linked:
        node = socket.links[0].from_node
        if node.type != 'REROUTE':
            return node
        socket = node.inputs[0]
    return None


def output_node(tree):
    """The active material or world output of a node tree (Cycles' target, or any)."""
    outputs = [n for n in tree.nodes if n.type in ('OUTPUT_MATERIAL', 'OUTPUT_WORLD')]
    for n in outputs:
        if n.is_active_output and getattr(n, "target", 'ALL') in ('ALL', 'CYCLES'):
            return n
    return outputs[0] if outputs else None


class NodeReader:
    """Input values of one node, warning once for each input driven by another node."""

    def __init__(self, owner, node, warn):
        self.owner, self.node, self.warn = owner, node, warn

    def value(self, name):
        socket = self.node.inputs[name]
        if socket.is_linked:
            self.warn(f"{self.owner}: {self.node.name}: input \"{name}\" is driven by a node, which Caligo "
                      f"does not evaluate; its own value is used")
        v = socket.default_value
        return tuple(v) if hasattr(v, "__len__") and not isinstance(v, str) else v


def surface(name, node, warn):
    """A Caligo material for the shader node `node` (None: a null surface)."""
    r = NodeReader(f"material \"{name}\"", node, warn)
    if node.type == 'BSDF_PRINCIPLED':
        return _principled(r, warn)
    if node.type == 'BSDF_DIFFUSE':
        if r.value("Roughness") > 0.0:
            warn(f"{r.owner}: Diffuse BSDF roughness (Oren-Nayar) is exported as Lambertian")
        return {"type": "diffuse", "reflectance": convert.rgb(r.value("Color"))}
    if node.type == 'EMISSION':
        return {"type": "emissive", "color": convert.rgb(r.value("Color")), "radiance": float(r.value("Strength"))}
    if node.type in ('BSDF_GLASS', 'BSDF_REFRACTION'):
        if r.value("Roughness") > 0.0:
            warn(f"{r.owner}: rough glass is exported as smooth")
        if any(abs(c - 1.0) > 1e-6 for c in r.value("Color")[:3]):
            warn(f"{r.owner}: tinted glass is exported clear (give the interior a medium for colour)")
        return {"type": "dielectric", "ior": float(r.value("IOR"))}
    if node.type == 'BSDF_TRANSPARENT':
        return None
    warn(f"{r.owner}: shader node {node.bl_idname} has no Caligo counterpart; exported as grey diffuse")
    return {"type": "diffuse", "reflectance": 0.8}


def _principled(r, warn):
    for name, exact in _PRINCIPLED_EXACT_AT.items():
        if abs(r.value(name) - exact) > 1e-6:
            warn(f"{r.owner}: Principled BSDF \"{name}\" = {r.value(name):g} is not supported "
                 f"(Caligo's diffuse and dielectric have no such lobe); it is ignored")
    if r.value("Transmission") >= 0.5:
        if r.value("Roughness") > 0.0 or r.value("Transmission Roughness") > 0.0:
            warn(f"{r.owner}: rough transmission is exported as smooth glass")
        return {"type": "dielectric", "ior": float(r.value("IOR"))}
    if r.value("Transmission") > 0.0:
        warn(f"{r.owner}: a Transmission below 0.5 is exported as opaque")
    out = {"type": "diffuse", "reflectance": convert.rgb(r.value("Base Color"))}
    strength = float(r.value("Emission Strength"))
    if strength > 0.0 and any(c > 0.0 for c in r.value("Emission")[:3]):
        out["emission"] = convert.rgb(r.value("Emission"), strength)
    alpha = float(r.value("Alpha"))
    if alpha < 1.0:
        out["opacity"] = max(0.0, alpha)
    return out


def volume(owner, node, warn, on_grid=False):
    """(Caligo medium, grid names) for a volume shader node; None for an unsupported node.

    On a grid, density multiplies the medium (Caligo scales every coefficient by the grid's
    value, emission too, where Cycles does not scale Principled Volume's emission)."""
    r = NodeReader(owner, node, warn)
    if node.type == 'PRINCIPLED_VOLUME':
        medium = convert.principled_volume(r.value("Density"), r.value("Color"), r.value("Absorption Color"),
                                           r.value("Anisotropy"), r.value("Emission Strength"),
                                           r.value("Emission Color"))
        grids = {"density": node.inputs["Density Attribute"].default_value or "density"}
        if node.inputs["Color Attribute"].default_value:
            grids["color"] = node.inputs["Color Attribute"].default_value
        intensity = float(r.value("Blackbody Intensity"))
        if intensity > 0.0:
            if on_grid and node.inputs["Temperature Attribute"].default_value:
                grids["temperature"] = node.inputs["Temperature Attribute"].default_value
                tint = r.value("Blackbody Tint")
                if any(abs(c - 1.0) > 1e-6 for c in tint[:3]):
                    warn(f"{owner}: the blackbody tint is not exported")
                medium["blackbody"] = {"intensity": intensity * convert.BLACKBODY_SCALE,
                                       "scale": float(r.value("Temperature")), "offset": 0.0}
            else:
                warn(f"{owner}: blackbody emission needs a temperature grid in Caligo; it is not exported")
        if on_grid and "emission" in medium:
            warn(f"{owner}: emission on a grid is scaled by the density grid in Caligo (not in Cycles)")
        return medium, grids
    if node.type == 'VOLUME_SCATTER':
        medium = {"sigma_s": convert.rgb(r.value("Color"), r.value("Density"))}
        if abs(r.value("Anisotropy")) > 1e-6:
            medium["phase"] = {"type": "hg", "g": max(-0.99, min(0.99, r.value("Anisotropy")))}
        return medium, {"density": "density"}
    if node.type == 'VOLUME_ABSORPTION':
        color = r.value("Color")
        return {"sigma_a": [r.value("Density") * max(0.0, 1.0 - c) for c in color[:3]]}, {"density": "density"}
    warn(f"{owner}: volume node {node.bl_idname} has no Caligo counterpart; the volume is not exported")
    return None
