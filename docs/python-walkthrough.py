# %% [markdown]
# # Python: the `imagepro` module
#
# The pipeline from Python, on numpy arrays: the settings by key, `detect` and
# `reconstruct` on one image, an `Engine` that runs frame after frame with tracking,
# and `render` for virtual frames. It runs the same stage chain, engine and renderer as
# `imagepro-cli` and the application, with Python's interpreter lock released while a
# frame is processed, so other Python threads go on meanwhile.
#
# ## Building and importing it
#
# `tools/setup.sh build` installs `pybind11-dev`, `python3-dev`, `python3-numpy` and
# `python3-pytest` and builds the module into `build/python/` (CMake option
# `IMAGEPRO_PYTHON`, on when pybind11 and a Python 3 with numpy are found; the first
# `python3` on the `PATH` that has numpy is the one built for, `-DPython_EXECUTABLE=...`
# chooses another). Then:
#
# ```sh
# PYTHONPATH=build/python /usr/bin/python3 -c "import imagepro; print(imagepro.__version__)"
# ```
#
# The Debian package (`tools/setup.sh package`, README) holds it in
# `/usr/lib/python3/dist-packages`, so `apt install ./build/package/imagepro_*.deb` gives
# `import imagepro` for Debian's `python3`; the package is built with the module when the
# module is built for `/usr/bin/python3`. Without the package,
# `cmake --install build --component python` puts it where Debian's `python3` finds it:
# `/usr/lib/python3/dist-packages` under the prefix `/usr`,
# `lib/python3.X/dist-packages` under another (`/usr/local`). ctest runs its tests,
# `tests/python/` (pytest).
#
# ## What it has
#
# | name | what it does |
# | --- | --- |
# | `Settings()`, `Settings.load(path)`, `s.save(path)` | the settings file (`docs/conventions.md`): defaults, read, written atomically |
# | `s["pipeline.tracking.mode"]`, `s.get(key)`, `s.set(key, value)` | a value by its key; `Settings.keys()` lists them, `Settings.key_info(key)` gives a key's type and range or choices |
# | `detect(image, settings=None)` | the ellipse stage on one image (`imagepro-cli detect`): a `Result` with the ellipse and the spots |
# | `reconstruct(image, settings=None)` | the whole pipeline on one image: the ellipse, the spots and the pose |
# | `Engine(settings=None)`, `engine.process(image, timestamp_s=None)` | a stream, frame after frame, with tracking; `engine.settings`, `engine.reset_tracking()` |
# | `render(pose, settings=None, pattern=False, frame_seed=0)` | the Virtual source's frame at a pose, HxW uint8; `target_in_view(pose, settings)` |
# | `Pose(rx_deg, ry_deg, rz_deg, tx_mm, ty_mm, tz_mm)` | a pose (`docs/conventions.md`); `p.rotation_error_deg(q)`, `p.as_tuple()` |
#
# An image is a numpy `uint8` array, HxW grey or HxWx3 BGR (OpenCV's order, converted to
# grey). It is reconstructed with the camera model of the settings' source in use,
# `settings.source` ("file", "camera" or "virtual", the default; not saved in the file),
# each source having its own (`cameras.virtual.width`, `cameras.file.distortion.k1` ...),
# and its size must be that camera's, as in the application. A `Result` has `status`
# ("ok" or the name of the first stage's failure),
# `message`, `ok`, `ellipse`, `spots` (the centre spot's and the offset spot's `(u, v)` in
# image pixels as seen), `pose`, `candidates` (the two poses of an `AmbiguousPose`),
# `targets`, `index`, `timestamp_s`, `search_region`, `detected_region`, `threshold`,
# `times_us` (each stage's time), `rim_seen` (the share of the rim seen, or `None`),
# `target` (the id of the settings' target it is, 0 for the one target of `target`, or
# `None` when no target was told), `spot_error_px` and `rim_error_px` (the pose's self-check in pixels, or `None` when no pose
# was checked: `docs/reconstruction.md`) and `lens_inverse` (which inverse of the lens
# corrected the features, or `None` before the reconstruction stage): the last six are the
# frame record's, as every output names them (`docs/conventions.md`), with the poses in
# the chosen frames (`world_Rx_deg` ... and `ref_Rx_deg` ...) and the pair's
# `pair_distance_mm` and `pair_angle_deg` (settings `frames`), each `None` when not chosen.
#
# With a set of targets (`targets` in the settings) a frame's fields are its shown target's
# and `result.targets` lists every target found, each a `Target` with its `ellipse`,
# `bbox`, `target` (its id, or `None`), `status` (its own: "ok", "UnknownTarget",
# "DuplicateTarget" ...), `pose` (`None` unless ok), `pose_in_reference` and
# `pose_in_world`:
#
# ```python
# for t in result.targets:
#     if t.status == "ok":
#         print(t.target, t.pose.tz_mm)
# ```
#
# A list is read and set whole under its own key: `s["targets"]` is the set of targets, a
# list of dicts with the settings file's fields (`[]` for none), and an array such as
# `s["frames.measured_targets"] = [1, 2]` takes a list or tuple; the file's checks apply (two
# targets with one id, a pair naming no target) and raise `InvalidSettings` naming the key.
#
# ## Errors: what raises and what is reported
#
# Every status of the project has its exception class, named after it, under
# `imagepro.Error`: `imagepro.NoTarget`, `imagepro.FileNotFound`, `imagepro.InvalidSettings`,
# ... (each class's `status` is its name, its docstring the status's sentence). The rule:
#
# - **A call that cannot run raises**: an image that is not a uint8 HxW or HxWx3 array
#   (`EmptyFrame`), a larger one than a frame may hold (`ImageTooLarge`), a settings file
#   that is missing (`FileNotFound`), malformed (`InvalidSettings`) or cannot be written
#   (`FileNotWritable`), an unknown key or a value the settings file would refuse
#   (`InvalidSettings`, naming the key).
# - **A frame that runs reports**: a frame without a target, or whose pose cannot be
#   trusted, is not an exception, since a frame loop goes on past it. Its `Result.status`
#   says what happened (`NoTarget`, `SpotsNotFound`, `AmbiguousPose`, `FrameSizeMismatch`,
#   ...), as the CLI's rows do; `result.raise_for_status()` raises it where a failure
#   should stop the script.
#
# ## A walk-through
#
# This page is made by running `docs/python-walkthrough.py`, cell by cell, with what each
# cell prints below it (`tools/regenerate-docs.sh --only python`; the plot needs
# `python3-matplotlib`). Open the script as a notebook to run it yourself.
#
# The settings: the defaults here; `imagepro.Settings.load("my-settings.json")` reads a file.

# %%
import numpy as np

import imagepro

settings = imagepro.Settings()
print(settings["cameras.virtual.width"], "x", settings["cameras.virtual.height"], "pixels,",
      "target radius", settings["target.radius_mm"], "mm")
print(imagepro.Settings.key_info("pipeline.ellipse.method"))

# %% [markdown]
# Render the target at a pose through the Virtual source's camera (`cameras.virtual`, its
# lens distortion included), then reconstruct the pose from that image:

# %%
truth = imagepro.Pose(rx_deg=20, ry_deg=-30, rz_deg=45, tx_mm=30, ty_mm=-20, tz_mm=900)
image = imagepro.render(truth, settings)
print(image.shape, image.dtype)

print(imagepro.detect(image, settings))
result = imagepro.reconstruct(image, settings)
print(result)
print(result.ellipse)
print("spots:", np.round(result.spots, 2).tolist())
print("rotation error %.4f deg, position error %.4f mm" % (
    result.pose.rotation_error_deg(truth),
    np.linalg.norm(np.subtract(result.pose.as_tuple()[3:], truth.as_tuple()[3:]))))

# %% [markdown]
# A frame without the target is reported in its result; a bad image raises:

# %%
blank = np.full_like(image, 20)
lost = imagepro.reconstruct(blank, settings)
print(lost.status, "-", lost.message)
try:
    lost.raise_for_status()
except imagepro.Error as e:
    print("raise_for_status:", type(e).__name__)

try:
    imagepro.reconstruct(image.astype(np.float32), settings)
except imagepro.EmptyFrame as e:
    print("EmptyFrame:", e)

# %% [markdown]
# ## The error against the tilt
#
# The pose error as the target turns away from the camera, with the look of a real frame:
# noise of sigma 3 grey levels and a blur of 0.8 pixels (the settings' `virtual` section).
# At each tilt about Y, 12 frames with the target turned about its normal in 30 degree
# steps, 1 m away:

# %%
settings["virtual.noise_sigma"] = 3.0
settings["virtual.blur_sigma_px"] = 0.8

tilts = np.arange(0, 71, 5)
rotation_error = np.full((len(tilts), 12), np.nan)
position_error = np.full((len(tilts), 12), np.nan)
statuses = {}
for i, tilt in enumerate(tilts):
    for k in range(12):
        truth = imagepro.Pose(rx_deg=0, ry_deg=tilt, rz_deg=30 * k, tx_mm=0, ty_mm=0, tz_mm=1000)
        r = imagepro.reconstruct(imagepro.render(truth, settings, frame_seed=k), settings)
        statuses[r.status] = statuses.get(r.status, 0) + 1
        if r.ok:
            rotation_error[i, k] = r.pose.rotation_error_deg(truth)
            position_error[i, k] = np.linalg.norm(np.subtract(r.pose.as_tuple()[3:], truth.as_tuple()[3:]))

print("statuses:", statuses)
print("tilt  rotation error (deg)  position error (mm)")
print("deg   median     max        median   max")
for tilt, rot, pos in zip(tilts, rotation_error, position_error):
    print("%3d   %.3f      %.3f      %.2f     %.2f" % (tilt, np.nanmedian(rot), np.nanmax(rot),
                                                    np.nanmedian(pos), np.nanmax(pos)))

# %% [markdown]
# The plot, with matplotlib:

# %%
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

fig, (left, right) = plt.subplots(1, 2, figsize=(9, 3.4), constrained_layout=True)
for axes, error, unit in ((left, rotation_error, "deg"), (right, position_error, "mm")):
    axes.plot(tilts, np.nanmedian(error, axis=1), "o-", label="median")
    axes.plot(tilts, np.nanmax(error, axis=1), "s--", label="max")
    axes.set_xlabel("tilt about Y (deg)")
    axes.set_ylabel(f"error ({unit})")
    axes.grid(alpha=0.3)
left.set_title("orientation")
right.set_title("position")
left.legend()
fig.suptitle("Pose error of imagepro.reconstruct, rendered target 1 m away, noise 3, blur 0.8 px")
fig.savefig("docs/python-pose-error.png", dpi=100)

# %% [markdown]
# ![Pose error against the tilt](python-pose-error.png)
#
# Face-on (tilt 0) the orientation is least certain: the rim's image is then nearly a
# circle, and which way the target leans rests on the little eccentricity that noise
# leaves. Tilted, the ellipse says it plainly, and the error falls to a tenth of a degree.
#
# ## A stream with tracking
#
# An `Engine` keeps the tracking history from frame to frame: after the first few frames
# it searches only a region around where the target is expected (`search_region`). Here
# the target swings across the image at 25 frames a second:

# %%
engine = imagepro.Engine(settings)
searched, errors = [], []
for i in range(50):
    t = i / 25
    truth = imagepro.Pose(rx_deg=10, ry_deg=25 * np.sin(t * 2), rz_deg=0,
                          tx_mm=150 * np.sin(t * 3), ty_mm=20, tz_mm=900)
    r = engine.process(imagepro.render(truth, settings, frame_seed=i), timestamp_s=t)
    r.raise_for_status()  # every frame of this run has its pose
    x, y, w, h = r.search_region
    searched.append(w * h / (640 * 480))
    errors.append(r.pose.rotation_error_deg(truth))

print("frames", engine.frames, "- searched: first frame %.0f %%, then %.0f %% of the image on average"
      % (100 * searched[0], 100 * np.mean(searched[1:])))
print("rotation error: median %.3f deg, max %.3f deg" % (np.median(errors), np.max(errors)))
