#include "app/worker/image_list_source.h"

#include <algorithm>
#include <filesystem>

#include "core/source/image_file.h"

namespace imagepro::app {

ImageListSource::ImageListSource(std::vector<std::string> paths) : paths_(std::move(paths)) {}

Status ImageListSource::next(Frame& out) {
  if (atEnd()) {
    error_ = "no more files";
    return Status::EndOfStream;
  }
  const std::string& file = paths_[static_cast<std::size_t>(next_)];
  out.index = next_;
  out.timestamp_s = 0.0;
  out.name = std::filesystem::path(file).filename().string();
  out.truth.reset();
  shown_ = next_++;
  const Status s = readGreyImage(file, out.image, error_);
  if (ok(s)) error_.clear();
  return s;
}

std::string ImageListSource::describe() const {
  const int index = std::max(shown_, 0);
  if (paths_.empty()) return "file: none open";
  std::string d = "file " + std::filesystem::path(paths_[static_cast<std::size_t>(index)]).filename().string();
  if (count() > 1) d += " (" + std::to_string(index + 1) + " of " + std::to_string(count()) + ")";
  return d;
}

void ImageListSource::seek(int index) { next_ = std::clamp(index, 0, std::max(count() - 1, 0)); }

}  // namespace imagepro::app
