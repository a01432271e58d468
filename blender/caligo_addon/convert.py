"""Blender's units and conventions in Caligo's: the frame, lights, camera and volumes.

Pure functions of numbers (no bpy), so that every conversion is stated once and can be read
beside the Cycles 3.x behaviour it reproduces.

Frame: Blender is Z-up, Caligo's environment maps are Y-up, so the whole scene is turned by
-90 degrees about X: Blender (x, y, z) is Caligo (x, z, -y). It is a rotation, so nothing is
mirrored and every length, angle and handedness is kept.
"""
import math

# Blender -> Caligo, row-major, acting on column vectors (p' = C p).
FRAME = ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0), (0.0, -1.0, 0.0))


def point(p):
    """A Blender position or direction in Caligo's frame."""
    return [sum(FRAME[r][c] * p[c] for c in range(3)) for r in range(3)]


def matrix(m):
    """A Blender 4x4 (rows, column vectors) as Caligo's row-major "matrix" transform: C M."""
    rows = [[m[r][c] for c in range(4)] for r in range(4)]
    out = []
    for r in range(3):
        out.append([sum(FRAME[r][k] * rows[k][c] for k in range(3)) for c in range(4)])
    out.append([0.0, 0.0, 0.0, 1.0])
    return [v for row in out for v in row]


def rgb(color, scale=1.0):
    return [float(color[0]) * scale, float(color[1]) * scale, float(color[2]) * scale]


# ---- lights (Cycles 3.x: measured on a white Lambertian plane and read in its light code) ----

def point_intensity(power):
    """A point or spot light of power P watts has intensity P / (4 pi) W/sr (a spot is a point
    light masked by its cone: its power is not concentrated into the cone)."""
    return power / (4.0 * math.pi)


def spot_angles(spot_size, spot_blend):
    """Blender's full cone angle and blend -> Caligo's inner and outer half-angles in degrees.
    Cycles fades with smoothstep over cos(theta) from cos(outer) to cos(outer) + (1 - cos(outer))
    * blend, which is Caligo's smoothstep between its outer and inner cosines."""
    outer = 0.5 * spot_size
    cos_outer = math.cos(outer)
    cos_inner = min(1.0, cos_outer + (1.0 - cos_outer) * max(0.0, min(1.0, spot_blend)))
    return math.degrees(math.acos(cos_inner)), math.degrees(outer)


def area_radiance(power, area):
    """An area light of power P watts over A square metres, one-sided Lambertian: L = P / (pi A)."""
    return power / (math.pi * area)


def sun_irradiance(strength):
    """A sun's strength is its irradiance in W/m^2 on a surface facing it."""
    return strength


# ---- camera ----

def vertical_fov(sensor_fit, sensor_width, sensor_height, lens, width, height):
    """Caligo's vertical field of view (degrees) of a Blender perspective camera. The sensor
    fits the wider side of the image when the fit is AUTO (both sides use the sensor width)."""
    if sensor_fit == 'AUTO':
        fit, sensor = ('HORIZONTAL' if width >= height else 'VERTICAL'), sensor_width
    elif sensor_fit == 'HORIZONTAL':
        fit, sensor = 'HORIZONTAL', sensor_width
    else:
        fit, sensor = 'VERTICAL', sensor_height
    tan_half = sensor / (2.0 * lens)
    if fit == 'HORIZONTAL':
        tan_half *= height / width
    return math.degrees(2.0 * math.atan(tan_half))


def ortho_width(sensor_fit, ortho_scale, width, height):
    """Caligo's orthographic window width: Blender's scale spans the fitted side."""
    horizontal = sensor_fit == 'HORIZONTAL' or (sensor_fit == 'AUTO' and width >= height)
    return ortho_scale if horizontal else ortho_scale * width / height


def aperture_radius(lens_mm, fstop):
    """Cycles' lens: aperture radius = focal length / (2 N), millimetres to metres."""
    return 0.001 * lens_mm / (2.0 * fstop)


# ---- Principled Volume (Cycles' closure: scattering d c; absorption d (1 - c) (1 - sqrt(a))) ----

def principled_volume(density, color, absorption_color, anisotropy, emission_strength, emission_color):
    """Caligo medium coefficients of a Principled Volume of constant density."""
    d = max(0.0, density)
    sigma_s = [d * max(0.0, c) for c in color[:3]]
    sigma_a = [d * max(0.0, 1.0 - c) * max(0.0, 1.0 - math.sqrt(max(0.0, a)))
               for c, a in zip(color[:3], absorption_color[:3])]
    medium = {"sigma_s": sigma_s, "sigma_a": sigma_a}
    if emission_strength > 0.0 and any(c > 0.0 for c in emission_color[:3]):
        medium["emission"] = rgb(emission_color, emission_strength)
    if abs(anisotropy) > 1e-6:
        medium["phase"] = {"type": "hg", "g": max(-0.99, min(0.99, anisotropy))}
    return medium


# Cycles' blackbody emission is sigma_SB T^4 / pi scaled by 1e-6 at intensity 1; Caligo's
# intensity 1 is the full blackbody radiance (docs/scene-format.md, media).
BLACKBODY_SCALE = 1e-6
