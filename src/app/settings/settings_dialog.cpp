#include "app/settings/settings_dialog.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QPushButton>
#include <QSignalBlocker>

#include "app/panels/panels.h"
#include "app/settings/settings_binder.h"
#include "app/worker/source_kind.h"
#include "ui_settings_dialog.h"

namespace imagepro::app {

namespace {
const QString kMm = QStringLiteral(" mm");
const QString kDeg = QStringLiteral(" deg");
const QString kPx = QStringLiteral(" px");
const char* const kPoseParameterNames[] = {"Rx", "Ry", "Rz", "Tx", "Ty", "Tz"};

// Parameter i of a pose-shaped group, in the pose's order (Rx, Ry, Rz, Tx, Ty, Tz).
double& poseParameter(Pose& p, int i) {
  double* fields[] = {&p.rx_deg, &p.ry_deg, &p.rz_deg, &p.tx_mm, &p.ty_mm, &p.tz_mm};
  return *fields[i];
}
}  // namespace

SettingsDialog::SettingsDialog(const Settings& settings, QWidget* parent, CameraDevices devices)
    : QDialog(parent), ui_(std::make_unique<Ui::SettingsDialog>()), settings_(settings),
      binder_(new SettingsBinder(settings_, this)) {
  ui_->setupUi(this);
  camera_page_ = new CameraSettingsPage(settings_, std::move(devices));
  ui_->tabs->insertTab(ui_->tabs->indexOf(ui_->cameraTab) + 1, camera_page_, tr("Camera device"));
  buildTarget();
  buildCamera();
  buildDistortion();
  buildVirtual();
  buildScene();
  binder_->refresh();
  connect(binder_, &SettingsBinder::changed, camera_page_, &CameraSettingsPage::cameraModelChanged);
  ui_->note->setText(tr("Each source has its own camera model and distortion (thesis A.3); the virtual source "
                        "renders with its own. The source in use is the one shown first."));
  connect(ui_->buttons, &QDialogButtonBox::accepted, this, [this] {
    emit applied();
    accept();
  });
  connect(ui_->buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  connect(ui_->buttons->button(QDialogButtonBox::Apply), &QPushButton::clicked, this, &SettingsDialog::applied);
}

SettingsDialog::~SettingsDialog() = default;

void SettingsDialog::applyTo(Settings& into) const {
  into.cameras = settings_.cameras;
  into.target = settings_.target;
  into.pattern.card_size_mm = settings_.pattern.card_size_mm;  // the only pattern key shown here
  into.virtual_scene = settings_.virtual_scene;
  into.camera_source = settings_.camera_source;
}

void SettingsDialog::buildTarget() {
  auto* f = ui_->targetForm;
  auto& b = *binder_;
  f->addRow(tr("Disk radius R"), named(b.doubleSpin([](Settings& s) -> auto& { return s.target.radius_mm; }, 3, kMm),
                                       "targetRadius", tr("Radius of the white disk")));
  f->addRow(tr("Spot radius r0"), named(b.doubleSpin([](Settings& s) -> auto& { return s.target.spot_radius_mm; }, 3, kMm),
                                        "targetSpotRadius", tr("Radius of the two black spots")));
  f->addRow(tr("Spot offset rf"), named(b.doubleSpin([](Settings& s) -> auto& { return s.target.spot_offset_mm; }, 3, kMm),
                                        "targetSpotOffset", tr("Distance between the centres of the two spots")));
  f->addRow(tr("Card size"), named(b.doubleSpin([](Settings& s) -> auto& { return s.pattern.card_size_mm; }, 1, kMm),
                                   "targetCardSize",
                                   tr("Side of the black square card the target is on; the calibration pattern has "
                                      "no grid spots on it")));
}

QComboBox* SettingsDialog::sourceChooser(const char* name) {
  auto* combo = new QComboBox;
  combo->setObjectName(QLatin1String(name));
  for (const SourceKind k : kSourceKinds) combo->addItem(sourceKindLabel(k), static_cast<int>(k));
  combo->setCurrentIndex(combo->findData(static_cast<int>(settings_.source)));
  combo->setToolTip(tr("Whose camera model the fields below show and edit: each source has its own"));
  connect(combo, &QComboBox::currentIndexChanged, this, [this, combo] {
    settings_.source = static_cast<SourceKind>(combo->currentData().toInt());
    for (QComboBox* other : source_choosers_) {
      const QSignalBlocker block(other);
      other->setCurrentIndex(combo->currentIndex());
    }
    binder_->refresh();
    camera_page_->cameraModelChanged();
  });
  source_choosers_.push_back(combo);
  return combo;
}

void SettingsDialog::showSource(SourceKind kind) {
  source_choosers_.front()->setCurrentIndex(source_choosers_.front()->findData(static_cast<int>(kind)));
}

void SettingsDialog::buildCamera() {
  auto* f = ui_->cameraForm;
  auto& b = *binder_;
  f->addRow(tr("Camera model of"), sourceChooser("cameraModelSource"));
  f->addRow(tr("Width"), named(b.intSpin([](Settings& s) -> auto& { return s.camera().width; }, kPx), "cameraWidth"));
  f->addRow(tr("Height"), named(b.intSpin([](Settings& s) -> auto& { return s.camera().height; }, kPx), "cameraHeight"));
  f->addRow(tr("Image plane distance d0"),
            named(b.doubleSpin([](Settings& s) -> auto& { return s.camera().image_plane_distance_mm; }, 4, kMm),
                  "cameraD0", tr("Distance of the image plane from the projection centre (thesis 4.2)")));
  f->addRow(tr("Principal point u0"),
            named(b.doubleSpin([](Settings& s) -> auto& { return s.camera().principal_point_px[0]; }, 2, kPx), "cameraU0"));
  f->addRow(tr("Principal point v0"),
            named(b.doubleSpin([](Settings& s) -> auto& { return s.camera().principal_point_px[1]; }, 2, kPx), "cameraV0"));
  f->addRow(tr("Pixel size sx"), named(b.number([](Settings& s) -> auto& { return s.camera().pixel_size_mm[0]; }), "cameraSx",
                                       tr("mm per pixel, horizontal")));
  f->addRow(tr("Pixel size sy"), named(b.number([](Settings& s) -> auto& { return s.camera().pixel_size_mm[1]; }), "cameraSy",
                                       tr("mm per pixel, vertical")));
}

void SettingsDialog::buildDistortion() {
  auto* f = ui_->distortionForm;
  auto& b = *binder_;
  f->addRow(tr("Distortion of"), sourceChooser("distortionSource"));
  f->addRow(tr("k1 (px^-2)"), named(b.number([](Settings& s) -> auto& { return s.camera().distortion.k1; }), "distortionK1",
                                     tr("Radial distortion, second order (thesis eq. 4.7)")));
  f->addRow(tr("k2 (px^-4)"), named(b.number([](Settings& s) -> auto& { return s.camera().distortion.k2; }), "distortionK2",
                                     tr("Radial distortion, fourth order (thesis eq. 4.7)")));
  f->addRow(tr("p1 (px^-1)"), named(b.number([](Settings& s) -> auto& { return s.camera().distortion.p1; }), "distortionP1",
                                     tr("Tangential distortion (thesis eq. 4.5)")));
  f->addRow(tr("p2 (px^-1)"), named(b.number([](Settings& s) -> auto& { return s.camera().distortion.p2; }), "distortionP2",
                                     tr("Tangential distortion (thesis eq. 4.5)")));
}

void SettingsDialog::buildVirtual() {
  auto* f = ui_->virtualForm;
  auto& b = *binder_;
  auto v = [](Settings& s) -> VirtualSceneOptions& { return s.virtual_scene; };
  f->addRow(tr("Frame rate"), named(b.doubleSpin([v](Settings& s) -> auto& { return v(s).frame_rate_hz; }, 2, QStringLiteral(" Hz")),
                                    "virtualFrameRate"));
  f->addRow(tr("Translation per key"), named(b.doubleSpin([v](Settings& s) -> auto& { return v(s).key_step_mm; }, 2, kMm),
                                             "virtualKeyStepMm", tr("How far 4/6, 2/8 and Insert/Delete move the target")));
  f->addRow(tr("Rotation per key"), named(b.doubleSpin([v](Settings& s) -> auto& { return v(s).key_step_deg; }, 2, kDeg),
                                          "virtualKeyStepDeg", tr("How far the arrows and Home/End turn the target")));
  f->addRow(tr("Motion"), named(b.combo<MotionKind>([v](Settings& s) -> auto& { return v(s).motion.kind; }), "virtualMotion"));
  f->addRow(tr("Axis"), named(b.combo<PoseAxis>([v](Settings& s) -> auto& { return v(s).motion.axis; }), "virtualAxis"));
  f->addRow(tr("Amplitude"), named(b.doubleSpin([v](Settings& s) -> auto& { return v(s).motion.amplitude; }, 2),
                                   "virtualAmplitude", tr("mm for translations, degrees for rotations")));
  f->addRow(tr("Period"), named(b.doubleSpin([v](Settings& s) -> auto& { return v(s).motion.period_s; }, 3, QStringLiteral(" s")),
                                "virtualPeriod"));
  f->addRow(tr("Pendulum length"), named(b.doubleSpin([v](Settings& s) -> auto& { return v(s).pendulum.length_mm; }, 1, kMm),
                                         "pendulumLength", tr("Pivot to target centre (thesis 5.3.2)")));
  f->addRow(tr("Pendulum amplitude"), named(b.doubleSpin([v](Settings& s) -> auto& { return v(s).pendulum.amplitude_deg; }, 2, kDeg),
                                            "pendulumAmplitude"));
  const char* pose_labels[] = {"Start Rx", "Start Ry", "Start Rz", "Start Tx", "Start Ty", "Start Tz"};
  const char* pose_names[] = {"virtualStartRx", "virtualStartRy", "virtualStartRz",
                              "virtualStartTx", "virtualStartTy", "virtualStartTz"};
  for (int i = 0; i < 6; ++i) {
    const bool angle = i < 3;
    f->addRow(tr(pose_labels[i]),
              named(b.doubleSpin([v, i](Settings& s) -> double& { return poseParameter(v(s).initial_pose, i); }, 2,
                                 angle ? kDeg : kMm),
                    pose_names[i]));
  }
  // The constant-velocity motion (thesis A.2): three parameters a row, named
  // <name>Rx ... <name>Tz.
  const auto triple = [&](const QString& label, Pose& (*group)(Settings&), const char* name, int first,
                          const QString& suffix, const QString& tooltip) {
    auto* row = new QWidget;
    auto* layout = new QHBoxLayout(row);
    layout->setContentsMargins(0, 0, 0, 0);
    for (int i = first; i < first + 3; ++i) {
      const QString object = QLatin1String(name) + QLatin1String(kPoseParameterNames[i]);
      auto* box = b.doubleSpin([group, i](Settings& s) -> double& { return poseParameter(group(s), i); }, 1, suffix);
      box->setObjectName(object);
      box->setToolTip(tooltip);
      layout->addWidget(box);
    }
    f->addRow(label, row);
  };
  const auto velocity = [](Settings& s) -> Pose& { return s.virtual_scene.motion.velocity; };
  const auto box = [](Settings& s) -> Pose& { return s.virtual_scene.motion.wrap_box; };
  const QString velocity_tip = tr("Constant velocity motion: how fast each parameter changes");
  const QString box_tip = tr("Constant velocity motion: the parameter wraps around inside this width centred on "
                             "its start value (0: it never wraps)");
  triple(tr("Velocity Rx Ry Rz"), velocity, "virtualVelocity", 0, QStringLiteral(" deg/s"), velocity_tip);
  triple(tr("Velocity Tx Ty Tz"), velocity, "virtualVelocity", 3, QStringLiteral(" mm/s"), velocity_tip);
  triple(tr("Wrap box Rx Ry Rz"), box, "virtualWrapBox", 0, kDeg, box_tip);
  triple(tr("Wrap box Tx Ty Tz"), box, "virtualWrapBox", 3, kMm, box_tip);
}

void SettingsDialog::buildScene() {
  auto* f = ui_->sceneForm;
  auto& b = *binder_;
  auto v = [](Settings& s) -> VirtualSceneOptions& { return s.virtual_scene; };
  f->addRow(tr("Rendering"), named(b.combo<RenderMode>([v](Settings& s) -> auto& { return v(s).mode; }), "virtualRenderMode"));
  f->addRow(tr("Backdrop"), named(b.combo<Backdrop>([v](Settings& s) -> auto& { return v(s).backdrop; }), "virtualBackdrop"));
  f->addRow(tr("Supersampling"), named(b.intSpin([v](Settings& s) -> auto& { return v(s).supersampling; }), "virtualSupersampling"));
  f->addRow(tr("Blur sigma"), named(b.doubleSpin([v](Settings& s) -> auto& { return v(s).blur_sigma_px; }, 2, kPx), "virtualBlur"));
  f->addRow(tr("Noise sigma"), named(b.doubleSpin([v](Settings& s) -> auto& { return v(s).noise_sigma; }, 1), "virtualNoise",
                                     tr("Gaussian noise, grey levels")));
  f->addRow(tr("Illumination gradient"),
            named(b.doubleSpin([v](Settings& s) -> auto& { return v(s).illumination_gradient; }, 2), "virtualGradient",
                  tr("Fractional brightness change across the width")));
  f->addRow(tr("Clutter"), named(b.intSpin([v](Settings& s) -> auto& { return v(s).clutter; }), "virtualClutter",
                                 tr("Number of white bars and rectangles")));
  f->addRow(tr("White level"), named(b.intSpin([v](Settings& s) -> auto& { return v(s).white_level; }), "virtualWhite"));
  f->addRow(tr("Black level"), named(b.intSpin([v](Settings& s) -> auto& { return v(s).black_level; }), "virtualBlack"));
  f->addRow(tr("Background level"), named(b.intSpin([v](Settings& s) -> auto& { return v(s).background_level; }), "virtualBackground"));
  f->addRow(tr("Card size"), named(b.doubleSpin([v](Settings& s) -> auto& { return v(s).card_size_mm; }, 1, kMm), "virtualCard"));
}

}  // namespace imagepro::app
