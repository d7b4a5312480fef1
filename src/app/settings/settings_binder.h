#pragma once
// Binds control-panel widgets to fields of the one Settings struct. A widget edit
// writes its field and emits changed(); refresh() writes every field back into its
// widget (after Load or Restore defaults) without emitting. Lists show the enum
// tables' display names with their descriptions as tooltips (enum_names.h), and
// number widgets take their range from the settings table (settings.cpp), so no
// name, range or default is written down twice. Every bound widget carries its
// settings key in the property kSettingKeyProperty.
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLineEdit>
#include <QObject>
#include <QSpinBox>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "app/settings/enum_text.h"
#include "core/settings/settings.h"

class QButtonGroup;
class QRadioButton;

namespace imagepro::app {

// The property of a bound widget that names its settings key ("pipeline.ellipse.trace_inlier_px").
inline constexpr const char* kSettingKeyProperty = "settingKey";

// The settings table's range of `key` on a spin box, which then carries the key. A
// double spin box shows `decimals` places (its step is ten of the last place); a
// range end finer than that is rounded inwards, so the box offers no invalid value.
void setTableRange(QSpinBox* box, const SettingKey& key);
void setTableRange(QDoubleSpinBox* box, const SettingKey& key, int decimals);

class SettingsBinder : public QObject {
  Q_OBJECT

 public:
  explicit SettingsBinder(Settings& model, QObject* parent = nullptr) : QObject(parent), model_(model) {}

  Settings& model() { return model_; }
  const Settings& model() const { return model_; }

  // Field is a callable Settings& -> T&. The list offers the values its key takes (a
  // key may take only some of its enum's: the frame's threshold is never None).
  template <class E, class Field>
  QComboBox* combo(Field field);
  // One radio button per enum value, stacked vertically in a new widget.
  template <class E, class Field>
  QWidget* radios(Field field);
  template <class Field>
  QCheckBox* check(const QString& text, Field field);
  // Number widgets, their range the settings table's for the field's key (setTableRange).
  template <class Field>
  QSpinBox* intSpin(Field field, const QString& suffix = {});
  template <class Field>
  QDoubleSpinBox* doubleSpin(Field field, int decimals, const QString& suffix = {});
  // Free text for numbers too small or too wide for a spin box (distortion coefficients).
  template <class Field>
  QLineEdit* number(Field field);
  // A line of text (a host name); an emptied line is not taken (the table wants text) and
  // shows the value again.
  template <class Field>
  QLineEdit* text(Field field);

  // Writes the whole model into the widgets, emitting nothing.
  void refresh();
  // Runs after every refresh and every edit (enabling dependent widgets).
  void onAnyUpdate(std::function<void()> fn);

 signals:
  void changed();

 private:
  void edited();
  // The settings key of the model's value at `field`, recorded on `widget`.
  const SettingKey& bindKey(QWidget* widget, const void* field);
  void addRefresher(std::function<void()> fn) { refreshers_.push_back(std::move(fn)); }
  QWidget* radioBox(std::vector<std::pair<QString, QString>> items, std::function<int()> get,
                    std::function<void(int)> set);
  QLineEdit* numberEdit(const void* field, std::function<double()> get, std::function<void(double)> set);
  QLineEdit* textEdit(const void* field, std::function<std::string()> get, std::function<void(std::string)> set);

  Settings& model_;
  std::vector<std::function<void()>> refreshers_;
  std::vector<std::function<void()>> followers_;
  bool refreshing_ = false;
};

// ---- templates -------------------------------------------------------------------

template <class E, class Field>
QComboBox* SettingsBinder::combo(Field field) {
  auto* box = new QComboBox;
  const SettingKey& key = bindKey(box, &field(model_));
  for (const auto& entry : enumEntries(E{})) {
    if (key.type == SettingKey::Type::Choice &&
        std::none_of(key.choices.begin(), key.choices.end(), [&entry](const auto& c) { return c.key == entry.key; }))
      continue;
    box->addItem(fromView(entry.label), static_cast<int>(entry.value));
    box->setItemData(box->count() - 1, entryToolTip(entry), Qt::ToolTipRole);
  }
  addRefresher([this, box, field] {
    box->setCurrentIndex(box->findData(static_cast<int>(field(model_))));
    box->setToolTip(box->currentData(Qt::ToolTipRole).toString());
  });
  connect(box, &QComboBox::currentIndexChanged, this, [this, box, field](int index) {
    if (refreshing_ || index < 0) return;
    field(model_) = static_cast<E>(box->itemData(index).toInt());
    box->setToolTip(box->currentData(Qt::ToolTipRole).toString());
    edited();
  });
  return box;
}

template <class E, class Field>
QWidget* SettingsBinder::radios(Field field) {
  std::vector<std::pair<QString, QString>> items;
  for (const auto& entry : enumEntries(E{})) items.emplace_back(fromView(entry.label), entryToolTip(entry));
  const auto values = enumEntries(E{});
  QWidget* box = radioBox(
      std::move(items),
      [this, field, values] {
        for (std::size_t i = 0; i < values.size(); ++i)
          if (values[i].value == field(model_)) return static_cast<int>(i);
        return -1;
      },
      [this, field, values](int i) { field(model_) = values[static_cast<std::size_t>(i)].value; });
  bindKey(box, &field(model_));
  return box;
}

template <class Field>
QCheckBox* SettingsBinder::check(const QString& text, Field field) {
  auto* box = new QCheckBox(text);
  bindKey(box, &field(model_));
  addRefresher([this, box, field] { box->setChecked(field(model_)); });
  connect(box, &QCheckBox::toggled, this, [this, field](bool on) {
    if (refreshing_) return;
    field(model_) = on;
    edited();
  });
  return box;
}

template <class Field>
QSpinBox* SettingsBinder::intSpin(Field field, const QString& suffix) {
  auto* box = new QSpinBox;
  setTableRange(box, bindKey(box, &field(model_)));
  box->setSuffix(suffix);
  box->setKeyboardTracking(false);  // one change per finished entry, not per digit
  addRefresher([this, box, field] { box->setValue(static_cast<int>(field(model_))); });
  connect(box, &QSpinBox::valueChanged, this, [this, field](int v) {
    if (refreshing_) return;
    field(model_) = v;
    edited();
  });
  return box;
}

template <class Field>
QDoubleSpinBox* SettingsBinder::doubleSpin(Field field, int decimals, const QString& suffix) {
  auto* box = new QDoubleSpinBox;
  setTableRange(box, bindKey(box, &field(model_)), decimals);
  box->setSuffix(suffix);
  box->setKeyboardTracking(false);
  addRefresher([this, box, field] { box->setValue(field(model_)); });
  connect(box, &QDoubleSpinBox::valueChanged, this, [this, field](double v) {
    if (refreshing_ || !std::isfinite(v)) return;
    field(model_) = v;
    edited();
  });
  return box;
}

template <class Field>
QLineEdit* SettingsBinder::number(Field field) {
  return numberEdit(&field(model_), [this, field] { return static_cast<double>(field(model_)); },
                    [this, field](double v) { field(model_) = v; });
}

template <class Field>
QLineEdit* SettingsBinder::text(Field field) {
  return textEdit(&field(model_), [this, field] { return std::string(field(model_)); },
                  [this, field](std::string v) { field(model_) = std::move(v); });
}

}  // namespace imagepro::app
