#include "cli/image_inputs.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "core/source/image_file.h"

namespace imagepro::cli {

std::vector<ImageInput> expandImageInputs(const std::vector<std::string>& inputs) {
  std::vector<ImageInput> out;
  std::vector<std::string> listed;
  for (const std::string& input : inputs) {
    std::error_code ec;
    const bool folder = std::filesystem::is_directory(input, ec);
    const bool list = !folder && std::filesystem::path(input).extension() == ".txt";
    if (!folder && !list) {
      out.push_back({input, Status::Ok, {}});
      continue;
    }
    std::string error;
    const Status status = listImageSequence(input, listed, error);
    if (!ok(status)) {
      out.push_back({input, status, error});
      continue;
    }
    for (std::string& path : listed) out.push_back({std::move(path), Status::Ok, {}});
  }
  return out;
}

DecoderMessagesSilenced::DecoderMessagesSilenced() {
  std::fflush(stderr);
  std::cerr.flush();
  saved_stderr_ = dup(STDERR_FILENO);
  const int null = open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (saved_stderr_ >= 0 && null >= 0) dup2(null, STDERR_FILENO);
  if (null >= 0) close(null);
}

DecoderMessagesSilenced::~DecoderMessagesSilenced() {
  if (saved_stderr_ < 0) return;
  std::fflush(stderr);
  std::cerr.flush();
  dup2(saved_stderr_, STDERR_FILENO);
  close(saved_stderr_);
}

Status readGreyImageQuietly(const std::string& path, cv::Mat& grey, std::string& error) {
  const DecoderMessagesSilenced quiet;
  return readGreyImage(path, grey, error);
}

std::string UniqueNames::take(const std::string& stem) {
  std::string name = stem;
  for (int n = 2; !taken_.insert(name).second; ++n) name = stem + "_" + std::to_string(n);
  return name;
}

}  // namespace imagepro::cli
