#include "cli/image_inputs.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <iostream>

#include "core/source/image_file.h"

namespace imagepro::cli {

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
