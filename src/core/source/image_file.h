#pragma once
// Image files for the File source (thesis 2.2, "digital image file"): PNG, PGM/PPM,
// BMP, JPEG and TIFF through OpenCV, delivered as 8-bit grey. Colour is converted to
// grey (ITU-R 601 weights), 16-bit is scaled to 8-bit (v / 257, so 65535 -> 255) and
// floating point is taken as 0..1. Nothing here throws: a missing file is
// FileNotFound, a PNG or JPEG that ends before its image does (which the decoders
// would hand back partly grey) is FileTruncated, an image beyond 16384 pixels a side
// or 64 megapixels (core/common/image_limits.h) is ImageTooLarge, anything else that
// cannot be read is FileUnreadable, and `error` names the file and the reason.
#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include "core/common/status.h"

namespace imagepro {

// Reads `path` into `grey` (CV_8UC1). On failure `grey` is released.
Status readGreyImage(const std::string& path, cv::Mat& grey, std::string& error);

// Converts a decoded image (1-4 channels; 8U, 16U, 32F or 64F) to CV_8UC1.
// Returns FileUnreadable for an empty image or another pixel type.
Status toGrey8(const cv::Mat& decoded, cv::Mat& grey, std::string& error);

// True when the extension is one of the formats above (case-insensitive).
bool isImageFileName(const std::string& path);

// Natural order: digit runs compare as numbers ("img2" < "img10"), letters without
// regard to case; ties are broken by plain comparison so the order is total.
bool naturalLess(const std::string& a, const std::string& b);

// The images of an image sequence: every image file of a folder in natural order of
// the file names, or the paths listed in a text file (one per line, blank lines and
// lines starting with '#' skipped, relative paths taken from the list's folder), in
// the listed order (an image file itself is a sequence of one). FileNotFound when the folder or list is missing or holds no
// image; FileUnreadable when it cannot be read.
Status listImageSequence(const std::string& folderOrListFile, std::vector<std::string>& paths, std::string& error);

}  // namespace imagepro
