#pragma once
// Images between numpy and the pipeline.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <opencv2/core.hpp>

namespace imagepro::python {

// A numpy uint8 array as the pipeline's 8-bit grey image: HxW (or HxWx1) as it is, its
// pixels shared with `holder`, which must outlive the result; HxWx3 taken as BGR (OpenCV's
// order) and converted. Anything else raises imagepro.EmptyFrame, and a size beyond what a
// frame may hold imagepro.ImageTooLarge: a bad image is the caller's mistake, not a frame
// without a target.
cv::Mat greyImageArg(const pybind11::handle& image, pybind11::array& holder);

// A copy of an 8-bit grey image as a new HxW uint8 array.
pybind11::array_t<std::uint8_t> numpyImage(const cv::Mat& grey);

}  // namespace imagepro::python
