#include "core/common/status.h"

#include <ostream>

#include "core/common/image_limits.h"

namespace imagepro {

namespace {
static_assert(kMaxImageSide == 16384 && kMaxImagePixels == 64 << 20, "ImageTooLarge's message names the bounds");

struct StatusText {
  std::string_view name;
  std::string_view message;
};

StatusText text(Status s) {
  switch (s) {
    case Status::Ok: return {"ok", "success"};
    case Status::EmptyFrame: return {"EmptyFrame", "the frame is empty or not 8-bit grey"};
    case Status::FileNotFound: return {"FileNotFound", "the file does not exist"};
    case Status::FileUnreadable: return {"FileUnreadable", "the file cannot be read or decoded as an image"};
    case Status::FileTruncated: return {"FileTruncated", "the image file ends before its image does (cut off in a copy or a download): only part of the image is there"};
    case Status::ImageTooLarge: return {"ImageTooLarge", "the image is larger than a frame may be (at most 16384 pixels a side and 64 megapixels)"};
    case Status::FileNotWritable: return {"FileNotWritable", "the file cannot be written"};
    case Status::EndOfStream: return {"EndOfStream", "the source has no more frames"};
    case Status::ThresholdUndefined: return {"ThresholdUndefined", "the histogram has fewer than two grey levels, so no threshold separates two classes"};
    case Status::UniformFrame: return {"UniformFrame", "the binary image is all black or all white"};
    case Status::NoEdges: return {"NoEdges", "no edge pixels were found"};
    case Status::InvalidEdgeList: return {"InvalidEdgeList", "an edge pixel lies outside the image or is listed twice"};
    case Status::TooFewPoints: return {"TooFewPoints", "fewer than six contour points for an ellipse fit"};
    case Status::DegenerateFit: return {"DegenerateFit", "the contour points are collinear or degenerate"};
    case Status::NotAnEllipse: return {"NotAnEllipse", "the best conic through the points is not an ellipse"};
    case Status::NoTarget: return {"NoTarget", "no target was found in the frame"};
    case Status::AmbiguousTarget: return {"AmbiguousTarget", "more than one target was found in the frame"};
    case Status::UnknownTarget:
      return {"UnknownTarget", "a target was found whose offset spot matches no target of the settings' set"};
    case Status::DuplicateTarget:
      return {"DuplicateTarget", "two targets in the frame carry the same id: the same print is in the scene twice"};
    case Status::SingularConic: return {"SingularConic", "the target's conic is singular"};
    case Status::SpotsNotFound: return {"SpotsNotFound", "the target's two spots were not found"};
    case Status::AmbiguousPose:
      return {"AmbiguousPose", "the target's two possible poses fit the image about equally well (far or blurred target)"};
    case Status::PoseInconsistent:
      return {"PoseInconsistent", "the pose does not put the spots where the image shows them"};
    case Status::AmbiguousSpots: return {"AmbiguousSpots", "more than two spot candidates inside the target"};
    case Status::CentreSpotOutsideEllipse: return {"CentreSpotOutsideEllipse", "the centre spot lies outside the target's ellipse"};
    case Status::NormalFacingAway: return {"NormalFacingAway", "the reconstructed target faces away from the camera"};
    case Status::OutOfImage: return {"OutOfImage", "the target or region lies outside the image"};
    case Status::FrameSizeMismatch: return {"FrameSizeMismatch", "the frame's size differs from the camera model's: calibrate the camera at this resolution or set its size in the settings"};
    case Status::CameraNotFound: return {"CameraNotFound", "no camera device at that path"};
    case Status::CameraPermissionDenied: return {"CameraPermissionDenied", "permission denied opening the camera"};
    case Status::CameraBusy: return {"CameraBusy", "the camera is in use by another program"};
    case Status::CameraNoSupportedFormat: return {"CameraNoSupportedFormat", "the camera offers no pixel format ImagePro can read"};
    case Status::CameraFormatRefused: return {"CameraFormatRefused", "the camera refused the requested format"};
    case Status::CameraNoSuchInput: return {"CameraNoSuchInput", "the capture card has no input of that number"};
    case Status::CameraStandardRefused: return {"CameraStandardRefused", "the capture card's input does not take that TV standard"};
    case Status::CameraTimeout: return {"CameraTimeout", "the camera delivered no frame in time"};
    case Status::CameraDisconnected: return {"CameraDisconnected", "the camera vanished while streaming"};
    case Status::InvalidSettings: return {"InvalidSettings", "the settings are invalid"};
    case Status::TooFewMatches: return {"TooFewMatches", "too few calibration spots were matched"};
    case Status::MatchAmbiguity: return {"MatchAmbiguity", "a calibration spot matches more than one ideal position"};
    case Status::Diverged: return {"Diverged", "the iteration diverged"};
    case Status::PoorCoverage: return {"PoorCoverage", "the pattern covers too little of the image to calibrate it to its corners: move the pattern closer or print it larger"};
    case Status::InvalidPattern: return {"InvalidPattern", "the calibration pattern's description is impossible: check its rows, columns, spacing and dot diameter"};
    case Status::GridNotFound: return {"GridNotFound", "the dot grid of the pattern was not found in the image: the whole grid must be in view, sharp and not too small"};
    case Status::TooFewViews: return {"TooFewViews", "fewer than three images show the pattern: take 4 to 10 views of it, tilted differently"};
    case Status::StreamHostNotFound: return {"StreamHostNotFound", "the stream's host is neither an address nor a name that resolves: check the host in the stream settings"};
    case Status::StreamUnreachable: return {"StreamUnreachable", "the stream's host cannot be reached from here (no route or the network refuses): datagrams are dropped"};
    case Status::StreamRefused: return {"StreamRefused", "nothing listens on the stream's port at its host yet: datagrams are dropped until a reader starts"};
    case Status::TooFewTargets: return {"TooFewTargets", "fewer targets were reconstructed in the frame than the measurement needs"};
    case Status::TooFewFrames: return {"TooFewFrames", "too few frames with a reconstructed pose for the analysis"};
    case Status::NoSwing: return {"NoSwing", "the target does not swing: no repeated oscillation stands out from the noise"};
    case Status::TargetLost: return {"TargetLost", "the target has no pose in half of the frames or more"};
    case Status::Stopped: return {"Stopped", "processing stopped at the selected application level"};
  }
  return {"Unknown", "unknown status"};
}
}  // namespace

std::string_view statusName(Status s) { return text(s).name; }
std::string_view statusMessage(Status s) { return text(s).message; }

std::ostream& operator<<(std::ostream& os, Status s) { return os << statusName(s); }

}  // namespace imagepro
