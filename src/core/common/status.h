#pragma once
// Status codes returned by every stage of the pipeline (thesis 1.4: "all methods
// should check their inputs and outputs ... and return a success or error code").
// A stage never throws across the frame loop; the frame result carries the status.
#include <cstdint>
#include <iosfwd>
#include <string_view>

namespace imagepro {

enum class Status : std::uint8_t {
  Ok,
  // input
  EmptyFrame,          // no pixels (zero size) or wrong pixel type
  FileNotFound,
  FileUnreadable,      // exists but cannot be read or decoded
  FileTruncated,       // an image file that ends before its image does (a cut-off copy)
  ImageTooLarge,       // an image size beyond what a frame may hold (core/common/image_limits.h)
  FileNotWritable,     // cannot be written (permissions, disk full, missing folder)
  EndOfStream,         // a finite source has no more frames
  // segmentation
  ThresholdUndefined,  // histogram has a single populated grey level or is empty
  UniformFrame,        // all black or all white after thresholding: nothing to segment
  // edges / connectivity
  NoEdges,
  InvalidEdgeList,     // an edge pixel lies outside the image or is listed twice
  // ellipse detection
  TooFewPoints,
  DegenerateFit,       // collinear or otherwise rank-deficient points
  NotAnEllipse,        // the best conic is a hyperbola or a parabola
  NoTarget,
  AmbiguousTarget,
  UnknownTarget,    // a target whose offset spot codes no member of the settings' set
  DuplicateTarget,  // two targets in the frame are coded as the same member (each gets it)
  // reconstruction
  SingularConic,
  SpotsNotFound,
  AmbiguousSpots,
  CentreSpotOutsideEllipse,
  NormalFacingAway,
  OutOfImage,
  FrameSizeMismatch,   // the frame's size differs from the camera model's: its pose would be wrong
  AmbiguousPose,       // the rim's two circles fit the spots about equally: either pose may be the one
  PoseInconsistent,    // the pose does not reproject the spots where the image has them
  // camera
  CameraNotFound,
  CameraPermissionDenied,
  CameraBusy,
  CameraNoSupportedFormat,
  CameraFormatRefused,
  CameraNoSuchInput,      // the capture card has no input of the number asked for
  CameraStandardRefused,  // the card's input does not take the TV standard asked for
  CameraTimeout,
  CameraDisconnected,
  // settings / calibration
  InvalidSettings,
  TooFewMatches,
  MatchAmbiguity,
  Diverged,
  PoorCoverage,        // the calibration's matched spots reach too little of the image
  InvalidPattern,      // a calibration pattern's description cannot be drawn or found (rows 0, spacing <= 0, ...)
  GridNotFound,        // the image shows no dot grid of the pattern's description
  TooFewViews,         // fewer usable views of the pattern than the calibration needs
  // live pose stream (core/pipeline/pose_stream.h)
  StreamHostNotFound,  // the stream's host is not a valid address and no name resolves to it
  StreamUnreachable,   // no route to the stream's host, or the network refuses to send there
  StreamRefused,       // the host answers that nothing listens on the stream's port
  // analysis (case studies, thesis 5.3)
  TooFewTargets,       // fewer targets in the frame than the measurement needs
  TooFewFrames,        // too few frames with a pose for the analysis
  NoSwing,             // the target does not oscillate
  TargetLost,          // no pose in half of the frames or more
  // processing deliberately stopped at an earlier stage (application level)
  Stopped,
};

// Stable machine name used in CSV output ("ok", "NoTarget", ...).
std::string_view statusName(Status s);
// One sentence for a person: what went wrong, in words.
std::string_view statusMessage(Status s);

inline bool ok(Status s) { return s == Status::Ok; }

// Writes the status's name (so test failures and logs read "NoTarget", not a number).
std::ostream& operator<<(std::ostream& os, Status s);

}  // namespace imagepro
