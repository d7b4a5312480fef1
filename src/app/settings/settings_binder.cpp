#include "app/settings/settings_binder.h"

#include <QButtonGroup>
#include <QDoubleValidator>
#include <QRadioButton>
#include <QVBoxLayout>

namespace imagepro::app {

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

QLineEdit* SettingsBinder::numberEdit(double lo, double hi, std::function<double()> get,
                                      std::function<void(double)> set) {
  auto* edit = new QLineEdit;
  auto* validator = new QDoubleValidator(lo, hi, 17, edit);
  validator->setNotation(QDoubleValidator::ScientificNotation);
  validator->setLocale(QLocale::c());
  edit->setValidator(validator);
  addRefresher([edit, get] { edit->setText(QString::number(get(), 'g', 12)); });
  connect(edit, &QLineEdit::editingFinished, this, [this, edit, get, set] {
    if (refreshing_) return;
    bool ok = false;
    const double v = QLocale::c().toDouble(edit->text(), &ok);
    if (!ok || v == get()) return;
    set(v);
    edited();
  });
  return edit;
}

}  // namespace imagepro::app
