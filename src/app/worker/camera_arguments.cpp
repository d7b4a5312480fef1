#include "app/worker/camera_arguments.h"

#include <QRegularExpression>

namespace imagepro::app {

bool applyCameraArguments(const QString& device, const QString& size, const QString& fps, CameraSourceOptions& out,
                          QString& error) {
  CameraSourceOptions next = out;
  if (device.trimmed().isEmpty()) {
    error = QStringLiteral("--camera needs a device, e.g. /dev/video0");
    return false;
  }
  const std::string path = device.trimmed().toStdString();
  if (path != next.device) next.controls.clear();
  next.device = path;
  if (!size.isEmpty()) {
    static const QRegularExpression pattern(QStringLiteral("^([0-9]{1,6})[xX]([0-9]{1,6})$"));
    const QRegularExpressionMatch m = pattern.match(size.trimmed());
    const int width = m.hasMatch() ? m.captured(1).toInt() : 0;
    const int height = m.hasMatch() ? m.captured(2).toInt() : 0;
    if (width <= 0 || height <= 0) {
      error = QStringLiteral("--size: \"%1\" is not WIDTHxHEIGHT, e.g. 640x480").arg(size);
      return false;
    }
    next.width = width;
    next.height = height;
  }
  if (!fps.isEmpty()) {
    bool number = false;
    const double rate = fps.trimmed().toDouble(&number);
    if (!number || !(rate > 0.0) || rate > 1e6) {
      error = QStringLiteral("--fps: \"%1\" is not a frame rate above 0").arg(fps);
      return false;
    }
    next.frame_rate_hz = rate;
  }
  out = std::move(next);
  return true;
}

}  // namespace imagepro::app
