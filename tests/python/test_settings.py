"""imagepro.Settings: the settings file's keys, read, set and checked; load and save."""
import pytest

import imagepro


def test_defaults_read_by_key():
    s = imagepro.Settings()
    assert s == imagepro.Settings.defaults()
    assert s["cameras.virtual.width"] == 640
    assert s.get("cameras.virtual.principal_point_px[1]") == pytest.approx(239.5)
    assert s["pipeline.tracking.mode"] in imagepro.Settings.key_info("pipeline.tracking.mode")["choices"]
    assert isinstance(s["camera_source.controls"], dict)
    assert "cameras.virtual.width" in s and "cameras.virtual.nothing" not in s
    assert "the defaults" in repr(s)


def test_every_key_reads_and_sets_back_to_itself():
    s = imagepro.Settings()
    keys = imagepro.Settings.keys()
    assert len(keys) > 50 and keys[0] == "cameras.file.width"
    for key in keys:
        s[key] = s[key]
    assert s == imagepro.Settings()


def test_set_changes_the_value_and_the_json():
    s = imagepro.Settings()
    s["cameras.virtual.principal_point_px[0]"] = 321.25
    s.set("pipeline.tracking.mode", "off")
    s["camera_source.controls"] = {"exposure_absolute": 150}
    assert s["cameras.virtual.principal_point_px[0]"] == 321.25
    assert s["pipeline.tracking.mode"] == "off"
    assert s["camera_source.controls"] == {"exposure_absolute": 150}
    assert '"exposure_absolute": 150' in s.to_json()
    assert imagepro.Settings.from_json(s.to_json()) == s
    assert "3 keys changed" in repr(s)


def test_round_trip_through_a_file(tmp_path):
    s = imagepro.Settings()
    s["cameras.virtual.width"] = 800
    s["cameras.virtual.height"] = 600
    s["target.radius_mm"] = 40.0
    s["virtual.noise_sigma"] = 2.5
    s["pipeline.ellipse.method"] = "bennett"
    path = tmp_path / "settings.json"
    s.save(str(path))
    loaded = imagepro.Settings.load(str(path))
    assert loaded == s
    assert loaded["cameras.virtual.width"] == 800 and loaded["target.radius_mm"] == 40.0
    assert loaded["pipeline.ellipse.method"] == "bennett"


def test_values_the_file_refuses_raise_named_errors():
    s = imagepro.Settings()
    with pytest.raises(imagepro.InvalidSettings, match="cameras.virtual.width"):
        s["cameras.virtual.width"] = 0  # below the key's range
    with pytest.raises(imagepro.InvalidSettings, match="pipeline.tracking.mode"):
        s["pipeline.tracking.mode"] = "sideways"
    with pytest.raises(imagepro.InvalidSettings, match="cameras.virtual.width"):
        s["cameras.virtual.width"] = 640.5  # a whole number expected
    with pytest.raises(imagepro.InvalidSettings, match="unknown key"):
        s["cameras.virtual.colour"] = 1
    with pytest.raises(imagepro.InvalidSettings):
        s["target.radius_mm"] = [1, 2]
    with pytest.raises(imagepro.InvalidSettings):
        s["target.radius_mm"] = float("inf")
    with pytest.raises(imagepro.InvalidSettings):
        s["cameras.virtual.width"] = 2**80
    assert s == imagepro.Settings()  # a refused value changes nothing
    info = imagepro.Settings.key_info("cameras.virtual.width")
    assert info["type"] == "whole number" and info["min"] == 1


def test_file_errors_raise_named_errors(tmp_path):
    with pytest.raises(imagepro.FileNotFound):
        imagepro.Settings.load(str(tmp_path / "missing.json"))
    bad = tmp_path / "bad.json"
    bad.write_text('{"camera": {"width": "wide"}}')  # an older file's one camera
    with pytest.raises(imagepro.InvalidSettings, match="camera.width"):
        imagepro.Settings.load(str(bad))
    with pytest.raises(imagepro.FileNotWritable):
        imagepro.Settings().save(str(tmp_path / "no" / "such" / "folder" / "s.json"))
    with pytest.raises(imagepro.InvalidSettings):
        imagepro.Settings.from_json("[1, 2]")


def test_a_camera_per_source_and_the_source_in_use(tmp_path):
    s = imagepro.Settings()
    assert s.source == "virtual"
    s["cameras.file.image_plane_distance_mm"] = 12.0
    s["cameras.camera.width"], s["cameras.camera.height"] = 768, 576
    path = tmp_path / "cameras.json"
    s.save(str(path))
    loaded = imagepro.Settings.load(str(path))
    assert loaded["cameras.file.image_plane_distance_mm"] == 12.0
    assert loaded["cameras.camera.width"] == 768
    assert loaded["cameras.virtual.image_plane_distance_mm"] == 8.0
    s.source = "file"
    assert s.source == "file"
    with pytest.raises(imagepro.InvalidSettings, match="source"):
        s.source = "tv"
    old = tmp_path / "old.json"
    old.write_text('{"camera": {"image_plane_distance_mm": 9.5}}')
    loaded = imagepro.Settings.load(str(old))
    assert [loaded[f"cameras.{k}.image_plane_distance_mm"] for k in ("file", "camera", "virtual")] == [9.5] * 3


def test_a_set_of_targets_is_set_and_read_as_a_list():
    s = imagepro.Settings()
    assert s["targets"] == [] and "targets" in s and "frames.measured_targets" in s
    pair = [
        {"id": 1, "name": "arm", "radius_mm": 50.0, "spot_radius_mm": 6.0, "spot_offset_mm": 20.0},
        {"id": 2, "radius_mm": 50.0, "spot_radius_mm": 6.0, "spot_offset_mm": 30.0},
    ]
    s["targets"] = pair
    s["frames.measured_targets"] = (1, 2)
    assert [t["id"] for t in s["targets"]] == [1, 2]
    assert s["targets"][0]["name"] == "arm" and s["targets"][1]["spot_offset_mm"] == 30.0
    assert s["frames.measured_targets"] == [1, 2] and s["frames.measured_targets[1]"] == 2
    assert imagepro.Settings.from_json(s.to_json()) == s
    # Refused as the settings file refuses them, naming what is wrong; nothing changes.
    before = imagepro.Settings.from_json(s.to_json())
    with pytest.raises(imagepro.InvalidSettings, match="id"):
        s["targets"] = [pair[0], dict(pair[1], id=1)]
    with pytest.raises(imagepro.InvalidSettings, match="a list is wanted"):
        s["targets"] = pair[0]
    with pytest.raises(imagepro.InvalidSettings, match="measured_targets"):
        s["frames.measured_targets"] = [1, 7]
    assert s == before
    s["frames.measured_targets"] = [-1, -1]
    s["targets"] = []
    assert s["targets"] == [] and s == imagepro.Settings()
