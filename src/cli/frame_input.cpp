#include "cli/frame_input.h"

#include <filesystem>

#include "core/source/image_file.h"
#include "core/source/sources.h"

namespace imagepro::cli {

namespace {

// Ends an endless source after a number of frames.
class FrameLimit final : public FrameSource {
 public:
  FrameLimit(std::unique_ptr<FrameSource> inner, std::int64_t frames) : inner_(std::move(inner)), left_(frames) {}
  Status next(Frame& out) override {
    if (left_ <= 0) return Status::EndOfStream;
    --left_;
    return inner_->next(out);
  }
  std::string lastError() const override { return inner_->lastError(); }
  double frameRateHz() const override { return inner_->frameRateHz(); }
  std::string describe() const override { return inner_->describe(); }

 private:
  std::unique_ptr<FrameSource> inner_;
  std::int64_t left_;
};

}  // namespace

std::unique_ptr<FrameSource> openFrameInput(const Args& args, const Settings& settings) {
  if (args.has("virtual")) {
    if (!args.positionals().empty()) throw UsageError("give either --virtual or image files, not both");
    const int frames = args.integer("frames", 100);
    if (frames < 1) throw UsageError("--frames must be at least 1");
    return std::make_unique<FrameLimit>(makeVirtualSource(settings), frames);
  }
  if (args.positionals().empty()) throw UsageError("no input: give image files, a folder, or --virtual");
  std::vector<std::string> paths;
  for (const std::string& p : args.positionals()) {
    std::error_code ec;
    const bool folder = std::filesystem::is_directory(p, ec);
    const bool list = !folder && std::filesystem::path(p).extension() == ".txt";
    if (folder || list) {
      std::vector<std::string> more;
      std::string error;
      if (!ok(listImageSequence(p, more, error))) throw InputError(error);
      paths.insert(paths.end(), more.begin(), more.end());
    } else {
      // A missing or corrupt image is reported in its own row; the others go on.
      paths.push_back(p);
    }
  }
  return makeFileSource(std::move(paths));
}

}  // namespace imagepro::cli
