// Target Tracking and Application panels (thesis appendix A, chapter 3, figure 5.1).
#include <QCheckBox>
#include <QComboBox>
#include <QFormLayout>

#include "app/panels/panels.h"

namespace imagepro::app {

QWidget* trackingPanel(SettingsBinder& binder) {
  auto* box = new QWidget;
  auto* form = new QFormLayout(box);
  form->setContentsMargins(0, 0, 0, 0);
  auto t = [](Settings& s) -> TrackingOptions& { return s.pipeline.tracking; };

  // The thesis's "ON" box and strategy list are one option here: mode Off, or a strategy.
  auto* on = named(new QCheckBox(QObject::tr("On")), "trackingOn",
                   QObject::tr("Search only the region estimated from the previous frames (thesis ch. 3)"));
  auto* strategy = named(new QComboBox, "trackingStrategy");
  for (const auto& entry : enumEntries(TrackingMode{})) {
    if (entry.value == TrackingMode::Off) continue;
    strategy->addItem(fromView(entry.label), static_cast<int>(entry.value));
    strategy->setItemData(strategy->count() - 1, entryToolTip(entry), Qt::ToolTipRole);
  }
  const auto write_mode = [&binder, on, strategy] {
    binder.model().pipeline.tracking.mode =
        on->isChecked() ? static_cast<TrackingMode>(strategy->currentData().toInt()) : TrackingMode::Off;
  };
  // Reading back: a mode other than Off selects its strategy; Off keeps the last one shown.
  binder.onAnyUpdate([&binder, on, strategy] {
    const TrackingMode mode = binder.model().pipeline.tracking.mode;
    const QSignalBlocker block_on(on), block_strategy(strategy);
    on->setChecked(mode != TrackingMode::Off);
    if (mode != TrackingMode::Off) strategy->setCurrentIndex(strategy->findData(static_cast<int>(mode)));
  });
  QObject::connect(on, &QCheckBox::toggled, &binder, [&binder, write_mode] {
    write_mode();
    emit binder.changed();
  });
  QObject::connect(strategy, &QComboBox::currentIndexChanged, &binder, [&binder, on, write_mode] {
    if (!on->isChecked()) return;
    write_mode();
    emit binder.changed();
  });

  form->addRow(on);
  form->addRow(QObject::tr("Strategy"), strategy);
  form->addRow(QObject::tr("Data points"),
               named(binder.intSpin([t](Settings& s) -> auto& { return t(s).data_points; }), "trackingDataPoints",
                     QObject::tr("The last n frames the polynomial is fitted to (thesis 3.3)")));
  form->addRow(QObject::tr("Degree"),
               named(binder.intSpin([t](Settings& s) -> auto& { return t(s).degree; }), "trackingDegree",
                     QObject::tr("Degree of the extrapolating polynomial (thesis 3.2)")));
  form->addRow(QObject::tr("min r"),
               named(binder.doubleSpin([t](Settings& s) -> auto& { return t(s).min_r; }, 3), "trackingMinR",
                     QObject::tr("Critical correlation coefficient: below it the degree and data points are reduced (thesis 3.3.1)")));
  form->addRow(QObject::tr("red [%]"),
               named(binder.doubleSpin([t](Settings& s) -> auto& { return t(s).reduction_percent; }, 1), "trackingReduction",
                     QObject::tr("Slows the shrinking of the estimated region (thesis 3.3)")));
  form->addRow(QObject::tr("Enlarge"),
               named(binder.doubleSpin([t](Settings& s) -> auto& { return t(s).enlarge_px; }, 1, QStringLiteral(" px")),
                     "trackingEnlargePx", QObject::tr("Fixed pixels added to the region's width and height (thesis 3.3.3, 1)")));
  form->addRow(QObject::tr("Scale"),
               named(binder.doubleSpin([t](Settings& s) -> auto& { return t(s).enlarge_scale; }, 3), "trackingEnlargeScale",
                     QObject::tr("Fixed scale factor of the region (thesis 3.3.3, 2)")));
  form->addRow(QObject::tr("Speed scale"),
               named(binder.doubleSpin([t](Settings& s) -> auto& { return t(s).enlarge_speed_scale; }, 4),
                     "trackingEnlargeSpeed",
                     QObject::tr("Scale per pixel/frame of the target centre's speed (thesis 3.3.3, 3)")));
  return box;
}

QWidget* applicationPanel(SettingsBinder& binder) {
  return named(binder.radios<ApplicationLevel>([](Settings& s) -> auto& { return s.pipeline.level; }), "applicationLevel",
               QObject::tr("Process each frame up to the chosen stage (thesis figure 5.1)"));
}

}  // namespace imagepro::app
