#pragma once
// The Settings menu of thesis appendix A: target dimensions, image plane distance,
// principal point, pixel size and lens distortion of each source's camera (the source in
// use shown first), the virtual target's velocities (per key press), motion and
// rendering, and the camera device (camera_settings_page.h).
// Edits a copy; OK or Apply hands it back (camera controls are also set at once).
#include <QDialog>

#include <memory>
#include <vector>

#include "app/settings/camera_settings_page.h"
#include "core/settings/settings.h"

class QComboBox;

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
  // Copies the dialog's sections (every source's camera, target, virtual scene, camera
  // source) into `into`; its source in use stays.
  void applyTo(Settings& into) const;
  // Shows and edits `kind`'s camera model on the Camera and Distortion tabs.
  void showSource(SourceKind kind);

 signals:
  void applied();

 private:
  void buildTarget();
  void buildCamera();
  void buildDistortion();
  void buildVirtual();
  void buildScene();
  // A list of the sources choosing whose camera model the tab shows; all such lists agree.
  QComboBox* sourceChooser(const char* name);

  std::unique_ptr<Ui::SettingsDialog> ui_;
  Settings settings_;
  SettingsBinder* binder_;
  CameraSettingsPage* camera_page_;
  std::vector<QComboBox*> source_choosers_;
};

}  // namespace imagepro::app
