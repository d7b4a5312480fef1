// Thresholding, Edge Detection, Connectivity, Ellipse Detection, Re-Thresholding
// and Reconstruction panels (thesis appendix A).
#include <QFormLayout>
#include <QLabel>
#include <QVBoxLayout>

#include <vector>

#include "app/panels/panels.h"

namespace imagepro::app {

namespace {

// A method list (the methods its key takes) plus "Val" for Manual, enabled only when
// Manual is chosen.
template <class Field>
QWidget* thresholdControls(SettingsBinder& binder, Field field, const char* prefix) {
  auto* box = new QWidget;
  auto* form = new QFormLayout(box);
  form->setContentsMargins(0, 0, 0, 0);
  const std::string p(prefix);
  auto* method = binder.combo<ThresholdMethod>([field](Settings& s) -> auto& { return field(s).method; });
  method->setObjectName(QString::fromStdString(p + "Method"));
  auto* value = binder.intSpin([field](Settings& s) -> auto& { return field(s).manual_value; });
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
  auto* box = new QWidget;
  auto* layout = new QVBoxLayout(box);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(thresholdControls(binder, [](Settings& s) -> ThresholdOptions& { return s.pipeline.threshold; },
                                      "threshold"));
  // How the region is binarized with it (beyond the thesis: uneven light).
  auto* form = new QFormLayout;
  form->setContentsMargins(0, 0, 0, 0);
  auto b = [](Settings& s) -> BinarizationOptions& { return s.pipeline.binarization; };
  form->addRow(QObject::tr("Binarization"),
               named(binder.combo<Binarization>([b](Settings& s) -> auto& { return b(s).mode; }), "binarizationMode"));
  auto* window = named(binder.intSpin([b](Settings& s) -> auto& { return b(s).window_px; }, QStringLiteral(" px")),
                       "localWindow", QObject::tr("Side of the local window; 0: a sixteenth of the image width"));
  auto* offset = named(binder.doubleSpin([b](Settings& s) -> auto& { return b(s).offset; }, 2),
                       "localOffset", QObject::tr("Black: darker than the window's mean by more than this fraction of it ..."));
  auto* contrast = named(binder.intSpin([b](Settings& s) -> auto& { return b(s).min_contrast; }),
                         "localMinContrast", QObject::tr("... and by more than this many grey levels"));
  form->addRow(QObject::tr("Window"), window);
  form->addRow(QObject::tr("Offset"), offset);
  form->addRow(QObject::tr("Min contrast"), contrast);
  form->addRow(named(binder.check(QObject::tr("Coarse search first"), [b](Settings& s) -> auto& { return b(s).coarse_search; }),
                     "coarseSearch", QObject::tr("Search a whole frame reduced (2x at 640x480) first, and at full size only when that misses the target")));
  layout->addLayout(form);
  binder.onAnyUpdate([&binder, window, offset, contrast] {
    const bool local = binder.model().pipeline.binarization.mode != Binarization::Global;
    for (QWidget* w : {static_cast<QWidget*>(window), static_cast<QWidget*>(offset), static_cast<QWidget*>(contrast)})
      w->setEnabled(local);
  });
  return box;
}

QWidget* rethresholdPanel(SettingsBinder& binder) {
  return thresholdControls(binder, [](Settings& s) -> ThresholdOptions& { return s.pipeline.rethreshold; },
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
  auto* max_rel = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).max_relative_error; }, 4),
                        "ellipseMaxRelativeError", QObject::tr("Largest accepted relative fit error E_rel (thesis eq. 2.42)"));
  auto* max_sampson = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).max_sampson_distance_px; }, 3, QStringLiteral(" px")),
                            "ellipseMaxSampson", QObject::tr("Largest accepted mean Sampson distance"));
  auto* min_path = named(binder.intSpin([e](Settings& s) -> auto& { return e(s).min_path_pixels; }, QStringLiteral(" px")),
                         "ellipseMinPath", QObject::tr("Shorter connected paths are not considered"));
  auto* min_score = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).bennett_min_score; }, 0), "bennettMinScore");
  auto* max_score = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).bennett_max_score; }, 0), "bennettMaxScore");
  auto* min_quality = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).bennett_min_quality; }, 0), "bennettMinQuality");
  auto* max_quality = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).bennett_max_quality; }, 0), "bennettMaxQuality");
  auto* min_peak = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).bennett_min_peak_fraction; }, 4),
                         "bennettMinPeakFraction",
                         QObject::tr("Least share of the path's point pairs that must vote for the accumulator's peak "
                                     "(thesis 2.6.1, rule 3; 1/16 measured on the synthetic library)"));
  auto* max_fit_error = named(
      binder.doubleSpin([e](Settings& s) -> auto& { return e(s).bennett_max_relative_error; }, 4),
      "bennettMaxRelativeError",
      QObject::tr("Largest E_rel of the direct fit that gives an accepted path's ellipse (beyond the thesis's rules: a "
                  "point-symmetric bar passes rules 1-3, as in sample06_no_target.png; 1e9: the thesis's rules alone)"));
  auto* max_points = named(binder.intSpin([e](Settings& s) -> auto& { return e(s).bennett_max_points; }, QStringLiteral(" px")),
                           "bennettMaxPoints",
                           QObject::tr("Longer paths vote with a random sample of this many pixels, all pairs of them "
                                       "(0: never sampled; thesis 2.6.1)"));
  for (auto* w : {min_score, max_score}) w->setToolTip(QObject::tr("Bennett accumulation score range (thesis 2.6.1, rule 3)"));
  for (auto* w : {min_quality, max_quality}) w->setToolTip(QObject::tr("Bennett quality factor range (thesis 2.6.1, rule 2)"));
  auto* trace_inlier = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).trace_inlier_px; }, 2, QStringLiteral(" px")),
                             "ellipseTraceInlier",
                             QObject::tr("The trace: a path pixel within this distance of the fitted ellipse traces the "
                                         "arc (about 3 px of perimeter) its foot lies on"));
  auto* min_traced = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).min_traced_fraction; }, 3),
                           "ellipseMinTraced",
                           QObject::tr("Direct fit: share of the ellipse's perimeter inside the image that its path must "
                                       "trace (a rectangle fails it at its blunt ends)"));
  auto* min_arc = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).min_arc_fraction; }, 3),
                        "ellipseMinArc",
                        QObject::tr("Direct fit: share of the whole perimeter the path must trace, so that an ellipse "
                                    "cut by the image border (thesis fig. 2.27) passes only with enough of it inside"));
  auto* robust = named(binder.check(QObject::tr("Consensus refit (occluded contour)"), [e](Settings& s) -> auto& { return e(s).robust_fit; }),
                       "ellipseRobustFit",
                       QObject::tr("Direct fit: when no ellipse holds the target's spots, a path that may hold them but "
                                   "fails the fit (an occluder's edges in its contour, thesis fig. 2.28) is refitted on "
                                   "the inliers of the six-point fit whose ellipse it traces most; with no target still, "
                                   "the rim's arcs round a pair of spots are fitted (an occluder joining the disk to "
                                   "the scene)"));
  auto* robust_iterations = named(binder.intSpin([e](Settings& s) -> auto& { return e(s).robust_iterations; }),
                                  "ellipseRobustIterations",
                                  QObject::tr("Consensus refit: at most this many six-point fits (fewer once 99 % sure "
                                              "of one clean sample)"));
  auto* robust_traced = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).robust_min_traced_fraction; }, 3),
                              "ellipseRobustMinTraced",
                              QObject::tr("Consensus refit: share of the observable ellipse its inliers must trace; it "
                                          "must also pass the accept rule on them"));
  auto* spot_tolerance = named(binder.doubleSpin([e](Settings& s) -> auto& { return e(s).target_spot_tolerance; }, 3),
                               "ellipseSpotTolerance",
                               QObject::tr("Target selection: how far, in disk radii, the centre spot may lie from the "
                                           "ellipse's centre and the offset spot from rf/R beside it"));
  form->addRow(QObject::tr("Accept by"), accept);
  form->addRow(QObject::tr("Max E_rel"), max_rel);
  form->addRow(QObject::tr("Max Sampson"), max_sampson);
  form->addRow(QObject::tr("Min path"), min_path);
  form->addRow(QObject::tr("Trace within"), trace_inlier);
  form->addRow(QObject::tr("Min traced"), min_traced);
  form->addRow(QObject::tr("Min arc"), min_arc);
  form->addRow(robust);
  form->addRow(QObject::tr("Refit tries"), robust_iterations);
  form->addRow(QObject::tr("Refit traced"), robust_traced);
  form->addRow(QObject::tr("Score min"), min_score);
  form->addRow(QObject::tr("Score max"), max_score);
  form->addRow(QObject::tr("Quality min"), min_quality);
  form->addRow(QObject::tr("Quality max"), max_quality);
  form->addRow(QObject::tr("Peak share"), min_peak);
  form->addRow(QObject::tr("Max fit E_rel"), max_fit_error);
  form->addRow(QObject::tr("Max points"), max_points);
  form->addRow(QObject::tr("Spot tolerance"), spot_tolerance);
  form->addRow(named(binder.check(QObject::tr("Require the target's spots"), [e](Settings& s) -> auto& { return e(s).require_target_spots; }),
                     "ellipseRequireSpots",
                     QObject::tr("NoTarget unless an ellipse holds the target's two spots; off, the thesis's rule: the "
                                 "best ellipse (lowest error, highest Bennett score) when none does")));
  form->addRow(named(binder.check(QObject::tr("Report all targets"), [e](Settings& s) -> auto& { return e(s).report_all_targets; }),
                     "ellipseReportAll", QObject::tr("Two targets or more: report every one found instead of failing with AmbiguousTarget")));
  const std::vector<QWidget*> fit_only{accept, min_traced, min_arc, robust};
  const std::vector<QWidget*> bennett_only{min_score, max_score, min_quality, max_quality, min_peak, max_fit_error,
                                           max_points};
  binder.onAnyUpdate([&binder, fit_only, bennett_only, max_rel, max_sampson, robust_iterations, robust_traced] {
    const EllipseOptions& o = binder.model().pipeline.ellipse;
    const bool fit = o.method == EllipseMethod::DirectFit;
    for (QWidget* w : fit_only) w->setEnabled(fit);
    for (QWidget* w : bennett_only) w->setEnabled(!fit);
    max_rel->setEnabled(fit && o.accept_rule == FitAcceptRule::RelativeError);
    max_sampson->setEnabled(fit && o.accept_rule == FitAcceptRule::SampsonDistance);
    robust_iterations->setEnabled(fit && o.robust_fit);
    robust_traced->setEnabled(fit && o.robust_fit);
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
  form->addRow(named(binder.check(QObject::tr("Centre spot in the normal"), [r](Settings& s) -> auto& { return r(s).centre_spot_normal; }),
                     "centreSpotNormal", QObject::tr("Weigh the centre spot's polar line into the target plane's normal (most gain seen head-on)")));
  form->addRow(named(binder.check(QObject::tr("Weighted spot centres"), [r](Settings& s) -> auto& { return r(s).weighted_spot_centres; }),
                     "weightedSpotCentres", QObject::tr("Centre each spot under a Gaussian window that follows it, instead of the plain centroid of its box")));
  form->addRow(named(binder.check(QObject::tr("Rim edge model"), [r](Settings& s) -> auto& { return r(s).rim_edge_model; }),
                     "rimEdgeModel", QObject::tr("Sub-pixel rim: edge levels fitted over the whole rim and the blur's shrink of a curved edge undone, instead of each point between its own plateaus")));
  form->addRow(named(binder.check(QObject::tr("Robust rim fit"), [r](Settings& s) -> auto& { return r(s).robust_rim_fit; }),
                     "robustRimFit", QObject::tr("Sub-pixel rim: leave contour points off the rim (an occluder's edge, glare) out of the rim's fit and the self-check")));
  form->addRow(named(binder.check(QObject::tr("Refine the pose"), [r](Settings& s) -> auto& { return r(s).refine_pose; }),
                     "refinePose", QObject::tr("A few Levenberg-Marquardt steps of the pose against the rim's edge points and the two spots")));
  form->addRow(QObject::tr("Crop margin"), named(binder.intSpin([r](Settings& s) -> auto& { return r(s).crop_margin_px; }, QStringLiteral(" px")),
                                                 "cropMargin", QObject::tr("Pixels added around the detected target before re-thresholding")));
  // The self-check and the choice between the rim's two circles (docs/reconstruction.md).
  form->addRow(QObject::tr("Max spot error"), named(binder.doubleSpin([r](Settings& s) -> auto& { return r(s).max_spot_error_px; }, 2, QStringLiteral(" px")),
                                                    "maxSpotError", QObject::tr("PoseInconsistent when the pose puts a spot further than this from where it was found")));
  form->addRow(QObject::tr("Max rim error"), named(binder.doubleSpin([r](Settings& s) -> auto& { return r(s).max_rim_error_px; }, 2, QStringLiteral(" px")),
                                                   "maxRimError", QObject::tr("PoseInconsistent when the pose's rim lies further (RMS) than this from the contour points")));
  form->addRow(QObject::tr("Ambiguity ratio"), named(binder.doubleSpin([r](Settings& s) -> auto& { return r(s).ambiguity_ratio; }, 2),
                                                     "ambiguityRatio", QObject::tr("AmbiguousPose unless one of the rim's two poses fits the spots this many times better")));
  form->addRow(QObject::tr("Ambiguity margin"), named(binder.doubleSpin([r](Settings& s) -> auto& { return r(s).ambiguity_margin_px; }, 2, QStringLiteral(" px")),
                                                      "ambiguityMargin", QObject::tr("AmbiguousPose unless the better of the two poses also fits the spots by this much on a sharp image; the margin grows with the rim's measured blur beyond 1 px")));
  form->addRow(QObject::tr("Ambiguity tolerance"), named(binder.doubleSpin([r](Settings& s) -> auto& { return r(s).ambiguity_tolerance_deg; }, 1, QStringLiteral(" °")),
                                                         "ambiguityTolerance", QObject::tr("When the spots cannot tell the two poses apart but the pose halfway between them lies within this of both, that pose is given; 0: AmbiguousPose always")));
  binder.onAnyUpdate([&binder, exact] { exact->setEnabled(binder.model().pipeline.reconstruction.distortion_correction); });
  return box;
}

}  // namespace imagepro::app
