// The small live charts of the main window (histogram, stage times): one chart filling
// its widget, thin margins, antialiased.
#pragma once

#include <QChart>
#include <QChartView>
#include <QPainter>
#include <QVBoxLayout>
#include <QWidget>

namespace imagepro::app {

inline void fillWithChart(QWidget* owner, QChart* chart) {
  chart->setMargins(QMargins(2, 2, 2, 2));
  auto* view = new QChartView(chart);
  view->setRenderHint(QPainter::Antialiasing);
  auto* layout = new QVBoxLayout(owner);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(view);
}

}  // namespace imagepro::app
