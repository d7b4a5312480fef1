#pragma once
// The pictures of the calibration wizard.
//  * CalibrationImageView: one calibration image with what the procedure made of it, as in
//    thesis fig. 4.6: the detected target's outline (green), the spot centres found
//    (cyan rings), the spots' ideal positions (red points) and the match lines from each
//    ideal position to the spot matched to it (yellow), optionally lengthened.
//  * DistortionFieldView: the displacement of the distortion model (thesis eq. 4.7) as
//    arrows from undistorted positions over the camera's image, lengthened by a stated
//    factor, with the principal point marked.
#include <QImage>
#include <QPointF>
#include <QWidget>

#include <optional>
#include <vector>

#include "core/common/geometry.h"
#include "core/ellipse/ellipse.h"

namespace imagepro::app {

struct CalibrationOverlay {
  std::optional<Ellipse> target;
  std::vector<QPointF> spots;  // centres found (step 5)
  std::vector<QPointF> ideal;  // ideal positions of the matched spots (step 4)
  std::vector<QPointF> seen;   // the spot matched to each ideal position (step 6)
};

class CalibrationImageView : public QWidget {
  Q_OBJECT

 public:
  explicit CalibrationImageView(QWidget* parent = nullptr);

  // A null image shows `placeholder` instead.
  void setImage(const QImage& image, const QString& placeholder = {});
  void setOverlay(CalibrationOverlay overlay);
  // Match lines are drawn `factor` times their length (1: as measured).
  void setMatchScale(int factor);

  const QImage& image() const { return image_; }
  const CalibrationOverlay& overlay() const { return overlay_; }
  QSize sizeHint() const override { return {400, 300}; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  QImage image_;
  QString placeholder_;
  CalibrationOverlay overlay_;
  int match_scale_ = 1;
};

class DistortionFieldView : public QWidget {
  Q_OBJECT

 public:
  static constexpr int kColumns = 16;  // arrows across the image; rows keep them square
  // A field whose largest displacement is below this is no distortion to speak of (less
  // than the sub-pixel rim resolves): it is not drawn, since magnified thousands of times
  // a distortion-free fit's residue would look like a real lens's field.
  static constexpr double kNegligiblePx = 0.05;

  explicit DistortionFieldView(QWidget* parent = nullptr);

  void setField(const CameraModel& camera, const Distortion& distortion);

  // Largest displacement over every pixel of the image, px.
  double largestDisplacementPx() const { return largest_px_; }
  // Arrows are drawn this many times their displacement (0: nothing to draw, or a
  // negligible field).
  double arrowScale() const { return arrow_scale_; }
  QSize sizeHint() const override { return {400, 300}; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  CameraModel camera_;
  std::vector<std::pair<QPointF, QPointF>> arrows_;  // from, displacement (px)
  double largest_px_ = 0.0;
  double arrow_scale_ = 0.0;
};

}  // namespace imagepro::app
