"""The Python module against the programs: same pixels, arrays out, clear errors, threads.

Run by CTest (python.module) with PYTHONPATH at the build tree's python/ and
SIERRA_RENDER naming the sierra-render program.
"""

import json
import os
import subprocess
import threading

import numpy as np
import pytest

import sierra

SMALL = dict(width=160, height=90, msaa=0)


def rough(rows=97, columns=129, seed=3):
    """A smooth random surface (sums of waves), float64, rows x columns."""
    rng = np.random.default_rng(seed)
    z, x = np.mgrid[0:rows, 0:columns].astype(np.float64)
    h = np.zeros((rows, columns))
    for _ in range(12):
        k = rng.uniform(0.02, 0.25, 2)
        h += rng.uniform(2, 10) * np.sin(k[0] * x + k[1] * z + rng.uniform(0, 6.3))
    return h


@pytest.fixture(scope="module")
def renderer():
    return sierra.Renderer()


def test_frame_equals_sierra_render(renderer, tmp_path):
    heights = rough().astype(np.float32)
    np.save(tmp_path / "dem.npy", heights)
    img = renderer.render(heights, spacing=(1, 1), azimuth=200, elevation=30, **SMALL)
    assert img.shape == (90, 160, 4) and img.dtype == np.uint8
    subprocess.run([os.environ["SIERRA_RENDER"], "--heightmap", str(tmp_path / "dem.npy"),
                    "--size", "160x90", "--msaa", "0", "--azimuth", "200", "--elevation", "30",
                    "--no-debug", "--out", str(tmp_path / "frame.png")], check=True,
                   capture_output=True)
    expected = sierra.read_png(tmp_path / "frame.png")
    assert np.array_equal(img, expected)
    # Terrain fills the middle of the frame: not a frame of sky alone.
    sky = img[0, 0, :3]
    terrain = np.any(img[:, :, :3] != sky, axis=2)
    assert 0.2 < terrain.mean() < 0.95


def test_dtypes_orders_and_masks_give_the_same_frame(renderer):
    heights = np.round(rough()).astype(np.float32)
    base = renderer.render(heights, **SMALL)
    assert np.array_equal(base, renderer.render(heights.astype(np.int16), **SMALL))
    assert np.array_equal(base, renderer.render(np.asfortranarray(heights), **SMALL))
    holes = np.ma.masked_array(heights, mask=np.zeros_like(heights, dtype=bool))
    holes.mask[40:50, 60:70] = True
    masked = renderer.render(holes, **SMALL)
    nan = heights.copy()
    nan[40:50, 60:70] = np.nan
    assert np.array_equal(masked, renderer.render(nan, **SMALL))
    assert not np.array_equal(masked, base)  # the hole is not drawn


def test_depth_is_an_array_of_world_distances(renderer):
    heights = rough()
    depth = renderer.render(heights, spacing=(30, 30), output="depth", **SMALL)
    assert depth.shape == (90, 160) and depth.dtype == np.float32
    terrain = np.isfinite(depth)
    assert 0.2 < terrain.mean() < 0.95
    assert np.isnan(depth[0, 0])  # the sky
    # The terrain is 128 x 96 samples of 30 m: every depth lies within a few extents.
    extent = 128 * 30
    assert np.all(depth[terrain] > 0) and np.all(depth[terrain] < 4 * extent)


def test_hillshade_map(renderer):
    heights = rough()
    hs = sierra.maps.hillshade(heights, spacing=(30, 30))
    assert hs.shape == heights.shape and hs.dtype == np.float32
    assert 0 <= np.nanmin(hs) and np.nanmax(hs) <= 255 and np.nanstd(hs) > 1
    flat = sierra.maps.hillshade(np.zeros((20, 30)), altitude=45)
    assert np.allclose(flat, 1 + 254 * np.sin(np.radians(45)), atol=1e-3)  # gdaldem's scale
    holes = heights.copy()
    holes[5, 7] = np.nan
    assert np.isnan(sierra.maps.hillshade(holes)[5, 7])


def test_slope_and_relief_fields():
    # A plane rising 1 in 2 to the east: slope atan(0.5), facing west.
    plane = np.tile(np.arange(40, dtype=np.float64) * 0.5, (30, 1))
    inner = (slice(1, -1), slice(1, -1))  # the border is extrapolated as gdaldem does
    assert np.allclose(sierra.maps.slope(plane)[inner], np.degrees(np.arctan(0.5)), atol=1e-4)
    assert np.allclose(sierra.maps.aspect(plane)[inner], 270.0, atol=1e-4)
    # Open ground sees the whole sky and the whole sun.
    flat = np.zeros((33, 33))
    assert np.allclose(sierra.maps.relief("sky-view", flat), 1.0)
    assert np.allclose(sierra.maps.relief("shadow", flat, sun_altitude=30), 1.0)
    # A wall to the west shades the ground east of it from a low western sun.
    wall = np.zeros((33, 33))
    wall[:, :4] = 10.0
    # 10 high at a 30-degree sun: a shadow 17.3 samples long past the wall's edge at 3.
    shadow = sierra.maps.relief("shadow", wall, sun_azimuth=270, sun_altitude=30)
    assert shadow[16, 6] == 0.0 and shadow[16, 19] == 0.0 and shadow[16, 23] == 1.0
    with pytest.raises(sierra.Error, match="unknown"):
        sierra.maps.field("glow", flat)


def test_scene_round_trip_and_render_from_scene(renderer):
    scene = sierra.Scene(camera={"azimuth": 120.0}, output={"width": 160, "height": 90,
                                                            "msaa": 0})
    again = sierra.Scene.from_json(scene.to_json())
    assert again == scene and again.to_dict()["camera"]["azimuth"] == 120.0
    assert json.loads(scene.to_json())["terrain"]["generate"] == 1025
    heights = rough()
    assert np.array_equal(renderer.render(heights, scene=scene),
                          renderer.render(heights, azimuth=120, **SMALL))
    # The scene's own terrain when no heights are given: a generated grid.
    generated = renderer.render(scene=scene, generate=65)
    assert generated.shape == (90, 160, 4)


@pytest.mark.parametrize("bad, message", [
    (dict(heights=np.zeros(10)), "2-D"),
    (dict(heights=np.zeros((10, 10), dtype=np.complex64)), "real numeric"),
    (dict(heights=np.zeros((1, 1))), "2x2"),
    (dict(heights=np.zeros((10, 10)), colour="red"), "unknown keyword colour"),
    (dict(heights=np.zeros((10, 10)), tau=-1), "tau"),
    (dict(heights=np.zeros((10, 10)), fov="wide"), "camera.fov"),
    (dict(heights=np.zeros((10, 10)), output="normals"), "output must be"),
    (dict(heights=np.zeros((10, 10)), spacing=(1, 2, 3)), "spacing"),
    (dict(heights=np.zeros((10, 10)), snow_line=3), "more than one part"),
    (dict(heights=np.full((10, 10), np.nan)), "no finite sample"),
])
def test_bad_input_raises_sierra_error(renderer, bad, message):
    heights = bad.pop("heights")
    with pytest.raises(sierra.Error, match=message):
        renderer.render(heights, **SMALL, **bad)


def test_bad_scene_json_raises_sierra_error():
    with pytest.raises(sierra.Error, match="JSON"):
        sierra.Scene.from_json("{not json")
    with pytest.raises(sierra.Error, match="camera"):
        sierra.Scene.from_json('{"camera": {"zoom": 2}}')


def test_a_second_thread_renders_the_same_frame(renderer):
    heights = rough()
    here = renderer.render(heights, **SMALL)
    result = {}

    def work():
        try:
            result["image"] = renderer.render(heights, **SMALL)
        except Exception as e:  # reported below, in the test's thread
            result["error"] = e

    t = threading.Thread(target=work)
    t.start()
    t.join(120)
    assert "error" not in result, result.get("error")
    assert np.array_equal(result["image"], here)
    # And back on this thread afterwards.
    assert np.array_equal(renderer.render(heights, **SMALL), here)


def test_two_renderers_are_independent():
    heights = rough()
    a = sierra.Renderer()
    first = a.render(heights, **SMALL)
    b = sierra.Renderer()
    b.render(heights, width=64, height=36, msaa=0)
    del b  # its context goes; a's stays usable
    assert np.array_equal(a.render(heights, **SMALL), first)


def test_layers_are_keywords_too(renderer, tmp_path):
    # The scene's layers (docs/layers.md): labels and furniture change the
    # frame, a vector layer off the terrain is no error, a bad drape is one.
    heights = np.outer(np.linspace(0, 20, 65), np.ones(65)).astype(np.float32)
    plain = renderer.render(heights, width=160, height=90)
    marked = renderer.render(heights, width=160, height=90, scale_bar=True, title="T",
                             labels=[{"text": "Hut", "x": 32, "z": 32, "geographic": False}])
    assert marked.shape == plain.shape
    assert (marked != plain).any(axis=2).sum() > 100
    far = tmp_path / "far.geojson"
    far.write_text(json.dumps({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {},
         "geometry": {"type": "Point", "coordinates": [5000, 5000]}}]}))
    assert renderer.render(heights, width=160, height=90,
                           vectors=[{"file": str(far)}]).shape == plain.shape
    with pytest.raises(sierra.Error, match="missing.tif"):
        renderer.render(heights, width=160, height=90, drapes=[{"image": str(tmp_path / "missing.tif")}])
