// imagepro-cli estimate-d0: the image plane distance d0 from frames of the target at an
// unknown depth, by the thesis's iteration (eqs. 4.1-4.2) from the lens's focal length.
#include <cstdio>
#include <vector>

#include "cli/command.h"
#include "cli/frame_input.h"
#include "core/calibration/d0_estimation.h"

namespace imagepro::cli {
namespace {

int run(const Args& args) {
  std::vector<std::string> known = kFrameInputOptions;
  known.insert(known.end(), {"focal-length", "epsilon", "max-iterations"});
  args.rejectUnknown(known);
  if (!args.has("focal-length")) throw UsageError("--focal-length MM is required");
  const double focal = args.number("focal-length", 0.0);
  const double epsilon = args.number("epsilon", 1e-6);
  const int maxIterations = args.integer("max-iterations", 20);
  if (!(focal > 0.0)) throw UsageError("--focal-length must be positive");
  if (!(epsilon > 0.0)) throw UsageError("--epsilon must be positive");
  if (maxIterations < 1) throw UsageError("--max-iterations must be at least 1");

  const Settings settings = loadConfigForInput(args);
  auto source = openFrameInput(args, settings);
  D0Estimator estimator(settings, D0Options{focal, epsilon, maxIterations});

  std::printf("frame,status,d0_mm,depth_mm,iterations\n");
  std::vector<double> estimates;
  std::string first_problem;  // why the first frame without an estimate had none
  FrameResult result;
  D0FrameEstimate frame_estimate;
  while (estimator.step(*source, result, frame_estimate) != Status::EndOfStream) {
    const std::string frame = result.name.empty() ? std::to_string(result.index) : result.name;
    const Status status = frame_estimate.status;
    const ImagePlaneDistanceEstimate& est = frame_estimate.estimate;
    if (ok(status)) {
      std::printf("%s,ok,%.6f,%.3f,%d\n", frame.c_str(), est.d0_mm, est.depth_mm, est.iterations);
      estimates.push_back(est.d0_mm);
    } else {
      std::printf("%s,%s,,,\n", frame.c_str(), std::string(statusName(status)).c_str());
      // A frame the source could not deliver (a missing or corrupt file) is named with its reason.
      const bool source_failed = !ok(result.status) && !source->lastError().empty();
      const std::string problem =
          source_failed ? frameProblem(frame, source->lastError())
                        : frame + ": " + std::string(statusName(status)) + ": " + std::string(statusMessage(status));
      if (source_failed) std::fprintf(stderr, "%s\n", problem.c_str());
      if (first_problem.empty()) first_problem = problem;
    }
    std::fflush(stdout);
  }
  if (const D0Summary summary = summarizeD0(estimates); summary.count > 0) {
    std::fprintf(stderr, "d0 = %.6f mm (mean of %d frames, standard deviation %.6f mm)\n", summary.mean_mm,
                 summary.count, summary.sd_mm);
    return 0;
  }
  // Without an estimate the command has failed, whatever the reason: say the first one.
  throw InputError("no frame gave an estimate of d0" + (first_problem.empty() ? "" : " (" + first_problem + ")"));
}

const CommandRegistration kRegistration{{
    "estimate-d0",
    "estimate the image plane distance d0 from frames of the target (thesis eq. 4.1)",
    std::string("usage: imagepro-cli estimate-d0 --focal-length MM [--config FILE] [--epsilon MM]\n"
                "                                [--max-iterations N] INPUT\n\n"
                "Finds the target in each frame and iterates thesis eq. 4.1 from d0 = f:\n"
                "  d0(i+1) = d(d0(i)) f / (d(d0(i)) - f)\n"
                "where d(d0) is the target's depth reconstructed with image plane distance d0,\n"
                "until d0 changes by less than epsilon (eq. 4.2). The camera's other parameters\n"
                "(pixel size, principal point, distortion) come from the settings.\n"
                "Prints CSV: frame,status,d0_mm,depth_mm,iterations; the mean d0 goes to stderr.\n"
                "A frame that cannot be read is named on stderr with its reason; when no frame\n"
                "gives an estimate the command fails (exit code 1) and says why.\n"
                "  --focal-length MM   the lens's focal length f (required)\n"
                "  --epsilon MM        convergence threshold of eq. 4.2 (default 1e-6)\n"
                "  --max-iterations N  give up (Diverged) after N steps (default 20)\n") +
        kFrameInputHelp,
    {"virtual"},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
