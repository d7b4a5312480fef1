#pragma once
// The Settings dialog's Camera device page (thesis 2.2: the frame grabber, here a V4L2
// device): which device the Camera source opens (the /dev/video* nodes found, or any
// path typed in), at which size and rate (those the device lists), a capture card's input
// and TV standard (shown only for a device that offers a choice of them), and the device's
// controls (exposure, gain, brightness, focus ...), one widget per control type, showing
// the device's current values. A changed control is set at once (on the streaming
// camera, or on the device) and stored in the settings' camera_source, which sets it
// again whenever the camera is opened.
#include <QWidget>

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/camera/camera_info.h"
#include "core/settings/settings.h"

class QComboBox;
class QFormLayout;
class QLabel;

namespace imagepro::app {

// What the page asks of the machine. The tests hand it devices of their own.
struct CameraDevices {
  // The device nodes to offer.
  std::function<std::vector<std::string>()> list;
  // What a device offers (queryDevice); a device that cannot be opened gives its Status.
  std::function<Status(const std::string& path, DeviceInfo& info, std::string& error)> query;
  // Sets a control now; returns why not, or nothing (a refusal may also come later, from
  // elsewhere, when the control is set on a streaming camera).
  std::function<std::string(const std::string& device, const std::string& key, std::int64_t value)> set;
  // This machine's /dev/video* nodes, queried and set directly.
  static CameraDevices system();
};

class CameraSettingsPage : public QWidget {
  Q_OBJECT

 public:
  // Edits `model.camera_source` (the dialog's copy, which outlives the page).
  CameraSettingsPage(Settings& model, CameraDevices devices, QWidget* parent = nullptr);
  ~CameraSettingsPage() override;

  // Lists the devices again and shows the chosen one anew.
  void rescan();
  // Shows `info` as the chosen device's: its sizes, rates and controls.
  void showDevice(const DeviceInfo& info);
  // The camera model's size changed elsewhere in the dialog: the size choices follow.
  void cameraModelChanged();
  // "No camera found", the device's name, or why it cannot be opened.
  QString statusText() const;

 signals:
  // A control widget changed: the value was set and stored.
  void controlChanged(const QString& key, qint64 value);

 private:
  void chooseDevice(const QString& path);
  void showDeviceError(Status status, const std::string& error);
  void fillSizes();
  void fillRates();
  void fillInputs();
  void fillStandards();  // those of the chosen input
  void noteModelSize();
  void buildControls();
  QWidget* controlWidget(const CameraControl& control);
  // Sets the control now and, unless it is a button (an action), stores its value.
  void controlEdited(const std::string& key, std::int64_t value, bool store);
  void refreshControls();  // flags and values read from the device again
  void showControlValue(const CameraControl& control);

  Settings& model_;
  CameraDevices devices_;
  DeviceInfo info_;
  std::string shown_;      // the device the page shows (or failed to open)
  bool updating_ = false;  // widgets being filled: their signals are not edits
  QComboBox* device_;
  QLabel* status_;
  QComboBox* size_;
  QComboBox* rate_;
  QComboBox* input_;
  QComboBox* standard_;
  QFormLayout* form_;
  QLabel* note_;
  QLabel* problem_;  // why the last control change was refused
  QWidget* controls_box_;
  QFormLayout* controls_form_;
  std::map<std::string, QWidget*> control_widgets_;  // key -> the widget holding its value
};

}  // namespace imagepro::app
