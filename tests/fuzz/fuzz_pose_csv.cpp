// The pose CSV readers: data out or `imagepro-cli reconstruct`'s output read back for the
// pendulum study (readPoseSeries), and whatever rows it accepts analysed as a pendulum.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/analysis/pendulum.h"
#include "core/analysis/pose_series.h"
#include "fuzz_support.h"

using namespace imagepro;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::scratchFile("poses.csv", data, size);
  std::vector<PoseSample> samples;
  std::string error;
  const Status s = readPoseSeries(path, 25.0, samples, error);
  if (s != Status::Ok) {
    if (error.empty()) fuzz::fail("a refused pose file names no reason", std::string(statusName(s)));
    return 0;
  }
  for (const PoseSample& p : samples)
    if (!std::isfinite(p.t_s)) fuzz::fail("a read sample has no finite time", path);
  PendulumAnalysis analysis;
  analyzePendulum(samples, PendulumAnalysisOptions{}, analysis);
  return 0;
}
