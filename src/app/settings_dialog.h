#pragma once
// The Settings menu of thesis appendix A: target dimensions, image plane distance,
// principal point, pixel size, lens distortion, and the virtual target's velocities
// (per key press), motion and rendering. Edits a copy; OK or Apply hands it back.
#include <QDialog>

#include <memory>

#include "core/settings/settings.h"

namespace Ui {
class SettingsDialog;
}

namespace imagepro::app {

class SettingsBinder;

class SettingsDialog : public QDialog {
  Q_OBJECT

 public:
  SettingsDialog(const Settings& settings, QWidget* parent = nullptr);
  ~SettingsDialog() override;

  const Settings& edited() const { return settings_; }
  // Copies the dialog's sections (camera, target, virtual scene) into `into`.
  void applyTo(Settings& into) const;

 signals:
  void applied();

 private:
  void buildTarget();
  void buildCamera();
  void buildDistortion();
  void buildVirtual();
  void buildScene();

  std::unique_ptr<Ui::SettingsDialog> ui_;
  Settings settings_;
  SettingsBinder* binder_;
};

}  // namespace imagepro::app
