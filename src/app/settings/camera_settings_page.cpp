#include "app/settings/camera_settings_page.h"

#include <QCheckBox>
#include <QComboBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QScrollArea>
#include <QSignalBlocker>
#include <QSlider>
#include <QSpinBox>
#include <QTimer>
#include <QToolButton>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/settings/enum_names.h"

namespace imagepro::app {

namespace {

// After a control is set, the device is read again this much later: a streaming camera's
// control is set by the worker thread, and a mode may have made others (in)active.
constexpr int kRereadMs = 150;

QString text(const std::string& s) { return QString::fromStdString(s); }

bool fitsInt(std::int64_t v) {
  return v >= std::numeric_limits<int>::min() && v <= std::numeric_limits<int>::max();
}

QString controlToolTip(const CameraControl& c) {
  QString tip = text(c.name);
  switch (c.type) {
    case ControlType::Integer:
    case ControlType::Integer64:
      tip += QObject::tr(": %1 to %2").arg(c.minimum).arg(c.maximum);
      if (c.step > 1) tip += QObject::tr(" in steps of %1").arg(c.step);
      tip += QObject::tr(", default %1").arg(c.default_value);
      break;
    case ControlType::Boolean:
      tip += QObject::tr(": default %1").arg(c.default_value ? QObject::tr("on") : QObject::tr("off"));
      break;
    case ControlType::Menu:
    case ControlType::IntegerMenu:
      for (const ControlMenuItem& item : c.menu)
        if (item.value == c.default_value) tip += QObject::tr(": default %1").arg(text(item.name));
      break;
    case ControlType::Button:
      tip += QObject::tr(": an action, not stored in the settings");
      break;
    case ControlType::Other:
      break;
  }
  tip += QObject::tr(" (key %1)").arg(text(c.key));
  if (c.read_only) tip += QObject::tr("\nRead-only.");
  if (c.inactive) tip += QObject::tr("\nInactive: it depends on another control, e.g. an automatic mode that is on.");
  return tip;
}

// The rates a format lists at width x height, in frames/s.
void addRates(const FrameSize& s, std::vector<double>& rates) {
  for (const FrameInterval& i : s.rates.discrete) rates.push_back(i.rateHz());
  if (s.rates.is_range) {
    const double lo = s.rates.longest.rateHz(), hi = s.rates.shortest.rateHz();
    rates.push_back(lo);
    rates.push_back(hi);
    if (lo < 25.0 && 25.0 < hi) rates.push_back(25.0);  // the thesis's rate
  }
}

bool sizeOffered(const FrameSize& s, int width, int height) {
  if (!s.is_range) return s.width == width && s.height == height;
  return width >= s.min_width && width <= s.width && height >= s.min_height && height <= s.height &&
         (width - s.min_width) % s.step_width == 0 && (height - s.min_height) % s.step_height == 0;
}

}  // namespace

CameraDevices CameraDevices::system() {
  CameraDevices d;
  d.list = [] { return listVideoDevices(); };
  d.query = [](const std::string& path, DeviceInfo& info, std::string& error) {
    return queryDevice(systemDeviceIo(), path, info, error);
  };
  d.set = [](const std::string& device, const std::string& key, std::int64_t value) {
    std::string error;
    return ok(setDeviceControl(systemDeviceIo(), device, key, value, error)) ? std::string() : error;
  };
  return d;
}

CameraSettingsPage::CameraSettingsPage(Settings& model, CameraDevices devices, QWidget* parent)
    : QWidget(parent), model_(model), devices_(std::move(devices)) {
  setObjectName(QStringLiteral("cameraSettingsPage"));
  auto* form = new QFormLayout;
  device_ = new QComboBox;
  device_->setObjectName(QStringLiteral("cameraDevice"));
  device_->setEditable(true);
  device_->setInsertPolicy(QComboBox::NoInsert);
  device_->setToolTip(tr("The V4L2 device the Camera source opens: a /dev/video* node found on this machine, "
                         "or any path typed in (e.g. /dev/v4l/by-id/...)"));
  auto* rescan_button = new QToolButton;
  rescan_button->setObjectName(QStringLiteral("cameraRescan"));
  rescan_button->setText(tr("Rescan"));
  rescan_button->setToolTip(tr("Look for devices again and read the chosen one anew"));
  auto* device_row = new QHBoxLayout;
  device_row->addWidget(device_, 1);
  device_row->addWidget(rescan_button);
  form->addRow(tr("Device"), device_row);
  status_ = new QLabel;
  status_->setObjectName(QStringLiteral("cameraStatus"));
  status_->setWordWrap(true);
  status_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  form->addRow(status_);
  size_ = new QComboBox;
  size_->setObjectName(QStringLiteral("cameraSize"));
  size_->setToolTip(tr("The frame size asked for; the nearest the device offers is taken"));
  form->addRow(tr("Size"), size_);
  rate_ = new QComboBox;
  rate_->setObjectName(QStringLiteral("cameraRate"));
  rate_->setToolTip(tr("The frame rate asked for (thesis 5.2.1: 25 frames/s); the nearest the device offers is taken"));
  form->addRow(tr("Frame rate"), rate_);
  // A capture card's (composite, S-Video): rows shown only for a device that has the choice.
  input_ = new QComboBox;
  input_->setObjectName(QStringLiteral("cameraInput"));
  input_->setToolTip(tr("The capture card's input the Camera source reads (VIDIOC_S_INPUT)"));
  form->addRow(tr("Input"), input_);
  standard_ = new QComboBox;
  standard_->setObjectName(QStringLiteral("cameraStandard"));
  standard_->setToolTip(tr("The TV standard of the analogue signal at the input (VIDIOC_S_STD)"));
  form->addRow(tr("TV standard"), standard_);
  form_ = form;
  note_ = new QLabel;
  note_->setObjectName(QStringLiteral("cameraNote"));
  note_->setWordWrap(true);
  form->addRow(note_);

  controls_box_ = new QWidget;
  controls_form_ = new QFormLayout(controls_box_);
  auto* scroll = new QScrollArea;
  scroll->setWidget(controls_box_);
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  auto* group = new QGroupBox(tr("Controls"));
  auto* group_layout = new QVBoxLayout(group);
  group_layout->addWidget(scroll);
  problem_ = new QLabel;
  problem_->setObjectName(QStringLiteral("cameraControlProblem"));
  problem_->setWordWrap(true);
  problem_->setStyleSheet(QStringLiteral("color: #b00020;"));
  group_layout->addWidget(problem_);
  auto* hint = new QLabel(tr("A changed control is set at once and kept with the settings (OK or Apply), "
                             "which set it again whenever the camera is opened."));
  hint->setWordWrap(true);
  group_layout->addWidget(hint);

  auto* layout = new QVBoxLayout(this);
  layout->addLayout(form);
  layout->addWidget(group, 1);

  connect(device_, &QComboBox::activated, this, [this](int index) { chooseDevice(device_->itemText(index)); });
  connect(device_->lineEdit(), &QLineEdit::editingFinished, this,
          [this] { chooseDevice(device_->currentText().trimmed()); });
  connect(rescan_button, &QToolButton::clicked, this, &CameraSettingsPage::rescan);
  connect(size_, &QComboBox::currentIndexChanged, this, [this](int index) {
    if (updating_ || index < 0) return;
    const QSize s = size_->itemData(index).toSize();
    model_.camera_source.width = s.width();
    model_.camera_source.height = s.height();
    fillRates();
    noteModelSize();
  });
  connect(rate_, &QComboBox::currentIndexChanged, this, [this](int index) {
    if (updating_ || index < 0) return;
    model_.camera_source.frame_rate_hz = rate_->itemData(index).toDouble();
  });
  connect(input_, &QComboBox::currentIndexChanged, this, [this](int index) {
    if (updating_ || index < 0) return;
    model_.camera_source.input = input_->itemData(index).toInt();
    fillStandards();  // the standards are the input's
  });
  connect(standard_, &QComboBox::currentIndexChanged, this, [this](int index) {
    if (updating_ || index < 0) return;
    model_.camera_source.standard = static_cast<TvStandard>(standard_->itemData(index).toInt());
  });
  rescan();
}

CameraSettingsPage::~CameraSettingsPage() {
  // Closing takes the focus from the device field, whose editingFinished would otherwise
  // reach this page after its members are gone.
  QObject::disconnect(device_->lineEdit(), nullptr, this, nullptr);
  QObject::disconnect(device_, nullptr, this, nullptr);
}

QString CameraSettingsPage::statusText() const { return status_->text(); }

void CameraSettingsPage::cameraModelChanged() {
  fillSizes();
  fillRates();
  noteModelSize();
}

void CameraSettingsPage::rescan() {
  const std::vector<std::string> paths = devices_.list ? devices_.list() : std::vector<std::string>{};
  {
    QSignalBlocker block(device_);
    device_->clear();
    for (const std::string& p : paths) device_->addItem(text(p));
    device_->setEditText(text(model_.camera_source.device));
  }
  shown_.clear();
  if (!paths.empty()) {
    chooseDevice(text(model_.camera_source.device));
    return;
  }
  // Nothing to open; a path typed in is still tried.
  shown_ = model_.camera_source.device;
  info_ = DeviceInfo{};
  info_.path = shown_;
  status_->setText(tr("No camera found"));
  fillSizes();
  fillRates();
  fillInputs();
  noteModelSize();
  buildControls();
}

void CameraSettingsPage::chooseDevice(const QString& path) {
  const std::string p = path.toStdString();
  if (p.empty() || p == shown_) return;
  if (p != model_.camera_source.device) {
    model_.camera_source.device = p;
    model_.camera_source.controls.clear();  // they were another device's
  }
  shown_ = p;
  DeviceInfo info;
  std::string error;
  const Status s = devices_.query ? devices_.query(p, info, error) : Status::CameraNotFound;
  if (!ok(s)) {
    showDeviceError(s, error.empty() ? p : error);
    return;
  }
  showDevice(info);
}

void CameraSettingsPage::showDevice(const DeviceInfo& info) {
  info_ = info;
  shown_ = info.path;
  QString about = text(info.card.empty() ? info.path : info.card);
  if (!info.driver.empty()) about += tr(" (%1, %2)").arg(text(info.driver), text(info.bus));
  if (!info.video_capture) about += tr(": not a video capture device (a metadata or output node)");
  status_->setText(about);
  problem_->clear();
  fillSizes();
  fillRates();
  fillInputs();
  noteModelSize();
  buildControls();
}

void CameraSettingsPage::showDeviceError(Status status, const std::string& error) {
  info_ = DeviceInfo{};
  info_.path = shown_;
  const std::string_view name = statusName(status);
  status_->setText(QString::fromUtf8(name.data(), static_cast<qsizetype>(name.size())) + QStringLiteral(": ") +
                   text(error));
  problem_->clear();
  fillSizes();
  fillRates();
  fillInputs();
  noteModelSize();
  buildControls();
}

void CameraSettingsPage::fillSizes() {
  const CameraModel& cam = model_.camera(SourceKind::Camera);
  std::vector<std::pair<int, int>> sizes;
  for (const FormatInfo& f : info_.formats) {
    if (!f.format) continue;  // not readable: not offered
    for (const FrameSize& s : f.sizes) {
      sizes.emplace_back(s.width, s.height);
      if (s.is_range && sizeOffered(s, cam.width, cam.height)) sizes.emplace_back(cam.width, cam.height);
    }
  }
  std::sort(sizes.begin(), sizes.end());
  sizes.erase(std::unique(sizes.begin(), sizes.end()), sizes.end());
  updating_ = true;
  size_->clear();
  size_->addItem(tr("As the camera model (%1 x %2)").arg(cam.width).arg(cam.height), QSize(0, 0));
  for (const auto& [w, h] : sizes) size_->addItem(tr("%1 x %2").arg(w).arg(h), QSize(w, h));
  const CameraSourceOptions& o = model_.camera_source;
  const QSize wanted = o.width > 0 && o.height > 0 ? QSize(o.width, o.height) : QSize(0, 0);
  int index = size_->findData(wanted);
  if (index < 0) {
    size_->addItem(tr("%1 x %2 (not listed by the device)").arg(wanted.width()).arg(wanted.height()), wanted);
    index = size_->count() - 1;
  }
  size_->setCurrentIndex(index);
  updating_ = false;
}

void CameraSettingsPage::fillRates() {
  const CameraSourceOptions& o = model_.camera_source;
  const bool own_size = o.width > 0 && o.height > 0;
  const int width = own_size ? o.width : model_.camera(SourceKind::Camera).width;
  const int height = own_size ? o.height : model_.camera(SourceKind::Camera).height;
  std::vector<double> rates;
  for (const FormatInfo& f : info_.formats) {
    if (!f.format) continue;
    for (const FrameSize& s : f.sizes)
      if (sizeOffered(s, width, height)) addRates(s, rates);
  }
  std::sort(rates.begin(), rates.end(), std::greater<>());
  rates.erase(std::unique(rates.begin(), rates.end(), [](double a, double b) { return std::abs(a - b) < 1e-6; }),
              rates.end());
  updating_ = true;
  rate_->clear();
  for (double r : rates)
    if (r > 0.0) rate_->addItem(tr("%1 frames/s").arg(r, 0, 'g', 5), r);
  rate_->addItem(tr("The driver's rate"), 0.0);
  int index = rate_->findData(o.frame_rate_hz);
  if (index < 0) {
    rate_->addItem(tr("%1 frames/s (not listed at this size)").arg(o.frame_rate_hz, 0, 'g', 5), o.frame_rate_hz);
    index = rate_->count() - 1;
  }
  rate_->setCurrentIndex(index);
  updating_ = false;
}

void CameraSettingsPage::fillInputs() {
  const CameraSourceOptions& o = model_.camera_source;
  updating_ = true;
  input_->clear();
  input_->addItem(tr("As the device has it"), -1);
  for (const VideoInput& in : info_.inputs)
    input_->addItem(tr("%1: %2").arg(in.index).arg(text(in.name)), static_cast<int>(in.index));
  int index = input_->findData(o.input);
  if (index < 0) {
    input_->addItem(tr("%1 (not on this device)").arg(o.input), o.input);
    index = input_->count() - 1;
  }
  input_->setCurrentIndex(index);
  updating_ = false;
  // One input is no choice (a USB camera lists its sensor as one).
  form_->setRowVisible(input_, info_.inputs.size() > 1 || index > 0);
  fillStandards();
}

void CameraSettingsPage::fillStandards() {
  const CameraSourceOptions& o = model_.camera_source;
  const std::vector<TvStandard> offered = tvStandardsOffered(info_, o.input);
  updating_ = true;
  standard_->clear();
  standard_->addItem(tr("As the device has it"), static_cast<int>(TvStandard::Keep));
  for (const TvStandard t : offered) {
    const std::string_view label = enumLabel(t);
    standard_->addItem(QString::fromUtf8(label.data(), static_cast<qsizetype>(label.size())), static_cast<int>(t));
  }
  int index = standard_->findData(static_cast<int>(o.standard));
  if (index < 0) {
    const std::string_view label = enumLabel(o.standard);
    const QString name = QString::fromUtf8(label.data(), static_cast<qsizetype>(label.size()));
    standard_->addItem(tr("%1 (not taken by this input)").arg(name), static_cast<int>(o.standard));
    index = standard_->count() - 1;
  }
  standard_->setCurrentIndex(index);
  updating_ = false;
  form_->setRowVisible(standard_, !offered.empty() || index > 0);
}

void CameraSettingsPage::noteModelSize() {
  const CameraSourceOptions& o = model_.camera_source;
  const CameraModel& cam = model_.camera(SourceKind::Camera);
  if (o.width > 0 && o.height > 0 && (o.width != cam.width || o.height != cam.height))
    note_->setText(tr("The Camera source's camera model (Camera tab) is for %1 x %2 frames: poses from %3 x %4 "
                      "frames need a model calibrated at that size.")
                       .arg(cam.width)
                       .arg(cam.height)
                       .arg(o.width)
                       .arg(o.height));
  else
    note_->clear();
}

void CameraSettingsPage::buildControls() {
  while (controls_form_->rowCount() > 0) controls_form_->removeRow(0);
  control_widgets_.clear();
  int shown = 0;
  for (const CameraControl& c : info_.controls) {
    if (c.type == ControlType::Other) continue;  // cannot be set as a number
    QWidget* w = controlWidget(c);
    if (c.type == ControlType::Button) controls_form_->addRow(w);
    else controls_form_->addRow(text(c.name), w);
    showControlValue(c);
    ++shown;
  }
  if (shown == 0) controls_form_->addRow(new QLabel(tr("No controls")));
}

QWidget* CameraSettingsPage::controlWidget(const CameraControl& c) {
  const std::string key = c.key;
  const QString name = QStringLiteral("control_") + text(key);
  QWidget* value_widget = nullptr;
  QWidget* row = nullptr;
  switch (c.type) {
    case ControlType::Integer:
    case ControlType::Integer64: {
      if (!fitsInt(c.minimum) || !fitsInt(c.maximum)) {
        auto* edit = new QLineEdit;
        connect(edit, &QLineEdit::editingFinished, this, [this, edit, key] {
          bool number = false;
          const qlonglong v = edit->text().toLongLong(&number);
          if (!updating_ && number) controlEdited(key, v, true);
        });
        value_widget = row = edit;
        break;
      }
      const int lo = static_cast<int>(c.minimum), hi = static_cast<int>(c.maximum);
      const int step = static_cast<int>(std::clamp<std::int64_t>(c.step, 1, std::max(1, hi - lo)));
      auto* slider = new QSlider(Qt::Horizontal);
      slider->setObjectName(name + QStringLiteral("_slider"));
      slider->setRange(lo, hi);
      slider->setSingleStep(step);
      slider->setPageStep(std::max(step, (hi - lo) / 10 / step * step));
      slider->setTracking(false);  // one setting when the handle is let go, not one per pixel
      auto* spin = new QSpinBox;
      spin->setRange(lo, hi);
      spin->setSingleStep(step);
      spin->setKeyboardTracking(false);
      const auto snap = [lo, step](int v) { return lo + static_cast<int>(std::lround((v - lo) / double(step))) * step; };
      connect(slider, &QSlider::valueChanged, spin, [spin, snap](int v) { spin->setValue(snap(v)); });
      connect(spin, &QSpinBox::valueChanged, this, [this, spin, slider, snap, key](int v) {
        if (snap(v) != v) {  // typed between two steps: the nearest step instead
          spin->setValue(snap(v));
          return;
        }
        {
          const QSignalBlocker block(slider);
          slider->setValue(v);
        }
        if (!updating_) controlEdited(key, v, true);
      });
      row = new QWidget;
      auto* layout = new QHBoxLayout(row);
      layout->setContentsMargins(0, 0, 0, 0);
      layout->addWidget(slider, 1);
      layout->addWidget(spin);
      value_widget = spin;
      break;
    }
    case ControlType::Boolean: {
      auto* box = new QCheckBox;
      connect(box, &QCheckBox::toggled, this, [this, key](bool on) {
        if (!updating_) controlEdited(key, on ? 1 : 0, true);
      });
      value_widget = row = box;
      break;
    }
    case ControlType::Menu:
    case ControlType::IntegerMenu: {
      auto* box = new QComboBox;
      for (const ControlMenuItem& item : c.menu) box->addItem(text(item.name), QVariant::fromValue<qlonglong>(item.value));
      connect(box, &QComboBox::currentIndexChanged, this, [this, box, key](int index) {
        if (!updating_ && index >= 0) controlEdited(key, box->itemData(index).toLongLong(), true);
      });
      value_widget = row = box;
      break;
    }
    case ControlType::Button: {
      auto* button = new QPushButton(text(c.name));
      connect(button, &QPushButton::clicked, this, [this, key] { controlEdited(key, 1, false); });
      value_widget = row = button;
      break;
    }
    case ControlType::Other:
      break;
  }
  value_widget->setObjectName(name);
  row->setToolTip(controlToolTip(c));
  value_widget->setToolTip(controlToolTip(c));
  control_widgets_[key] = row;
  return row;
}

void CameraSettingsPage::showControlValue(const CameraControl& c) {
  const auto it = control_widgets_.find(c.key);
  if (it == control_widgets_.end()) return;
  QWidget* row = it->second;
  const QString name = QStringLiteral("control_") + text(c.key);
  const auto stored = model_.camera_source.controls.find(c.key);
  const std::int64_t value = stored != model_.camera_source.controls.end() ? stored->second : c.value;
  updating_ = true;
  if (auto* spin = row->findChild<QSpinBox*>(name)) {
    spin->setValue(static_cast<int>(value));
  } else if (auto* edit = qobject_cast<QLineEdit*>(row)) {
    edit->setText(QString::number(value));
  } else if (auto* box = qobject_cast<QCheckBox*>(row)) {
    box->setChecked(value != 0);
  } else if (auto* menu = qobject_cast<QComboBox*>(row)) {
    menu->setCurrentIndex(menu->findData(QVariant::fromValue<qlonglong>(value)));
  }
  updating_ = false;
  row->setEnabled(!c.read_only && !c.inactive);
  row->setToolTip(controlToolTip(c));
}

void CameraSettingsPage::controlEdited(const std::string& key, std::int64_t value, bool store) {
  if (store) model_.camera_source.controls[key] = value;
  const std::string problem = devices_.set ? devices_.set(model_.camera_source.device, key, value) : std::string();
  problem_->setText(text(problem));
  emit controlChanged(text(key), value);
  QTimer::singleShot(kRereadMs, this, &CameraSettingsPage::refreshControls);
}

void CameraSettingsPage::refreshControls() {
  if (info_.controls.empty() || !devices_.query) return;
  DeviceInfo now;
  std::string error;
  if (!ok(devices_.query(shown_, now, error)) || now.path != shown_) return;
  for (const CameraControl& c : now.controls) {
    const auto it = std::find_if(info_.controls.begin(), info_.controls.end(),
                                 [&](const CameraControl& old) { return old.key == c.key; });
    if (it == info_.controls.end()) continue;
    *it = c;
    showControlValue(c);
  }
}

}  // namespace imagepro::app
