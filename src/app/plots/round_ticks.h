#pragma once
// Round axis ticks for the charts: a step of 1, 2 or 5 times a power of ten, ticks on
// its multiples, labelled with just the decimals the step needs, so that an axis reads
// 0 / 5 / 10 s or 2.4 / 2.6 / 2.8, never 63 / 127 / 191, -0.0 or one value twice.
#include <QString>

class QValueAxis;

namespace imagepro::app {

// The smallest round step (1, 2 or 5 times a power of ten) that cuts `span` into at most
// `max_intervals` intervals, and not below `min_step` (> 0; e.g. 1 for frame numbers).
double roundStep(double span, int max_intervals, double min_step = 0.0);

// Decimals that print every multiple of `step` exactly (0 for 5, 1 for 0.5, 2 for 0.25 ...).
int stepDecimals(double step);

// The range [lo, hi] with its ends moved out to multiples of `step`.
struct AxisRange {
  double lo = 0.0, hi = 1.0;
};
AxisRange roundOutward(double lo, double hi, double step);

// Shows [lo, hi] on `axis` with ticks on the multiples of `step`, each label the tick's
// value with `prefix` and `suffix` ("#" for frame numbers, " s" for seconds).
void setRoundTicks(QValueAxis* axis, double lo, double hi, double step, const QString& prefix = {},
                   const QString& suffix = {});

}  // namespace imagepro::app
