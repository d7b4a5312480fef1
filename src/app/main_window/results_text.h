#pragma once
// The text part of the results area (thesis appendix A.1.2): status in words,
// threshold, edge and path counts, fit error, the six parameters (and the ground
// truth for virtual frames), per-stage times, rate and CPU.
#include <QString>

#include "app/worker/display_packet.h"

namespace imagepro::app {

// The text's width in characters: no line is longer (the column beside the frame is
// this wide, main_window.cpp).
inline constexpr int kResultsColumns = 44;

QString formatResults(const DisplayPacket& packet);
// "ok" or "NoTarget: no target was found in the frame".
QString statusInWords(Status status);

}  // namespace imagepro::app
