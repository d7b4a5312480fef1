// Save / Load / Restore defaults through the window, and files that cannot be used.
#include <QCheckBox>
#include <QComboBox>
#include <QDockWidget>
#include <QFile>
#include <QDoubleSpinBox>
#include <QSpinBox>
#include <QMenu>
#include <QTest>

#include "app/panels/collapsible_group.h"
#include "app/panels/control_panel.h"
#include "app/main_window/main_window.h"
#include "app/worker/worker.h"
#include "app_test_classes.h"
#include "app_test_support.h"

namespace imagepro::app::test {

namespace {

std::string json(const Settings& s) { return settingsToJson(s); }

void writeText(const QString& path, const char* text) {
  QFile f(path);
  QVERIFY(f.open(QIODevice::WriteOnly));
  f.write(text);
}

}  // namespace

void SettingsFileTest::init() {
  window_ = std::make_unique<MainWindow>();
  window_->show();
}

void SettingsFileTest::cleanup() { window_.reset(); }

void SettingsFileTest::roundTrip() {
  MainWindow& w = *window_;
  const QString path = scratchDir(QStringLiteral("settings")) + QStringLiteral("/mine.json");
  auto* method = w.findChild<QComboBox*>(QStringLiteral("thresholdMethod"));
  auto* value = w.findChild<QSpinBox*>(QStringLiteral("thresholdValue"));
  QVERIFY(choose(method, ThresholdMethod::Manual));
  value->setValue(77);
  QVERIFY(choose(w.findChild<QComboBox*>(QStringLiteral("edgeMethod")), EdgeMethod::SobelThinning));
  QVERIFY(chooseRadio(w.findChild<QWidget*>(QStringLiteral("applicationLevel")), ApplicationLevel::Edges));
  Settings changed = w.settings();
  QVERIFY(w.saveSettingsFile(path));

  w.restoreDefaults();
  QCOMPARE(json(w.settings()), json(Settings{}));
  QCOMPARE(method->currentData().toInt(), static_cast<int>(ThresholdOptions{}.method));
  QCOMPARE(value->value(), ThresholdOptions{}.manual_value);
  QVERIFY(waitForApplied(w, [](const Settings& s) { return json(s) == json(Settings{}); }));

  QVERIFY(w.loadSettingsFile(path));
  QCOMPARE(json(w.settings()), json(changed));
  QCOMPARE(method->currentData().toInt(), static_cast<int>(ThresholdMethod::Manual));
  QCOMPARE(value->value(), 77);
  QVERIFY(waitForApplied(w, [&](const Settings& s) { return json(s) == json(changed); }));
  // What was saved is the settings file of the core, key for key.
  Settings from_file;
  std::string error;
  QVERIFY(ok(loadSettings(path.toStdString(), from_file, error)));
  QCOMPARE(json(from_file), json(changed));
}

void SettingsFileTest::malformedFileNamesTheKey() {
  MainWindow& w = *window_;
  const QString dir = scratchDir(QStringLiteral("malformed"));
  const std::string before = json(w.settings());
  writeText(dir + QStringLiteral("/unknown.json"), R"({"pipeline": {"threshold": {"methd": "manual"}}})");
  QVERIFY(!w.loadSettingsFile(dir + QStringLiteral("/unknown.json")));
  QVERIFY2(w.lastError().contains(QStringLiteral("methd")), qPrintable(w.lastError()));
  QCOMPARE(json(w.settings()), before);

  writeText(dir + QStringLiteral("/type.json"), R"({"camera": {"width": "wide"}})");
  QVERIFY(!w.loadSettingsFile(dir + QStringLiteral("/type.json")));
  QVERIFY2(w.lastError().contains(QStringLiteral("width")), qPrintable(w.lastError()));

  // A number beyond a double: the key is named and the window goes on (it aborted once).
  writeText(dir + QStringLiteral("/overflow.json"), R"({"camera": {"image_plane_distance_mm": 1e400}})");
  QVERIFY(!w.loadSettingsFile(dir + QStringLiteral("/overflow.json")));
  QVERIFY2(w.lastError().contains(QStringLiteral("camera.image_plane_distance_mm")), qPrintable(w.lastError()));
  QCOMPARE(json(w.settings()), before);

  writeText(dir + QStringLiteral("/broken.json"), "{ not json");
  QVERIFY(!w.loadSettingsFile(dir + QStringLiteral("/broken.json")));
  QVERIFY(!w.lastError().isEmpty());
  QCOMPARE(json(w.settings()), before);
  QCOMPARE(json(w.worker()->appliedSettings()), before);
}

// "threshold": {"method": "none"} is refused at load, by its key, with the values that
// key takes; the window keeps running with the options before.
void SettingsFileTest::thresholdNoneIsRefusedByItsKey() {
  MainWindow& w = *window_;
  const QString dir = scratchDir(QStringLiteral("threshold_none"));
  const std::string before = json(w.settings());
  writeText(dir + QStringLiteral("/none.json"), R"({"pipeline": {"threshold": {"method": "none"}}})");
  QVERIFY(!w.loadSettingsFile(dir + QStringLiteral("/none.json")));
  QVERIFY2(w.bannerText().contains(QStringLiteral("pipeline.threshold.method: \"none\" is not allowed here")),
           qPrintable(w.bannerText()));
  QVERIFY(w.lastError().contains(QStringLiteral("(expected one of: manual, at-orig, at-mod)")));
  QCOMPARE(json(w.settings()), before);
  QCOMPARE(json(w.worker()->appliedSettings()), before);
  // The re-threshold's by-pass loads, and the panel shows it.
  writeText(dir + QStringLiteral("/rethreshold.json"), R"({"pipeline": {"rethreshold": {"method": "none"}}})");
  QVERIFY(w.loadSettingsFile(dir + QStringLiteral("/rethreshold.json")));
  QCOMPARE(w.findChild<QComboBox*>(QStringLiteral("rethresholdMethod"))->currentData().toInt(),
           static_cast<int>(ThresholdMethod::None));
  QVERIFY(w.bannerText().isEmpty());
}

// A file with a key's old name loads, the panel shows the value, and the banner names both
// names.
void SettingsFileTest::aRenamedKeyLoadsWithAWarning() {
  MainWindow& w = *window_;
  const QString dir = scratchDir(QStringLiteral("renamed"));
  writeText(dir + QStringLiteral("/old.json"), R"({"pipeline": {"reconstruction": {"ambiguity_min_deg": 2.5}}})");
  QVERIFY(w.loadSettingsFile(dir + QStringLiteral("/old.json")));
  QCOMPARE(w.settings().pipeline.reconstruction.ambiguity_tolerance_deg, 2.5);
  QCOMPARE(w.findChild<QDoubleSpinBox*>(QStringLiteral("ambiguityTolerance"))->value(), 2.5);
  QVERIFY2(w.bannerText().contains(QStringLiteral("ambiguity_min_deg")) &&
               w.bannerText().contains(QStringLiteral("ambiguity_tolerance_deg")),
           qPrintable(w.bannerText()));
  // A source that starts ends an earlier error, not this warning (as imagepro --config
  // FILE --source virtual meets it).
  w.startSource();
  QTRY_VERIFY_WITH_TIMEOUT(w.worker()->isRunning(), 5000);
  QTest::qWait(100);
  QVERIFY2(w.bannerText().contains(QStringLiteral("ambiguity_tolerance_deg")), qPrintable(w.bannerText()));
  w.stopSource();
  QTRY_VERIFY_WITH_TIMEOUT(!w.worker()->isRunning(), 5000);
}

void SettingsFileTest::unreadableFileIsAnError() {
  MainWindow& w = *window_;
  const QString dir = scratchDir(QStringLiteral("unreadable"));
  QVERIFY(!w.loadSettingsFile(dir + QStringLiteral("/absent.json")));
  QVERIFY(w.lastError().contains(QStringLiteral("absent.json")));
  QVERIFY(!w.saveSettingsFile(dir + QStringLiteral("/no/such/dir/s.json")));
  QVERIFY(!w.lastError().isEmpty());
}

void SettingsFileTest::windowLayoutIsRemembered() {
  MainWindow& w = *window_;
  w.resize(1111, 777);
  auto* plots = w.findChild<QDockWidget*>(QStringLiteral("plotDock"));
  QVERIFY(plots && plots->isVisible());
  plots->hide();
  CollapsibleGroup* folded = w.controlPanel()->groups().at(2);
  folded->setExpanded(false);
  const QString title = folded->title();
  w.close();  // saves the layout
  window_.reset();

  MainWindow again;
  again.show();
  QCOMPARE(again.size(), QSize(1111, 777));
  QVERIFY(!again.findChild<QDockWidget*>(QStringLiteral("plotDock"))->isVisible());
  for (CollapsibleGroup* g : again.controlPanel()->groups()) QCOMPARE(g->isExpanded(), g->title() != title);
  // Put things back for the tests after this one.
  again.findChild<QDockWidget*>(QStringLiteral("plotDock"))->show();
  for (CollapsibleGroup* g : again.controlPanel()->groups()) g->setExpanded(true);
  again.close();
}

// Tools > Targets of the Set offers the settings' set and changes its frames live: the
// shown target, the reference target and the measured pair; without a set it says so.
void SettingsFileTest::targetSetMenuChoosesTheFrames() {
  MainWindow& w = *window_;
  auto* menu = w.findChild<QMenu*>(QStringLiteral("targetSetMenu"));
  QVERIFY(menu);
  emit menu->aboutToShow();
  QCOMPARE(menu->actions().size(), 1);
  QVERIFY(!menu->actions().front()->isEnabled());

  Settings s = w.settings();
  TargetGeometry near = s.target, far = s.target;
  near.spot_offset_mm = 20.0;
  far.spot_offset_mm = 30.0;
  s.targets = {TargetSpec{1, "arm", near}, TargetSpec{2, "", far}};
  w.setSettings(s);
  emit menu->aboutToShow();
  auto trigger = [&](const char* name) {
    auto* a = w.findChild<QAction*>(QString::fromLatin1(name));
    QVERIFY2(a, name);
    a->trigger();
  };
  QVERIFY(w.findChild<QAction*>(QStringLiteral("shownTarget_first"))->isChecked());
  trigger("shownTarget_2");
  QCOMPARE(w.settings().frames.shown_target, 2);
  trigger("referenceTarget_1");
  QCOMPARE(w.settings().frames.reference_target, 1);
  trigger("measuredPair_1_2");
  QCOMPARE(w.settings().frames.measured_targets[0], 1);
  QCOMPARE(w.settings().frames.measured_targets[1], 2);
  QVERIFY(waitForApplied(w, [](const Settings& a) { return a.frames.shown_target == 2 && a.frames.reference_target == 1; }));

  // Opened again, the menu shows the choices made; the first found and none undo them.
  emit menu->aboutToShow();
  QVERIFY(w.findChild<QAction*>(QStringLiteral("shownTarget_2"))->isChecked());
  QVERIFY(!w.findChild<QAction*>(QStringLiteral("shownTarget_first"))->isChecked());
  trigger("shownTarget_first");
  trigger("referenceTarget_none");
  trigger("measuredPair_none");
  QCOMPARE(w.settings().frames.shown_target, -1);
  QCOMPARE(w.settings().frames.reference_target, -1);
  QCOMPARE(w.settings().frames.measured_targets[0], -1);
}

}  // namespace imagepro::app::test
