"""Caligo from Python: load a scene, render it, get numpy arrays.

    import caligo
    scene = caligo.load_scene("cloud")               # a built-in, a .json path or a dict
    layers = caligo.render(scene, spp=16, res=(320, 180), aovs=["albedo"])
    layers["beauty"].shape                           # (180, 320, 3), float32, linear
    caligo.write_exr("cloud.exr", layers)

Keyword settings of render() are the keys of the scene's "render" object (spp, max_bounces,
max_volume_bounces, seed, aovs, guiding, adaptive, clamp, filter, crop, priority_shadows;
docs/scene-format.md), and those of realtime() the keys of its "realtime" object; res sets the
camera's resolution. They are merged into the scene's JSON and parsed by the same parser as
files, so a bad value raises SceneError naming the key, as the command line does, and a render
equals `caligo render` with the same settings bit for bit. See docs/python.md.
"""

import json
import os

from . import _caligo

SceneError = _caligo.SceneError

__all__ = ["SceneError", "Scene", "load_scene", "builtins", "render", "realtime", "compare", "read_exr", "write_exr"]


class Scene:
    """A parsed scene: its file (or "builtin:NAME", "<dict>"), resolution and warnings."""

    def __init__(self, parsed):
        self._parsed = parsed

    file = property(lambda self: self._parsed.file)
    resolution = property(lambda self: self._parsed.resolution)
    warnings = property(lambda self: list(self._parsed.warnings))
    files = property(lambda self: list(self._parsed.files))

    def to_dict(self):
        """The scene's JSON as a dict (edit it and load it again)."""
        return json.loads(self._parsed.text)

    def __repr__(self):
        w, h = self.resolution
        return f"<caligo.Scene {self.file} {w}x{h}>"


def builtins():
    """The built-in scenes: a dict of name -> one-line description."""
    return dict(_caligo.builtins())


def load_scene(source, base_dir=None):
    """A Scene from a built-in's name, a scene file's path or a dict in the scene format.

    Relative file names in a dict are resolved against base_dir (default: the current folder).
    Raises SceneError (a ValueError) naming the file and the JSON path of what is wrong.
    """
    if isinstance(source, Scene):
        return source
    if isinstance(source, dict):
        text = _dumps(source, "the scene")
        return Scene(_caligo.parse_text(text, "<dict>", os.fspath(base_dir) if base_dir else os.getcwd()))
    if isinstance(source, (str, os.PathLike)):
        return Scene(_caligo.parse_named(os.fspath(source)))
    raise TypeError(f"load_scene: expected a path, a built-in's name or a dict, got {type(source).__name__}")


def _dumps(value, what):
    try:
        # allow_nan=False: NaN and Infinity are not JSON, and no setting takes them.
        return json.dumps(value, allow_nan=False)
    except (TypeError, ValueError) as e:
        raise SceneError(f"<dict>: {what} is not JSON: {e}") from None


def _with_settings(scene, section, settings, res):
    """The scene re-parsed with `settings` merged into its `section` object and `res`."""
    scene = load_scene(scene)
    if not settings and res is None:
        return scene
    data = scene.to_dict()
    if settings:
        target = data.setdefault(section, {})
        if not isinstance(target, dict):
            raise SceneError(f"{scene.file}: /{section}: expected an object")
        target.update(settings)
    if res is not None:
        if (not isinstance(res, (tuple, list)) or len(res) != 2
                or not all(isinstance(v, int) and not isinstance(v, bool) for v in res)):
            raise SceneError(f"res: expected (width, height) as two integers, got {res!r}")
        data.setdefault("camera", {})["resolution"] = list(res)
    return Scene(_caligo.parse_text(_dumps(data, "the scene with its settings"), scene.file, scene._parsed.base_dir))


def _check_threads(threads):
    if threads is None:
        return 0
    if not isinstance(threads, int) or isinstance(threads, bool) or not 1 <= threads <= 1024:
        raise SceneError(f"threads: expected an integer from 1 to 1024, got {threads!r}")
    return threads


def render(scene, spp=None, res=None, aovs=None, seed=None, threads=None, progress=None, **settings):
    """Path-traces the scene; returns {layer name: float32 array}.

    "beauty" is (height, width, 3); "alpha", "depth" and "samples" are (height, width);
    "normal", "albedo", the light layers and "variance" are (height, width, 3).
    progress(done_spp, target_spp) is called between passes. The GIL is released while
    rendering; Ctrl-C stops the render and raises KeyboardInterrupt, with no thread left running.
    """
    for key, value in (("spp", spp), ("aovs", aovs), ("seed", seed)):
        if value is not None:
            settings[key] = value
    if progress is not None and not callable(progress):
        raise TypeError("render: progress must be callable")
    prepared = _with_settings(scene, "render", settings, res)
    _warn(prepared)
    return _caligo.render(prepared._parsed, _check_threads(threads), progress)


def realtime(scene, frames=1, res=None, method="march", **settings):
    """Runs the real-time pipeline for `frames` frames (at the scene's fps).

    Returns {"frames": [float32 (height, width, 3) per frame], "times": [{pass: seconds}]},
    with the passes depth, shadows, accumulation, gather, upsample, temporal, surfaces,
    composite, total, volumetric and per_light. method: "march" (per light) or "froxel".
    """
    prepared = _with_settings(scene, "realtime", settings, res)
    _warn(prepared)
    return _caligo.realtime(prepared._parsed, frames, method)


def compare(image, reference):
    """Error metrics of `image` against `reference` (arrays (h, w, 3+) or render() dicts):
    rmse, relative_mse, mean_difference (positive: image brighter), max_abs_difference, pixels."""
    def beauty(x):
        return x["beauty"] if isinstance(x, dict) else x
    return _caligo.compare(beauty(image), beauty(reference))


def read_exr(path):
    """The layers of an EXR file as render() names them."""
    return _caligo.read_exr(os.fspath(path))


def write_exr(path, layers, half=False):
    """Writes {layer name: array} (render()'s names) as one EXR, all or nothing."""
    if not isinstance(layers, dict):
        raise TypeError("write_exr: expected a dict of layer name -> array")
    _caligo.write_exr(os.fspath(path), layers, bool(half))


def _warn(scene):
    import warnings
    for w in scene.warnings:
        warnings.warn(w, stacklevel=3)
