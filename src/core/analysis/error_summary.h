#pragma once
// Mean, standard deviation and largest magnitude of a set of errors: the summary the
// case studies (thesis 5.3) give of a measured quantity against its known value.
#include <span>

namespace imagepro {

struct ErrorSummary {
  int samples = 0;
  double mean = 0.0;     // signed: a bias shows
  double std = 0.0;      // population standard deviation about the mean
  double max_abs = 0.0;  // largest |error|
};

// All zero for an empty set.
ErrorSummary summarizeErrors(std::span<const double> errors);

}  // namespace imagepro
