#pragma once
// Image inputs of the command line, shared by every command that reads image files:
// folders and list files expanded to their images (by the rule of
// core/source/image_inputs.h, which the GUI's File source follows too), images decoded
// without the decoders' own messages on stderr, and output file names kept unique.
#include <opencv2/core.hpp>

#include <set>
#include <string>
#include <vector>

#include "core/common/status.h"
#include "core/source/image_inputs.h"

namespace imagepro::cli {

using imagepro::expandImageInputs;
using imagepro::ImageInput;

// Keeps fd 2 on /dev/null while alive: OpenCV's image decoders and libpng print their
// own lines on a corrupt file ("imdecode_(...)", "libpng error: ..."), which would
// stand beside the command's one-line error. Only around a decode, never around
// output of our own.
class DecoderMessagesSilenced {
 public:
  DecoderMessagesSilenced();
  ~DecoderMessagesSilenced();
  DecoderMessagesSilenced(const DecoderMessagesSilenced&) = delete;
  DecoderMessagesSilenced& operator=(const DecoderMessagesSilenced&) = delete;

 private:
  int saved_stderr_ = -1;
};

// readGreyImage with the decoders' messages silenced.
Status readGreyImageQuietly(const std::string& path, cv::Mat& grey, std::string& error);

// Output names from input file stems, unique within one run: the first "a" stays
// "a", the next "a_2", then "a_3" ... (a stem that is itself taken gets the next free
// number too), so same-named images from different folders do not overwrite each other.
class UniqueNames {
 public:
  std::string take(const std::string& stem);

 private:
  std::set<std::string> taken_;
};

}  // namespace imagepro::cli
