#pragma once
// Tooltips for the control panel: what each method or option is and where the
// thesis describes it. The names shown in the lists come from enum_names.h.
#include <QString>

#include "core/settings/options.h"

namespace imagepro::app {

QString methodToolTip(ThresholdMethod m);
QString methodToolTip(Binarization m);
QString methodToolTip(EdgeMethod m);
QString methodToolTip(ConnectivityMethod m);
QString methodToolTip(EllipseMethod m);
QString methodToolTip(FitAcceptRule m);
QString methodToolTip(ContourMode m);
QString methodToolTip(TrackingMode m);
QString methodToolTip(ApplicationLevel m);
QString methodToolTip(DisplayOptions::Background m);
QString methodToolTip(DisplayOptions::Edges m);
QString methodToolTip(DisplayOptions::Target m);
QString methodToolTip(RenderMode m);
QString methodToolTip(MotionKind m);
QString methodToolTip(PoseAxis m);

}  // namespace imagepro::app
