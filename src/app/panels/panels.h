#pragma once
// The content of each appendix A panel, its controls bound to the Settings model.
// Every control has an objectName (used by the tests and the layout memory).
#include <QWidget>

#include "app/settings/settings_binder.h"

namespace imagepro::app {

// method_panels.cpp
QWidget* thresholdPanel(SettingsBinder& binder);
QWidget* edgePanel(SettingsBinder& binder);
QWidget* connectivityPanel(SettingsBinder& binder);
QWidget* ellipsePanel(SettingsBinder& binder);
QWidget* rethresholdPanel(SettingsBinder& binder);
QWidget* reconstructionPanel(SettingsBinder& binder);
// tracking_panels.cpp
QWidget* trackingPanel(SettingsBinder& binder);
QWidget* applicationPanel(SettingsBinder& binder);
// display_panels.cpp
QWidget* backgroundDisplayPanel(SettingsBinder& binder);
QWidget* edgeDisplayPanel(SettingsBinder& binder);
QWidget* targetDisplayPanel(SettingsBinder& binder);
QWidget* featuresDisplayPanel(SettingsBinder& binder);

// Gives `w` an objectName and a tooltip, and returns it.
template <class W>
W* named(W* w, const char* name, const QString& tooltip = {}) {
  w->setObjectName(QLatin1String(name));
  if (!tooltip.isEmpty()) w->setToolTip(tooltip);
  return w;
}

}  // namespace imagepro::app
