#pragma once
// What the studies' Markdown reports share: printf-style formatting into a string of any
// length, and quantiles interpolated between order statistics.
#include <string>
#include <vector>

namespace imagepro::studies {

std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

// The q-quantile of `v` (0..1), linear between neighbours; NaN when `v` is empty.
double quantile(std::vector<double> v, double q);

}  // namespace imagepro::studies
