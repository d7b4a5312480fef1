"""imagepro.Engine: a stream of frames with tracking."""
import numpy as np

import imagepro
from pose_check import assert_pose_near


def sequence(n):
    """A target gliding right and turning, 25 frames a second."""
    return [imagepro.Pose(10, 5 + 0.5 * i, 3 * i, -60 + 6 * i, 10, 850 + 4 * i) for i in range(n)]


def test_tracking_follows_a_moving_target():
    engine = imagepro.Engine(imagepro.Settings())
    whole = (0, 0, 640, 480)
    regions = []
    for i, truth in enumerate(sequence(20)):
        r = engine.process(imagepro.render(truth), timestamp_s=i / 25)
        assert r.ok, (i, r)
        assert r.index == i and r.timestamp_s == i / 25
        assert_pose_near(r.pose, truth)
        x, y, w, h = r.search_region
        det = r.detected_region
        # The searched region holds the target it found.
        assert x <= det[0] and y <= det[1] and det[0] + det[2] <= x + w and det[1] + det[3] <= y + h
        regions.append(r.search_region)
    assert regions[0] == whole
    tracked = regions[5:]
    assert all(w * h < 0.5 * 640 * 480 for _, _, w, h in tracked)  # a region around the target, not the frame
    assert len(set(tracked)) > 5  # that moves with it
    assert engine.frames == 20
    engine.reset_tracking()
    assert engine.process(imagepro.render(sequence(21)[20])).search_region == whole


def test_a_lost_frame_is_reported_and_the_stream_goes_on():
    engine = imagepro.Engine()
    statuses = []
    for i, truth in enumerate(sequence(12)):
        image = imagepro.render(truth)
        if i in (6, 7):
            image = np.full_like(image, 20)  # the target hidden
        statuses.append(engine.process(image).status)
    assert statuses[6] != "ok" and statuses[7] != "ok"
    assert statuses[:6] == ["ok"] * 6 and statuses[-2:] == ["ok"] * 2


def test_settings_change_from_the_next_frame():
    engine = imagepro.Engine()
    s = engine.settings
    s["pipeline.tracking.mode"] = "off"
    engine.settings = s
    assert engine.settings["pipeline.tracking.mode"] == "off"
    for truth in sequence(6):
        assert engine.process(imagepro.render(truth)).search_region == (0, 0, 640, 480)
