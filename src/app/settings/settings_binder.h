#pragma once
// Binds control-panel widgets to fields of the one Settings struct. A widget edit
// writes its field and emits changed(); refresh() writes every field back into its
// widget (after Load or Restore defaults) without emitting. Lists are built from
// the enum name tables, so no name or default is written down twice.
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLineEdit>
#include <QObject>
#include <QSpinBox>

#include <functional>
#include <vector>

#include "app/panels/method_info.h"
#include "core/settings/enum_names.h"
#include "core/settings/settings.h"

class QButtonGroup;
class QRadioButton;

namespace imagepro::app {

class SettingsBinder : public QObject {
  Q_OBJECT

 public:
  explicit SettingsBinder(Settings& model, QObject* parent = nullptr) : QObject(parent), model_(model) {}

  Settings& model() { return model_; }
  const Settings& model() const { return model_; }

  // Field is a callable Settings& -> T&.
  template <class E, class Field>
  QComboBox* combo(Field field, std::function<bool(E)> keep = {});
  // One radio button per enum value, stacked vertically in a new widget.
  template <class E, class Field>
  QWidget* radios(Field field);
  template <class Field>
  QCheckBox* check(const QString& text, Field field);
  template <class Field>
  QSpinBox* intSpin(Field field, int lo, int hi, const QString& suffix = {});
  template <class Field>
  QDoubleSpinBox* doubleSpin(Field field, double lo, double hi, int decimals, const QString& suffix = {});
  // Free text for numbers too small or too wide for a spin box (distortion coefficients).
  template <class Field>
  QLineEdit* number(Field field, double lo, double hi);

  // Writes the whole model into the widgets, emitting nothing.
  void refresh();
  // Runs after every refresh and every edit (enabling dependent widgets).
  void onAnyUpdate(std::function<void()> fn);

 signals:
  void changed();

 private:
  void edited();
  void addRefresher(std::function<void()> fn) { refreshers_.push_back(std::move(fn)); }
  QWidget* radioBox(std::vector<std::pair<QString, QString>> items, std::function<int()> get,
                    std::function<void(int)> set);
  QLineEdit* numberEdit(double lo, double hi, std::function<double()> get, std::function<void(double)> set);

  Settings& model_;
  std::vector<std::function<void()>> refreshers_;
  std::vector<std::function<void()>> followers_;
  bool refreshing_ = false;
};

// ---- templates -------------------------------------------------------------------

template <class E, class Field>
QComboBox* SettingsBinder::combo(Field field, std::function<bool(E)> keep) {
  auto* box = new QComboBox;
  for (const auto& entry : enumEntries(E{})) {
    if (keep && !keep(entry.value)) continue;
    box->addItem(QString::fromUtf8(entry.name.data(), static_cast<qsizetype>(entry.name.size())),
                 static_cast<int>(entry.value));
    box->setItemData(box->count() - 1, methodToolTip(entry.value), Qt::ToolTipRole);
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
  for (const auto& entry : enumEntries(E{}))
    items.emplace_back(QString::fromUtf8(entry.name.data(), static_cast<qsizetype>(entry.name.size())),
                       methodToolTip(entry.value));
  const auto values = enumEntries(E{});
  return radioBox(
      std::move(items),
      [this, field, values] {
        for (std::size_t i = 0; i < values.size(); ++i)
          if (values[i].value == field(model_)) return static_cast<int>(i);
        return -1;
      },
      [this, field, values](int i) { field(model_) = values[static_cast<std::size_t>(i)].value; });
}

template <class Field>
QCheckBox* SettingsBinder::check(const QString& text, Field field) {
  auto* box = new QCheckBox(text);
  addRefresher([this, box, field] { box->setChecked(field(model_)); });
  connect(box, &QCheckBox::toggled, this, [this, field](bool on) {
    if (refreshing_) return;
    field(model_) = on;
    edited();
  });
  return box;
}

template <class Field>
QSpinBox* SettingsBinder::intSpin(Field field, int lo, int hi, const QString& suffix) {
  auto* box = new QSpinBox;
  box->setRange(lo, hi);
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
QDoubleSpinBox* SettingsBinder::doubleSpin(Field field, double lo, double hi, int decimals, const QString& suffix) {
  auto* box = new QDoubleSpinBox;
  box->setDecimals(decimals);
  box->setRange(lo, hi);
  box->setSuffix(suffix);
  box->setKeyboardTracking(false);
  double step = 1.0;
  for (int i = 0; i < decimals - 1; ++i) step /= 10.0;
  box->setSingleStep(step);
  addRefresher([this, box, field] { box->setValue(field(model_)); });
  connect(box, &QDoubleSpinBox::valueChanged, this, [this, field](double v) {
    if (refreshing_) return;
    field(model_) = v;
    edited();
  });
  return box;
}

template <class Field>
QLineEdit* SettingsBinder::number(Field field, double lo, double hi) {
  return numberEdit(lo, hi, [this, field] { return static_cast<double>(field(model_)); },
                    [this, field](double v) { field(model_) = v; });
}

}  // namespace imagepro::app
