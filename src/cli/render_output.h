#pragma once
// Where `imagepro-cli render` writes: frames and truth.csv that always agree, even when
// the command is killed. Frames are written into a staging folder DIR/.render-<pid>;
// only when all are there does commit() remove the old truth.csv, move the new frames
// in and write the new truth.csv atomically. A run killed while rendering leaves DIR as it was (plus the
// staging folder, removed by the next run); one killed while committing leaves no
// truth.csv, never one that names other frames.
#include <opencv2/core.hpp>

#include <set>
#include <string>

namespace imagepro::cli {

class RenderOutput {
 public:
  // Creates DIR and the staging folder; with `append`, the rows of DIR/truth.csv are
  // kept and the new ones follow. `header` is truth.csv's first line (without newline)
  // when it is written anew. Throws InputError.
  RenderOutput(const std::string& dir, bool append, const std::string& header);
  ~RenderOutput();
  RenderOutput(const RenderOutput&) = delete;
  RenderOutput& operator=(const RenderOutput&) = delete;

  // Writes frame `file_name` (PNG) into the staging folder and keeps its truth.csv row
  // (without newline). Throws InputError.
  void write(const std::string& file_name, const cv::Mat& image, const std::string& row);
  void commit();

  const std::string& truthPath() const { return truth_path_; }

 private:
  std::string dir_;
  std::string staging_;
  std::string truth_path_;
  std::string csv_;
  std::set<std::string> new_frames_;
};

}  // namespace imagepro::cli
