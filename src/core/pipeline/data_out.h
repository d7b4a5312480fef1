#pragma once
// Data out (thesis appendix A, "dataout.txt"): one CSV row per frame (per target of a set) in the format of
// docs/conventions.md, followed by the timestamp, the estimated (searched) and detected
// regions and the per-stage times. Each row is flushed as it is written, so a killed
// process loses at most the frame in flight; an existing file is never overwritten.
// Appending to a file whose last row a killed run left cut off starts on a new line
// (the cut-off row is counted lost, never glued to the next one). Rows are appended only
// under today's header: a file that starts otherwise (an older version's columns, another
// program's) is refused with the difference named, and nothing is written to it.
#include <cstdio>
#include <string>

#include "core/common/status.h"
#include "core/pipeline/frame_result.h"

namespace imagepro {

enum class ExistingFile : std::uint8_t {
  Fail,     // refuse: the caller asks the user
  Append,   // add rows to the end (no second header), when its header is today's
  NewName,  // write to "name-1.csv", "name-2.csv", ... instead
};

class DataOut {
 public:
  DataOut() = default;
  ~DataOut();
  DataOut(const DataOut&) = delete;
  DataOut& operator=(const DataOut&) = delete;

  // Opens `path`; `error` names the file and the reason on failure. The path actually
  // written (after NewName) is path().
  Status open(const std::string& path, ExistingFile existing, std::string& error);
  bool isOpen() const { return file_ != nullptr; }
  const std::string& path() const { return path_; }
  // Rows of an earlier run that open() found cut off at the end of the file it appends
  // to (0 or 1), and a sentence saying so for the user (empty when none).
  int lostRows() const { return lost_rows_; }
  const std::string& notice() const { return notice_; }
  // Writes and flushes the frame's rows (one per target of a set, recordRowCount); false (with the file closed) when the disk refuses.
  bool write(const FrameResult& result, std::string& error);
  void close();

  static std::string header();
  static std::string row(const FrameResult& result);

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
  int lost_rows_ = 0;
  std::string notice_;
};

}  // namespace imagepro
