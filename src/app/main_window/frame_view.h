#pragma once
// The image part of the results area (thesis appendix A.1.2): the background the
// display options chose, edge pixels or coloured connected paths, the green
// estimated region, the blue detected region, the fitted ellipse, the contour
// features and spots, the fit numbers at the ellipse centre, and the live calibration
// check (the pattern's ideal spots, the spots found and their matching). Zoom with the
// wheel, pan by dragging, double-click to fit the frame to the view.
#include <QImage>
#include <QPointF>
#include <QWidget>

#include <vector>

#include "app/worker/display_packet.h"

namespace imagepro::app {

class FrameView : public QWidget {
  Q_OBJECT

 public:
  explicit FrameView(QWidget* parent = nullptr);

  void setPacket(DisplayPacketPtr packet);
  // No frame: the view is empty but for `message` (what to do to get one).
  void clear(const QString& message);
  QString message() const { return message_; }
  const DisplayPacketPtr& packet() const { return packet_; }

  double zoom() const { return zoom_; }  // screen pixels per image pixel
  void zoomBy(double factor, QPointF anchor);
  void zoomIn();
  void zoomOut();
  void fitToWindow();

  QSize sizeHint() const override { return {660, 500}; }
  // The live calibration check's line over the frame (empty when the check is off).
  QString calibrationCheckText() const;
  // Each target's detection numbers (fit error E, or Bennett's S, Q, Y) and where they are
  // drawn, in the view's coordinates: beside the target, never over it.
  struct NumberLabel {
    QString text;
    QRectF box;
  };
  std::vector<NumberLabel> numberLabels() const;
  // The target's ellipse's bounding box in the view's coordinates.
  QRectF targetScreenBox(const TargetSummary& target) const;

 signals:
  void painted();  // a new packet has been drawn (the worker may send the next one)

 protected:
  void paintEvent(QPaintEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void mouseDoubleClickEvent(QMouseEvent* event) override;
  void resizeEvent(QResizeEvent* event) override;

 private:
  void paintOverlays(QPainter& painter) const;
  void paintNumbers(QPainter& painter) const;
  void paintCalibrationCheck(QPainter& painter) const;
  QPointF toScreen(QPointF image_point) const;
  QFont numbersFont() const;
  QSize imageSize() const;

  DisplayPacketPtr packet_;
  QString message_;
  const DisplayPacket* last_painted_ = nullptr;  // repaints of the same packet do not count
  bool fit_ = true;       // keep the frame fitted to the view until the user zooms or pans
  double zoom_ = 1.0;
  QPointF offset_;        // screen position of image point (0, 0)'s top-left corner
  QPointF drag_start_;
  QPointF drag_offset_;
  bool dragging_ = false;
};

}  // namespace imagepro::app
