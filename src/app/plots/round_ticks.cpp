#include "app/plots/round_ticks.h"

#include <QValueAxis>

#include <algorithm>
#include <cmath>

namespace imagepro::app {

double roundStep(double span, int max_intervals, double min_step) {
  const double raw = std::max(std::abs(span) / std::max(1, max_intervals), min_step);
  if (!(raw > 0.0) || !std::isfinite(raw)) return min_step > 0.0 ? min_step : 1.0;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * power >= raw * (1.0 - 1e-9)) return m * power;
  return 10.0 * power;
}

int stepDecimals(double step) {
  if (!(step > 0.0)) return 0;
  // 1 and 2 times 10^-k need k decimals, 5 times 10^-k as well (0.5 -> 1, 0.05 -> 2).
  return std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
}

AxisRange roundOutward(double lo, double hi, double step) {
  if (!(step > 0.0)) return {lo, hi};
  return {std::floor(lo / step + 1e-9) * step, std::ceil(hi / step - 1e-9) * step};
}

void setRoundTicks(QValueAxis* axis, double lo, double hi, double step, const QString& prefix, const QString& suffix) {
  if (!(hi > lo)) hi = lo + step;
  // A hair past hi, so that the tick at hi, anchored just above it (below), is drawn.
  axis->setRange(lo, hi + step * 1e-5);
  axis->setTickType(QValueAxis::TicksDynamic);
  axis->setTickInterval(step);
  // Qt Charts reaches each tick by adding the step to the one before, so the tick at zero
  // can come out a hair below it and read "-0.0": anchored a millionth of a step above
  // the round values, every tick stays on the right side of its label.
  axis->setTickAnchor(step * 1e-6);
  QString escaped_prefix = prefix, escaped_suffix = suffix;
  escaped_prefix.replace(QLatin1Char('%'), QStringLiteral("%%"));
  escaped_suffix.replace(QLatin1Char('%'), QStringLiteral("%%"));
  axis->setLabelFormat(escaped_prefix + QStringLiteral("%.") + QString::number(stepDecimals(step)) + QLatin1Char('f') +
                       escaped_suffix);
}

}  // namespace imagepro::app
