#pragma once
// Lets GoogleTest print a Status by its name in failure messages.
#include <ostream>

#include "core/common/status.h"

namespace imagepro {
inline void PrintTo(Status s, std::ostream* os) { *os << statusName(s); }
}  // namespace imagepro
