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
