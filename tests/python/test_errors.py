"""The exceptions: one class per failure status under imagepro.Error; bad images raise."""
import numpy as np
import pytest

import imagepro


def test_one_class_per_failure_status():
    for name in ("NoTarget", "SpotsNotFound", "AmbiguousPose", "FileNotFound", "InvalidSettings", "EmptyFrame"):
        cls = getattr(imagepro, name)
        assert issubclass(cls, imagepro.Error) and issubclass(cls, Exception)
        assert cls.status == name
        assert cls.__doc__  # the status's sentence
    assert not hasattr(imagepro, "ok")


@pytest.mark.parametrize(
    "image",
    [
        np.zeros((480, 640), dtype=np.float32),  # not uint8
        np.zeros((480, 640, 4), dtype=np.uint8),  # four channels
        np.zeros((4, 480, 640, 3), dtype=np.uint8),  # a stack
        np.zeros(640, dtype=np.uint8),  # one row
        np.zeros((0, 640), dtype=np.uint8),  # no pixels
        [[0, 255], [255, 0]],  # not an array
        None,
    ],
)
def test_a_bad_image_raises_empty_frame(image):
    for call in (imagepro.detect, imagepro.reconstruct, imagepro.Engine().process):
        with pytest.raises(imagepro.EmptyFrame):
            call(image)


def test_a_huge_image_raises_image_too_large():
    huge = np.lib.stride_tricks.as_strided(np.zeros(1, dtype=np.uint8), shape=(20000, 20000), strides=(0, 0))
    with pytest.raises(imagepro.ImageTooLarge):
        imagepro.detect(huge)


def test_a_frame_without_target_is_reported_not_raised():
    blank = np.full((480, 640), 128, dtype=np.uint8)
    r = imagepro.reconstruct(blank)
    assert not r.ok and r.status == "ThresholdUndefined" and r.pose is None
    with pytest.raises(imagepro.ThresholdUndefined):
        r.raise_for_status()
    with pytest.raises(imagepro.Error):
        r.raise_for_status()


def test_a_frame_of_another_size_reports_frame_size_mismatch():
    image = imagepro.render(imagepro.Pose(tz_mm=800))
    r = imagepro.reconstruct(image[:, :600].copy())
    assert r.status == "FrameSizeMismatch"
