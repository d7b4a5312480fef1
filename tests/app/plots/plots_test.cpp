// The plots through the window: one clock per source run (File, then Virtual again,
// starts at the run's first second, not where another run left off; a clock that starts
// again starts the plots again), one time window shared by the six charts, a still as a
// point at its image's number, and tick labels that are round numbers, read as Qt Charts
// draws them from the axes.
#include <QChart>
#include <QChartView>
#include <QLineSeries>
#include <QRegularExpression>
#include <QScatterSeries>
#include <QTabWidget>
#include <QTest>
#include <QValueAxis>

#include <cmath>

#include "app/main_window/main_window.h"
#include "app/plots/histogram_chart.h"
#include "app/plots/pose_plots.h"
#include "app/plots/stage_time_chart.h"
#include "app/worker/worker.h"
#include "app_test_classes.h"
#include "app_test_support.h"

namespace imagepro::app::test {

namespace {

const QString kSamples = QStringLiteral(IMAGEPRO_DATA_DIR "/samples/");

QList<QChart*> chartsOf(QWidget* widget) {
  QList<QChart*> charts;
  for (QChartView* view : widget->findChildren<QChartView*>()) charts << view->chart();
  return charts;
}

QValueAxis* axisOf(QChart* chart, Qt::Orientation orientation) {
  return qobject_cast<QValueAxis*>(chart->axes(orientation).value(0));
}

// The labels the chart draws on `axis`, made as Qt Charts makes them: the ticks from the
// anchor in steps of the interval up to the maximum, each printed with the label format.
QStringList tickLabels(const QValueAxis* axis) {
  QStringList labels;
  if (axis->tickType() != QValueAxis::TicksDynamic) {
    for (int i = 0; i < axis->tickCount(); ++i)
      labels << QString::asprintf(axis->labelFormat().toLatin1().constData(),
                                  axis->min() + i * (axis->max() - axis->min()) / (axis->tickCount() - 1));
    return labels;
  }
  const double step = axis->tickInterval();
  double value = axis->tickAnchor() - std::floor((axis->tickAnchor() - axis->min()) / step) * step;
  for (; value <= axis->max(); value += step)
    labels << QString::asprintf(axis->labelFormat().toLatin1().constData(), value);
  return labels;
}

// Round labels: at least `min_ticks`, each a different multiple of a step of 1, 2 or 5
// times a power of ten, none "-0"; the problem in words, or empty.
QString roundnessProblem(const QValueAxis* axis, int min_ticks = 2) {
  const QStringList labels = tickLabels(axis);
  if (labels.size() < min_ticks) return QStringLiteral("%1 ticks: %2").arg(labels.size()).arg(labels.join(u' '));
  if (QStringList unique = labels; unique.removeDuplicates() > 0)
    return QStringLiteral("a label twice: %1").arg(labels.join(u' '));
  const double step = axis->tickInterval();
  const double mantissa = step / std::pow(10.0, std::floor(std::log10(step)));
  if (std::abs(mantissa - 1.0) > 1e-9 && std::abs(mantissa - 2.0) > 1e-9 && std::abs(mantissa - 5.0) > 1e-9)
    return QStringLiteral("step %1").arg(step);
  static const QRegularExpression number(QStringLiteral("-?[0-9]+(\\.[0-9]+)?"));
  for (const QString& label : labels) {
    const QRegularExpressionMatch m = number.match(label);
    if (!m.hasMatch()) return QStringLiteral("no number in %1").arg(label);
    const double value = m.captured(0).toDouble();
    if (m.captured(0).startsWith(u'-') && value == 0.0) return QStringLiteral("label %1").arg(label);
    if (std::abs(value / step - std::round(value / step)) > 1e-6) return QStringLiteral("%1 is not a multiple of %2").arg(label).arg(step);
  }
  return {};
}

bool sameXWindow(const QList<QChart*>& charts) {
  const QValueAxis* first = axisOf(charts.front(), Qt::Horizontal);
  for (QChart* c : charts) {
    const QValueAxis* x = axisOf(c, Qt::Horizontal);
    if (x->min() != first->min() || x->max() != first->max() || x->tickInterval() != first->tickInterval() ||
        x->labelFormat() != first->labelFormat())
      return false;
  }
  return true;
}

// What the six views show as painted: one window and one last sample, or all six held
// back mid-round (none painting then); the problem in words, or empty.
QString paintedProblem(QWidget* plots, bool& painting) {
  const QList<QChartView*> views = plots->findChildren<QChartView*>();
  int enabled = 0;
  for (QChartView* v : views) enabled += v->updatesEnabled() ? 1 : 0;
  painting = enabled == views.size();
  if (enabled != 0 && !painting) return QStringLiteral("%1 of %2 views painting").arg(enabled).arg(views.size());
  if (!painting) return {};
  QList<QChart*> charts;
  for (QChartView* v : views) charts << v->chart();
  if (!sameXWindow(charts)) return QStringLiteral("different windows");
  double last = std::nan("");
  for (QChart* c : charts) {
    for (QAbstractSeries* s : c->series()) {
      auto* line = qobject_cast<QLineSeries*>(s);
      if (!line || line->pen().style() != Qt::SolidLine || line->count() == 0) continue;
      const double x = line->points().back().x();
      if (std::isnan(last)) last = x;
      else if (x != last) return QStringLiteral("%1 ends at %2 s, another at %3 s").arg(c->title()).arg(x).arg(last);
    }
  }
  return {};
}

// The measured samples as markers.
QScatterSeries* markersOf(QChart* chart) {
  for (QAbstractSeries* s : chart->series())
    if (auto* markers = qobject_cast<QScatterSeries*>(s)) return markers;
  return nullptr;
}

// The measured line (a QLineSeries drawn in the measured colour, not the dashed truth).
qsizetype measuredLinePoints(QChart* chart) {
  for (QAbstractSeries* s : chart->series()) {
    auto* line = qobject_cast<QLineSeries*>(s);
    if (line && line->pen().style() == Qt::SolidLine)
      return line->count();
  }
  return -1;
}

}  // namespace

void PlotsTest::init() {
  window_ = std::make_unique<MainWindow>();
  Settings s;
  s.virtual_scene.frame_rate_hz = 100.0;
  s.virtual_scene.motion.kind = MotionKind::Sinusoid;  // values that move, so the y axes do
  s.virtual_scene.motion.period_s = 1.0;
  window_->setSettings(s);
  window_->resize(1200, 900);
  window_->show();
}

void PlotsTest::cleanup() { window_.reset(); }

// Virtual for a while, then a file, then Virtual again: the file's still is one point at
// #1; the new Virtual run's plots start at its own first second, in one window for all six.
void PlotsTest::fileThenVirtualStartsOneClock() {
  MainWindow& w = *window_;
  PosePlots* plots = w.posePlots();
  const QList<QChart*> charts = chartsOf(plots);
  QCOMPARE(charts.size(), 6);
  w.startSource();
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.index >= 150; }));

  w.openPaths({kSamples + QStringLiteral("sample01_facing.png")});
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "sample01_facing.png"; }));
  QTRY_COMPARE(plots->recorded().size(), std::size_t{1});
  for (QChart* c : charts) {
    QTRY_COMPARE(markersOf(c)->count(), 1);         // the still, as a marker (one plot redrawn per tick)
    QCOMPARE(measuredLinePoints(c), qsizetype{0});  // and no line through it
    QValueAxis* x = axisOf(c, Qt::Horizontal);
    QCOMPARE(tickLabels(x), QStringList{QStringLiteral("#1")});
    QCOMPARE(markersOf(c)->at(0).x(), 1.0);
    QVERIFY(x->min() < 1.0 && x->max() > 1.0);
    QVERIFY2(roundnessProblem(axisOf(c, Qt::Vertical)).isEmpty(), qPrintable(roundnessProblem(axisOf(c, Qt::Vertical))));
  }

  w.selectSource(SourceKind::Virtual);
  QTRY_VERIFY(plots->recorded().empty());
  w.startSource();
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.truth && r.index >= 50; }));
  for (const PoseSample& s : plots->recorded()) QVERIFY(!s.still && s.timestamp_s < 5.0);
  // The run's own clock, from its first frame over the whole window: 0 s to 20 s.
  QTRY_VERIFY(sameXWindow(charts) && axisOf(charts.front(), Qt::Horizontal)->min() == plots->recorded().front().timestamp_s);
  QValueAxis* x = axisOf(charts.front(), Qt::Horizontal);
  QCOMPARE(x->min(), 0.0);
  QVERIFY(std::abs(x->max() - PosePlots::kWindowS) < 1e-3);
  QCOMPARE(tickLabels(x), (QStringList{QStringLiteral("0 s"), QStringLiteral("5 s"), QStringLiteral("10 s"),
                                       QStringLiteral("15 s"), QStringLiteral("20 s")}));
  QTRY_VERIFY(measuredLinePoints(charts.front()) > 20);
  w.stopSource();
  QTRY_VERIFY(!w.worker()->isRunning());
}

// While the source runs, the six charts show one window and end at one sample at every
// moment they paint, and every axis of the plots, the histogram and the stage times reads
// in round numbers.
void PlotsTest::sixChartsShareOneWindowWithRoundTicks() {
  MainWindow& w = *window_;
  const QList<QChart*> charts = chartsOf(w.posePlots());
  w.startSource();
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.index >= 20; }));
  int painting_seen = 0, held_seen = 0;
  for (int i = 0; i < 80; ++i) {
    QTest::qWait(i % 2 ? 11 : 17);  // out of step with the redraw's 33 ms ticks
    bool painting = false;
    const QString problem = paintedProblem(w.posePlots(), painting);
    QVERIFY2(problem.isEmpty(), qPrintable(problem));
    (painting ? painting_seen : held_seen) += 1;
  }
  QVERIFY(painting_seen > 0);
  QVERIFY(held_seen > 0);  // a round seen in progress, held back
  for (QChart* c : charts) {
    for (Qt::Orientation o : {Qt::Horizontal, Qt::Vertical}) {
      const QString problem = roundnessProblem(axisOf(c, o), 3);
      QVERIFY2(problem.isEmpty(), qPrintable(c->title() + QStringLiteral(": ") + problem));
    }
  }
  // The histogram and the stage times, shown.
  auto* tabs = w.findChild<QTabWidget*>(QStringLiteral("plotTabs"));
  QVERIFY(tabs);
  for (QWidget* page : {static_cast<QWidget*>(w.histogramChart()), static_cast<QWidget*>(w.stageTimeChart())}) {
    tabs->setCurrentWidget(page);
    QTest::qWait(400);  // a readout refresh or two
    const QList<QChart*> page_charts = chartsOf(page);
    QCOMPARE(page_charts.size(), 1);
    for (QAbstractAxis* axis : page_charts.front()->axes()) {
      auto* value_axis = qobject_cast<QValueAxis*>(axis);
      if (!value_axis) continue;  // the stage chart's one category
      const QString problem = roundnessProblem(value_axis, 3);
      QVERIFY2(problem.isEmpty(), qPrintable(page_charts.front()->title() + QStringLiteral(": ") + problem));
    }
  }
  QCOMPARE(tickLabels(axisOf(chartsOf(w.histogramChart()).front(), Qt::Horizontal)),
           (QStringList{QStringLiteral("0"), QStringLiteral("50"), QStringLiteral("100"), QStringLiteral("150"),
                        QStringLiteral("200"), QStringLiteral("250")}));
  w.stopSource();
  QTRY_VERIFY(!w.worker()->isRunning());
}

// A clock that goes back within one source (here the Virtual frame rate raised while
// stopped: the same frame numbers now come earlier) starts the plots again, so no run's
// samples sit on another run's time axis.
void PlotsTest::aClockThatStartsAgainStartsThePlotsAgain() {
  MainWindow& w = *window_;
  PosePlots* plots = w.posePlots();
  Settings s = w.settings();
  s.virtual_scene.frame_rate_hz = 25.0;
  w.setSettings(s);
  w.startSource();
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.index >= 40; }));  // 1.6 s and on
  w.stopSource();
  QTRY_VERIFY(!w.worker()->isRunning());
  QTRY_VERIFY(!plots->recorded().empty() && plots->recorded().back().timestamp_s >= 1.5);
  const double stopped_at = plots->recorded().back().timestamp_s;
  s.virtual_scene.frame_rate_hz = 100.0;
  w.setSettings(s);
  QVERIFY(waitForApplied(w, [](const Settings& a) { return a.virtual_scene.frame_rate_hz == 100.0; }));
  w.startSource();
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.index >= 60; }));
  w.stopSource();
  QTRY_VERIFY(!w.worker()->isRunning());
  // Only the new clock's samples, in order, and the window starts at the first of them.
  const auto& recorded = plots->recorded();
  QVERIFY(!recorded.empty());
  QVERIFY(recorded.front().timestamp_s < stopped_at);
  for (std::size_t k = 1; k < recorded.size(); ++k) QVERIFY(recorded[k].timestamp_s >= recorded[k - 1].timestamp_s);
  const QList<QChart*> charts = chartsOf(plots);
  QTRY_COMPARE(axisOf(charts.front(), Qt::Horizontal)->min(), recorded.front().timestamp_s);
  QTRY_VERIFY(sameXWindow(charts));  // the round that sets them one by one ends
}

// A folder stepped through: each image a point at its number, an image shown again
// (or processed again) keeps one point, its latest; another folder starts afresh.
void PlotsTest::stillsArePointsByTheirNumber() {
  MainWindow& w = *window_;
  PosePlots* plots = w.posePlots();
  const QList<QChart*> charts = chartsOf(plots);
  w.openPaths({numberedFolder(QStringLiteral("plots-stills"), 3)});
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "img1.png"; }));
  w.stepFile(FileStep::Next);
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "img2.png"; }));
  w.stepFile(FileStep::Next);
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "img3.png"; }));
  w.stepFile(FileStep::Previous);
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "img2.png"; }));
  QTRY_COMPARE(plots->recorded().size(), std::size_t{4});
  QTRY_VERIFY(sameXWindow(charts) && tickLabels(axisOf(charts.front(), Qt::Horizontal)).size() == 3);
  for (QChart* c : charts) {
    QCOMPARE(tickLabels(axisOf(c, Qt::Horizontal)),
             (QStringList{QStringLiteral("#1"), QStringLiteral("#2"), QStringLiteral("#3")}));
    QScatterSeries* points = markersOf(c);
    QTRY_COMPARE(points->count(), 3);  // img2 twice: one point
    for (int k = 0; k < 3; ++k) QCOMPARE(points->at(k).x(), double(k + 1));
    QCOMPARE(measuredLinePoints(c), qsizetype{0});
  }

  // One file opened after the folder: its still alone, at #1.
  w.openPaths({kSamples + QStringLiteral("sample03_tilted50.png")});
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "sample03_tilted50.png"; }));
  QTRY_COMPARE(plots->recorded().size(), std::size_t{1});
  for (QChart* c : charts) QTRY_COMPARE(markersOf(c)->count(), 1);
  QCOMPARE(tickLabels(axisOf(charts.front(), Qt::Horizontal)), QStringList{QStringLiteral("#1")});
}

}  // namespace imagepro::app::test
