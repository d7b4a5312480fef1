#include "app/main_window/results_text.h"

#include <QStringList>

#include "app/settings/enum_text.h"
#include "core/pipeline/frame_record.h"

namespace imagepro::app {

namespace {

// Two lines: rotations, then translations, in fixed columns.
QString poseLines(const char* label, const Pose& p) {
  return QStringLiteral("%1 Rx %2  Ry %3  Rz %4 deg\n%5 Tx %6  Ty %7  Tz %8 mm")
      .arg(QLatin1String(label), -5)
      .arg(p.rx_deg, 7, 'f', 2)
      .arg(p.ry_deg, 7, 'f', 2)
      .arg(p.rz_deg, 7, 'f', 2)
      .arg(QString(), -5)
      .arg(p.tx_mm, 7, 'f', 2)
      .arg(p.ty_mm, 7, 'f', 2)
      .arg(p.tz_mm, 7, 'f', 2);
}

// `text` after `label` (padded to the value column), broken between words into lines of
// at most kResultsColumns characters, the later ones indented to the value column: the
// status in words is longer than the column beside the frame.
QString wrapped(const QString& label, const QString& text) {
  const int indent = 10;
  QStringList lines{label.leftJustified(indent)};
  for (const QString& word : text.split(QLatin1Char(' '), Qt::SkipEmptyParts)) {
    QString& line = lines.back();
    const bool first = line.size() <= indent;
    if (!first && line.size() + 1 + word.size() > kResultsColumns) lines << QString(indent, QLatin1Char(' ')) + word;
    else line += (first ? QString() : QStringLiteral(" ")) + word;
  }
  return lines.join(QLatin1Char('\n'));
}

}  // namespace

QString statusInWords(Status status) {
  if (status == Status::Ok) return QStringLiteral("ok");
  return fromView(statusName(status)) + QStringLiteral(": ") + fromView(statusMessage(status));
}

QString formatResults(const DisplayPacket& packet) {
  // A narrow column: it sits beside the frame.
  const FrameResult& r = packet.result;
  QStringList lines;
  lines << wrapped(QStringLiteral("Status"), statusInWords(r.status));
  lines << QStringLiteral("Frame     %1").arg(r.index);
  if (!r.name.empty()) lines << QStringLiteral("File      %1").arg(QString::fromStdString(r.name));
  lines << QStringLiteral("Reached   %1").arg(labelOf(r.reached));
  const double total = r.times.total();
  lines << QStringLiteral("Rate      %1 Hz   CPU %2 %").arg(packet.hz, 0, 'f', 1).arg(packet.cpu_percent, 0, 'f', 0);
  lines << QStringLiteral("Pipeline  %1 us (%2 Hz possible)").arg(total, 0, 'f', 0).arg(total > 0.0 ? 1e6 / total : 0.0, 0, 'f', 0);
  lines << QStringLiteral("Threshold %1").arg(r.threshold >= 0 ? QString::number(r.threshold) : QStringLiteral("-"));
  lines << QStringLiteral("Edges     %1 px   Paths %2").arg(r.edge_pixels).arg(r.paths);
  for (std::size_t i = 0; i < r.targets.size(); ++i) {
    const TargetSummary& t = r.targets[i];
    lines << QStringLiteral("Target %1  centre %2, %3 px").arg(i + 1).arg(t.ellipse.cx, 0, 'f', 2).arg(t.ellipse.cy, 0, 'f', 2);
    // A set's target: its id, its own status and, with a pose, its distance and tilt.
    if (r.set_of_targets && (t.target_id >= 0 || t.status == Status::UnknownTarget)) {
      QString told = t.target_id >= 0 ? QStringLiteral("          id %1, %2").arg(t.target_id) : QStringLiteral("          no id, %1");
      told = told.arg(QString::fromUtf8(statusName(t.status).data()));
      if (ok(t.status) && t.pose) told += QStringLiteral(", %1 mm away").arg(translation(*t.pose).norm(), 0, 'f', 1);
      lines << told;
    }
    lines << QStringLiteral("          axes %1 x %2 px, %3 deg")
                 .arg(t.ellipse.a, 0, 'f', 2)
                 .arg(t.ellipse.b, 0, 'f', 2)
                 .arg(t.ellipse.angle_deg, 0, 'f', 1);
    if (packet.ellipse_method == EllipseMethod::Bennett) {
      lines << QStringLiteral("          score %1  quality %2").arg(t.bennett_score, 0, 'f', 0).arg(t.bennett_quality, 0, 'f', 0);
      lines << QStringLiteral("          symmetry %1").arg(t.bennett_symmetry, 0, 'f', 3);
    } else {
      lines << QStringLiteral("          fit error %1").arg(t.fit_error, 0, 'g', 4);
      lines << QStringLiteral("          Sampson %1 px").arg(t.sampson_px, 0, 'f', 3);
    }
  }
  // The frame record's fields for the results text (core/pipeline/frame_record.h), when they have a value.
  for (const FrameField& field : frameFields()) {
    if (!(field.outputs & kResultsText)) continue;
    const FieldValue v = field.value(r, field.arg);
    if (v.kind == FieldValue::Kind::None) continue;
    const QString value = v.kind == FieldValue::Kind::Number ? QString::number(v.number, 'f', field.decimals)
                                                             : QString::fromStdString(v.text);
    lines << QStringLiteral("%1 %2 %3").arg(fromView(field.label), -9).arg(value, fromView(field.unit)).trimmed();
  }
  if (r.pose) lines << poseLines("Pose", *r.pose);
  else lines << QStringLiteral("Pose      -");
  if (r.ambiguous_poses) {
    // The spots could not tell the rim's two circles apart (AmbiguousPose, or an ok pose
    // halfway between them): both, the one fitting the spots better first.
    lines << (r.pose ? QStringLiteral("          halfway between:") : QStringLiteral("          the rim's two poses:"));
    lines << poseLines("Alt 1", (*r.ambiguous_poses)[0]) << poseLines("Alt 2", (*r.ambiguous_poses)[1]);
  }
  if (r.truth) lines << poseLines("Truth", *r.truth);
  lines << QStringLiteral("Times [us]");
  for (std::size_t s = 0; s < kStageCount; ++s)
    lines << QStringLiteral("  %1 %2").arg(QLatin1String(stageName(static_cast<Stage>(s))), -16).arg(r.times.us[s], 8, 'f', 0);
  return lines.join(QLatin1Char('\n'));
}

}  // namespace imagepro::app
