// AnalysisWindow: the summary table, the status line and the charts of a result.
#include <QHeaderView>
#include <QLabel>
#include <QStringList>
#include <QTableWidget>

#include "app/plots/analysis_plots.h"
#include "app/analysis/analysis_window.h"

namespace imagepro::app {

namespace {

QString number(double v, int decimals) { return QString::number(v, 'f', decimals); }

QString signedPercent(double measured, double truth, int decimals) {
  const double p = 100.0 * (measured / truth - 1.0);
  return (p >= 0.0 ? QStringLiteral("+") : QString()) + number(p, decimals) + QStringLiteral(" %");
}

// `stretch`: the column that takes the spare width, or -1.
void fillTable(QTableWidget* table, const QStringList& header, const std::vector<QStringList>& rows, int stretch) {
  table->clear();
  table->setColumnCount(static_cast<int>(header.size()));
  table->setRowCount(static_cast<int>(rows.size()));
  table->setHorizontalHeaderLabels(header);
  for (int r = 0; r < static_cast<int>(rows.size()); ++r)
    for (int c = 0; c < static_cast<int>(rows[static_cast<std::size_t>(r)].size()); ++c) {
      auto* item = new QTableWidgetItem(rows[static_cast<std::size_t>(r)][c]);
      if (c > 0) item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
      table->setItem(r, c, item);
    }
  table->horizontalHeader()->setSectionResizeMode(QHeaderView::Interactive);
  table->resizeColumnsToContents();
  table->horizontalHeader()->setStretchLastSection(false);
  if (stretch >= 0) table->horizontalHeader()->setSectionResizeMode(stretch, QHeaderView::Stretch);
}

QString failureText(const std::vector<std::pair<Status, int>>& failures) {
  QStringList lines;
  for (const auto& [s, count] : failures)
    lines << QObject::tr("%1 measurements: %2 (%3)")
                 .arg(count)
                 .arg(QString::fromUtf8(statusName(s).data(), static_cast<qsizetype>(statusName(s).size())),
                      QString::fromUtf8(statusMessage(s).data(), static_cast<qsizetype>(statusMessage(s).size())));
  return lines.join(QLatin1Char('\n'));
}

}  // namespace

void AnalysisWindow::showPendulum() {
  const PendulumStudyResult& r = pendulum_;
  pendulum_chart_->setResult(r);
  if (!ok(r.status)) {
    summary_->clear();
    summary_->setRowCount(0);
    summary_->setColumnCount(0);
    setMessage(QString::fromStdString(r.error), true);
    return;
  }
  const PendulumAnalysis& a = r.analysis;
  const bool t = r.has_truth;
  std::vector<QStringList> rows;
  rows.push_back({tr("Frames"), tr("%1 (%2 with a pose)").arg(a.frames).arg(a.valid_frames), QString(), QString(),
                  QString()});
  if (a.length_from_still)
    rows.push_back({tr("Still frames (the length)"), tr("%1 (%2 with a pose)").arg(a.still_frames).arg(a.still_valid_frames),
                    QString(), QString(), QString()});
  rows.push_back({tr("Length [mm]"), number(a.length_mm, 2), number(a.length_sigma_mm, 2),
                  t ? number(r.truth.length_mm, 2) : QString(),
                  t ? signedPercent(a.length_mm, r.truth.length_mm, 3) : QString()});
  const bool maxima = r.options.period_method == PeriodMethod::Maxima;
  rows.push_back({maxima ? tr("Period, mid-swing crossings [s]") : tr("Period, mid-swing crossings [s] (g's)"),
                  number(a.period.period_s, 6), number(a.period.period_sigma_s, 6),
                  t ? number(r.truth.period_s, 6) : QString(),
                  t ? signedPercent(a.period.period_s, r.truth.period_s, 4) : QString()});
  if (ok(a.maxima_status))
    rows.push_back({maxima ? tr("Period, thesis's first to last maximum [s] (g's)")
                           : tr("Period, thesis's first to last maximum [s]"),
                    number(a.maxima.period_s, 6), number(a.maxima.period_sigma_s, 6),
                    t ? number(r.truth.period_s, 6) : QString(),
                    t ? signedPercent(a.maxima.period_s, r.truth.period_s, 4) : QString()});
  else
    rows.push_back({tr("Period, thesis's first to last maximum [s]"), QString::fromStdString(std::string(statusName(a.maxima_status))),
                    QString(), QString(), QString()});
  rows.push_back({tr("g [m/s²]"), number(a.g_m_s2, 4), number(a.g_sigma_m_s2, 4),
                  t ? number(r.truth.g_m_s2, 5) : QString(), t ? signedPercent(a.g_m_s2, r.truth.g_m_s2, 3) : QString()});
  rows.push_back({tr("Swing amplitude [deg]"), number(a.amplitude_deg, 2), number(a.amplitude_sigma_deg, 2), QString(),
                  QString()});
  if (r.options.amplitude_correction) {
    rows.push_back({tr("Small-swing period T0 [s]"), number(a.small_amplitude_period_s, 6),
                    number(a.small_amplitude_period_sigma_s, 6), QString(), QString()});
    rows.push_back({tr("g by eq. 5.1 with the measured period [m/s²]"), number(a.g_uncorrected_m_s2, 4), QString(),
                    QString(), t ? signedPercent(a.g_uncorrected_m_s2, r.truth.g_m_s2, 3) : QString()});
  }
  rows.push_back({tr("Pivot [mm]"),
                  QStringLiteral("%1, %2, %3")
                      .arg(number(a.sphere.centre_mm.x(), 1), number(a.sphere.centre_mm.y(), 1),
                           number(a.sphere.centre_mm.z(), 1)),
                  QString(), QString(), QString()});
  rows.push_back({tr("RMS off the sphere [mm]"), number(a.sphere.radial_rms_mm, 3), QString(), QString(), QString()});
  rows.push_back({tr("Mid-swing crossings"), QString::number(a.period.crossings), QString(), QString(), QString()});
  fillTable(summary_, {tr("Pendulum (thesis 5.3.2)"), tr("measured"), tr("± 1 sigma"), tr("true"), tr("error")}, rows, 0);
  setMessage(tr("g = %1 ± %2 m/s² from %3 frames%4")
                 .arg(number(a.g_m_s2, 4), number(a.g_sigma_m_s2, 4))
                 .arg(a.frames)
                 .arg(r.options.amplitude_correction ? tr(" (amplitude corrected)") : tr(" (eq. 5.1)")),
             false);
}

void AnalysisWindow::showTwoTargets() {
  const TwoTargetStudyResult& r = two_targets_;
  two_target_charts_->setResult(r);
  std::vector<QStringList> rows;
  for (const TwoTargetSummary& s : r.summaries) {
    rows.push_back({s.position > 0 ? QString::number(s.position) : tr("live"), s.correction ? tr("on") : tr("off"),
                    QStringLiteral("%1/%2").arg(s.distance_mm.samples).arg(s.frames), number(s.distance_mm.mean, 3),
                    number(s.distance_mm.std, 3), number(s.distance_mm.max_abs, 3), number(s.angle_deg.mean, 3),
                    number(s.angle_deg.std, 3), number(s.angle_deg.max_abs, 3)});
  }
  fillTable(summary_,
            {tr("Position"), tr("Correction"), tr("Measured"), tr("Distance error mean [mm]"), tr("std"), tr("max"),
             tr("Angle error mean [deg]"), tr("std"), tr("max")},
            rows, -1);
  const QString known = tr("Known: distance %1 mm, angle %2 deg.")
                            .arg(number(r.object.spacing_mm, 2), number(r.object.angle_deg, 2));
  const QString failures = failureText(r.failures);
  const QString why = failures.isEmpty() ? QString() : QLatin1Char('\n') + failures;
  if (!ok(r.status)) setMessage(QString::fromStdString(r.error) + why, true);
  else setMessage(known + why, false);
}

QString AnalysisWindow::summaryText() const {
  QStringList lines;
  QStringList header;
  for (int c = 0; c < summary_->columnCount(); ++c)
    header << (summary_->horizontalHeaderItem(c) ? summary_->horizontalHeaderItem(c)->text() : QString());
  if (!header.isEmpty()) lines << header.join(QLatin1Char('\t'));
  for (int r = 0; r < summary_->rowCount(); ++r) {
    QStringList cells;
    for (int c = 0; c < summary_->columnCount(); ++c)
      cells << (summary_->item(r, c) ? summary_->item(r, c)->text() : QString());
    lines << cells.join(QLatin1Char('\t'));
  }
  return lines.join(QLatin1Char('\n'));
}

}  // namespace imagepro::app
