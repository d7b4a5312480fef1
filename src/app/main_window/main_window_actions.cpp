// MainWindow: menus, file dialogs, settings files, Data Out and Screenshot.
#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QDateTime>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QKeySequence>
#include <QMenuBar>
#include <QMessageBox>
#include <QPixmap>
#include <QPushButton>
#include <QSettings>
#include <QStringList>

#include <functional>

#include "app/analysis/analysis_window.h"
#include "app/calibration_wizard/calibration_wizard.h"
#include "app/calibration_wizard/d0_dialog.h"
#include "app/panels/control_panel.h"
#include "app/main_window/frame_view.h"
#include "app/main_window/main_window.h"
#include "app/main_window/message_banner.h"
#include "app/panels/output_panel.h"
#include "app/main_window/recent_files.h"
#include "app/settings/settings_binder.h"
#include "app/settings/settings_dialog.h"
#include "app/panels/source_panel.h"
#include "app/worker/worker.h"
#include "app/main_window/dialog_folder.h"
#include "core/common/data_directory.h"

namespace imagepro::app {

namespace {
const QString kImageFilter = QObject::tr(
    "Images and videos (*.png *.pgm *.ppm *.pnm *.bmp *.jpg *.jpeg *.tif *.tiff *.avi *.mp4 *.mkv *.mov);;All files (*)");
const QString kSettingsFilter = QObject::tr("Settings (*.json);;All files (*)");
}  // namespace

void MainWindow::buildMenus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  QAction* open = file->addAction(tr("&Open Images..."), this, [this] { openDialog(false); });
  open->setShortcut(QKeySequence::Open);
  file->addAction(tr("Open &Folder..."), this, [this] { openDialog(true); })->setShortcut(QKeySequence(tr("Ctrl+Shift+O")));
  file->addAction(tr("Open S&amples"), this, &MainWindow::openSamples);
  QMenu* recent_menu = file->addMenu(tr("&Recent"));
  recent_ = new RecentFiles(recent_menu, this);
  connect(recent_, &RecentFiles::chosen, this, [this](const QString& path) {
    rememberDialogFolder(path);
    openPaths({path});
  });
  file->addSeparator();
  file->addAction(tr("&Save Settings..."), this, &MainWindow::saveSettingsDialog)->setShortcut(QKeySequence::Save);
  file->addAction(tr("&Load Settings..."), this, &MainWindow::loadSettingsDialog)->setShortcut(QKeySequence(tr("Ctrl+L")));
  file->addAction(tr("Restore &Defaults"), this, &MainWindow::restoreDefaults);
  file->addAction(tr("Se&ttings..."), this, &MainWindow::settingsDialog)->setShortcut(QKeySequence(tr("Ctrl+,")));
  file->addSeparator();
  file->addAction(tr("Screens&hot..."), this, &MainWindow::screenshotDialog)->setShortcut(QKeySequence(tr("Ctrl+Shift+S")));
  freeze_action_ = file->addAction(tr("&Freeze While Saving Screenshot"));
  freeze_action_->setObjectName(QStringLiteral("screenshotFreezeAction"));
  freeze_action_->setCheckable(true);
  connect(freeze_action_, &QAction::toggled, this, &MainWindow::setFreezeOnScreenshot);
  // Checked while Data Out writes; Ctrl+D then switches it off (thesis appendix A's toggle).
  data_out_action_ = file->addAction(tr("Data &Out"));
  data_out_action_->setObjectName(QStringLiteral("dataOutAction"));
  data_out_action_->setCheckable(true);
  data_out_action_->setShortcut(QKeySequence(tr("Ctrl+D")));
  connect(data_out_action_, &QAction::triggered, this, [this] {
    data_out_action_->setChecked(!data_out_path_.isEmpty());  // the worker's answer sets it
    toggleDataOut();
  });
  file->addSeparator();
  file->addAction(tr("&Quit"), this, &QWidget::close)->setShortcut(QKeySequence::Quit);

  QMenu* run = menuBar()->addMenu(tr("&Run"));
  QAction* start_stop = run->addAction(tr("&Start / Stop"), this, [this] {
    if (worker_->isRunning()) stopSource();
    else startSource();
  });
  start_stop->setShortcut(QKeySequence(Qt::Key_F5));
  // The File source's image list; the keys are the frame's (main_window_events.cpp), so a
  // number field keeps its own Page Up / Page Down: shown here, not made shortcuts.
  const struct {
    FileStep step;
    const char* text;
  } steps[] = {{FileStep::First, QT_TR_NOOP("&First Image\tHome")},
               {FileStep::Previous, QT_TR_NOOP("&Previous Image\tLeft, PgUp")},
               {FileStep::Next, QT_TR_NOOP("&Next Image\tRight, PgDown")},
               {FileStep::Last, QT_TR_NOOP("&Last Image\tEnd")}};
  for (const auto& s : steps) run->addAction(tr(s.text), this, [this, step = s.step] { stepFile(step); });
  run->addSeparator();
  for (SourceKind k : kSourceKinds) {
    QAction* a = run->addAction(tr("Source: %1").arg(sourceKindLabel(k)), this, [this, k] { selectSource(k); });
    a->setShortcut(QKeySequence(QStringLiteral("Alt+%1").arg(static_cast<int>(k) + 1)));
  }
  run->addSeparator();
  run->addAction(tr("&Analysis..."), this, [this] {
    auto* analysis = findChild<AnalysisWindow*>();
    if (!analysis) analysis = new AnalysisWindow(*this, this);
    analysis->show();
    analysis->raise();
    analysis->activateWindow();
  })->setShortcut(QKeySequence(tr("Ctrl+Shift+A")));

  QMenu* view = menuBar()->addMenu(tr("&View"));
  view->addAction(tr("Zoom &In"), this, [this] { view_->zoomIn(); })->setShortcut(QKeySequence::ZoomIn);
  view->addAction(tr("Zoom &Out"), this, [this] { view_->zoomOut(); })->setShortcut(QKeySequence::ZoomOut);
  view->addAction(tr("&Fit Frame"), this, [this] { view_->fitToWindow(); })->setShortcut(QKeySequence(tr("Ctrl+0")));
  view->addSeparator();
  for (QDockWidget* dock : findChildren<QDockWidget*>()) view->addAction(dock->toggleViewAction());

  QMenu* tools = menuBar()->addMenu(tr("&Tools"));
  tools->setToolTipsVisible(true);
  tools->addAction(tr("&Calibration Wizard..."), this, [this] { showCalibrationWizard(*this); })
      ->setToolTip(tr("Lens distortion calibration from up to four images of the calibration pattern (thesis 4.6)"));
  tools->addAction(tr("Image Plane &Distance d0..."), this, [this] { showD0Dialog(*this); })
      ->setToolTip(tr("d0 from frames of the target at known distances by the iteration of thesis eq. 4.1"));
  tools->addSeparator();
  // The world frame (settings frames.origin, docs/conventions.md): the shown target's pose now.
  tools->addAction(tr("Set &Origin"), this, [this] {
    if (!latest_ || !ok(latest_->result.status) || !latest_->result.pose) {
      showInfo(tr("Set Origin: no target pose in the frame shown; start the source and show the target first"));
      return;
    }
    Settings s = binder_->model();
    s.frames.origin_set = true;
    s.frames.origin = *latest_->result.pose;
    setSettings(s);
    showInfo(tr("Origin set at target %1's pose: poses are now also given in this world frame (world_* columns)")
                 .arg(latest_->result.target_id));
  })->setToolTip(tr("Store the shown target's current pose as the origin of a world frame; every pose is then also "
                    "given in it"));
  tools->addAction(tr("&Clear Origin"), this, [this] {
    Settings s = binder_->model();
    s.frames.origin_set = false;
    setSettings(s);
    showInfo(tr("Origin cleared: poses are given in the camera frame only"));
  });

  QMenu* set = tools->addMenu(tr("&Targets of the Set"));
  set->setObjectName(QStringLiteral("targetSetMenu"));
  set->setToolTipsVisible(true);
  connect(set, &QMenu::aboutToShow, this, [this, set] { fillTargetSetMenu(*set); });

  QMenu* help = menuBar()->addMenu(tr("&Help"));
  help->addAction(tr("&Keys"), this, &MainWindow::showKeys)->setShortcut(QKeySequence::HelpContents);
  help->addAction(tr("&About ImagePro"), this, [this] {
    QMessageBox::about(this, tr("About ImagePro"),
                       tr("<b>ImagePro %1</b><p>Real-time monocular 3D reconstruction of a secondary passive target: "
                          "a white disk with two black spots, found and reconstructed in every frame.</p>")
                           .arg(QApplication::applicationVersion()));
  });
}

void MainWindow::fillTargetSetMenu(QMenu& menu) {
  menu.clear();
  const Settings& s = binder_->model();
  if (s.targets.empty()) {
    menu.addAction(tr("No set of targets in the settings (its \"targets\" list)"))->setEnabled(false);
    return;
  }
  auto label = [](const TargetSpec& t) {
    return t.name.empty() ? tr("Target %1").arg(t.id) : tr("Target %1, %2").arg(t.id).arg(QString::fromStdString(t.name));
  };
  // One checkable entry of a submenu: choosing it changes the settings' frames live.
  auto entry = [this](QMenu* sub, QActionGroup* group, const QString& name, const QString& text, bool checked,
                      std::function<void(PoseFramesOptions&)> apply, const QString& done) {
    QAction* a = sub->addAction(text);
    a->setObjectName(name);
    a->setCheckable(true);
    a->setChecked(checked);
    group->addAction(a);
    connect(a, &QAction::triggered, this, [this, apply, done] {
      Settings changed = binder_->model();
      apply(changed.frames);
      setSettings(changed);
      showInfo(done);
    });
  };
  const PoseFramesOptions& f = s.frames;

  QMenu* shown = menu.addMenu(tr("&Shown Target"));
  shown->setToolTip(tr("The target whose pose the results, the plots and the frame's own outputs follow"));
  auto* shownGroup = new QActionGroup(shown);
  entry(shown, shownGroup, QStringLiteral("shownTarget_first"), tr("The First Found"), f.shown_target < 0,
        [](PoseFramesOptions& o) { o.shown_target = -1; }, tr("Shown target: the first target found"));
  for (const TargetSpec& t : s.targets)
    entry(shown, shownGroup, QStringLiteral("shownTarget_%1").arg(t.id), label(t), f.shown_target == t.id,
          [id = t.id](PoseFramesOptions& o) { o.shown_target = id; },
          tr("Shown target: %1; the results and plots follow it").arg(label(t)));

  QMenu* reference = menu.addMenu(tr("&Reference Target"));
  reference->setToolTip(tr("Every other target's pose is also given in this target's frame (ref_* columns)"));
  auto* referenceGroup = new QActionGroup(reference);
  entry(reference, referenceGroup, QStringLiteral("referenceTarget_none"), tr("None: the Camera Frame Only"),
        f.reference_target < 0, [](PoseFramesOptions& o) { o.reference_target = -1; },
        tr("Reference target: none; poses are given in the camera frame"));
  for (const TargetSpec& t : s.targets)
    entry(reference, referenceGroup, QStringLiteral("referenceTarget_%1").arg(t.id), label(t),
          f.reference_target == t.id, [id = t.id](PoseFramesOptions& o) { o.reference_target = id; },
          tr("Reference target: %1; the others' poses are also given in its frame").arg(label(t)));

  QMenu* pair = menu.addMenu(tr("&Measured Pair"));
  pair->setToolTip(tr("The distance and angle between two targets, shown live (pair_distance_mm, pair_angle_deg)"));
  auto* pairGroup = new QActionGroup(pair);
  entry(pair, pairGroup, QStringLiteral("measuredPair_none"), tr("None"), f.measured_targets[0] < 0,
        [](PoseFramesOptions& o) { o.measured_targets = {-1, -1}; }, tr("Measured pair: none"));
  for (std::size_t i = 0; i < s.targets.size(); ++i)
    for (std::size_t j = i + 1; j < s.targets.size(); ++j) {
      const TargetSpec &a = s.targets[i], &b = s.targets[j];
      const bool on = (f.measured_targets[0] == a.id && f.measured_targets[1] == b.id) ||
                      (f.measured_targets[0] == b.id && f.measured_targets[1] == a.id);
      entry(pair, pairGroup, QStringLiteral("measuredPair_%1_%2").arg(a.id).arg(b.id),
            tr("%1 and %2").arg(label(a), label(b)), on,
            [ia = a.id, ib = b.id](PoseFramesOptions& o) { o.measured_targets = {ia, ib}; },
            tr("Measured pair: %1 and %2; their distance and angle are shown live").arg(label(a), label(b)));
    }
}

void MainWindow::showKeys() {
  QMessageBox::information(this, tr("Keys"),
                           tr("<p>With the Virtual source, these keys move the target (thesis appendix A):</p>"
                              "<table><tr><td>4 / 6</td><td>Tx - / +</td></tr><tr><td>2 / 8</td><td>Ty - / +</td></tr>"
                              "<tr><td>Insert / Delete</td><td>Tz - / +</td></tr><tr><td>Up / Down</td><td>Rx - / +</td></tr>"
                              "<tr><td>Left / Right</td><td>Ry - / +</td></tr><tr><td>Home / End</td><td>Rz - / +</td></tr></table>"
                              "<p>With the File source and a list of images open, Right or Page Down shows the next "
                              "image, Left or Page Up the previous one, Home the first and End the last.</p>"
                              "<p>F5 start / stop, Ctrl+O open, Ctrl+S / Ctrl+L save / load settings, Ctrl+Shift+S screenshot, "
                              "Ctrl+D data out on / off, Ctrl+0 fit, Ctrl++ / Ctrl+- zoom. The keys do not reach the target "
                              "while a number or list field has the focus: click the frame first.</p>"));
}

void MainWindow::openDialog(bool folder) {
  QStringList paths;
  if (folder) {
    const QString dir = QFileDialog::getExistingDirectory(this, tr("Open an image folder"), dialogFolder());
    if (!dir.isEmpty()) paths << dir;
  } else {
    paths = QFileDialog::getOpenFileNames(this, tr("Open images"), dialogFolder(), kImageFilter);
  }
  if (!paths.isEmpty()) rememberDialogFolder(paths.front());
  openPaths(paths);
}

void MainWindow::openSamples() {
  const std::filesystem::path data = dataDirectory();
  const QString samples = data.empty() ? QString() : QString::fromStdString((data / "samples").string());
  if (samples.isEmpty() || !QFileInfo(samples).isDir()) {
    showError(tr("The sample frames are not installed"));
    return;
  }
  openPaths({samples});  // the dialogs stay where the user was: not the shipped folder
}

bool MainWindow::loadSettingsFile(const QString& path) {
  Settings loaded = settings_;
  std::string error;
  std::vector<std::string> warnings;
  if (!ok(loadSettings(path.toStdString(), loaded, error, &warnings))) {
    showError(tr("Settings not loaded from %1: %2").arg(QFileInfo(path).fileName(), QString::fromStdString(error)));
    return false;
  }
  if (!mayLoseCalibration(tr("loading %1").arg(QFileInfo(path).fileName()), &loaded)) {
    showInfo(tr("Settings not loaded from %1: the calibration in use is kept").arg(QFileInfo(path).fileName()));
    return false;
  }
  setSettings(loaded);
  banner_->hide();  // an earlier load's error is over
  QStringList notes;
  for (const std::string& w : warnings) notes << QString::fromStdString(w);
  if (!notes.isEmpty()) banner_->showWarning(notes.join(QLatin1Char('\n')));
  showInfo(tr("Settings loaded from %1").arg(path));
  return true;
}

bool MainWindow::saveSettingsFile(const QString& path) {
  std::string error;
  if (!ok(saveSettings(path.toStdString(), settings_, error))) {
    showError(tr("Settings not saved: %1").arg(QString::fromStdString(error)));
    return false;
  }
  calibrationSaved(settings_);
  showInfo(tr("Settings saved to %1").arg(path));
  return true;
}

namespace {

bool sameCamera(const CameraModel& a, const CameraModel& b) {
  const Distortion &d = a.distortion, &e = b.distortion;
  return a.width == b.width && a.height == b.height && a.pixel_size_mm == b.pixel_size_mm &&
         a.image_plane_distance_mm == b.image_plane_distance_mm && a.principal_point_px == b.principal_point_px &&
         d.k1 == e.k1 && d.k2 == e.k2 && d.p1 == e.p1 && d.p2 == e.p2;
}

}  // namespace

void MainWindow::calibrationInUse() { unsaved_calibration_.emplace(settings_.source, settings_.camera()); }

void MainWindow::calibrationSaved(const Settings& saved) {
  if (unsaved_calibration_ && sameCamera(saved.camera(unsaved_calibration_->first), unsaved_calibration_->second))
    unsaved_calibration_.reset();
}

bool MainWindow::hasUnsavedCalibration() const {
  // Replaced since (another file loaded, the defaults, an edit): nothing of it is left to lose.
  return unsaved_calibration_ &&
         sameCamera(settings_.camera(unsaved_calibration_->first), unsaved_calibration_->second);
}

bool MainWindow::mayLoseCalibration(const QString& action, const Settings* next) {
  if (!hasUnsavedCalibration()) return true;
  if (next && sameCamera(next->camera(unsaved_calibration_->first), unsaved_calibration_->second)) return true;
  QMessageBox ask(QMessageBox::Warning, tr("Unsaved calibration"),
                  tr("The %1 source's camera has a calibration set and in use that has not been saved: %2 "
                     "loses it. Save the settings first?")
                      .arg(sourceKindLabel(unsaved_calibration_->first), action),
                  QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, this);
  ask.setObjectName(QStringLiteral("unsavedCalibration"));
  ask.setDefaultButton(QMessageBox::Save);
  switch (ask.exec()) {
    case QMessageBox::Save:
      saveSettingsDialog();
      return !hasUnsavedCalibration();  // saved: go on; the dialog cancelled or the save failed: stay
    case QMessageBox::Discard:
      return true;
    default:
      return false;
  }
}

void MainWindow::saveSettingsDialog() {
  const QString path = QFileDialog::getSaveFileName(
      this, tr("Save settings"), dialogFolderWith(QStringLiteral("settings.json")), kSettingsFilter);
  if (path.isEmpty()) return;
  rememberDialogFolder(path);
  saveSettingsFile(path);
}

void MainWindow::loadSettingsDialog() {
  const QString path = QFileDialog::getOpenFileName(this, tr("Load settings"), dialogFolder(), kSettingsFilter);
  if (path.isEmpty()) return;
  rememberDialogFolder(path);
  loadSettingsFile(path);
}

void MainWindow::settingsDialog() {
  // Camera controls go through the worker, which sets them on the streaming camera.
  CameraDevices devices = CameraDevices::system();
  devices.set = [worker = worker_](const std::string& device, const std::string& key, std::int64_t value) {
    worker->setCameraControl(QString::fromStdString(device), QString::fromStdString(key), value);
    return std::string();  // a refusal arrives as the worker's error
  };
  auto* dialog = new SettingsDialog(settings_, this, std::move(devices));
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  connect(dialog, &SettingsDialog::applied, this, [this, dialog] {
    Settings next = settings_;
    dialog->applyTo(next);
    setSettings(next);
  });
  dialog->open();
}

bool MainWindow::saveScreenshot(const QString& path) {
  const QPixmap shot = results_area_->grab();
  if (shot.isNull() || !shot.save(path, "PNG")) {
    showError(tr("Screenshot not saved: %1 cannot be written").arg(path));
    return false;
  }
  showInfo(tr("Screenshot saved to %1").arg(path));
  return true;
}

void MainWindow::setFreezeOnScreenshot(bool on) {
  if (freeze_action_ && freeze_action_->isChecked() != on) freeze_action_->setChecked(on);  // comes back here
  control_panel_->outputPanel()->setFreezeOnScreenshot(on);
  QSettings().setValue(QStringLiteral("screenshot/freeze"), on);
}

bool MainWindow::freezeOnScreenshot() const { return freeze_action_ && freeze_action_->isChecked(); }

void MainWindow::screenshotDialog() {
  // Taken now, so the picture is the frame on screen when the button was pressed.
  const QPixmap shot = results_area_->grab();
  // With the option, a live source stops until the file is chosen: the results area keeps
  // showing the frame of the screenshot (thesis A.1.1). Files are not live: they go on.
  const SourceKind kind = control_panel_->sourcePanel()->kind();
  const bool freeze = freezeOnScreenshot() && worker_->isRunning() && kind != SourceKind::File;
  if (freeze) {
    frozen_for_screenshot_ = true;
    worker_->stop();
    showInfo(tr("Processing frozen while the screenshot is saved"));
  }
  const QString name = QStringLiteral("imagepro-%1.png").arg(QDateTime::currentDateTime().toString(QStringLiteral("yyyyMMdd-hhmmss")));
  const QString path = QFileDialog::getSaveFileName(this, tr("Save screenshot"), dialogFolderWith(name),
                                                    tr("PNG images (*.png)"));
  if (!path.isEmpty()) {
    rememberDialogFolder(path);
    if (!shot.save(path, "PNG")) showError(tr("Screenshot not saved: %1 cannot be written").arg(path));
    else showInfo(tr("Screenshot saved to %1").arg(path));
  }
  if (freeze) {
    frozen_for_screenshot_ = false;
    worker_->start(kind);
  }
}

namespace {

// Data Out's file by its name: CSV text, as .csv or the thesis's .txt. A name without an
// extension gets .csv; any other extension (an image's, say) is refused: empty.
QString dataOutFileName(const QString& path) {
  const QFileInfo info(path);
  const QString suffix = info.suffix().toLower();
  if (suffix == QLatin1String("csv") || suffix == QLatin1String("txt")) return path;
  if (suffix.isEmpty() && !info.fileName().isEmpty()) return path + QStringLiteral(".csv");
  return {};
}

}  // namespace

bool MainWindow::startDataOut(const QString& path, ExistingFile existing, bool replace) {
  if (dataOutFileName(path) != path) {
    showError(tr("Data Out not started: it writes CSV text, so the file's name must end in .csv or .txt, not "
                 "\"%1\"").arg(QFileInfo(path).fileName()));
    return false;
  }
  worker_->setDataOut(path, existing, replace);
  return true;
}

void MainWindow::stopDataOut() { worker_->closeDataOut(); }

void MainWindow::toggleDataOut() {
  if (!data_out_path_.isEmpty()) stopDataOut();
  else dataOutDialog(true);
}

void MainWindow::dataOutDialog(bool on) {
  if (!on) {
    stopDataOut();
    return;
  }
  // Unticked until the worker confirms the file is open.
  control_panel_->outputPanel()->setDataOutPath(data_out_path_);
  const QString chosen = QFileDialog::getSaveFileName(this, tr("Data Out: write the parameters to"),
                                                      dialogFolderWith(QStringLiteral("dataout.csv")),
                                                      tr("CSV files (*.csv *.txt)"), nullptr,
                                                      QFileDialog::DontConfirmOverwrite);
  if (chosen.isEmpty()) return;
  rememberDialogFolder(chosen);
  const QString path = dataOutFileName(chosen);
  if (path.isEmpty()) {
    startDataOut(chosen, ExistingFile::Fail, false);  // refused, the reason shown
    return;
  }
  if (path != chosen) showInfo(tr("Data Out writes CSV: the file is %1").arg(QFileInfo(path).fileName()));
  if (!QFileInfo::exists(path)) {
    startDataOut(path, ExistingFile::Fail, false);
    return;
  }
  QMessageBox ask(QMessageBox::Question, tr("Data Out"),
                  tr("%1 already exists. Add the new rows to its end, write to a new numbered file beside it, or "
                     "replace it?").arg(QFileInfo(path).fileName()),
                  QMessageBox::Cancel, this);
  QPushButton* append = ask.addButton(tr("Append"), QMessageBox::AcceptRole);
  QPushButton* numbered = ask.addButton(tr("New File"), QMessageBox::AcceptRole);
  QPushButton* replace = ask.addButton(tr("Replace"), QMessageBox::DestructiveRole);
  ask.setDefaultButton(append);
  ask.exec();
  if (ask.clickedButton() == append) startDataOut(path, ExistingFile::Append, false);
  else if (ask.clickedButton() == numbered) startDataOut(path, ExistingFile::NewName, false);
  else if (ask.clickedButton() == replace) startDataOut(path, ExistingFile::Fail, true);
}

}  // namespace imagepro::app
