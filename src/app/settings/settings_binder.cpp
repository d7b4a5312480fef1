#include "app/settings/settings_binder.h"

#include <QButtonGroup>
#include <QDoubleValidator>
#include <QRadioButton>
#include <QVBoxLayout>

#include <climits>
#include <cmath>

#include "core/common/contract.h"

namespace imagepro::app {

namespace {

// `value` on the grid of `decimals` places, rounded towards the inside of the range
// (up for its low end): a bound finer than the box shows (1e-9 for "above zero")
// becomes the first value the box can show inside it.
double onGrid(double value, int decimals, bool low_end) {
  if (!std::isfinite(value)) return value;
  const double scale = std::pow(10.0, decimals);
  const double scaled = value * scale;
  const double nearest = std::round(scaled);
  // A bound already on the grid stays, whatever the last bit of its product says.
  if (std::abs(scaled - nearest) <= 1e-9 * std::max(1.0, std::abs(scaled))) return nearest / scale;
  return (low_end ? std::ceil(scaled) : std::floor(scaled)) / scale;
}

int toInt(double value) {
  return value <= double(INT_MIN) ? INT_MIN : value >= double(INT_MAX) ? INT_MAX : static_cast<int>(value);
}

}  // namespace

const SettingKey& SettingsBinder::bindKey(QWidget* widget, const void* field) {
  const SettingKey* key = settingKeyOf(model_, field);
  IMAGEPRO_EXPECTS(key != nullptr, "a bound widget edits a value of the settings table");
  // Unbound in a release build: no range to take, the widget keeps Qt's and lacks the property.
  static const SettingKey kUnbound{};
  if (!key) return kUnbound;
  widget->setProperty(kSettingKeyProperty, QString::fromStdString(key->path));
  return *key;
}

void setTableRange(QSpinBox* box, const SettingKey& key) {
  if (key.path.empty()) return;
  box->setProperty(kSettingKeyProperty, QString::fromStdString(key.path));
  box->setRange(toInt(key.lo), toInt(key.hi));
}

void setTableRange(QDoubleSpinBox* box, const SettingKey& key, int decimals) {
  box->setDecimals(decimals);
  double step = 1.0;
  for (int i = 0; i < decimals - 1; ++i) step /= 10.0;
  box->setSingleStep(step);
  if (key.path.empty()) return;
  box->setProperty(kSettingKeyProperty, QString::fromStdString(key.path));
  box->setRange(onGrid(key.lo, decimals, true), onGrid(key.hi, decimals, false));
}

void SettingsBinder::refresh() {
  refreshing_ = true;
  for (const auto& fn : refreshers_) fn();
  refreshing_ = false;
  for (const auto& fn : followers_) fn();
}

void SettingsBinder::onAnyUpdate(std::function<void()> fn) {
  fn();
  followers_.push_back(std::move(fn));
}

void SettingsBinder::edited() {
  for (const auto& fn : followers_) fn();
  emit changed();
}

QWidget* SettingsBinder::radioBox(std::vector<std::pair<QString, QString>> items, std::function<int()> get,
                                  std::function<void(int)> set) {
  auto* box = new QWidget;
  auto* layout = new QVBoxLayout(box);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(2);
  auto* group = new QButtonGroup(box);
  for (std::size_t i = 0; i < items.size(); ++i) {
    auto* button = new QRadioButton(items[i].first);
    button->setToolTip(items[i].second);
    group->addButton(button, static_cast<int>(i));
    layout->addWidget(button);
  }
  addRefresher([group, get] {
    if (QAbstractButton* b = group->button(get())) b->setChecked(true);
  });
  connect(group, &QButtonGroup::idToggled, this, [this, set](int id, bool on) {
    if (refreshing_ || !on) return;
    set(id);
    edited();
  });
  return box;
}

QLineEdit* SettingsBinder::numberEdit(const void* field, std::function<double()> get,
                                      std::function<void(double)> set) {
  auto* edit = new QLineEdit;
  const SettingKey& key = bindKey(edit, field);
  auto* validator = key.path.empty() ? new QDoubleValidator(edit) : new QDoubleValidator(key.lo, key.hi, 17, edit);
  validator->setNotation(QDoubleValidator::ScientificNotation);
  validator->setLocale(QLocale::c());
  edit->setValidator(validator);
  addRefresher([edit, get] { edit->setText(QString::number(get(), 'g', 12)); });
  connect(edit, &QLineEdit::editingFinished, this, [this, edit, get, set] {
    if (refreshing_) return;
    bool ok = false;
    const double v = QLocale::c().toDouble(edit->text(), &ok);
    if (!ok || !std::isfinite(v) || v == get()) return;
    set(v);
    edited();
  });
  return edit;
}

QLineEdit* SettingsBinder::textEdit(const void* field, std::function<std::string()> get,
                                    std::function<void(std::string)> set) {
  auto* edit = new QLineEdit;
  bindKey(edit, field);
  addRefresher([edit, get] { edit->setText(QString::fromStdString(get())); });
  connect(edit, &QLineEdit::editingFinished, this, [this, edit, get, set] {
    if (refreshing_) return;
    const std::string v = edit->text().trimmed().toStdString();
    if (v.empty()) {
      edit->setText(QString::fromStdString(get()));
      return;
    }
    if (v == get()) return;
    set(v);
    edited();
  });
  return edit;
}

}  // namespace imagepro::app
