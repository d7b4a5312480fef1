#pragma once
// The keys of thesis appendix A.2.1 that move the virtual target: 4-6 Tx, 2-8 Ty,
// Insert-Delete Tz, Up-Down Rx, Left-Right Ry, Home-End Rz. The first key of each
// pair decreases the parameter, the second increases it. Digits work on the keypad
// and on the main keyboard.
#include <optional>

#include "core/source/virtual_motion.h"

namespace imagepro::app {

using VirtualKey = imagepro::VirtualKey;

std::optional<VirtualKey> virtualKeyFor(int qt_key);

}  // namespace imagepro::app
