#include "core/source/image_inputs.h"

#include <filesystem>
#include <fstream>

#include "core/source/image_file.h"

namespace imagepro {

namespace {

// A list is text: a NUL byte in its first 4 KB says it is some binary file (a video,
// an image with a name of another kind), whose "lines" would be nonsense paths.
bool looksLikeText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char buf[4096];
  in.read(buf, sizeof buf);
  const std::streamsize n = in.gcount();
  for (std::streamsize i = 0; i < n; ++i)
    if (buf[i] == '\0') return false;
  return true;
}

}  // namespace

std::vector<ImageInput> expandImageInputs(const std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  std::vector<ImageInput> out;
  std::vector<std::string> listed;
  for (const std::string& input : inputs) {
    std::error_code ec;
    const fs::file_status st = fs::status(input, ec);
    if (!fs::is_directory(st) && isImageFileName(input)) {
      out.push_back({input, Status::Ok, {}});
      continue;
    }
    if (fs::is_regular_file(st) && !looksLikeText(input)) {
      out.push_back({input, Status::FileUnreadable,
                     input + ": neither an image file (by its name) nor a text list of image paths"});
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

}  // namespace imagepro
