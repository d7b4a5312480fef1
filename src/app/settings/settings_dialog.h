#pragma once
// The Settings menu of thesis appendix A: target dimensions, image plane distance,
// principal point, pixel size, lens distortion, the virtual target's velocities (per
// key press), motion and rendering, and the camera device (camera_settings_page.h).
// Edits a copy; OK or Apply hands it back (camera controls are also set at once).
#include <QDialog>

#include <memory>

#include "app/settings/camera_settings_page.h"
#include "core/settings/settings.h"

namespace Ui {
class SettingsDialog;
}

namespace imagepro::app {

class SettingsBinder;

class SettingsDialog : public QDialog {
  Q_OBJECT

 public:
  // `devices`: the cameras the Camera device page offers and how it sets their controls.
  SettingsDialog(const Settings& settings, QWidget* parent = nullptr,
                 CameraDevices devices = CameraDevices::system());
  ~SettingsDialog() override;

  const Settings& edited() const { return settings_; }
  // Copies the dialog's sections (camera, target, virtual scene, camera source) into `into`.
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
  CameraSettingsPage* camera_page_;
};

}  // namespace imagepro::app
