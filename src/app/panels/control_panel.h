#pragma once
// The control panel (thesis appendix A.1.1): every sub-panel as a collapsible
// group in one scrollable column, all bound to the one Settings model. The mouse wheel
// scrolls the column: a list, number field or slider takes the wheel only once it has
// the keyboard focus (clicked or tabbed to), so scrolling past it changes nothing.
#include <QScrollArea>
#include <QStringList>

#include <vector>

#include "app/settings/settings_binder.h"

class QSettings;

namespace imagepro::app {

class CalibrationPanel;
class CollapsibleGroup;
class OutputPanel;
class SourcePanel;

class ControlPanel : public QScrollArea {
  Q_OBJECT

 public:
  ControlPanel(SettingsBinder& binder, QWidget* parent = nullptr);

  SourcePanel* sourcePanel() const { return source_; }
  OutputPanel* outputPanel() const { return output_; }
  CalibrationPanel* calibrationPanel() const { return calibration_; }
  const std::vector<CollapsibleGroup*>& groups() const { return groups_; }

  // Which groups are folded, remembered between runs.
  void saveState(QSettings& store) const;
  void restoreState(const QSettings& store);

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  void addGroup(const QString& title, const QString& tooltip, QWidget* content);

  SourcePanel* source_;
  OutputPanel* output_;
  CalibrationPanel* calibration_;
  std::vector<CollapsibleGroup*> groups_;
  QWidget* column_;
};

}  // namespace imagepro::app
