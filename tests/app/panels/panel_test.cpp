// Each appendix A panel's controls change the options the worker thread runs with.
#include <QApplication>
#include <QCheckBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QLineEdit>
#include <QPushButton>
#include <QScrollBar>
#include <QWheelEvent>
#include <QSpinBox>
#include <QTest>

#include <QDoubleValidator>

#include <cmath>
#include <limits>

#include "app/analysis/analysis_window.h"
#include "app/panels/control_panel.h"
#include "app/settings/camera_settings_page.h"
#include "app/main_window/main_window.h"
#include "app/settings/settings_dialog.h"
#include "app/worker/worker.h"
#include "app_test_classes.h"
#include "app_test_support.h"

namespace imagepro::app::test {

namespace {

template <class W>
W* find(MainWindow& w, const char* name) {
  return w.findChild<W*>(QLatin1String(name));
}

}  // namespace

void PanelTest::init() {
  window_ = std::make_unique<MainWindow>();
  window_->show();
}

void PanelTest::cleanup() { window_.reset(); }

void PanelTest::thresholdPanel() {
  MainWindow& w = *window_;
  auto* method = find<QComboBox>(w, "thresholdMethod");
  auto* value = find<QSpinBox>(w, "thresholdValue");
  QVERIFY(method && value);
  QVERIFY(choose(method, ThresholdMethod::Manual));
  QVERIFY(value->isEnabled());
  value->setValue(77);
  QVERIFY(waitForApplied(w, [](const Settings& s) {
    return s.pipeline.threshold.method == ThresholdMethod::Manual && s.pipeline.threshold.manual_value == 77;
  }));
  QVERIFY(choose(method, ThresholdMethod::AtOrig));
  QVERIFY(!value->isEnabled());  // "Val" only means something for Manual
  QVERIFY(waitForApplied(w, [](const Settings& s) { return s.pipeline.threshold.method == ThresholdMethod::AtOrig; }));
  // The first thresholding has no by-pass: None is a re-thresholding choice only.
  QCOMPARE(method->findData(static_cast<int>(ThresholdMethod::None)), -1);
}

namespace {

// One notch of the mouse wheel, turned towards the user (down the page), over `widget`.
bool wheelDown(QWidget* widget) {
  const QPointF at(widget->width() / 2.0, widget->height() / 2.0);
  QWheelEvent wheel(at, widget->mapToGlobal(at), QPoint(), QPoint(0, -120), Qt::NoButton, Qt::NoModifier,
                    Qt::NoScrollPhase, false);
  return QApplication::sendEvent(widget, &wheel);
}

}  // namespace

// Scrolling the control panel with the wheel scrolls it, whatever passes under the
// pointer: the lists and number fields keep their values until the user has focused one.
void PanelTest::wheelScrollsThePanelNotItsValues() {
  MainWindow& w = *window_;
  w.resize(1200, 700);  // the panel is taller than its dock: it scrolls
  QTest::qWait(50);
  auto* panel = find<ControlPanel>(w, "controlPanel");
  QScrollBar* scroll = panel->verticalScrollBar();
  QVERIFY(scroll->maximum() > 0);
  auto* rule = find<QComboBox>(w, "ellipseAcceptRule");
  auto* margin = find<QSpinBox>(w, "cropMargin");
  QVERIFY(rule && margin);
  const Settings before = w.settings();
  const int rule_index = rule->currentIndex();
  const int margin_value = margin->value();
  for (QWidget* widget : std::initializer_list<QWidget*>{rule, margin}) {
    QVERIFY(!widget->hasFocus());
    QCOMPARE(widget->focusPolicy(), Qt::StrongFocus);  // the wheel does not focus it either
    const int at = scroll->value();
    wheelDown(widget);
    QVERIFY2(scroll->value() > at, qPrintable(widget->objectName()));
  }
  QCOMPARE(rule->currentIndex(), rule_index);
  QCOMPARE(margin->value(), margin_value);
  QTest::qWait(50);
  QCOMPARE(w.settings().pipeline.ellipse.accept_rule, before.pipeline.ellipse.accept_rule);
  QCOMPARE(w.settings().pipeline.reconstruction.crop_margin_px, before.pipeline.reconstruction.crop_margin_px);

  // Focused (clicked or tabbed to), a field takes the wheel as usual.
  margin->setFocus();
  QTRY_VERIFY(margin->hasFocus());
  const int at = scroll->value();
  wheelDown(margin);
  QCOMPARE(margin->value(), margin_value - 1);
  QCOMPARE(scroll->value(), at);
}

void PanelTest::edgeAndConnectivityPanels() {
  MainWindow& w = *window_;
  QVERIFY(choose(find<QComboBox>(w, "edgeMethod"), EdgeMethod::SobelThinning));
  QVERIFY(choose(find<QComboBox>(w, "connectivityMethod"), ConnectivityMethod::CN0));
  QVERIFY(waitForApplied(w, [](const Settings& s) {
    return s.pipeline.edge_method == EdgeMethod::SobelThinning && s.pipeline.connectivity == ConnectivityMethod::CN0;
  }));
  QVERIFY(choose(find<QComboBox>(w, "edgeMethod"), EdgeMethod::Laplace));
  QVERIFY(choose(find<QComboBox>(w, "connectivityMethod"), ConnectivityMethod::CN1));
  QVERIFY(waitForApplied(w, [](const Settings& s) {
    return s.pipeline.edge_method == EdgeMethod::Laplace && s.pipeline.connectivity == ConnectivityMethod::CN1;
  }));
}

void PanelTest::ellipsePanel() {
  MainWindow& w = *window_;
  const EllipseOptions defaults;
  QVERIFY(choose(find<QComboBox>(w, "ellipseMethod"), EllipseMethod::Bennett));
  auto* min_score = find<QDoubleSpinBox>(w, "bennettMinScore");
  auto* min_peak = find<QDoubleSpinBox>(w, "bennettMinPeakFraction");
  auto* max_points = find<QSpinBox>(w, "bennettMaxPoints");
  QVERIFY(min_score && min_score->isEnabled() && min_peak && min_peak->isEnabled() && max_points && max_points->isEnabled());
  QCOMPARE(min_peak->value(), defaults.bennett_min_peak_fraction);
  QCOMPARE(max_points->value(), defaults.bennett_max_points);
  // The direct fit's own controls mean nothing to Bennett.
  for (const char* name : {"ellipseMinTraced", "ellipseMinArc", "ellipseRobustFit", "ellipseRobustIterations",
                           "ellipseRobustMinTraced"})
    QVERIFY2(!find<QWidget>(w, name)->isEnabled(), name);
  min_score->setValue(500.0);
  find<QDoubleSpinBox>(w, "bennettMaxQuality")->setValue(400.0);
  min_peak->setValue(0.08);
  max_points->setValue(128);
  QVERIFY(waitForApplied(w, [](const Settings& s) {
    const EllipseOptions& e = s.pipeline.ellipse;
    return e.method == EllipseMethod::Bennett && e.bennett_min_score == 500.0 && e.bennett_max_quality == 400.0 &&
           e.bennett_min_peak_fraction == 0.08 && e.bennett_max_points == 128;
  }));
  QVERIFY(choose(find<QComboBox>(w, "ellipseMethod"), EllipseMethod::DirectFit));
  QVERIFY(!min_score->isEnabled() && !min_peak->isEnabled() && !max_points->isEnabled());
  QVERIFY(choose(find<QComboBox>(w, "ellipseAcceptRule"), FitAcceptRule::SampsonDistance));
  find<QDoubleSpinBox>(w, "ellipseMaxSampson")->setValue(0.75);
  find<QSpinBox>(w, "ellipseMinPath")->setValue(33);
  find<QCheckBox>(w, "ellipseReportAll")->click();
  QVERIFY(waitForApplied(w, [](const Settings& s) {
    const EllipseOptions& e = s.pipeline.ellipse;
    return e.method == EllipseMethod::DirectFit && e.accept_rule == FitAcceptRule::SampsonDistance &&
           e.max_sampson_distance_px == 0.75 && e.min_path_pixels == 33 && e.report_all_targets;
  }));
  QVERIFY(!find<QDoubleSpinBox>(w, "ellipseMaxRelativeError")->isEnabled());

  // The trace, the consensus refit for an occluded contour, and target selection.
  auto* robust = find<QCheckBox>(w, "ellipseRobustFit");
  auto* iterations = find<QSpinBox>(w, "ellipseRobustIterations");
  auto* robust_traced = find<QDoubleSpinBox>(w, "ellipseRobustMinTraced");
  QVERIFY(robust && iterations && robust_traced);
  QCOMPARE(robust->isChecked(), defaults.robust_fit);
  QVERIFY(robust->isEnabled() && iterations->isEnabled() && robust_traced->isEnabled());
  robust->click();
  QVERIFY(!iterations->isEnabled() && !robust_traced->isEnabled());  // only mean something with the refit on
  QVERIFY(waitForApplied(w, [](const Settings& s) { return !s.pipeline.ellipse.robust_fit; }));
  robust->click();
  QVERIFY(iterations->isEnabled());
  find<QDoubleSpinBox>(w, "ellipseTraceInlier")->setValue(1.5);
  find<QDoubleSpinBox>(w, "ellipseMinTraced")->setValue(0.9);
  find<QDoubleSpinBox>(w, "ellipseMinArc")->setValue(0.45);
  iterations->setValue(400);
  robust_traced->setValue(0.6);
  find<QDoubleSpinBox>(w, "ellipseSpotTolerance")->setValue(0.35);
  auto* require = find<QCheckBox>(w, "ellipseRequireSpots");
  QCOMPARE(require->isChecked(), defaults.require_target_spots);
  require->click();
  QVERIFY(waitForApplied(w, [defaults](const Settings& s) {
    const EllipseOptions& e = s.pipeline.ellipse;
    return e.robust_fit && e.trace_inlier_px == 1.5 && e.min_traced_fraction == 0.9 && e.min_arc_fraction == 0.45 &&
           e.robust_iterations == 400 && e.robust_min_traced_fraction == 0.6 && e.target_spot_tolerance == 0.35 &&
           e.require_target_spots == !defaults.require_target_spots &&
           e.bennett_min_peak_fraction == 0.08 && e.bennett_max_points == 128;  // kept while unused
  }));
  // Every new control says what it does.
  for (const char* name : {"bennettMinPeakFraction", "bennettMaxPoints", "ellipseTraceInlier", "ellipseMinTraced",
                           "ellipseMinArc", "ellipseRobustFit", "ellipseRobustIterations", "ellipseRobustMinTraced",
                           "ellipseSpotTolerance", "ellipseRequireSpots"})
    QVERIFY2(!find<QWidget>(w, name)->toolTip().isEmpty(), name);
}

void PanelTest::rethresholdPanel() {
  MainWindow& w = *window_;
  auto* method = find<QComboBox>(w, "rethresholdMethod");
  QVERIFY(choose(method, ThresholdMethod::None));
  QVERIFY(waitForApplied(w, [](const Settings& s) { return s.pipeline.rethreshold.method == ThresholdMethod::None; }));
  QVERIFY(choose(method, ThresholdMethod::Manual));
  find<QSpinBox>(w, "rethresholdValue")->setValue(201);
  QVERIFY(waitForApplied(w, [](const Settings& s) {
    return s.pipeline.rethreshold.method == ThresholdMethod::Manual && s.pipeline.rethreshold.manual_value == 201;
  }));
  // The first threshold is untouched.
  QCOMPARE(w.settings().pipeline.threshold.manual_value, Settings{}.pipeline.threshold.manual_value);
}

void PanelTest::reconstructionPanel() {
  MainWindow& w = *window_;
  const bool before = w.settings().pipeline.reconstruction.distortion_correction;
  find<QCheckBox>(w, "distortionCorrection")->click();
  QVERIFY(choose(find<QComboBox>(w, "contourMode"), ContourMode::SubPixel));
  find<QSpinBox>(w, "cropMargin")->setValue(9);
  find<QDoubleSpinBox>(w, "ambiguityMargin")->setValue(0.12);
  find<QDoubleSpinBox>(w, "ambiguityTolerance")->setValue(2.5);
  QVERIFY(waitForApplied(w, [before](const Settings& s) {
    const ReconstructionOptions& r = s.pipeline.reconstruction;
    return r.distortion_correction == !before && r.contour_mode == ContourMode::SubPixel && r.crop_margin_px == 9 &&
           std::abs(r.ambiguity_margin_px - 0.12) < 1e-9 && std::abs(r.ambiguity_tolerance_deg - 2.5) < 1e-9;
  }));
  for (ContourMode m : {ContourMode::EightPointsOrg, ContourMode::EightPointsMod, ContourMode::FullPathOrg}) {
    QVERIFY(choose(find<QComboBox>(w, "contourMode"), m));
    QVERIFY(waitForApplied(w, [m](const Settings& s) { return s.pipeline.reconstruction.contour_mode == m; }));
  }
}

void PanelTest::trackingPanel() {
  MainWindow& w = *window_;
  auto* on = find<QCheckBox>(w, "trackingOn");
  auto* strategy = find<QComboBox>(w, "trackingStrategy");
  QVERIFY(on && strategy);
  if (!on->isChecked()) on->click();
  QVERIFY(choose(strategy, TrackingMode::Parameters3D));
  QVERIFY(waitForApplied(w, [](const Settings& s) { return s.pipeline.tracking.mode == TrackingMode::Parameters3D; }));
  on->click();
  QVERIFY(waitForApplied(w, [](const Settings& s) { return s.pipeline.tracking.mode == TrackingMode::Off; }));
  on->click();  // back on with the strategy still chosen
  QVERIFY(waitForApplied(w, [](const Settings& s) { return s.pipeline.tracking.mode == TrackingMode::Parameters3D; }));
  QVERIFY(choose(strategy, TrackingMode::Corners2D));
  find<QSpinBox>(w, "trackingDataPoints")->setValue(7);
  find<QSpinBox>(w, "trackingDegree")->setValue(3);
  find<QDoubleSpinBox>(w, "trackingMinR")->setValue(0.8);
  find<QDoubleSpinBox>(w, "trackingReduction")->setValue(25.0);
  find<QDoubleSpinBox>(w, "trackingEnlargePx")->setValue(12.0);
  find<QDoubleSpinBox>(w, "trackingEnlargeScale")->setValue(0.25);
  find<QDoubleSpinBox>(w, "trackingEnlargeSpeed")->setValue(0.05);
  QVERIFY(waitForApplied(w, [](const Settings& s) {
    const TrackingOptions& t = s.pipeline.tracking;
    return t.mode == TrackingMode::Corners2D && t.data_points == 7 && t.degree == 3 && t.min_r == 0.8 &&
           t.reduction_percent == 25.0 && t.enlarge_px == 12.0 && t.enlarge_scale == 0.25 && t.enlarge_speed_scale == 0.05;
  }));
}

void PanelTest::applicationPanel() {
  MainWindow& w = *window_;
  auto* level = w.findChild<QWidget*>(QStringLiteral("applicationLevel"));
  for (const auto& entry : enumEntries(ApplicationLevel{})) {
    QVERIFY(chooseRadio(level, entry.value));
    const ApplicationLevel want = entry.value;
    QVERIFY(waitForApplied(w, [want](const Settings& s) { return s.pipeline.level == want; }));
  }
}

void PanelTest::displayPanels() {
  MainWindow& w = *window_;
  QVERIFY(chooseRadio(w.findChild<QWidget*>(QStringLiteral("displayBackground")), DisplayOptions::Background::Binary));
  QVERIFY(chooseRadio(w.findChild<QWidget*>(QStringLiteral("displayEdges")), DisplayOptions::Edges::ConnectedPaths));
  QVERIFY(chooseRadio(w.findChild<QWidget*>(QStringLiteral("displayTarget")), DisplayOptions::Target::Source));
  const DisplayOptions defaults;
  find<QCheckBox>(w, "displayFeatureEdge")->click();
  find<QCheckBox>(w, "displayFeatureSpots")->click();
  QVERIFY(waitForApplied(w, [defaults](const Settings& s) {
    const DisplayOptions& d = s.pipeline.display;
    return d.background == DisplayOptions::Background::Binary && d.edges == DisplayOptions::Edges::ConnectedPaths &&
           d.target == DisplayOptions::Target::Source && d.feature_edge == !defaults.feature_edge &&
           d.feature_spots == !defaults.feature_spots;
  }));
}

void PanelTest::settingsDialog() {
  MainWindow& w = *window_;
  w.findChild<QPushButton*>(QStringLiteral("settingsDialog"))->click();
  auto* dialog = w.findChild<SettingsDialog*>();
  QVERIFY(dialog);
  dialog->findChild<QDoubleSpinBox*>(QStringLiteral("targetRadius"))->setValue(42.5);
  // The Target tab has the card's size too, as the manual says.
  auto* card = dialog->findChild<QDoubleSpinBox*>(QStringLiteral("targetCardSize"));
  QVERIFY(card);
  QCOMPARE(card->property("settingKey").toString(), QStringLiteral("pattern.card_size_mm"));
  QCOMPARE(card->value(), Settings{}.pattern.card_size_mm);
  card->setValue(150.0);
  dialog->findChild<QDoubleSpinBox*>(QStringLiteral("cameraD0"))->setValue(12.0);
  dialog->findChild<QDoubleSpinBox*>(QStringLiteral("virtualKeyStepMm"))->setValue(7.5);
  auto* k1 = dialog->findChild<QLineEdit*>(QStringLiteral("distortionK1"));
  k1->setText(QStringLiteral("-2.05e-07"));
  emit k1->editingFinished();  // (Return would also press the dialog's default button)
  // Nothing reaches the worker before OK.
  QTest::qWait(50);
  QCOMPARE(w.worker()->appliedSettings().target.radius_mm, Settings{}.target.radius_mm);
  dialog->findChild<QDialogButtonBox*>()->button(QDialogButtonBox::Ok)->click();
  QVERIFY(waitForApplied(w, [](const Settings& s) {
    return s.target.radius_mm == 42.5 && s.camera().image_plane_distance_mm == 12.0 && s.virtual_scene.key_step_mm == 7.5 &&
           s.camera().distortion.k1 == -2.05e-7 && s.pattern.card_size_mm == 150.0;
  }));
}

void PanelTest::listsComeFromTheEnumTables() {
  MainWindow& w = *window_;
  auto* edges = find<QComboBox>(w, "edgeMethod");
  QCOMPARE(edges->count(), static_cast<int>(enumEntries(EdgeMethod{}).size()));
  for (int i = 0; i < edges->count(); ++i) {
    const auto value = static_cast<EdgeMethod>(edges->itemData(i).toInt());
    QCOMPARE(edges->itemText(i), labelOf(value));
    QCOMPARE(edges->itemData(i, Qt::ToolTipRole).toString(), entryToolTip(*enumEntry(value)));
  }
  // The lists show the thesis's names, not the settings file's keys.
  const auto texts = [&w](const char* name) {
    QStringList out;
    auto* box = find<QComboBox>(w, name);
    for (int i = 0; box && i < box->count(); ++i) out << box->itemText(i);
    return out;
  };
  QCOMPARE(texts("thresholdMethod"), (QStringList{"Manual", "AT-Orig", "AT-Mod"}));
  QCOMPARE(texts("rethresholdMethod"), (QStringList{"None", "Manual", "AT-Orig", "AT-Mod"}));
  QCOMPARE(texts("connectivityMethod"), (QStringList{"CN0", "CN1"}));
  QCOMPARE(texts("contourMode").first(), QStringLiteral("8 points ORG"));
  QCOMPARE(texts("trackingStrategy"), (QStringList{"2D Corners", "3D Parameters"}));
  QVERIFY(find<QComboBox>(w, "thresholdMethod")->itemData(2, Qt::ToolTipRole).toString().startsWith("AT-Mod: "));
  // The panels start at the defaults of options.h.
  QCOMPARE(edges->currentData().toInt(), static_cast<int>(PipelineOptions{}.edge_method));
  QCOMPARE(find<QSpinBox>(w, "thresholdValue")->value(), ThresholdOptions{}.manual_value);
}

namespace {

bool onCameraDevicePage(const QObject* o) {
  for (; o; o = o->parent())
    if (qobject_cast<const CameraSettingsPage*>(o)) return true;
  return false;
}

// The widget's range against its settings key's; an empty string when they agree.
QString rangeProblem(QWidget* widget, const SettingKey& key) {
  const QString name = widget->objectName() + QStringLiteral(" (") + QString::fromStdString(key.path) + QStringLiteral(")");
  if (auto* spin = qobject_cast<QSpinBox*>(widget)) {
    if (key.type != SettingKey::Type::WholeNumber || spin->minimum() != key.lo || spin->maximum() != key.hi)
      return name + QStringLiteral(": %1..%2 against %3..%4").arg(spin->minimum()).arg(spin->maximum()).arg(key.lo).arg(key.hi);
    return {};
  }
  if (auto* spin = qobject_cast<QDoubleSpinBox*>(widget)) {
    // A bound finer than the box's last place is the first value inside it that the box shows.
    const double place = std::pow(10.0, -spin->decimals());
    const bool lo_ok = spin->minimum() == key.lo || (spin->minimum() > key.lo && spin->minimum() - key.lo < place);
    const bool hi_ok = spin->maximum() == key.hi || (spin->maximum() < key.hi && key.hi - spin->maximum() < place);
    if (key.type != SettingKey::Type::Number || !lo_ok || !hi_ok)
      return name + QStringLiteral(": %1..%2 against %3..%4").arg(spin->minimum()).arg(spin->maximum()).arg(key.lo).arg(key.hi);
    return {};
  }
  if (auto* edit = qobject_cast<QLineEdit*>(widget)) {
    const auto* v = qobject_cast<const QDoubleValidator*>(edit->validator());
    if (!v || v->bottom() != key.lo || v->top() != key.hi) return name + QStringLiteral(": the validator's range differs");
    return {};
  }
  return {};
}

}  // namespace

void PanelTest::rangesComeFromTheSettingsTable() {
  MainWindow& w = *window_;
  w.findChild<QPushButton*>(QStringLiteral("settingsDialog"))->click();
  auto* dialog = w.findChild<SettingsDialog*>();
  QVERIFY(dialog);
  AnalysisWindow analysis(w);
  int numbers = 0, in_analysis = 0;
  for (QWidget* root : {static_cast<QWidget*>(w.controlPanel()), static_cast<QWidget*>(dialog),
                        static_cast<QWidget*>(&analysis)}) {
    for (QWidget* widget : root->findChildren<QWidget*>()) {
      const QString key = widget->property(kSettingKeyProperty).toString();
      const bool number = qobject_cast<QAbstractSpinBox*>(widget) ||
                          (qobject_cast<QLineEdit*>(widget) && !qobject_cast<QAbstractSpinBox*>(widget->parent()));
      // The camera device's controls take the device's ranges; the Analysis window's
      // study parameters (frames, noise, known distance ...) are no settings.
      if (onCameraDevicePage(widget) || (root == &analysis && key.isEmpty())) continue;
      if (!number && key.isEmpty()) continue;
      QVERIFY2(!key.isEmpty(), qPrintable(widget->objectName() + QStringLiteral(" is bound to no settings key")));
      const SettingKey* k = findSettingKey(key.toStdString());
      QVERIFY2(k, qPrintable(key));
      if (!number || k->type == SettingKey::Type::Text) continue;  // a host name is text, not a number
      const QString problem = rangeProblem(widget, *k);
      QVERIFY2(problem.isEmpty(), qPrintable(problem));
      ++numbers;
      in_analysis += root == &analysis;
    }
  }
  QVERIFY(numbers >= 60);
  QCOMPARE(in_analysis, 1);  // the rate for untimed frames: the settings' frame rate
  // The trace's inlier distance has no upper bound in the settings file, so none here.
  auto* trace = find<QDoubleSpinBox>(w, "ellipseTraceInlier");
  QCOMPARE(trace->maximum(), std::numeric_limits<double>::infinity());
  trace->setValue(150.0);
  QVERIFY(waitForApplied(w, [](const Settings& s) { return s.pipeline.ellipse.trace_inlier_px == 150.0; }));
  // "Above zero" in the file is the box's first step above zero.
  QCOMPARE(dialog->findChild<QDoubleSpinBox*>(QStringLiteral("targetRadius"))->minimum(), 0.001);
}

}  // namespace imagepro::app::test
