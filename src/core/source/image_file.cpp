#include "core/source/image_file.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/common/image_limits.h"

namespace imagepro {

namespace fs = std::filesystem;

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return {};
  const auto end = s.find_last_not_of(" \t\r\n");
  return s.substr(begin, end - begin + 1);
}

// What the container of a PNG or JPEG file says before any pixel is decoded: its
// size, and whether the file holds all of it. Decoders fill a cut-off JPEG with grey
// (and libpng may stop part-way) and hand back a partial image as if it were whole.
struct Container {
  bool known = false;      // a PNG or JPEG whose structure could be walked
  bool truncated = false;  // the file ends before the image's end marker
  std::int64_t width = 0, height = 0;
};

std::uint32_t bigEndian(const std::vector<unsigned char>& b, std::size_t at, int bytes) {
  std::uint32_t v = 0;
  for (int i = 0; i < bytes; ++i) v = (v << 8) | b[at + static_cast<std::size_t>(i)];
  return v;
}

// PNG: the signature, then chunks (length, type, data, CRC) up to IEND.
Container pngContainer(const std::vector<unsigned char>& b) {
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  Container c;
  if (b.size() < 8 || !std::equal(kSignature, kSignature + 8, b.begin())) return c;
  c.known = true;
  for (std::size_t at = 8;;) {
    if (b.size() - at < 12) break;
    const std::uint64_t length = bigEndian(b, at, 4);
    const std::string type(b.begin() + static_cast<std::ptrdiff_t>(at + 4), b.begin() + static_cast<std::ptrdiff_t>(at + 8));
    // Chunk types are four letters and IHDR comes first: anything else is corrupt, not cut off.
    const bool letters = std::all_of(type.begin(), type.end(), [](char ch) { return std::isalpha(static_cast<unsigned char>(ch)) != 0; });
    if (!letters || (at == 8 && type != "IHDR")) return Container{};
    if (b.size() - at - 12 < length) break;
    if (type == "IHDR" && length >= 8) {
      c.width = bigEndian(b, at + 8, 4);
      c.height = bigEndian(b, at + 12, 4);
    }
    if (type == "IEND") return c;
    at += 12 + length;
  }
  c.truncated = true;
  return c;
}

// JPEG: marker segments up to EOI; after each start of scan the entropy-coded data
// runs to the next marker that is neither a stuffed 0xFF00 nor a restart marker.
Container jpegContainer(const std::vector<unsigned char>& b) {
  Container c;
  if (b.size() < 3 || b[0] != 0xFF || b[1] != 0xD8 || b[2] != 0xFF) return c;
  c.known = true;
  std::size_t at = 2;
  while (at < b.size()) {
    if (b[at] != 0xFF) return Container{};  // not a marker: corrupt, which the decoder reports
    while (at < b.size() && b[at] == 0xFF) ++at;  // fill bytes
    if (at >= b.size()) break;
    const unsigned char marker = b[at++];
    if (marker == 0xD9) return c;                                       // EOI: the image is whole
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8)) continue;  // no length
    if (b.size() - at < 2) break;
    const std::size_t length = bigEndian(b, at, 2);
    if (length < 2 || b.size() - at < length) break;
    const bool frame_header = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (frame_header && length >= 7) {
      c.height = bigEndian(b, at + 3, 2);
      c.width = bigEndian(b, at + 5, 2);
    }
    at += length;
    if (marker != 0xDA) continue;
    while (at + 1 < b.size() && !(b[at] == 0xFF && b[at + 1] != 0x00 && !(b[at + 1] >= 0xD0 && b[at + 1] <= 0xD7)))
      ++at;
    if (at + 1 >= b.size()) break;
  }
  c.truncated = true;
  return c;
}

}  // namespace

Status toGrey8(const cv::Mat& decoded, cv::Mat& grey, std::string& error) {
  if (decoded.empty() || decoded.cols <= 0 || decoded.rows <= 0) {
    error = "the image has no pixels";
    return Status::FileUnreadable;
  }
  const int depth = decoded.depth();
  if (depth != CV_8U && depth != CV_16U && depth != CV_32F && depth != CV_64F) {
    error = "unsupported pixel type (only 8-bit, 16-bit and floating point)";
    return Status::FileUnreadable;
  }
  cv::Mat one_channel;
  switch (decoded.channels()) {
    case 1: one_channel = decoded; break;
    case 2: cv::extractChannel(decoded, one_channel, 0); break;  // grey + alpha
    case 3: cv::cvtColor(decoded, one_channel, cv::COLOR_BGR2GRAY); break;
    case 4: cv::cvtColor(decoded, one_channel, cv::COLOR_BGRA2GRAY); break;
    default:
      error = "unsupported number of channels (" + std::to_string(decoded.channels()) + ")";
      return Status::FileUnreadable;
  }
  switch (depth) {
    case CV_8U: one_channel.copyTo(grey); break;
    case CV_16U: one_channel.convertTo(grey, CV_8U, 1.0 / 257.0); break;
    default: one_channel.convertTo(grey, CV_8U, 255.0); break;  // floating point, 0..1
  }
  return Status::Ok;
}

Status readGreyImage(const std::string& path, cv::Mat& grey, std::string& error) {
  grey.release();
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) {
    error = path + ": no such file";
    return Status::FileNotFound;
  }
  if (fs::is_directory(st)) {
    error = path + ": is a folder, not an image file";
    return Status::FileUnreadable;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = path + ": cannot be opened (" + std::strerror(errno) + ")";
    return Status::FileUnreadable;
  }
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) {
    error = path + ": read error";
    return Status::FileUnreadable;
  }
  if (bytes.empty()) {
    error = path + ": empty file";
    return Status::FileUnreadable;
  }
  Container container = pngContainer(bytes);
  if (!container.known) container = jpegContainer(bytes);
  if (container.truncated) {
    error = path + ": the file ends before its image does (" + std::to_string(bytes.size()) +
            " bytes; cut off in a copy or a download?)";
    return Status::FileTruncated;
  }
  if (container.width > 0 && container.height > 0) {  // refused before the decoder allocates it
    if (const std::string problem = imageSizeProblem(container.width, container.height); !problem.empty()) {
      error = path + ": " + problem;
      return Status::ImageTooLarge;
    }
  }
  cv::Mat decoded;
  try {
    decoded = cv::imdecode(bytes, cv::IMREAD_ANYDEPTH | cv::IMREAD_ANYCOLOR);
  } catch (const cv::Exception& e) {
    error = path + ": cannot be decoded (" + e.err + ")";
    return Status::FileUnreadable;
  } catch (const std::exception& e) {
    error = path + ": cannot be decoded (" + e.what() + ")";
    return Status::FileUnreadable;
  }
  if (decoded.empty()) {
    error = path + ": not a readable image (unknown format or corrupt data)";
    return Status::FileUnreadable;
  }
  if (const std::string problem = imageSizeProblem(decoded.cols, decoded.rows); !problem.empty()) {
    error = path + ": " + problem;
    return Status::ImageTooLarge;
  }
  std::string reason;
  const Status s = toGrey8(decoded, grey, reason);
  if (!ok(s)) {
    grey.release();
    error = path + ": " + reason;
  }
  return s;
}

bool isImageFileName(const std::string& path) {
  static const char* const kExtensions[] = {".png", ".pgm", ".ppm", ".pbm", ".pnm", ".bmp", ".dib",
                                            ".jpg", ".jpeg", ".jpe", ".tif", ".tiff"};
  const std::string ext = lower(fs::path(path).extension().string());
  return std::any_of(std::begin(kExtensions), std::end(kExtensions), [&](const char* e) { return ext == e; });
}

bool naturalLess(const std::string& a, const std::string& b) {
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const bool da = std::isdigit(static_cast<unsigned char>(a[i])) != 0;
    const bool db = std::isdigit(static_cast<unsigned char>(b[j])) != 0;
    if (da && db) {
      // Compare the numbers without leading zeros: longer is larger, else digit by digit.
      size_t ia = i, jb = j;
      while (ia < a.size() && a[ia] == '0') ++ia;
      while (jb < b.size() && b[jb] == '0') ++jb;
      size_t ea = ia, eb = jb;
      while (ea < a.size() && std::isdigit(static_cast<unsigned char>(a[ea]))) ++ea;
      while (eb < b.size() && std::isdigit(static_cast<unsigned char>(b[eb]))) ++eb;
      if (ea - ia != eb - jb) return ea - ia < eb - jb;
      const int c = a.compare(ia, ea - ia, b, jb, eb - jb);
      if (c != 0) return c < 0;
      i = ea;
      j = eb;
    } else {
      const int ca = std::tolower(static_cast<unsigned char>(a[i]));
      const int cb = std::tolower(static_cast<unsigned char>(b[j]));
      if (ca != cb) return ca < cb;
      ++i;
      ++j;
    }
  }
  if ((i < a.size()) != (j < b.size())) return i >= a.size();  // a prefix comes first
  return a < b;  // equal apart from case or leading zeros
}

Status listImageSequence(const std::string& folderOrListFile, std::vector<std::string>& paths, std::string& error) {
  paths.clear();
  std::error_code ec;
  const fs::path where(folderOrListFile);
  const fs::file_status st = fs::status(where, ec);
  if (!fs::exists(st)) {
    error = folderOrListFile + ": no such file or folder";
    return Status::FileNotFound;
  }
  if (fs::is_directory(st)) {
    fs::directory_iterator it(where, ec);
    if (ec) {
      error = folderOrListFile + ": cannot be listed (" + ec.message() + ")";
      return Status::FileUnreadable;
    }
    std::vector<std::string> names;
    for (const auto& entry : it) {
      std::error_code entry_ec;
      if (entry.is_regular_file(entry_ec) && isImageFileName(entry.path().filename().string()))
        names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end(), naturalLess);
    for (const auto& name : names) paths.push_back((where / name).string());
    if (paths.empty()) {
      error = folderOrListFile + ": no image files in the folder";
      return Status::FileNotFound;
    }
    return Status::Ok;
  }
  if (isImageFileName(folderOrListFile)) {  // a single image is a sequence of one
    paths.push_back(folderOrListFile);
    return Status::Ok;
  }
  std::ifstream in(where);
  if (!in) {
    error = folderOrListFile + ": cannot be opened (" + std::strerror(errno) + ")";
    return Status::FileUnreadable;
  }
  const fs::path base = where.parent_path();
  std::string line;
  while (std::getline(in, line)) {
    const std::string entry = trim(line);
    if (entry.empty() || entry[0] == '#') continue;
    const fs::path p(entry);
    paths.push_back(p.is_absolute() || base.empty() ? p.string() : (base / p).string());
  }
  if (in.bad()) {
    paths.clear();
    error = folderOrListFile + ": read error";
    return Status::FileUnreadable;
  }
  if (paths.empty()) {
    error = folderOrListFile + ": the list names no image";
    return Status::FileNotFound;
  }
  return Status::Ok;
}

}  // namespace imagepro
