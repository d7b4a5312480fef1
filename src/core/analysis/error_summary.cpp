#include "core/analysis/error_summary.h"

#include <algorithm>
#include <cmath>

namespace imagepro {

ErrorSummary summarizeErrors(std::span<const double> errors) {
  ErrorSummary s;
  s.samples = static_cast<int>(errors.size());
  if (errors.empty()) return s;
  for (double e : errors) {
    s.mean += e;
    s.max_abs = std::max(s.max_abs, std::abs(e));
  }
  s.mean /= static_cast<double>(errors.size());
  for (double e : errors) s.std += (e - s.mean) * (e - s.mean);
  s.std = std::sqrt(s.std / static_cast<double>(errors.size()));
  return s;
}

}  // namespace imagepro
