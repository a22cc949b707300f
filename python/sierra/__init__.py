"""Sierra: terrain frames rendered off-screen (EGL), as numpy arrays.

    import numpy as np, sierra
    r = sierra.Renderer()
    img = r.render(heights, spacing=(30, 30), width=1280, height=720,
                   azimuth=200, elevation=30, zones="auto")      # (720, 1280, 4) uint8
    depth = r.render(heights, spacing=(30, 30), output="depth")  # (720, 1280) float32
    hs = sierra.maps.hillshade(heights, spacing=(30, 30))        # (H, W) float32

Keyword names are the keys of a scene file (docs/scene.md): a key that only
one part of the scene has may be given alone (azimuth=200 is camera.azimuth),
a whole part as a dict (camera={"fov": 30}), and zones="auto" names the zone
map. Unknown keys and wrong values raise sierra.Error with the programs'
messages.

Heights: any real numeric dtype, C or Fortran order, rows along +z (south
for a north-up grid), columns along +x (east); NaN and masked values are
no-data.
"""

import json as _json

import numpy as _np

from . import _sierra
from ._sierra import Error

__all__ = ["Error", "Renderer", "Scene", "maps", "read_png"]


def _defaults():
    return _json.loads(_sierra.scene_text("{}"))


_DEFAULTS = _defaults()
# Each key of a part that no other part has: the part it belongs to.
_PART_OF = {}
for _part, _keys in _DEFAULTS.items():
    for _key in _keys:
        _PART_OF.setdefault(_key, []).append(_part)


def _scene_json(scene, kwargs):
    """The scene's JSON text: `scene` (a Scene, a dict or None) with `kwargs` over it."""
    data = scene.to_dict() if isinstance(scene, Scene) else _json.loads(_json.dumps(scene or {}))
    if not isinstance(data, dict):
        raise Error("scene must be a sierra.Scene or a dict of the scene file's parts")
    for key, value in kwargs.items():
        if key in _DEFAULTS and isinstance(value, dict):
            data.setdefault(key, {}).update(value)
        elif key == "zones" and isinstance(value, str):
            data.setdefault("zones", {})["map"] = value
        elif key in _PART_OF and len(_PART_OF[key]) == 1:
            data.setdefault(_PART_OF[key][0], {})[key] = value
        elif key in _PART_OF:
            parts = " or ".join(f'{p}={{"{key}": ...}}' for p in _PART_OF[key])
            raise Error(f"keyword {key} is a key of more than one part of the scene: give {parts}")
        else:
            raise Error(f"unknown keyword {key}: the keywords are the scene file's keys "
                        f"(docs/scene.md) or its parts ({', '.join(_DEFAULTS)})")
    try:
        return _json.dumps(data, allow_nan=False)
    except (TypeError, ValueError) as e:
        raise Error(f"the scene holds a value JSON cannot carry: {e}") from None


def _heights(heights):
    """(float32 C-order array with NaN for no-data) for any real numeric 2-D input."""
    mask = _np.ma.getmaskarray(heights) if _np.ma.isMaskedArray(heights) else None
    array = _np.ma.getdata(heights) if mask is not None else _np.asarray(heights)
    if array.dtype.kind not in "biuf":
        raise Error(f"heights must be a real numeric array, got dtype {array.dtype}")
    if array.ndim != 2:
        raise Error(f"heights must be a 2-D array (rows, columns), got shape {array.shape}")
    out = _np.ascontiguousarray(array, dtype=_np.float32)
    if mask is not None and mask.any():
        out = out.copy()
        out[mask] = _np.nan
    return out


def _spacing(spacing):
    if spacing is None:
        return 1.0, 1.0
    if _np.isscalar(spacing):
        return float(spacing), float(spacing)
    values = tuple(float(v) for v in spacing)
    if len(values) != 2:
        raise Error(f"spacing must be one number or (x, z), got {spacing!r}")
    return values


class Scene:
    """A render job as a scene file describes it (docs/scene.md)."""

    def __init__(self, data=None, **kwargs):
        self._text = _sierra.scene_text(_scene_json(data, kwargs))

    @classmethod
    def from_json(cls, text):
        scene = cls.__new__(cls)
        scene._text = _sierra.scene_text(text)
        return scene

    def to_dict(self):
        return _json.loads(self._text)

    def to_json(self):
        return self._text

    def __eq__(self, other):
        return isinstance(other, Scene) and self._text == other._text

    def __repr__(self):
        return f"sierra.Scene({self.to_dict()!r})"


class Renderer:
    """Frames on one EGL context: the device the programs choose (SIERRA_EGL_DEVICE picks one).

    Any Python thread may use a renderer, one call at a time; the GIL is released
    while it draws.
    """

    def __init__(self):
        self._core = _sierra._Renderer()

    @property
    def gl_renderer(self):
        return self._core.gl_renderer

    def render(self, heights=None, *, scene=None, spacing=None, output="rgba", frame=0,
               **kwargs):
        """Frame `frame` of the scene, for `heights` or the scene's own terrain.

        output="rgba": (height, width, 4) uint8, top row first; "depth": (height, width)
        float32 linear eye-space depth in world units, NaN where no terrain.
        """
        text = _scene_json(scene, kwargs)
        grid = None if heights is None else _heights(heights)
        sx, sz = _spacing(spacing)
        return self._core.render(text, grid, sx, sz, output, int(frame))


class _Maps:
    """2-D maps of a heightfield, one float32 value per sample, NaN at no-data (no GL).

    Row 0 is north, columns run west to east; spacing is (x, z) in world units.
    The fields and their conventions are those of `sierra-gen map` (docs/maps.md).
    """

    @staticmethod
    def _dem(name, heights, spacing, compute_edges=True, azimuth=315.0, altitude=45.0,
             z_factor=1.0):
        sx, sz = _spacing(spacing)
        return _sierra.dem_field(_heights(heights), sx, sz, name, bool(compute_edges),
                                 float(azimuth), float(altitude), float(z_factor))

    def hillshade(self, heights, spacing=None, azimuth=315.0, altitude=45.0, z_factor=1.0,
                  compute_edges=True):
        """1..255 as gdaldem's hillshade (lit from `azimuth`, degrees clockwise from north,
        at `altitude` degrees)."""
        return self._dem("hillshade", heights, spacing, compute_edges, azimuth, altitude,
                         z_factor)

    def slope(self, heights, spacing=None, compute_edges=True):
        """Degrees, 0 = flat."""
        return self._dem("slope", heights, spacing, compute_edges)

    def aspect(self, heights, spacing=None, compute_edges=True):
        """Compass degrees the slope faces (0 = north, 90 = east), NaN where flat."""
        return self._dem("aspect", heights, spacing, compute_edges)

    def field(self, name, heights, spacing=None, compute_edges=True):
        """Any scalar map by its `sierra-gen map --scheme` name: tri, tpi, roughness,
        curvature-profile, curvature-plan, ...; shadow, sky-view, sky-light, openness-positive
        and openness-negative take the keywords of `relief`."""
        if name in ("shadow", "sky-view", "sky-light", "openness-positive", "openness-negative"):
            return self.relief(name, heights, spacing)
        return self._dem(name, heights, spacing, compute_edges)

    @staticmethod
    def relief(name, heights, spacing=None, directions=16, radius=0.0, sun_azimuth=315.0,
               sun_altitude=45.0, sun_size=0.53):
        """A relief lighting field (docs/relief.md): "shadow" (the share of the sun's disc
        seen, 0..1), "sky-view", "sky-light", "openness-positive", "openness-negative"."""
        sx, sz = _spacing(spacing)
        return _sierra.relief_field(_heights(heights), sx, sz, name, int(directions),
                                    float(radius), float(sun_azimuth), float(sun_altitude),
                                    float(sun_size))


maps = _Maps()


def read_png(path):
    """A PNG as (height, width, 4) uint8."""
    return _sierra.read_png(str(path))
