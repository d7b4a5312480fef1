#pragma once
// What the worker thread hands to the GUI for one displayed frame: the frame's
// result plus copies of only the images and pixel lists the current display
// options draw. The GUI paints from this alone and never touches the engine.
#include <QImage>
#include <QMetaType>
#include <QPoint>
#include <QString>

#include <memory>
#include <optional>
#include <vector>

#include "core/calibration/calibration_check.h"
#include "core/pipeline/frame_result.h"
#include "core/settings/options.h"

namespace imagepro::app {

// One processed frame, for the plots and the pose history (every frame, displayed or not).
struct PoseSample {
  std::int64_t index = 0;
  double timestamp_s = 0.0;
  Status status = Status::Ok;
  std::optional<Pose> pose;
  std::optional<Pose> truth;
  bool still = false;  // an image of a list (no clock): plotted by its number, not by time
};

struct DisplayPacket {
  FrameResult result;
  DisplayOptions display;                 // the options the copies below were made for
  EllipseMethod ellipse_method = EllipseMethod::DirectFit;
  // Images ready to paint (RGB32, converted in the worker thread, not the GUI's).
  QImage background;                      // full-frame grey source (Background::Source)
  QImage binary;                          // the searched region, thresholded (Background::Binary)
  QPoint binary_origin;                   // top-left of `binary` in the frame
  QImage target;                          // the target's region, grey or binary (Target::Source/Binary)
  QPoint target_origin;
  QImage edge_overlay;                    // frame-sized, transparent but for edge pixels or coloured paths
  // The live calibration check (display.calibration_check): status Stopped when off, the
  // frame's error (NoTarget ...) when it has no pattern pose.
  CalibrationCheck calibration;
  std::vector<PoseSample> history;        // every frame since the previous packet, this one last
  double hz = 0.0;                        // frames processed per second
  double cpu_percent = 0.0;               // worker thread CPU time over wall time
  QString source;                         // the source's description
  QString stream;                         // the live stream's report (PoseStream::report), empty when off
  bool stream_ok = true;                  // its status is Ok
  int file_index = -1;                    // the image shown of an open image list, from 0
  int file_count = 0;                     // the list's images (0: no list)
};

using DisplayPacketPtr = std::shared_ptr<const DisplayPacket>;

}  // namespace imagepro::app

Q_DECLARE_METATYPE(imagepro::app::DisplayPacketPtr)
