#include "app/main_window/frame_view.h"

#include <QMouseEvent>
#include <QPainter>
#include <QFontMetrics>
#include <QWheelEvent>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "app/main_window/results_text.h"

namespace imagepro::app {

namespace {

constexpr double kMinZoom = 0.05;
constexpr double kMaxZoom = 64.0;
const QColor kSearchRegion(40, 220, 60);    // thesis: green estimated region
const QColor kDetectedRegion(60, 120, 255); // thesis: blue detected region
const QColor kEllipse(255, 60, 60);
const QColor kContour(255, 0, 255);
const QColor kSpots(255, 200, 0);
// The live calibration check, as thesis fig. 4.6 draws it: ideal positions red, the
// matching yellow; the spots found cyan.
const QColor kIdealSpots(255, 40, 40);
const QColor kFoundSpots(0, 220, 255);
const QColor kSpotMatches(255, 230, 0);

QRectF toRectF(const cv::Rect& r) { return QRectF(r.x, r.y, r.width, r.height); }

}  // namespace

FrameView::FrameView(QWidget* parent) : QWidget(parent) {
  setMinimumSize(200, 150);
  setFocusPolicy(Qt::StrongFocus);  // the appendix A keys reach the window while the view has focus
  setAttribute(Qt::WA_OpaquePaintEvent);
  setMouseTracking(false);
  setToolTip(tr("Wheel: zoom, drag: pan, double-click: fit the frame"));
}

void FrameView::setPacket(DisplayPacketPtr packet) {
  const QSize old = imageSize();
  packet_ = std::move(packet);
  if (fit_ || old != imageSize()) fitToWindow();
  update();
}

void FrameView::clear(const QString& message) {
  packet_.reset();
  last_painted_ = nullptr;
  message_ = message;
  update();
}

QSize FrameView::imageSize() const {
  if (!packet_) return {};
  const cv::Size s = packet_->result.image_size;
  return {s.width, s.height};
}

void FrameView::fitToWindow() {
  fit_ = true;
  const QSize s = imageSize();
  if (s.isEmpty()) return;
  zoom_ = std::clamp(std::min(width() / double(s.width()), height() / double(s.height())), kMinZoom, kMaxZoom);
  offset_ = QPointF((width() - zoom_ * s.width()) / 2.0, (height() - zoom_ * s.height()) / 2.0);
  update();
}

void FrameView::zoomBy(double factor, QPointF anchor) {
  const double z = std::clamp(zoom_ * factor, kMinZoom, kMaxZoom);
  // Keep the image point under `anchor` where it is.
  offset_ = anchor - (anchor - offset_) * (z / zoom_);
  zoom_ = z;
  fit_ = false;
  update();
}

void FrameView::zoomIn() { zoomBy(1.25, rect().center()); }
void FrameView::zoomOut() { zoomBy(0.8, rect().center()); }

QPointF FrameView::toScreen(QPointF p) const { return offset_ + zoom_ * p; }

void FrameView::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  painter.fillRect(rect(), QColor(32, 34, 38));
  if (!packet_) {
    painter.setPen(QColor(180, 180, 180));
    painter.drawText(rect().adjusted(12, 12, -12, -12), Qt::AlignCenter | Qt::TextWordWrap,
                     message_.isEmpty() ? tr("No frame yet: choose a source and press Start, or open a file") : message_);
    return;
  }
  const DisplayPacket& p = *packet_;
  painter.save();
  painter.translate(offset_);
  painter.scale(zoom_, zoom_);
  painter.setRenderHint(QPainter::SmoothPixmapTransform, zoom_ < 1.0);
  const QSize size = imageSize();
  painter.fillRect(QRect(QPoint(0, 0), size), Qt::black);  // Empty background, and under Binary
  if (!p.background.isNull()) painter.drawImage(QPoint(0, 0), p.background);
  if (!p.binary.isNull()) painter.drawImage(p.binary_origin, p.binary);
  if (!p.target.isNull()) painter.drawImage(p.target_origin, p.target);
  if (!p.edge_overlay.isNull()) painter.drawImage(QPoint(0, 0), p.edge_overlay);
  paintOverlays(painter);
  painter.restore();
  paintNumbers(painter);
  if (last_painted_ != packet_.get()) {
    last_painted_ = packet_.get();
    emit painted();
  }
}

void FrameView::paintOverlays(QPainter& painter) const {
  const DisplayPacket& p = *packet_;
  const FrameResult& r = p.result;
  painter.setRenderHint(QPainter::Antialiasing, true);
  QPen pen;
  pen.setCosmetic(true);
  pen.setWidthF(2.0);
  painter.setBrush(Qt::NoBrush);
  // Regions are in whole pixels: their rectangles cover the pixels' full squares.
  if (!r.search_region.empty()) {
    pen.setColor(kSearchRegion);
    painter.setPen(pen);
    painter.drawRect(toRectF(r.search_region));
  }
  if (!r.detected_region.empty()) {
    pen.setColor(kDetectedRegion);
    painter.setPen(pen);
    painter.drawRect(toRectF(r.detected_region));
  }
  // Point features: pixel (u, v)'s centre sits at (u + 0.5, v + 0.5) in the painter.
  painter.translate(0.5, 0.5);
  if (p.display.target == DisplayOptions::Target::Path) {
    pen.setColor(kEllipse);
    painter.setPen(pen);
    for (const TargetSummary& t : r.targets) {
      painter.save();
      painter.translate(t.ellipse.cx, t.ellipse.cy);
      painter.rotate(t.ellipse.angle_deg);
      painter.drawEllipse(QPointF(0, 0), t.ellipse.a, t.ellipse.b);
      painter.restore();
    }
  }
  if (p.display.feature_edge && !r.contour_points.empty()) {
    // Square cosmetic points without antialiasing: hundreds of them cost next to nothing.
    painter.setRenderHint(QPainter::Antialiasing, false);
    QPen dots(kContour);
    dots.setCosmetic(true);
    dots.setWidthF(3.0);
    painter.setPen(dots);
    QPolygonF points;
    points.reserve(static_cast<qsizetype>(r.contour_points.size()));
    for (const cv::Point2f& c : r.contour_points) points.append(QPointF(c.x, c.y));
    painter.drawPoints(points);
    painter.setRenderHint(QPainter::Antialiasing, true);
  }
  if (p.display.feature_spots && r.reached >= ApplicationLevel::Reconstruction) {
    pen.setColor(kSpots);
    painter.setPen(pen);
    const double arm = 6.0 / zoom_;
    const auto cross = [&](const std::array<cv::Point2f, 2>& spots) {
      for (const cv::Point2f& s : spots) {
        painter.drawLine(QPointF(s.x - arm, s.y), QPointF(s.x + arm, s.y));
        painter.drawLine(QPointF(s.x, s.y - arm), QPointF(s.x, s.y + arm));
      }
    };
    // A set: every target with a pose its own spots; else the one target's.
    if (r.set_of_targets) {
      for (const TargetSummary& t : r.targets)
        if (ok(t.status) && t.pose) cross(t.spots);
    } else if (r.pose) {
      cross(r.spots);
    }
  }
  paintCalibrationCheck(painter);
}

void FrameView::paintCalibrationCheck(QPainter& painter) const {
  const CalibrationCheck& c = packet_->calibration;
  if (c.ideal.empty() && c.seen.empty()) return;
  // Hundreds of marks a frame: square cosmetic points and plain lines, no antialiasing.
  painter.save();
  painter.setRenderHint(QPainter::Antialiasing, false);
  const auto points = [](const std::vector<Eigen::Vector2d>& at) {
    QPolygonF out;
    out.reserve(static_cast<qsizetype>(at.size()));
    for (const Eigen::Vector2d& p : at) out.append(QPointF(p.x(), p.y()));
    return out;
  };
  QPen pen(kSpotMatches);
  pen.setCosmetic(true);
  pen.setWidthF(1.0);
  painter.setPen(pen);
  QList<QLineF> lines;
  lines.reserve(static_cast<qsizetype>(c.matches.size()));
  for (const auto& [i, o] : c.matches)
    if (i >= 0 && o >= 0 && static_cast<size_t>(i) < c.ideal.size() && static_cast<size_t>(o) < c.seen.size())
      lines.append(QLineF(c.ideal[i].x(), c.ideal[i].y(), c.seen[o].x(), c.seen[o].y()));
  painter.drawLines(lines);
  pen.setWidthF(5.0);
  pen.setColor(kFoundSpots);
  painter.setPen(pen);
  painter.drawPoints(points(c.seen));
  pen.setWidthF(3.0);
  pen.setColor(kIdealSpots);
  painter.setPen(pen);
  painter.drawPoints(points(c.ideal));
  painter.restore();
}

QString FrameView::calibrationCheckText() const {
  if (!packet_) return {};
  const CalibrationCheck& c = packet_->calibration;
  if (c.status == Status::Stopped) return {};
  if (!ok(c.status)) return tr("Calibration check: %1").arg(statusInWords(c.status));
  return tr("Calibration check: %1 of %2 spots matched, %3 ambiguous, %4 found")
      .arg(c.stats.matched)
      .arg(c.ideal.size())
      .arg(c.stats.ambiguous)
      .arg(c.seen.size());
}

void FrameView::paintNumbers(QPainter& painter) const {
  // Drawn in screen space so they stay readable at every zoom.
  const DisplayPacket& p = *packet_;
  const QFont font = numbersFont();
  painter.setFont(font);
  if (const QString check = calibrationCheckText(); !check.isEmpty()) {
    const QFontMetrics metrics(font);
    QRectF box = metrics.boundingRect(check);
    box.adjust(-4, -1, 4, 1);
    box.moveTopLeft(QPointF(6, 6));
    painter.setPen(Qt::NoPen);
    painter.setBrush(QColor(0, 0, 0, 150));
    painter.drawRoundedRect(box, 3, 3);
    painter.setPen(ok(p.calibration.status) ? kFoundSpots : QColor(255, 120, 120));
    painter.drawText(box, Qt::AlignCenter, check);
  }
  const std::vector<NumberLabel> labels = numberLabels();
  for (const NumberLabel& label : labels) {
    painter.setPen(Qt::NoPen);
    painter.setBrush(QColor(0, 0, 0, 150));
    painter.drawRoundedRect(label.box, 3, 3);
    painter.setPen(QColor(255, 255, 120));
    painter.drawText(label.box, Qt::AlignCenter, label.text);
  }
}

QFont FrameView::numbersFont() const {
  QFont f = font();
  f.setPointSizeF(std::max(8.0, f.pointSizeF()));
  f.setBold(true);
  return f;
}

QRectF FrameView::targetScreenBox(const TargetSummary& t) const {
  // The rotated ellipse's axis-aligned half extents.
  const double th = t.ellipse.angle_deg * std::numbers::pi / 180.0;
  const double c = std::cos(th), s = std::sin(th);
  const double hx = std::hypot(t.ellipse.a * c, t.ellipse.b * s);
  const double hy = std::hypot(t.ellipse.a * s, t.ellipse.b * c);
  const QPointF centre(t.ellipse.cx + 0.5, t.ellipse.cy + 0.5);
  return QRectF(toScreen(centre - QPointF(hx, hy)), toScreen(centre + QPointF(hx, hy)));
}

std::vector<FrameView::NumberLabel> FrameView::numberLabels() const {
  std::vector<NumberLabel> labels;
  if (!packet_) return labels;
  const DisplayPacket& p = *packet_;
  const QFontMetrics metrics(numbersFont());
  for (const TargetSummary& t : p.result.targets) {
    NumberLabel label;
    label.text = p.ellipse_method == EllipseMethod::Bennett ? tr("S %1  Q %2  Y %3")
                                                                  .arg(t.bennett_score, 0, 'f', 0)
                                                                  .arg(t.bennett_quality, 0, 'f', 0)
                                                                  .arg(t.bennett_symmetry, 0, 'f', 2)
                                                            : tr("E %1").arg(t.fit_error, 0, 'g', 3);
    // A set's target carries its id (and its own status when it has no pose) before its numbers.
    if (p.result.set_of_targets && (t.target_id >= 0 || t.status == Status::UnknownTarget)) {
      QString id = t.target_id >= 0 ? tr("id %1").arg(t.target_id) : tr("no id");
      if (!ok(t.status)) id += QStringLiteral(" ") + QString::fromUtf8(statusName(t.status).data());
      label.text = id + QStringLiteral("  ") + label.text;
    }
    label.box = metrics.boundingRect(label.text);
    label.box.adjust(-4, -1, 4, 1);
    // Beside the target, not on it: the spots and the rim it measured stay in sight. Below
    // the disk, or above it where the view ends; kept inside the view sideways.
    const QRectF target = targetScreenBox(t);
    const double gap = 4.0;
    label.box.moveTop(target.bottom() + gap);
    if (label.box.bottom() > height()) label.box.moveBottom(target.top() - gap);
    label.box.moveLeft(std::clamp(target.center().x() - label.box.width() / 2.0, 0.0,
                                  std::max(0.0, width() - label.box.width())));
    labels.push_back(label);
  }
  return labels;
}

void FrameView::wheelEvent(QWheelEvent* event) {
  const double steps = event->angleDelta().y() / 120.0;
  if (steps != 0.0) zoomBy(std::pow(1.25, steps), event->position());
  event->accept();
}

void FrameView::mousePressEvent(QMouseEvent* event) {
  if (event->button() == Qt::LeftButton) {
    dragging_ = true;
    drag_start_ = event->position();
    drag_offset_ = offset_;
    setCursor(Qt::ClosedHandCursor);
  }
  QWidget::mousePressEvent(event);
}

void FrameView::mouseMoveEvent(QMouseEvent* event) {
  if (dragging_) {
    offset_ = drag_offset_ + (event->position() - drag_start_);
    fit_ = false;
    update();
  }
}

void FrameView::mouseReleaseEvent(QMouseEvent* event) {
  if (event->button() == Qt::LeftButton && dragging_) {
    dragging_ = false;
    unsetCursor();
  }
}

void FrameView::mouseDoubleClickEvent(QMouseEvent*) { fitToWindow(); }

void FrameView::resizeEvent(QResizeEvent*) {
  if (fit_) fitToWindow();
}

}  // namespace imagepro::app
