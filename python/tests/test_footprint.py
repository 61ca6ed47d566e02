"""Tests of the footprint Python module: lookups against values known exactly, errors as
exceptions with the library's messages, the renderer and the metrics."""
import math

import numpy as np
import pytest

import footprint


@pytest.fixture
def texture(tmp_path):
    """A 64 × 32 RGB float texture with random texels, written as EXR."""
    rng = np.random.default_rng(3)
    pixels = rng.random((32, 64, 3), dtype=np.float32)
    path = str(tmp_path / "texture.exr")
    footprint.save_image(path, pixels)
    return path, pixels


def test_version():
    assert footprint.version().count(".") == 2


def test_point_lookups_at_texel_centres_are_the_texels(texture):
    path, pixels = texture
    ts = footprint.TextureSystem(max_memory_mb=16)
    ys, xs = np.mgrid[0:32, 0:64]
    s = ((xs + 0.5) / 64).ravel().astype(np.float32)
    t = ((ys + 0.5) / 32).ravel().astype(np.float32)
    for name in ("bilinear", "trilinear", "fa", "ewa"):
        out = ts.texture(path, s, t, 0, 0, 0, 0, filter=name)  # scalars broadcast
        assert out.shape == (64 * 32, 3) and out.dtype == np.float32
        np.testing.assert_allclose(out, pixels.reshape(-1, 3), atol=1e-6, err_msg=name)
    assert ts.channels(path) == 3
    assert ts.stats()["files"] == 1


def test_empty_arrays_make_no_lookups(texture):
    path, _ = texture
    ts = footprint.TextureSystem()
    empty = np.zeros(0, dtype=np.float32)
    assert ts.texture(path, empty, empty, 0, 0, 0, 0).shape == (0, 3)
    assert ts.texture(path, empty, [0.5], 0.01, 0, 0, 0.01).shape == (0, 3)  # one value broadcasts
    assert ts.environment(path, np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 3))).shape == (0, 3)
    with pytest.raises(ValueError, match="lengths"):
        ts.texture(path, empty, [0.5, 0.6], 0, 0, 0, 0)


def test_a_footprint_over_the_whole_texture_is_its_mean(texture):
    path, pixels = texture
    ts = footprint.TextureSystem()
    out = ts.texture(path, [0.5], [0.5], [1.0], [0.0], [0.0], [1.0], filter="trilinear")
    # The 1 × 1 level: the mean of a box pyramid's level 0 (64 × 32 → … → 1 × 1).
    np.testing.assert_allclose(out[0], pixels.reshape(-1, 3).mean(axis=0), atol=1e-5)


def test_a_constant_environment_is_constant_in_every_direction(tmp_path):
    path = str(tmp_path / "sky.exr")
    footprint.save_image(path, np.full((32, 64, 3), [0.25, 0.5, 2.0], dtype=np.float32))
    ts = footprint.TextureSystem()
    rng = np.random.default_rng(5)
    r = rng.normal(size=(100, 3)).astype(np.float32)
    out = ts.environment(path, r, 0.01 * np.ones((100, 3)), 0.02 * np.ones((100, 3)))
    np.testing.assert_allclose(out, np.tile([0.25, 0.5, 2.0], (100, 1)), rtol=1e-5)


def test_errors_are_exceptions_naming_the_file_or_value(tmp_path, texture):
    ts = footprint.TextureSystem()
    missing = str(tmp_path / "missing.png")
    with pytest.raises(RuntimeError, match="missing.png"):
        ts.texture(missing, [0.5], [0.5], [0.01], [0], [0], [0.01])
    with pytest.raises(ValueError, match="lengths"):
        ts.texture(texture[0], [0.5, 0.6], [0.5, 0.6, 0.7], 0, 0, 0, 0)
    with pytest.raises(ValueError, match="bicubic"):
        ts.texture(texture[0], [0.5], [0.5], 0, 0, 0, 0, filter="bicubic")
    with pytest.raises(ValueError, match=r"max_memory_mb must be at least 1 \(got 0\)"):
        footprint.TextureSystem(max_memory_mb=0)
    with pytest.raises(ValueError, match=r"max_memory_mb must be at least 1 \(got -5\)"):
        footprint.TextureSystem(max_memory_mb=-5)
    with pytest.raises(RuntimeError, match="unknown scene"):
        footprint.render("no-such-scene")


def test_render_checks_its_arguments_as_the_command_line_does():
    # ValueError, with the command line's ranges and messages in Python's argument names.
    with pytest.raises(ValueError, match=r"^width 8 is out of range \(16 to 16384\)$"):
        footprint.render("water", width=8)
    with pytest.raises(ValueError, match=r"^threads -1 is out of range \(0 to 1024; 0: all cores\)$"):
        footprint.render("water", width=32, threads=-1)
    with pytest.raises(ValueError, match=r"^spp 0 is out of range \(1 to 65536\)$"):
        footprint.render("water", width=32, spp=0)
    with pytest.raises(ValueError, match=r"^filter: unknown filter 'fa_rough' \(did you mean 'fa-rough'\?\)"):
        footprint.render("water", width=32, filter="fa_rough")


def test_render_and_metrics():
    image = footprint.render("water", filter="fa-rough", width=48)
    assert image.shape == (27, 48, 3) and image.dtype == np.float32
    assert np.isfinite(image).all() and image.max() > 0
    same = footprint.metrics(image, image)
    assert same["rmse"] == 0 and same["ssim"] == pytest.approx(1.0) and same["flip"] == 0
    other = footprint.metrics(image, image * 0.5)
    assert other["rmse"] == pytest.approx(math.sqrt(np.mean((image * 0.5) ** 2)), rel=1e-4)
    assert 0 < other["flip"] <= 1


def test_render_reads_its_maps_through_a_given_texture_system(tmp_path, texture):
    scene = tmp_path / "plane.json"
    scene.write_text(
        '{"image": {"width": 40, "height": 24},'
        ' "camera": {"position": [0, 1, 3], "look_at": [0, 0, 0], "fov_y_deg": 40},'
        ' "lights": [{"type": "directional", "direction": [0, -1, -0.5]}],'
        ' "objects": [{"shape": "plane", "size": [4, 4],'
        '              "material": {"base_color": "%s"}}]}' % texture[0])
    ts = footprint.TextureSystem(max_memory_mb=8)
    shared = footprint.render(str(scene), textures=ts)
    assert ts.stats()["files"] == 1  # the scene's texture, opened by the given system
    np.testing.assert_array_equal(shared, footprint.render(str(scene)))
