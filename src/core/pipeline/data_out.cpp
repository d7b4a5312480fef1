#include "core/pipeline/data_out.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

#include "core/pipeline/frame_record.h"

namespace imagepro {

namespace {

std::string numberedName(const std::filesystem::path& p, int k) {
  return (p.parent_path() / (p.stem().string() + "-" + std::to_string(k) + p.extension().string())).string();
}

enum class Ending : std::uint8_t { Whole, CutRow, CutHeader };

// How an existing data-out file ends: on a line end, or inside a row (or inside the
// header, when not even its first line is whole) that a killed write left behind.
Ending howItEnds(std::FILE* f) {
  if (std::fseek(f, -1, SEEK_END) != 0 || std::fgetc(f) == '\n') return Ending::Whole;
  std::rewind(f);
  for (int c; (c = std::fgetc(f)) != EOF;)
    if (c == '\n') return Ending::CutRow;
  return Ending::CutHeader;
}

// The file's first line, without its line end (what there is of it when cut off).
std::string firstLine(std::FILE* f) {
  std::rewind(f);
  std::string line;
  for (int c; (c = std::fgetc(f)) != EOF && c != '\n';)
    if (c != '\r') line += static_cast<char>(c);
  return line;
}

std::vector<std::string> columnsOf(const std::string& header) {
  std::vector<std::string> columns;
  std::size_t start = 0;
  for (std::size_t comma; (comma = header.find(',', start)) != std::string::npos; start = comma + 1)
    columns.push_back(header.substr(start, comma - start));
  columns.push_back(header.substr(start));
  return columns;
}

// Where `found` (an existing file's header) differs from `written` (today's), in words;
// empty when they are the same. A header cut off by a killed run (`cut`) need only be the
// start of today's.
std::string headerDifference(const std::string& found, const std::string& written, bool cut) {
  if (found == written || (cut && written.compare(0, found.size(), found) == 0)) return {};
  const std::vector<std::string> have = columnsOf(found), want = columnsOf(written);
  for (std::size_t k = 0; k < std::min(have.size(), want.size()); ++k)
    if (have[k] != want[k])
      return "its column " + std::to_string(k + 1) + " is \"" + have[k] + "\" where ImagePro writes \"" + want[k] +
             "\"";
  if (have.size() < want.size())
    return "it has " + std::to_string(have.size()) + " columns where ImagePro writes " + std::to_string(want.size()) +
           " (from \"" + want[have.size()] + "\" on)";
  return "it has " + std::to_string(have.size()) + " columns where ImagePro writes " + std::to_string(want.size()) +
         " (\"" + have[want.size()] + "\" and on are not written)";
}

}  // namespace

DataOut::~DataOut() { close(); }

std::string DataOut::header() { return recordCsvHeader(kDataOutCsv); }

std::string DataOut::row(const FrameResult& r) { return recordCsvRows(r, kDataOutCsv); }

Status DataOut::open(const std::string& path, ExistingFile existing, std::string& error) {
  close();
  namespace fs = std::filesystem;
  std::error_code ec;
  std::string target = path;
  bool append = false;
  if (fs::exists(target, ec)) {
    switch (existing) {
      case ExistingFile::Fail:
        error = path + ": file exists (choose append or a new name)";
        return Status::FileNotWritable;
      case ExistingFile::Append:
        append = true;
        break;
      case ExistingFile::NewName:
        for (int k = 1; fs::exists(target, ec); ++k) target = numberedName(path, k);
        break;
    }
  }
  lost_rows_ = 0;
  notice_.clear();
  bool empty = !append || fs::file_size(target, ec) == 0;
  // "a" never truncates (every write goes to the end, reads may go anywhere); "wx"
  // refuses to replace a file that appeared meanwhile.
  file_ = std::fopen(target.c_str(), append ? "a+" : "wx");
  if (!file_) {
    error = target + ": cannot open for writing: " + std::strerror(errno);
    return Status::FileNotWritable;
  }
  path_ = target;
  std::string start;  // what goes before the first row
  if (!empty) {
    const Ending ending = howItEnds(file_);
    // Rows go only under the header they belong to: an older version's or another program's
    // file is left as it is.
    if (const std::string difference = headerDifference(firstLine(file_), header(), ending == Ending::CutHeader);
        !difference.empty()) {
      error = target + ": not appended to, its header is not today's data-out header: " + difference +
              " (write to a new file, or a new numbered one beside it)";
      close();
      return Status::FileNotWritable;
    }
    switch (ending) {
      case Ending::Whole: break;
      case Ending::CutRow:
        start = "\n";
        lost_rows_ = 1;
        notice_ = target + ": its last row was cut off (an earlier run stopped while writing it); that row is "
                           "lost, new rows start on a line of their own";
        break;
      case Ending::CutHeader:
        start = "\n";
        empty = true;  // the header again, whole
        notice_ = target + ": its header was cut off (an earlier run stopped while writing it); the header is "
                           "written again on a line of its own";
        break;
    }
    std::fseek(file_, 0, SEEK_END);  // an update stream needs a seek between reading and writing
  }
  if (empty) start += header() + "\n";
  if (!start.empty()) {
    if (std::fputs(start.c_str(), file_) < 0 || std::fflush(file_) != 0) {
      error = target + ": cannot write: " + std::strerror(errno);
      close();
      return Status::FileNotWritable;
    }
  }
  return Status::Ok;
}

bool DataOut::write(const FrameResult& result, std::string& error) {
  if (!file_) {
    error = "data out is not open";
    return false;
  }
  const std::string line = row(result) + "\n";
  if (std::fputs(line.c_str(), file_) < 0 || std::fflush(file_) != 0) {
    error = path_ + ": cannot write: " + std::strerror(errno);
    close();
    return false;
  }
  return true;
}

void DataOut::close() {
  if (file_) std::fclose(file_);
  file_ = nullptr;
}

}  // namespace imagepro
