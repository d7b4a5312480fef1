#include "app/panels/control_panel.h"

#include <QAbstractSlider>
#include <QAbstractSpinBox>
#include <QComboBox>
#include <QCoreApplication>
#include <QScrollBar>
#include <QSettings>
#include <QVBoxLayout>
#include <QWheelEvent>

#include "app/panels/calibration_panel.h"
#include "app/panels/collapsible_group.h"
#include "app/panels/output_panel.h"
#include "app/panels/panels.h"
#include "app/panels/source_panel.h"

namespace imagepro::app {

ControlPanel::ControlPanel(SettingsBinder& binder, QWidget* parent)
    : QScrollArea(parent),
      source_(new SourcePanel),
      output_(new OutputPanel(binder)),
      calibration_(new CalibrationPanel(binder)),
      column_(new QWidget) {
  setObjectName(QStringLiteral("controlPanel"));
  setWidgetResizable(true);
  setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  new QVBoxLayout(column_);
  column_->layout()->setContentsMargins(4, 4, 4, 4);
  column_->layout()->setSpacing(4);

  addGroup(tr("Input Source"), tr("Where frames come from (thesis 2.2)"), source_);
  addGroup(tr("Thresholding"), tr("Segmentation of the frame (thesis 2.3)"), thresholdPanel(binder));
  addGroup(tr("Edge Detection"), tr("Edge pixels of the binary image (thesis 2.4)"), edgePanel(binder));
  addGroup(tr("Connectivity"), tr("Grouping edge pixels into connected paths (thesis 2.5)"), connectivityPanel(binder));
  addGroup(tr("Ellipse Detection"), tr("Which path is the target (thesis 2.6)"), ellipsePanel(binder));
  addGroup(tr("Re-Thresholding"), tr("Thresholding the cropped target again (thesis 2.3, figure 2.8)"), rethresholdPanel(binder));
  addGroup(tr("Reconstruction"), tr("Contour points, distortion correction and 3D reconstruction (thesis ch. 4, 5)"),
           reconstructionPanel(binder));
  addGroup(tr("Target Tracking"), tr("Estimating the target's region in the next frame (thesis ch. 3)"), trackingPanel(binder));
  addGroup(tr("Application"), tr("Process up to a stage (thesis figure 5.1)"), applicationPanel(binder));
  addGroup(tr("Background Display"), tr("What the results area shows behind the overlays"), backgroundDisplayPanel(binder));
  addGroup(tr("Edge Display"), tr("Edge pixels or coloured connected paths"), edgeDisplayPanel(binder));
  addGroup(tr("Target Display"), tr("How the detected target is shown"), targetDisplayPanel(binder));
  addGroup(tr("Target Features Display"), tr("The contour points and spots the reconstruction used"),
           featuresDisplayPanel(binder));
  addGroup(tr("Data Out, Screenshot, Settings"), tr("Output files and the settings file"), output_);
  addGroup(tr("Internal Camera Calibration"),
           tr("Lens distortion calibration from up to four images of the calibration pattern (thesis 4.6, "
              "appendix A)"),
           calibration_);
  static_cast<QVBoxLayout*>(column_->layout())->addStretch(1);
  setWidget(column_);
  binder.refresh();
  // Value widgets keep the wheel for the column until focused; by default the wheel
  // would focus them and change their value on the way past.
  for (QWidget* w : column_->findChildren<QWidget*>()) {
    if (!qobject_cast<QComboBox*>(w) && !qobject_cast<QAbstractSpinBox*>(w) && !qobject_cast<QAbstractSlider*>(w))
      continue;
    w->setFocusPolicy(Qt::StrongFocus);
    w->installEventFilter(this);
  }
}

bool ControlPanel::eventFilter(QObject* watched, QEvent* event) {
  // The scroll area watches its own scroll bars too: only the column's widgets are ours.
  if (event->type() == QEvent::Wheel && watched->isWidgetType()) {
    auto* widget = static_cast<QWidget*>(watched);
    if (column_->isAncestorOf(widget) && !widget->hasFocus()) {
      QCoreApplication::sendEvent(verticalScrollBar(), event);
      return true;
    }
  }
  return QScrollArea::eventFilter(watched, event);
}

void ControlPanel::addGroup(const QString& title, const QString& tooltip, QWidget* content) {
  auto* group = new CollapsibleGroup(title, content);
  group->setToolTip(tooltip);
  column_->layout()->addWidget(group);
  groups_.push_back(group);
}

void ControlPanel::saveState(QSettings& store) const {
  QStringList folded;
  for (const CollapsibleGroup* g : groups_)
    if (!g->isExpanded()) folded << g->title();
  store.setValue(QStringLiteral("controlPanel/folded"), folded);
}

void ControlPanel::restoreState(const QSettings& store) {
  const QStringList folded = store.value(QStringLiteral("controlPanel/folded")).toStringList();
  for (CollapsibleGroup* g : groups_) g->setExpanded(!folded.contains(g->title()));
}

}  // namespace imagepro::app
