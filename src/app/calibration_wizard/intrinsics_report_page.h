#pragma once
// The quality report of a full intrinsic calibration in the wizard (the CLI's
// `calibrate --intrinsics` report, core/calibration/intrinsics_report.h): the overall and
// each image's reprojection error, each parameter with its standard deviation, the
// coverage map as a picture (where every used dot fell, over 8 x 6 cells shaded by the
// views with dots there) and the named warnings, each with what to do.
#include <QStringList>
#include <QWidget>

#include <vector>

#include "core/calibration/intrinsics_report.h"

class QLabel;
class QListWidget;
class QTableWidget;

namespace imagepro::app {

class CalibrationImageView;

class IntrinsicsReportPage : public QWidget {
  Q_OBJECT

 public:
  explicit IntrinsicsReportPage(QWidget* parent = nullptr);

  // `names`: each image of the run, in the result's order. nullptr: no run yet.
  void setResult(const IntrinsicsResult* result, const QStringList& names);

  QString summary() const;
  QTableWidget* imageTable() const { return images_; }
  QTableWidget* parameterTable() const { return parameters_; }
  CalibrationImageView* coverageView() const { return coverage_; }
  const CoverageMap& coverage() const { return map_; }
  const std::vector<CalibrationWarning>& warnings() const { return warnings_; }
  QListWidget* warningList() const { return warning_list_; }

 private:
  void fillImages(const IntrinsicsResult& r, const QStringList& names);
  void fillParameters(const IntrinsicsResult& r);
  void fillWarnings();

  QLabel* summary_ = nullptr;
  QTableWidget* images_ = nullptr;
  QTableWidget* parameters_ = nullptr;
  CalibrationImageView* coverage_ = nullptr;
  QLabel* coverage_caption_ = nullptr;
  QListWidget* warning_list_ = nullptr;
  CoverageMap map_;
  std::vector<CalibrationWarning> warnings_;
  bool ok_ = false;  // a calibration succeeded
};

}  // namespace imagepro::app
