"""The tests' measure of a reconstructed pose against its truth."""


def assert_pose_near(pose, truth):
    """Rendered frames without noise: within a quarter of a degree and a thousandth of the depth."""
    assert pose is not None, truth
    assert pose.rotation_error_deg(truth) < 0.25, (pose, truth)
    for name in ("tx_mm", "ty_mm", "tz_mm"):
        assert abs(getattr(pose, name) - getattr(truth, name)) < 1e-3 * truth.tz_mm, (name, pose, truth)
