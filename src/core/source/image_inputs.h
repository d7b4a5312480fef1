#pragma once
// What the user's image inputs stand for: one rule for the CLI's positional inputs
// and the GUI's File source. An input is
//   - a folder: its image files, in natural order of their names;
//   - a file whose name is an image's (isImageFileName): that image, even when it is
//     missing or corrupt (found when it is read, in its own frame);
//   - any other file: a list of images, text with one path a line (listImageSequence:
//     '#' comments and blank lines skipped, relative paths from the list's folder).
//     A file that is not text is neither, and says so.
// A path that does not exist and has no image's name is a missing list or folder.
#include <string>
#include <vector>

#include "core/common/status.h"

namespace imagepro {

// One image to read, or an input that could not be expanded (status not Ok, `error`
// naming it and the reason; `path` is the input as given).
struct ImageInput {
  std::string path;
  Status status = Status::Ok;
  std::string error;
};

// The inputs in order, each folder and list replaced by the images it holds. An empty
// or missing folder or list is one entry with FileNotFound, an unreadable one (or a
// file that is neither an image nor a text list) one with FileUnreadable.
std::vector<ImageInput> expandImageInputs(const std::vector<std::string>& inputs);

}  // namespace imagepro
