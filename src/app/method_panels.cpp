// Thresholding, Edge Detection, Connectivity, Ellipse Detection, Re-Thresholding
// and Reconstruction panels (thesis appendix A).
#include <QFormLayout>
#include <QLabel>
#include <QVBoxLayout>

#include "app/panels.h"

namespace imagepro::app {

namespace {

// A method list plus "Val" for Manual, enabled only when Manual is chosen.
template <class Field>
QWidget* thresholdControls(SettingsBinder& binder, Field field, bool with_none, const char* prefix) {
  auto* box = new QWidget;
  auto* form = new QFormLayout(box);
  form->setContentsMargins(0, 0, 0, 0);
  const std::string p(prefix);
  auto* method = binder.combo<ThresholdMethod>([field](Settings& s) -> auto& { return field(s).method; },
                                               [with_none](ThresholdMethod m) { return with_none || m != ThresholdMethod::None; });
  method->setObjectName(QString::fromStdString(p + "Method"));
  auto* value = binder.intSpin([field](Settings& s) -> auto& { return field(s).manual_value; }, 0, 255);
  value->setObjectName(QString::fromStdString(p + "Value"));
  value->setToolTip(QObject::tr("Val: pixels brighter than this are white (thesis eq. 2.1)"));
  form->addRow(QObject::tr("Method"), method);
  form->addRow(QObject::tr("Val"), value);
  binder.onAnyUpdate([&binder, field, value] { value->setEnabled(field(binder.model()).method == ThresholdMethod::Manual); });
  return box;
}

QWidget* single(QWidget* w) {
  auto* box = new QWidget;
  auto* layout = new QVBoxLayout(box);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(w);
  return box;
}

}  // namespace

QWidget* thresholdPanel(SettingsBinder& binder) {
  return thresholdControls(binder, [](Settings& s) -> ThresholdOptions& { return s.pipeline.threshold; }, false,
                           "threshold");
}

QWidget* rethresholdPanel(SettingsBinder& binder) {
  return thresholdControls(binder, [](Settings& s) -> ThresholdOptions& { return s.pipeline.rethreshold; }, true,
                           "rethreshold");
}

QWidget* edgePanel(SettingsBinder& binder) {
  return single(named(binder.combo<EdgeMethod>([](Settings& s) -> auto& { return s.pipeline.edge_method; }), "edgeMethod"));
}

QWidget* connectivityPanel(SettingsBinder& binder) {
  return single(named(binder.combo<ConnectivityMethod>([](Settings& s) -> auto& { return s.pipeline.connectivity; }),
                      "connectivityMethod"));
}

QWidget* ellipsePanel(SettingsBinder& binder) {
  auto* box = new QWidget;
  auto* form = new QFormLayout(box);
  form->setContentsMargins(0, 0, 0, 0);
  auto e = [](Settings& s) -> EllipseOptions& { return s.pipeline.ellipse; };
  form->addRow(QObject::tr("Method"), named(binder.combo<EllipseMethod>([e](Settings& s) -> auto& { return e(s).method; }), "ellipseMethod"));
  auto* accept = named(binder.combo<FitAcceptRule>([e](Settings& s) -> auto& { return e(s).accept_rule; }), "ellipseAcceptRule");
  auto* max_rel = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).max_relative_error; }, 0.0, 10.0, 4),
                        "ellipseMaxRelativeError", QObject::tr("Largest accepted relative fit error E_rel (thesis eq. 2.42)"));
  auto* max_sampson = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).max_sampson_distance_px; }, 0.0, 100.0, 3, QStringLiteral(" px")),
                            "ellipseMaxSampson", QObject::tr("Largest accepted mean Sampson distance"));
  auto* min_path = named(binder.intSpin([e](Settings& s) -> auto& { return e(s).min_path_pixels; }, 6, 1000000, QStringLiteral(" px")),
                         "ellipseMinPath", QObject::tr("Shorter connected paths are not considered"));
  auto* min_score = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).bennett_min_score; }, 0.0, 1e9, 0), "bennettMinScore");
  auto* max_score = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).bennett_max_score; }, 0.0, 1e9, 0), "bennettMaxScore");
  auto* min_quality = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).bennett_min_quality; }, 0.0, 1e9, 0), "bennettMinQuality");
  auto* max_quality = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).bennett_max_quality; }, 0.0, 1e9, 0), "bennettMaxQuality");
  for (auto* w : {min_score, max_score}) w->setToolTip(QObject::tr("Bennett accumulation score range (thesis 2.6.1, rule 3)"));
  for (auto* w : {min_quality, max_quality}) w->setToolTip(QObject::tr("Bennett quality factor range (thesis 2.6.1, rule 2)"));
  form->addRow(QObject::tr("Accept by"), accept);
  form->addRow(QObject::tr("Max E_rel"), max_rel);
  form->addRow(QObject::tr("Max Sampson"), max_sampson);
  form->addRow(QObject::tr("Min path"), min_path);
  form->addRow(QObject::tr("Score min"), min_score);
  form->addRow(QObject::tr("Score max"), max_score);
  form->addRow(QObject::tr("Quality min"), min_quality);
  form->addRow(QObject::tr("Quality max"), max_quality);
  form->addRow(named(binder.check(QObject::tr("Report all targets"), [e](Settings& s) -> auto& { return e(s).report_all_targets; }),
                     "ellipseReportAll", QObject::tr("Show every target found instead of failing with AmbiguousTarget")));
  binder.onAnyUpdate([&binder, accept, max_rel, max_sampson, min_score, max_score, min_quality, max_quality] {
    const EllipseOptions& o = binder.model().pipeline.ellipse;
    const bool fit = o.method == EllipseMethod::DirectFit;
    accept->setEnabled(fit);
    max_rel->setEnabled(fit && o.accept_rule == FitAcceptRule::RelativeError);
    max_sampson->setEnabled(fit && o.accept_rule == FitAcceptRule::SampsonDistance);
    for (QWidget* w : {static_cast<QWidget*>(min_score), static_cast<QWidget*>(max_score),
                       static_cast<QWidget*>(min_quality), static_cast<QWidget*>(max_quality)})
      w->setEnabled(!fit);
  });
  return box;
}

QWidget* reconstructionPanel(SettingsBinder& binder) {
  auto* box = new QWidget;
  auto* form = new QFormLayout(box);
  form->setContentsMargins(0, 0, 0, 0);
  auto r = [](Settings& s) -> ReconstructionOptions& { return s.pipeline.reconstruction; };
  form->addRow(named(binder.check(QObject::tr("Distortion correction"), [r](Settings& s) -> auto& { return r(s).distortion_correction; }),
                     "distortionCorrection", QObject::tr("Correct the contour and spot pixels for lens distortion (thesis 4.5, eqs. 4.18-4.19)")));
  auto* exact = named(binder.check(QObject::tr("Exact inverse"), [r](Settings& s) -> auto& { return r(s).exact_undistortion; }),
                      "exactUndistortion", QObject::tr("Newton inverse of the distortion model instead of the Taylor inverse (thesis 4.5)"));
  form->addRow(exact);
  form->addRow(QObject::tr("Contour"), named(binder.combo<ContourMode>([r](Settings& s) -> auto& { return r(s).contour_mode; }), "contourMode"));
  form->addRow(QObject::tr("Crop margin"), named(binder.intSpin([r](Settings& s) -> auto& { return r(s).crop_margin_px; }, 0, 1000, QStringLiteral(" px")),
                                                 "cropMargin", QObject::tr("Pixels added around the detected target before re-thresholding")));
  binder.onAnyUpdate([&binder, exact] { exact->setEnabled(binder.model().pipeline.reconstruction.distortion_correction); });
  return box;
}

}  // namespace imagepro::app
