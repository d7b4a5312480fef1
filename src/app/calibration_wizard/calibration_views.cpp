#include "app/calibration_wizard/calibration_views.h"

#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <cmath>

#include "core/calibration/distortion_fit.h"

namespace imagepro::app {

namespace {

const QColor kTargetColour(40, 220, 60);
const QColor kSpotColour(0, 200, 255);
const QColor kIdealColour(255, 40, 40);    // thesis fig. 4.6: red ideal positions
const QColor kMatchColour(255, 230, 0);    // and yellow match lines
const QColor kArrowColour(20, 60, 160);

// The largest of 1, 2, 5 times a power of ten not above `limit` (> 0).
double niceFloor(double limit) {
  const double decade = std::pow(10.0, std::floor(std::log10(limit)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * decade <= limit * (1.0 + 1e-9)) return m * decade;
  return decade;
}

// Where an image of `size` goes in `area`, as large as fits, centred.
QRectF fitted(QSizeF size, const QRectF& area) {
  if (size.isEmpty()) return {};
  const double zoom = std::min(area.width() / size.width(), area.height() / size.height());
  const QSizeF s = size * zoom;
  return QRectF(area.center() - QPointF(s.width(), s.height()) / 2.0, s);
}

}  // namespace

// ---- CalibrationImageView ----------------------------------------------------------

CalibrationImageView::CalibrationImageView(QWidget* parent) : QWidget(parent) {
  setMinimumSize(240, 180);
  setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
}

void CalibrationImageView::setImage(const QImage& image, const QString& placeholder) {
  image_ = image;
  placeholder_ = placeholder;
  if (image.isNull()) overlay_ = {};
  update();
}

void CalibrationImageView::setOverlay(CalibrationOverlay overlay) {
  overlay_ = std::move(overlay);
  update();
}

void CalibrationImageView::setMatchScale(int factor) {
  match_scale_ = std::max(1, factor);
  update();
}

void CalibrationImageView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.fillRect(rect(), QColor(40, 40, 40));
  if (image_.isNull()) {
    p.setPen(QColor(200, 200, 200));
    p.drawText(rect().adjusted(8, 8, -8, -8), Qt::AlignCenter | Qt::TextWordWrap, placeholder_);
    return;
  }
  const QRectF target = fitted(image_.size(), QRectF(rect()));
  p.setRenderHint(QPainter::SmoothPixmapTransform);
  p.drawImage(target, image_);
  p.setRenderHint(QPainter::Antialiasing);
  // Image coordinates: the centre of pixel (0, 0) at (0, 0), so pixel i covers [i - 0.5, i + 0.5].
  const double zoom = target.width() / image_.width();
  p.translate(target.topLeft() + QPointF(0.5, 0.5) * zoom);
  p.scale(zoom, zoom);

  QPen pen(kTargetColour, 2.0);
  pen.setCosmetic(true);
  if (const auto& e = overlay_.target) {
    p.setPen(pen);
    p.setBrush(Qt::NoBrush);
    p.save();
    p.translate(e->cx, e->cy);
    p.rotate(e->angle_deg);
    p.drawEllipse(QPointF(0, 0), e->a, e->b);
    p.restore();
  }
  // Sizes in screen pixels, whatever the zoom.
  const double ring = 3.0 / zoom, dot = 1.6 / zoom;
  pen.setColor(kSpotColour);
  pen.setWidthF(1.0);
  p.setPen(pen);
  for (const QPointF& s : overlay_.spots) p.drawEllipse(s, ring, ring);
  pen.setColor(kMatchColour);
  pen.setWidthF(1.5);
  p.setPen(pen);
  const size_t matches = std::min(overlay_.ideal.size(), overlay_.seen.size());
  for (size_t i = 0; i < matches; ++i)
    p.drawLine(overlay_.ideal[i], overlay_.ideal[i] + match_scale_ * (overlay_.seen[i] - overlay_.ideal[i]));
  p.setPen(Qt::NoPen);
  p.setBrush(kIdealColour);
  for (const QPointF& q : overlay_.ideal) p.drawEllipse(q, dot, dot);
}

// ---- DistortionFieldView -------------------------------------------------------------

DistortionFieldView::DistortionFieldView(QWidget* parent) : QWidget(parent) {
  setMinimumSize(240, 180);
  setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
}

void DistortionFieldView::setField(const CameraModel& camera, const Distortion& distortion) {
  camera_ = camera;
  arrows_.clear();
  largest_px_ = compareDistortionFields(camera, distortion, Distortion{}).max_px;
  const double step = static_cast<double>(camera.width) / kColumns;
  const int rows = std::max(1, static_cast<int>(std::lround(camera.height / step)));
  const double row_step = static_cast<double>(camera.height) / rows;
  const Eigen::Vector2d pp(camera.u0(), camera.v0());
  double longest = 0.0;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < kColumns; ++c) {
      // Pixel centres run from 0 to width - 1: the cell centres of that span.
      const Eigen::Vector2d at(-0.5 + (c + 0.5) * step, -0.5 + (r + 0.5) * row_step);
      const Eigen::Vector2d d = distortionDelta(distortion, at - pp);
      arrows_.emplace_back(QPointF(at.x(), at.y()), QPointF(d.x(), d.y()));
      longest = std::max(longest, d.norm());
    }
  // The longest arrow at most 90 % of a cell, lengthened by a round factor.
  arrow_scale_ = largest_px_ >= kNegligiblePx && longest > 1e-9 ? niceFloor(0.9 * std::min(step, row_step) / longest)
                                                                 : 0.0;
  update();
}

void DistortionFieldView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.fillRect(rect(), palette().window());
  if (camera_.width <= 0 || camera_.height <= 0) return;
  const int text_height = fontMetrics().height();
  const QRectF frame =
      fitted(QSizeF(camera_.width, camera_.height), QRectF(rect()).adjusted(4, 4, -4, -4 - text_height));
  p.fillRect(frame, Qt::white);
  p.setPen(QColor(150, 150, 150));
  p.drawRect(frame);
  p.setRenderHint(QPainter::Antialiasing);
  const double zoom = frame.width() / camera_.width;
  auto toScreen = [&](QPointF image) { return frame.topLeft() + (image + QPointF(0.5, 0.5)) * zoom; };

  const QPointF pp = toScreen(QPointF(camera_.u0(), camera_.v0()));
  p.setPen(QPen(QColor(120, 120, 120), 1.0));
  p.drawLine(pp - QPointF(6, 0), pp + QPointF(6, 0));
  p.drawLine(pp - QPointF(0, 6), pp + QPointF(0, 6));

  QPen pen(kArrowColour, 1.3);
  p.setPen(pen);
  p.setBrush(kArrowColour);
  for (const auto& [from, d] : arrows_) {
    const QPointF a = toScreen(from);
    const QPointF b = toScreen(from + arrow_scale_ * d);
    const QPointF v = b - a;
    const double length = std::hypot(v.x(), v.y());
    if (length < 0.5) {
      p.drawPoint(a);
      continue;
    }
    p.drawLine(a, b);
    const QPointF unit = v / length, normal(-unit.y(), unit.x());
    const double head = std::min(5.0, 0.4 * length);
    QPainterPath tip;
    tip.moveTo(b);
    tip.lineTo(b - head * unit + 0.5 * head * normal);
    tip.lineTo(b - head * unit - 0.5 * head * normal);
    tip.closeSubpath();
    p.drawPath(tip);
  }
  p.setPen(QColor(60, 60, 60));
  const QString scale = arrow_scale_ > 0.0   ? tr("arrows x%1").arg(arrow_scale_)
                        : largest_px_ > 0.0 ? tr("no distortion to speak of (below %1 px)").arg(kNegligiblePx)
                                            : tr("no displacement");
  p.drawText(QRectF(frame.left(), frame.bottom() + 2, frame.width(), text_height), Qt::AlignLeft | Qt::AlignTop,
             scale + tr(";  + principal point"));
}

}  // namespace imagepro::app
