#pragma once
// Thresholding of thesis 2.3: Kittler and Illingworth's minimum error threshold from a
// grey-level histogram, in the thesis's two forms, and binarization by eq. 2.1.
//
// The threshold t splits the grey levels into a dark class 1 = [0, t] and a bright
// class 2 = [t+1, 255] (eqs. 2.8-2.9); t minimises the criterion J(t) of eq. 2.4 over
// every t for which J is defined, i.e. both classes hold at least two distinct grey
// levels (an empty class or one of zero variance has no ln(sigma)). Ties go to the
// smallest t, so t is always the top populated grey level of the dark class.
//
// Both forms reduce each class to exact integer sums and evaluate J(t) by one shared
// expression, so they return the same threshold on every histogram (thesis table 2.1).
//
// Degenerate histograms:
//   - empty, or a single populated grey level (all black, all white, any flat frame):
//     Status::ThresholdUndefined.
//   - two or three populated grey levels (J is defined for no t, e.g. a binary frame):
//     t splits at the widest gap between neighbouring populated levels (smallest t on a
//     tie), so a 0/255 frame gives t = 0.
// On an error `t` is left as it was.
#include <opencv2/core.hpp>

#include "core/common/status.h"
#include "core/segmentation/histogram.h"
#include "core/settings/options.h"

namespace imagepro {

// AT-Orig: eqs. 2.4-2.10 as in the earlier studies; for every t the class sums of
// eqs. 2.5-2.7 (count, mean, centred second moment) are recomputed over the class.
// O(256^2).
Status thresholdAtOrig(const Histogram& h, int& t);

// AT-Mod: the same criterion with each class's sums carried from t to t+1
// (eqs. 2.12-2.17) instead of recomputed. O(256). J(t) is first evaluated for every t
// in single precision, with a proven error bound; only the t whose J can still be the
// smallest are then evaluated by the shared expression in double, so the threshold is
// the one that evaluating every t in double gives.
Status thresholdAtMod(const Histogram& h, int& t);

// The threshold the options ask for: Manual gives o.manual_value (InvalidSettings
// outside 0..255); AtOrig and AtMod as above. None (re-threshold by-pass) names no
// threshold and gives InvalidSettings: the caller keeps its binary image instead.
Status computeThreshold(const ThresholdOptions& o, const Histogram& h, int& t);

// Eq. 2.1 with the classes above: binary = 255 (white) where grey > t, 0 elsewhere.
// (The thesis writes I >= t*; t* = t + 1 is the first grey level of the bright class.)
// t < 0 gives all white, t >= 255 all black. `binary` is CV_8UC1 of grey's size and
// keeps its allocation from call to call (see image_buffer.h); `binary` may be `grey`.
// An empty or non-CV_8UC1 `grey` gives an empty `binary`.
void binarize(const cv::Mat& grey, int t, cv::Mat& binary);

}  // namespace imagepro
