#include "cli/render_output.h"

#include <signal.h>
#include <unistd.h>

#include <opencv2/imgcodecs.hpp>

#include <cerrno>
#include <filesystem>

#include "cli/command.h"
#include "core/common/atomic_file.h"
#include "core/common/pose_csv.h"

namespace imagepro::cli {

namespace {

namespace fs = std::filesystem;

constexpr const char* kStagingPrefix = ".render-";

// Staging folders of renders that died (their process is gone).
void removeStaleStaging(const fs::path& dir) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(kStagingPrefix, 0) != 0) continue;
    const std::string digits = name.substr(std::string(kStagingPrefix).size());
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::stol(digits);
    if (pid == getpid() || (kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)) {
      std::error_code ignored;
      fs::remove_all(it->path(), ignored);
    }
  }
}

}  // namespace

RenderOutput::RenderOutput(const std::string& dir, bool append, const std::string& header) : dir_(dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw InputError(dir + ": cannot create the folder (" + ec.message() + ")");
  truth_path_ = (fs::path(dir) / "truth.csv").string();
  std::string error;
  if (append && fs::exists(truth_path_)) {
    if (!readWholeFile(truth_path_, csv_, error)) throw InputError(error);
    if (csv_.rfind(poseCsvHeader(), 0) != 0) throw InputError(truth_path_ + ": not a pose CSV, cannot append");
    if (!csv_.empty() && csv_.back() != '\n') csv_ += '\n';
  } else {
    csv_ = header + "\n";
  }
  removeStaleStaging(dir);
  staging_ = (fs::path(dir) / (kStagingPrefix + std::to_string(getpid()))).string();
  fs::create_directory(staging_, ec);
  if (ec) throw InputError(staging_ + ": cannot create the folder (" + ec.message() + ")");
}

RenderOutput::~RenderOutput() {
  std::error_code ignored;
  if (!staging_.empty()) fs::remove_all(staging_, ignored);
}

void RenderOutput::write(const std::string& file_name, const cv::Mat& image, const std::string& row) {
  const std::string path = (fs::path(staging_) / file_name).string();
  bool written = false;
  try {
    written = cv::imwrite(path, image);
  } catch (const cv::Exception& e) {
    throw InputError(path + ": cannot be written (" + e.err + ")");
  }
  if (!written) throw InputError(path + ": cannot be written");
  new_frames_.insert(file_name);
  csv_ += row + "\n";
}

void RenderOutput::commit() {
  std::error_code ec;
  // From here until truth.csv is written there is no truth.csv at all.
  fs::remove(truth_path_, ec);
  if (ec) throw InputError(truth_path_ + ": cannot be replaced (" + ec.message() + ")");
  for (const std::string& name : new_frames_) {
    fs::rename(fs::path(staging_) / name, fs::path(dir_) / name, ec);
    if (ec) throw InputError((fs::path(dir_) / name).string() + ": cannot be written (" + ec.message() + ")");
  }
  std::string error;
  if (!writeFileAtomically(truth_path_, csv_, error)) throw InputError(error);
}

}  // namespace imagepro::cli
