// Background, Edge, Target and Target Features Display panels (thesis appendix A).
#include <QVBoxLayout>

#include "app/panels/panels.h"

namespace imagepro::app {

QWidget* backgroundDisplayPanel(SettingsBinder& binder) {
  return named(binder.radios<DisplayOptions::Background>([](Settings& s) -> auto& { return s.pipeline.display.background; }),
               "displayBackground");
}

QWidget* edgeDisplayPanel(SettingsBinder& binder) {
  return named(binder.radios<DisplayOptions::Edges>([](Settings& s) -> auto& { return s.pipeline.display.edges; }),
               "displayEdges");
}

QWidget* targetDisplayPanel(SettingsBinder& binder) {
  return named(binder.radios<DisplayOptions::Target>([](Settings& s) -> auto& { return s.pipeline.display.target; }),
               "displayTarget");
}

QWidget* featuresDisplayPanel(SettingsBinder& binder) {
  auto* box = new QWidget;
  auto* layout = new QVBoxLayout(box);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(named(binder.check(QObject::tr("Edge"), [](Settings& s) -> auto& { return s.pipeline.display.feature_edge; }),
                          "displayFeatureEdge", QObject::tr("The contour points the reconstruction used")));
  layout->addWidget(named(binder.check(QObject::tr("Spots"), [](Settings& s) -> auto& { return s.pipeline.display.feature_spots; }),
                          "displayFeatureSpots", QObject::tr("The centres of the target's two spots")));
  return box;
}

}  // namespace imagepro::app
