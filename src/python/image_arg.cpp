#include "python/image_arg.h"

#include <opencv2/imgproc.hpp>

#include <cstring>
#include <string>

#include "core/common/image_limits.h"
#include "python/errors.h"

namespace py = pybind11;

namespace imagepro::python {

namespace {

[[noreturn]] void badImage(const std::string& what) {
  throw StatusError(Status::EmptyFrame, "the image must be a numpy array of uint8, HxW grey or HxWx3 BGR: " + what);
}

}  // namespace

cv::Mat greyImageArg(const py::handle& image, py::array& holder) {
  if (!py::isinstance<py::array>(image))
    badImage(std::string("got ") + py::str(py::type::handle_of(image).attr("__name__")).cast<std::string>());
  auto array = py::reinterpret_borrow<py::array>(image);
  if (!array.dtype().is(py::dtype::of<std::uint8_t>()))
    badImage("its dtype is " + py::str(array.dtype()).cast<std::string>());
  const auto dims = array.ndim();
  const py::ssize_t channels = dims == 3 ? array.shape(2) : 1;
  if (dims != 2 && !(dims == 3 && (channels == 1 || channels == 3)))
    badImage("its shape is " + py::str(image.attr("shape")).cast<std::string>());
  const py::ssize_t height = array.shape(0), width = array.shape(1);
  if (height == 0 || width == 0) throw StatusError(Status::EmptyFrame, "the image has no pixels");
  if (const std::string problem = imageSizeProblem(width, height); !problem.empty())
    throw StatusError(Status::ImageTooLarge, problem);
  // Rows one after the other: a slice or a transposed view is copied once here.
  holder = py::array::ensure(array, py::array::c_style);
  if (!holder) throw py::error_already_set();
  const cv::Mat pixels(static_cast<int>(height), static_cast<int>(width), channels == 3 ? CV_8UC3 : CV_8UC1,
                       const_cast<void*>(holder.data()));
  if (channels == 1) return pixels;
  cv::Mat grey;
  cv::cvtColor(pixels, grey, cv::COLOR_BGR2GRAY);
  return grey;
}

py::array_t<std::uint8_t> numpyImage(const cv::Mat& grey) {
  CV_Assert(grey.type() == CV_8UC1);
  py::array_t<std::uint8_t> out({grey.rows, grey.cols});
  auto* dst = out.mutable_data();
  for (int y = 0; y < grey.rows; ++y) std::memcpy(dst + std::size_t(y) * grey.cols, grey.ptr(y), std::size_t(grey.cols));
  return out;
}

}  // namespace imagepro::python
