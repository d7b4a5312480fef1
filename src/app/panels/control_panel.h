#pragma once
// The control panel (thesis appendix A.1.1): every sub-panel as a collapsible
// group in one scrollable column, all bound to the one Settings model.
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

 private:
  void addGroup(const QString& title, const QString& tooltip, QWidget* content);

  SourcePanel* source_;
  OutputPanel* output_;
  CalibrationPanel* calibration_;
  std::vector<CollapsibleGroup*> groups_;
  QWidget* column_;
};

}  // namespace imagepro::app
