#pragma once
// The photographs the real-scene tests draw over (core/source/background_photos.h): why a
// test must skip when there are none.
#include <string>

#include "core/source/background_photos.h"

namespace imagepro::test {

// Empty when the default folder holds photographs, else the reason to skip, with the remedy.
inline std::string missingPhotographs() {
  const std::string dir = defaultBackgroundsDir();
  if (!listBackgrounds(dir).empty()) return {};
  return "no photographs in " + dir + ": install Debian's opencv-doc (tools/setup.sh does) or set " +
         "IMAGEPRO_BACKGROUNDS to a folder of JPEG/PNG photographs";
}

}  // namespace imagepro::test
