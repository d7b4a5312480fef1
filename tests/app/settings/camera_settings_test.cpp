// The Settings dialog's Camera device page, the camera on the command line, and a
// camera that does not exist: named errors, no crash, the rest of the window goes on.
#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSlider>
#include <QSpinBox>
#include <QStatusBar>
#include <QTest>

#include <linux/videodev2.h>

#include "app/worker/camera_arguments.h"
#include "app/settings/camera_settings_page.h"
#include "app/panels/control_panel.h"
#include "app/main_window/main_window.h"
#include "app/settings/settings_dialog.h"
#include "app/panels/source_panel.h"
#include "app/worker/worker.h"
#include "app_test_classes.h"
#include "app_test_support.h"

namespace imagepro::app::test {

namespace {

const QString kMissing = QStringLiteral("/dev/video-imagepro-missing");
const QString kCameraNotFound = QStringLiteral("no camera device at that path");  // statusMessage(CameraNotFound)

CameraControl control(std::uint32_t id, const char* name, ControlType type, std::int64_t min, std::int64_t max,
                      std::int64_t step, std::int64_t def, std::int64_t value) {
  CameraControl c;
  c.id = id;
  c.name = name;
  c.key = controlKey(name);
  c.type = type;
  c.minimum = min;
  c.maximum = max;
  c.step = step;
  c.default_value = def;
  c.value = value;
  return c;
}

FrameSize discrete(int w, int h, std::vector<double> rates) {
  FrameSize s;
  s.width = s.min_width = w;
  s.height = s.min_height = h;
  for (double r : rates) s.rates.discrete.push_back({1, static_cast<std::uint32_t>(r)});
  return s;
}

// A hand-made USB camera: what queryDevice would read from one.
DeviceInfo handMadeCamera() {
  DeviceInfo info;
  info.path = "/dev/video-test";
  info.card = "Test Camera";
  info.driver = "uvcvideo";
  info.bus = "usb-0000:00:14.0-1";
  info.video_capture = true;
  info.streaming = true;
  FormatInfo yuyv;
  yuyv.fourcc = makeFourcc('Y', 'U', 'Y', 'V');
  yuyv.format = PixelFormat::Yuyv;
  yuyv.sizes = {discrete(640, 480, {30, 15}), discrete(320, 240, {30})};
  FormatInfo mjpg;
  mjpg.fourcc = makeFourcc('M', 'J', 'P', 'G');
  mjpg.format = PixelFormat::Mjpeg;
  mjpg.sizes = {discrete(1280, 720, {60, 30})};
  FormatInfo h264;  // not readable: its size is not offered
  h264.fourcc = makeFourcc('H', '2', '6', '4');
  h264.sizes = {discrete(1920, 1080, {30})};
  info.formats = {yuyv, mjpg, h264};
  info.controls = {control(1, "Brightness", ControlType::Integer, -64, 64, 1, 0, 5),
                   control(2, "Gain", ControlType::Integer, 0, 240, 16, 32, 48),
                   control(3, "Focus, Automatic Continuous", ControlType::Boolean, 0, 1, 1, 1, 1),
                   control(4, "Auto Exposure", ControlType::Menu, 0, 3, 1, 3, 3),
                   control(5, "Exposure Time, Absolute", ControlType::Integer, 3, 2047, 1, 250, 250),
                   control(6, "Pan, Reset", ControlType::Button, 0, 0, 0, 0, 0),
                   control(7, "Pixel Rate", ControlType::Integer64, 0, 5000000000LL, 1, 0, 12345678900LL / 10),
                   control(8, "Some Array", ControlType::Other, 0, 0, 0, 0, 0)};
  info.controls[3].menu = {{1, "Manual Mode"}, {3, "Aperture Priority Mode"}};
  info.controls[4].inactive = true;  // while the exposure is automatic
  info.controls[6].read_only = true;
  return info;
}

struct SetCall {
  std::string device, key;
  std::int64_t value;
};

// Devices as the test says, every control set recorded.
CameraDevices testDevices(std::vector<std::string> paths, DeviceInfo info, std::vector<SetCall>* calls) {
  CameraDevices d;
  d.list = [paths] { return paths; };
  d.query = [info](const std::string& path, DeviceInfo& out, std::string& error) {
    if (path != info.path) {
      error = path + ": " + std::string(statusMessage(Status::CameraNotFound)) + " (No such file or directory)";
      return Status::CameraNotFound;
    }
    out = info;
    return Status::Ok;
  };
  d.set = [calls](const std::string& device, const std::string& key, std::int64_t value) {
    calls->push_back({device, key, value});
    return std::string();
  };
  return d;
}

template <class W>
W* child(QWidget& parent, const QString& name) {
  return parent.findChild<W*>(name);
}

}  // namespace

void CameraSettingsTest::init() {
  window_ = std::make_unique<MainWindow>();
  window_->show();
}

void CameraSettingsTest::cleanup() { window_.reset(); }

void CameraSettingsTest::noCameraFoundAndTheRestWorks() {
  Settings model;
  std::vector<SetCall> calls;
  SettingsDialog dialog(model, nullptr, testDevices({}, DeviceInfo{}, &calls));
  auto* page = dialog.findChild<CameraSettingsPage*>();
  QVERIFY(page);
  QCOMPARE(page->statusText(), QStringLiteral("No camera found"));
  QCOMPARE(child<QComboBox>(*page, QStringLiteral("cameraDevice"))->currentText(), QStringLiteral("/dev/video0"));
  // The size and rate still say what the Camera source will ask for.
  auto* size = child<QComboBox>(*page, QStringLiteral("cameraSize"));
  QCOMPARE(size->count(), 1);
  QVERIFY(size->currentText().contains(QStringLiteral("640 x 480")));
  bool no_controls = false;
  for (QLabel* l : page->findChildren<QLabel*>()) no_controls = no_controls || l->text() == QStringLiteral("No controls");
  QVERIFY(no_controls);
  // Every other page works as before.
  dialog.findChild<QDoubleSpinBox*>(QStringLiteral("targetRadius"))->setValue(41.0);
  Settings out;
  dialog.applyTo(out);
  QCOMPARE(out.target.radius_mm, 41.0);
  QCOMPARE(out.camera_source.device, std::string("/dev/video0"));
  QVERIFY(calls.empty());
}

void CameraSettingsTest::deviceThatCannotBeOpenedShowsItsStatus() {
  Settings model;
  model.camera_source.controls = {{"gain", 32}};
  CameraSettingsPage page(model, CameraDevices::system());  // this machine's devices
  auto* device = child<QComboBox>(page, QStringLiteral("cameraDevice"));
  device->setEditText(kMissing);
  emit device->lineEdit()->editingFinished();
  QVERIFY2(page.statusText().contains(QStringLiteral("CameraNotFound")), qPrintable(page.statusText()));
  QVERIFY2(page.statusText().contains(kMissing + QStringLiteral(": ") + kCameraNotFound), qPrintable(page.statusText()));
  QCOMPARE(model.camera_source.device, kMissing.toStdString());
  QVERIFY(model.camera_source.controls.empty());  // they were the other device's
}

void CameraSettingsTest::controlWidgetsFollowTheDevice() {
  Settings model;
  std::vector<SetCall> calls;
  model.camera_source.device = "/dev/video-test";
  CameraSettingsPage page(model, testDevices({"/dev/video-other", "/dev/video-test"}, handMadeCamera(), &calls));
  QVERIFY2(page.statusText().startsWith(QStringLiteral("Test Camera (uvcvideo")), qPrintable(page.statusText()));
  QCOMPARE(child<QComboBox>(page, QStringLiteral("cameraDevice"))->count(), 2);

  // One widget per control type, with the device's range, step and current value.
  auto* brightness = child<QSpinBox>(page, QStringLiteral("control_brightness"));
  auto* brightness_slider = child<QSlider>(page, QStringLiteral("control_brightness_slider"));
  QVERIFY(brightness && brightness_slider);
  QCOMPARE(brightness->minimum(), -64);
  QCOMPARE(brightness->maximum(), 64);
  QCOMPARE(brightness->value(), 5);
  QCOMPARE(brightness_slider->value(), 5);
  QVERIFY(brightness->toolTip().contains(QStringLiteral("default 0")));
  auto* gain = child<QSpinBox>(page, QStringLiteral("control_gain"));
  QCOMPARE(gain->singleStep(), 16);
  QCOMPARE(gain->value(), 48);
  auto* focus = child<QCheckBox>(page, QStringLiteral("control_focus_automatic_continuous"));
  QVERIFY(focus && focus->isChecked());
  auto* exposure = child<QComboBox>(page, QStringLiteral("control_auto_exposure"));
  QVERIFY(exposure);
  QCOMPARE(exposure->count(), 2);
  QCOMPARE(exposure->currentText(), QStringLiteral("Aperture Priority Mode"));
  auto* exposure_time = child<QSpinBox>(page, QStringLiteral("control_exposure_time_absolute"));
  QVERIFY(exposure_time && !exposure_time->isEnabled());  // inactive while the exposure is automatic
  auto* pan_reset = child<QPushButton>(page, QStringLiteral("control_pan_reset"));
  QVERIFY(pan_reset && pan_reset->isEnabled());
  auto* pixel_rate = child<QLineEdit>(page, QStringLiteral("control_pixel_rate"));  // beyond a spin box's range
  QVERIFY(pixel_rate && !pixel_rate->isEnabled());                                   // read-only
  QCOMPARE(pixel_rate->text(), QStringLiteral("1234567890"));
  QVERIFY(!child<QWidget>(page, QStringLiteral("control_some_array")));
  QVERIFY(calls.empty());  // showing sets nothing

  // Each change sets that control on the chosen device and is stored; a button acts only.
  brightness->setValue(-20);
  brightness_slider->setValue(33);
  focus->click();
  exposure->setCurrentIndex(exposure->findText(QStringLiteral("Manual Mode")));
  gain->setValue(70);  // between two steps: the nearest step
  pan_reset->click();
  QCOMPARE(calls.size(), std::size_t{6});
  const std::vector<std::pair<std::string, std::int64_t>> expected{
      {"brightness", -20}, {"brightness", 33}, {"focus_automatic_continuous", 0}, {"auto_exposure", 1},
      {"gain", 64}, {"pan_reset", 1}};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    QCOMPARE(calls[i].device, std::string("/dev/video-test"));
    QCOMPARE(calls[i].key, expected[i].first);
    QCOMPARE(calls[i].value, expected[i].second);
  }
  QCOMPARE(brightness->value(), 33);
  const std::map<std::string, std::int64_t> stored{
      {"auto_exposure", 1}, {"brightness", 33}, {"focus_automatic_continuous", 0}, {"gain", 64}};
  QCOMPARE(model.camera_source.controls, stored);

  // Sizes the device can deliver (not the unreadable H.264's), rates at the chosen size.
  auto* size = child<QComboBox>(page, QStringLiteral("cameraSize"));
  QStringList sizes;
  for (int i = 0; i < size->count(); ++i) sizes << size->itemText(i);
  QCOMPARE(sizes, (QStringList{QStringLiteral("As the camera model (640 x 480)"), QStringLiteral("320 x 240"),
                               QStringLiteral("640 x 480"), QStringLiteral("1280 x 720")}));
  auto* rate = child<QComboBox>(page, QStringLiteral("cameraRate"));
  QCOMPARE(rate->currentData().toDouble(), 25.0);  // the default, not listed at 640 x 480
  QVERIFY(rate->currentText().contains(QStringLiteral("not listed")));
  size->setCurrentIndex(size->findText(QStringLiteral("1280 x 720")));
  QCOMPARE(model.camera_source.width, 1280);
  QCOMPARE(model.camera_source.height, 720);
  QVERIFY(child<QLabel>(page, QStringLiteral("cameraNote"))->text().contains(QStringLiteral("640 x 480")));
  QCOMPARE(rate->itemText(0), QStringLiteral("60 frames/s"));
  rate->setCurrentIndex(0);
  QCOMPARE(model.camera_source.frame_rate_hz, 60.0);
  size->setCurrentIndex(0);
  QCOMPARE(model.camera_source.width, 0);

  // Another device: its own controls, the stored ones dropped.
  auto* device = child<QComboBox>(page, QStringLiteral("cameraDevice"));
  device->setCurrentIndex(0);
  emit device->activated(0);
  QCOMPARE(model.camera_source.device, std::string("/dev/video-other"));
  QVERIFY(model.camera_source.controls.empty());
  QVERIFY(page.statusText().startsWith(QStringLiteral("CameraNotFound")));
  QVERIFY(!child<QSpinBox>(page, QStringLiteral("control_brightness")));
}

void CameraSettingsTest::missingCameraFromTheDialogIsNamedWhenStarted() {
  MainWindow& w = *window_;
  w.findChild<QPushButton*>(QStringLiteral("settingsDialog"))->click();
  auto* dialog = w.findChild<SettingsDialog*>();
  QVERIFY(dialog);
  auto* page = dialog->findChild<CameraSettingsPage*>();
  QVERIFY(page);
  auto* device = child<QComboBox>(*page, QStringLiteral("cameraDevice"));
  device->setEditText(kMissing);
  emit device->lineEdit()->editingFinished();
  QVERIFY2(page->statusText().contains(kCameraNotFound), qPrintable(page->statusText()));
  dialog->findChild<QDialogButtonBox*>()->button(QDialogButtonBox::Ok)->click();
  QVERIFY(waitForApplied(w, [](const Settings& s) { return s.camera_source.device == kMissing.toStdString(); }));
  w.selectSource(SourceKind::Camera);
  w.startSource();
  QTRY_VERIFY_WITH_TIMEOUT(w.lastError().contains(kMissing + QStringLiteral(": ") + kCameraNotFound), 5000);
  QVERIFY2(w.statusBar()->currentMessage().contains(kCameraNotFound), qPrintable(w.statusBar()->currentMessage()));
  QVERIFY(!w.worker()->isRunning());
  QCOMPARE(w.controlPanel()->sourcePanel()->button()->text(), QStringLiteral("Start"));
  // A control set on it is a named error too, and nothing else happens.
  w.worker()->setCameraControl(kMissing + QStringLiteral("2"), QStringLiteral("gain"), 10);
  QTRY_VERIFY_WITH_TIMEOUT(w.lastError().contains(kMissing + QStringLiteral("2")), 5000);
  // The window goes on with another source.
  w.selectSource(SourceKind::Virtual);
  w.startSource();
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.truth.has_value(); }));
  w.stopSource();
}

void CameraSettingsTest::commandLineChoosesTheCamera() {
  CameraSourceOptions o;
  o.controls = {{"gain", 32}};
  QString error;
  QVERIFY(applyCameraArguments(QStringLiteral("/dev/video0"), {}, {}, o, error));
  QCOMPARE(o.controls.size(), std::size_t{1});  // the same device keeps its controls
  QVERIFY(applyCameraArguments(kMissing, QStringLiteral("320x240"), QStringLiteral("30"), o, error));
  QCOMPARE(o.device, kMissing.toStdString());
  QCOMPARE(o.width, 320);
  QCOMPARE(o.height, 240);
  QCOMPARE(o.frame_rate_hz, 30.0);
  QVERIFY(o.controls.empty());
  const CameraSourceOptions before = o;
  QVERIFY(!applyCameraArguments(kMissing, QStringLiteral("320"), {}, o, error));
  QVERIFY(error.contains(QStringLiteral("--size")));
  QVERIFY(!applyCameraArguments(kMissing, {}, QStringLiteral("fast"), o, error));
  QVERIFY(error.contains(QStringLiteral("--fps")));
  QVERIFY(!applyCameraArguments(kMissing, {}, QStringLiteral("0"), o, error));
  QVERIFY(!applyCameraArguments(QStringLiteral(" "), {}, {}, o, error));
  QCOMPARE(o.device, before.device);
  QCOMPARE(o.width, before.width);

  // As imagepro --camera does it: over the settings, then started.
  MainWindow& w = *window_;
  Settings s = w.settings();
  QVERIFY(applyCameraArguments(kMissing, QStringLiteral("320x240"), QStringLiteral("30"), s.camera_source, error));
  w.setSettings(s);
  w.selectSource(SourceKind::Camera);
  w.startSource();
  QTRY_VERIFY_WITH_TIMEOUT(w.lastError().contains(kMissing + QStringLiteral(": ") + kCameraNotFound), 5000);
  QVERIFY(!w.worker()->isRunning());
}

void CameraSettingsTest::captureCardInputAndStandard() {
  // A USB camera: no input or standard to choose, so neither row shows.
  Settings model;
  std::vector<SetCall> calls;
  DeviceInfo usb = handMadeCamera();
  usb.inputs = {{0, "Camera 1", false, 0}};
  {
    CameraSettingsPage page(model, testDevices({usb.path}, usb, &calls));
    page.show();
    model.camera_source.device = usb.path;
    page.rescan();
    QVERIFY(!child<QComboBox>(page, QStringLiteral("cameraInput"))->isVisible());
    QVERIFY(!child<QComboBox>(page, QStringLiteral("cameraStandard"))->isVisible());
  }
  // A PXC200-like card: three inputs, the standards each takes.
  DeviceInfo card = handMadeCamera();
  card.card = "PXC200 frame grabber";
  card.inputs = {{0, "Composite0", false, V4L2_STD_PAL | V4L2_STD_NTSC | V4L2_STD_SECAM},
                 {1, "Composite1", false, V4L2_STD_PAL | V4L2_STD_NTSC},
                 {2, "S-Video", false, V4L2_STD_NTSC}};
  card.current_input = 0;
  card.standards = {{V4L2_STD_PAL_BG, "PAL-BG", 25.0}, {V4L2_STD_NTSC_M, "NTSC-M", 29.97}};
  model.camera_source.device = card.path;
  CameraSettingsPage page(model, testDevices({card.path}, card, &calls));
  page.show();
  auto* input = child<QComboBox>(page, QStringLiteral("cameraInput"));
  auto* standard = child<QComboBox>(page, QStringLiteral("cameraStandard"));
  QVERIFY(input->isVisible());
  QVERIFY(standard->isVisible());
  QCOMPARE(input->count(), 4);  // the device's own, then the three
  QCOMPARE(input->itemText(3), QStringLiteral("2: S-Video"));
  QCOMPARE(standard->count(), 4);  // the device's own, PAL, NTSC, SECAM (Composite0 is current)
  input->setCurrentIndex(3);
  QCOMPARE(model.camera_source.input, 2);
  QCOMPARE(standard->count(), 2);  // S-Video takes NTSC only
  QCOMPARE(standard->itemText(1), QStringLiteral("NTSC"));
  standard->setCurrentIndex(1);
  QCOMPARE(model.camera_source.standard, TvStandard::Ntsc);
  // A stored choice the device lacks is kept and marked.
  model.camera_source.input = 5;
  page.rescan();
  QVERIFY(input->currentText().contains(QStringLiteral("not on this device")));
  QCOMPARE(model.camera_source.input, 5);
  QVERIFY(calls.empty());
}

void CameraSettingsTest::dialogEditsEachSourcesCamera() {
  Settings model;
  model.source = SourceKind::File;
  std::vector<SetCall> calls;
  SettingsDialog dialog(model, nullptr, testDevices({}, DeviceInfo{}, &calls));
  auto* chooser = dialog.findChild<QComboBox*>(QStringLiteral("cameraModelSource"));
  auto* distortion_chooser = dialog.findChild<QComboBox*>(QStringLiteral("distortionSource"));
  auto* d0 = dialog.findChild<QDoubleSpinBox*>(QStringLiteral("cameraD0"));
  auto* k1 = dialog.findChild<QLineEdit*>(QStringLiteral("distortionK1"));
  QVERIFY(chooser && distortion_chooser && d0 && k1);
  QCOMPARE(chooser->currentText(), QStringLiteral("File"));  // the source in use first
  d0->setValue(12.0);
  k1->setText(QStringLiteral("-2e-07"));
  emit k1->editingFinished();
  // The Camera source's model: its own values, edited apart.
  chooser->setCurrentIndex(chooser->findData(static_cast<int>(SourceKind::Camera)));
  QCOMPARE(distortion_chooser->currentText(), QStringLiteral("Camera"));  // both tabs show one source
  QCOMPARE(d0->value(), CameraModel{}.image_plane_distance_mm);
  QCOMPARE(k1->text().toDouble(), 0.0);
  d0->setValue(6.0);
  Settings out;
  out.source = SourceKind::Virtual;
  dialog.applyTo(out);
  QCOMPARE(out.camera(SourceKind::File).image_plane_distance_mm, 12.0);
  QCOMPARE(out.camera(SourceKind::File).distortion.k1, -2e-7);
  QCOMPARE(out.camera(SourceKind::Camera).image_plane_distance_mm, 6.0);
  QCOMPARE(out.camera(SourceKind::Virtual).image_plane_distance_mm, CameraModel{}.image_plane_distance_mm);
  QCOMPARE(out.source, SourceKind::Virtual);  // the source in use is not the dialog's to change
}

}  // namespace imagepro::app::test
