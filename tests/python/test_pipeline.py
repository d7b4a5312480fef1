"""detect, reconstruct and render on numpy images: a rendered pose comes back."""
import threading

import numpy as np
import pytest

import imagepro
from pose_check import assert_pose_near

POSES = [
    imagepro.Pose(0, 0, 0, 0, 0, 800),
    imagepro.Pose(25, -15, 30, 40, -30, 900),
    imagepro.Pose(-35, 20, -120, -60, 45, 1100),
    imagepro.Pose(10, 40, 75, 20, 10, 650),
]


def test_render_gives_the_cameras_frame():
    s = imagepro.Settings()
    image = imagepro.render(POSES[0], s)
    assert image.shape == (480, 640) and image.dtype == np.uint8
    assert image.min() < 40 and image.max() > 200  # the black card and the white disk
    s["cameras.virtual.width"], s["cameras.virtual.height"] = 320, 240
    assert imagepro.render(POSES[0], s).shape == (240, 320)
    pattern = imagepro.render(POSES[0], pattern=True)
    assert not np.array_equal(pattern, image)
    assert imagepro.target_in_view(POSES[0])
    assert not imagepro.target_in_view(imagepro.Pose(tx_mm=5000, tz_mm=800))


@pytest.mark.parametrize("truth", POSES, ids=repr)
def test_reconstruct_returns_the_rendered_pose(truth):
    r = imagepro.reconstruct(imagepro.render(truth))
    assert r.ok and r.status == "ok", r
    assert_pose_near(r.pose, truth)
    assert r.ellipse is not None and r.spots is not None
    # The self-check's measures of a clean frame, well inside its limits.
    assert 0 <= r.spot_error_px < 0.2 and 0 <= r.rim_error_px < 0.2, (r.spot_error_px, r.rim_error_px)
    assert r.target == 0  # the settings' one target
    r.raise_for_status()  # nothing to raise
    assert "Pose(" in repr(r)


def test_detect_finds_the_ellipse_and_spots_without_a_pose():
    truth = POSES[1]
    image = imagepro.render(truth)
    r = imagepro.detect(image)
    assert r.ok and r.pose is None and r.reached == "ellipse"
    assert r.spot_error_px is None and r.rim_error_px is None  # no pose was checked
    assert r.target is None  # no target told before the reconstruction
    rec = imagepro.reconstruct(image)
    # The same target: the detected ellipse lies around the reconstruction's spots.
    e = r.ellipse
    assert e.a >= e.b > 10
    for (u, v), (ru, rv) in zip(r.spots, rec.spots):
        assert abs(u - ru) < 1.5 and abs(v - rv) < 1.5
        assert np.hypot(u - e.cx, v - e.cy) < e.a
    assert len(r.targets) >= 1 and r.targets[0].bbox[2] > 0
    assert "Ellipse(" in repr(r)


def test_bgr_and_strided_arrays_read_as_the_grey_image():
    image = imagepro.render(POSES[2])
    grey = imagepro.reconstruct(image).pose
    bgr = np.dstack([image, image, image])
    assert imagepro.reconstruct(bgr).pose == grey
    assert imagepro.reconstruct(np.asfortranarray(image)).pose == grey
    assert imagepro.reconstruct(image[:, :, np.newaxis]).pose == grey
    image.flags.writeable = False
    assert imagepro.reconstruct(image).pose == grey


def test_settings_reach_the_pipeline():
    truth = POSES[0]
    s = imagepro.Settings()
    s["target.radius_mm"] = 40.0  # a smaller target, rendered and measured as such
    s["target.spot_offset_mm"] = 20.0
    s["target.spot_radius_mm"] = 5.0
    r = imagepro.reconstruct(imagepro.render(truth, s), s)
    assert r.ok, r
    assert_pose_near(r.pose, truth)
    # Measured with the default target's 50 mm radius the same image is 25 % farther away.
    wrong = imagepro.reconstruct(imagepro.render(truth, s))
    assert wrong.pose is None or wrong.pose.tz_mm == pytest.approx(truth.tz_mm * 50 / 40, rel=0.01)
    s["pipeline.level"] = "ellipse"
    assert imagepro.reconstruct(imagepro.render(truth, s), s).pose is None


def test_threads_share_the_module():
    images = [imagepro.render(p) for p in POSES]
    expected = [imagepro.reconstruct(i).pose for i in images]
    failures = []

    def work():
        for _ in range(5):
            for image, pose in zip(images, expected):
                if imagepro.reconstruct(image).pose != pose:
                    failures.append(pose)

    threads = [threading.Thread(target=work) for _ in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not failures


def test_an_ambiguous_pose_gives_both_candidates():
    # Far and nearly face-on, turned 6 deg about y: the rim's two circles fit the spots about
    # equally, and lie more than twice ambiguity_tolerance_deg (5 deg) apart.
    plain = imagepro.Settings()
    plain["virtual.backdrop"] = "plain"  # the thesis's flat grey: at 6 m the room's window sets the threshold
    r = imagepro.reconstruct(imagepro.render(imagepro.Pose(0, 6, 0, 0, 0, 6000), plain))
    assert r.status == "AmbiguousPose" and r.pose is None
    first, second = r.candidates
    assert abs(first.ry_deg + second.ry_deg) < 0.5 and abs(first.ry_deg) > 1  # mirrored about the line of sight
    assert first.tz_mm == pytest.approx(6000, rel=0.05)
    with pytest.raises(imagepro.AmbiguousPose):
        r.raise_for_status()


def test_close_candidates_give_the_pose_halfway():
    # Turned 3 deg: the two circles lie within twice ambiguity_tolerance_deg of each other, and the
    # pose halfway between them is given, with both as candidates.
    truth = imagepro.Pose(0, 3, 0, 0, 0, 6000)
    r = imagepro.reconstruct(imagepro.render(truth))
    assert r.status == "ok"
    first, second = r.candidates
    assert r.pose.rotation_error_deg(first) == pytest.approx(r.pose.rotation_error_deg(second), abs=1e-6)
    assert r.pose.rotation_error_deg(first) > 1
    assert r.pose.rotation_error_deg(truth) < 5
    settings = imagepro.Settings()
    settings["pipeline.reconstruction.ambiguity_tolerance_deg"] = 0.0
    assert imagepro.reconstruct(imagepro.render(truth), settings).status == "AmbiguousPose"


def test_pose_values():
    p = imagepro.Pose(1, 2, 3, 4, 5, 600)
    assert p.as_tuple() == (1, 2, 3, 4, 5, 600)
    assert p == imagepro.Pose(rx_deg=1, ry_deg=2, rz_deg=3, tx_mm=4, ty_mm=5, tz_mm=600)
    assert repr(p) == "Pose(rx_deg=1, ry_deg=2, rz_deg=3, tx_mm=4, ty_mm=5, tz_mm=600)"
    assert imagepro.Pose().tz_mm == 1000
    assert p.rotation_error_deg(p) == pytest.approx(0, abs=1e-6)
    assert imagepro.Pose(rz_deg=10).rotation_error_deg(imagepro.Pose(rz_deg=-20)) == pytest.approx(30)
