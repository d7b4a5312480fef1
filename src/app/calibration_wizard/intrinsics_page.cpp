// IntrinsicsPage: the pattern's description, the printable sheet and the images.
#include "app/calibration_wizard/intrinsics_page.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QListWidget>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QTabWidget>
#include <QVBoxLayout>

#include <algorithm>

#include "app/calibration_wizard/calibration_images.h"
#include "app/calibration_wizard/calibration_views.h"
#include "app/calibration_wizard/intrinsics_report_page.h"
#include "app/calibration_wizard/wizard_widgets.h"
#include "app/main_window/main_window.h"
#include "app/main_window/results_text.h"
#include "app/worker/packet_builder.h"
#include "app/main_window/dialog_folder.h"
#include "core/calibration/pattern_document.h"
#include "core/common/atomic_file.h"

namespace imagepro::app {

namespace {

constexpr Paper kPapers[] = {Paper::A4, Paper::Letter, Paper::A3};

}  // namespace

IntrinsicsPage::IntrinsicsPage(MainWindow& window, QWidget* parent) : QWidget(parent), window_(window) {
  setObjectName(QStringLiteral("intrinsicsPage"));
  auto* setup = new QWidget;
  auto* left = new QVBoxLayout;
  left->addWidget(buildPatternBox());
  left->addWidget(buildRunBox(), 1);
  auto* setup_layout = new QHBoxLayout(setup);
  setup_layout->addLayout(left, 2);
  setup_layout->addWidget(buildImagesBox(), 3);

  report_ = new IntrinsicsReportPage;
  report_->setObjectName(QStringLiteral("intrinsicsReport"));
  tabs_ = new QTabWidget;
  tabs_->setObjectName(QStringLiteral("intrinsicsTabs"));
  tabs_->addTab(setup, tr("1. Pattern and images"));
  tabs_->addTab(report_, tr("2. Quality report"));

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(tabs_, 1);
  layout->addWidget(buildActions());
  refreshImages();
  updateButtons();
}

IntrinsicsPage::~IntrinsicsPage() {
  if (run_cancelled_) run_cancelled_->store(true);  // the run stops at its next image
}

QWidget* IntrinsicsPage::buildPatternBox() {
  kind_ = new QComboBox;
  kind_->setObjectName(QStringLiteral("gridKind"));
  kind_->addItem(tr("Asymmetric circles (OpenCV)"), static_cast<int>(DotGridKind::AsymmetricCircles));
  kind_->addItem(tr("Symmetric circles (OpenCV)"), static_cast<int>(DotGridKind::SymmetricCircles));
  kind_->addItem(tr("Thesis pattern (target and grid)"), static_cast<int>(DotGridKind::Thesis));
  kind_->setToolTip(tr("The printed grid: OpenCV's circle grids (no target: the grid gives its own orientation), "
                       "or the thesis pattern of the settings at any size, which may be partly in view"));
  columns_ = new QSpinBox;
  columns_->setObjectName(QStringLiteral("gridColumns"));
  columns_->setRange(0, 200);
  columns_->setToolTip(tr("Points per row (OpenCV's pattern width)"));
  rows_ = new QSpinBox;
  rows_->setObjectName(QStringLiteral("gridRows"));
  rows_->setRange(0, 200);
  rows_->setToolTip(tr("Rows (OpenCV's pattern height)"));
  spacing_ = new QDoubleSpinBox;
  spacing_->setObjectName(QStringLiteral("gridSpacing"));
  spacing_->setRange(0.0, 1000.0);
  spacing_->setDecimals(2);
  spacing_->setSuffix(tr(" mm"));
  spacing_->setToolTip(tr("s: the asymmetric grid's dot (row i, column j) lies at ((2j + i mod 2) s, i s), the "
                          "symmetric grid's at (j s, i s)"));
  diameter_ = new QDoubleSpinBox;
  diameter_->setObjectName(QStringLiteral("gridDotDiameter"));
  diameter_->setRange(0.0, 1000.0);
  diameter_->setDecimals(2);
  diameter_->setSuffix(tr(" mm"));
  diameter_->setSpecialValueText(tr("default"));
  diameter_->setToolTip(tr("The dots' diameter, which corrects each dot's centre for perspective; default: half the "
                           "spacing for OpenCV's grids, 0.32 of it for the thesis pattern"));
  paper_ = new QComboBox;
  paper_->setObjectName(QStringLiteral("patternPaper"));
  for (const Paper p : kPapers) paper_->addItem(QString::fromLatin1(paperName(p)));
  paper_->setToolTip(tr("The page the sheet is laid out on, landscape"));
  auto* write = wizardButton(tr("Write pattern PDF..."), QStringLiteral("writePatternPdf"),
                       tr("The pattern at true scale on the page chosen, with its parameters and a 100 mm scale bar "
                          "printed below (as imagepro-cli pattern writes it): print at 100 %, check the bar, glue "
                          "it to something flat"));

  auto* box = new QGroupBox(tr("Pattern"));
  auto* form = new QFormLayout(box);
  form->addRow(tr("Kind"), kind_);
  form->addRow(tr("Columns"), columns_);
  form->addRow(tr("Rows"), rows_);
  form->addRow(tr("Spacing"), spacing_);
  form->addRow(tr("Dot diameter"), diameter_);
  auto* print_row = new QHBoxLayout;
  print_row->addWidget(paper_);
  print_row->addWidget(write, 1);
  form->addRow(tr("Paper"), print_row);

  onKindChosen(0);
  connect(kind_, &QComboBox::currentIndexChanged, this, &IntrinsicsPage::onKindChosen);
  connect(write, &QPushButton::clicked, this, [this] {
    const QString path = QFileDialog::getSaveFileName(this, tr("Write pattern"),
                                                      dialogFolderWith(QStringLiteral("grid.pdf")), tr("PDF (*.pdf)"));
    if (path.isEmpty()) return;
    rememberDialogFolder(path);
    writePatternPdf(path);
  });
  return box;
}

QWidget* IntrinsicsPage::buildImagesBox() {
  auto* add = wizardButton(tr("Add images..."), QStringLiteral("addIntrinsicsImages"),
                     tr("Photographs of the printed grid: 4 to 10, tilted 30-50 deg about different axes, the grid "
                        "near every edge and corner of the image once"));
  auto* capture = wizardButton(tr("Capture"), QStringLiteral("captureIntrinsicsImage"),
                         tr("The current frame of the running source, with the grid in view"));
  remove_ = wizardButton(tr("Remove"), QStringLiteral("removeIntrinsicsImage"), tr("Take the selected image out"));
  clear_ = wizardButton(tr("Clear all"), QStringLiteral("clearIntrinsicsImages"), tr("Take every image out"));
  list_ = new QListWidget;
  list_->setObjectName(QStringLiteral("intrinsicsImages"));
  list_->setWordWrap(true);
  list_->setToolTip(tr("The images, each with what the last calibration made of it"));
  preview_ = new CalibrationImageView;
  preview_->setObjectName(QStringLiteral("intrinsicsPreview"));
  preview_->setToolTip(tr("The selected image; after a calibration the dots found in it (cyan rings)"));

  auto* buttons = new QHBoxLayout;
  for (QPushButton* b : {add, capture, remove_, clear_}) buttons->addWidget(b);
  auto* box = new QGroupBox(tr("Images"));
  auto* layout = new QVBoxLayout(box);
  layout->addLayout(buttons);
  layout->addWidget(list_, 1);
  layout->addWidget(preview_, 2);

  connect(add, &QPushButton::clicked, this, [this] {
    const QStringList paths = QFileDialog::getOpenFileNames(
        this, tr("Images of the grid"), dialogFolder(),
        tr("Images (*.png *.pgm *.ppm *.pnm *.bmp *.jpg *.jpeg *.tif *.tiff);;All files (*)"));
    if (paths.isEmpty()) return;
    rememberDialogFolder(paths.front());
    addImageFiles(paths);
  });
  connect(capture, &QPushButton::clicked, this, [this] {
    setRunStatus(tr("Asking the source for its frame..."), false);
    emit captureRequested();
  });
  connect(remove_, &QPushButton::clicked, this, [this] { removeImage(list_->currentRow()); });
  connect(clear_, &QPushButton::clicked, this, &IntrinsicsPage::clearImages);
  connect(list_, &QListWidget::currentRowChanged, this, &IntrinsicsPage::showPreview);
  return box;
}

void IntrinsicsPage::onKindChosen(int index) {
  // Each kind starts from a sheet that fits an A4 page: the docs' examples, or the settings' pattern.
  const auto kind = static_cast<DotGridKind>(kind_->itemData(index).toInt());
  DotGridSpec s;
  s.kind = kind;
  if (kind == DotGridKind::AsymmetricCircles) {
    s.columns = 4;
    s.rows = 11;
    s.spacing_mm = 15.0;
  } else if (kind == DotGridKind::SymmetricCircles) {
    s.columns = 9;
    s.rows = 6;
    s.spacing_mm = 25.0;
  } else {
    const PatternGeometry& p = window_.settings().pattern;
    s.columns = p.columns;
    s.rows = p.rows;
    s.spacing_mm = p.spot_spacing_mm;
    s.dot_diameter_mm = 2.0 * p.spot_radius_mm;
  }
  setSpec(s);
}

DotGridSpec IntrinsicsPage::spec() const {
  DotGridSpec s;
  s.kind = static_cast<DotGridKind>(kind_->currentData().toInt());
  s.columns = columns_->value();
  s.rows = rows_->value();
  s.spacing_mm = spacing_->value();
  s.dot_diameter_mm = diameter_->value();
  s.card_size_mm = window_.settings().pattern.card_size_mm;
  s.target = window_.settings().target;
  return s;
}

void IntrinsicsPage::setSpec(const DotGridSpec& s) {
  const QSignalBlocker block(kind_);
  kind_->setCurrentIndex(std::max(0, kind_->findData(static_cast<int>(s.kind))));
  columns_->setValue(s.columns);
  rows_->setValue(s.rows);
  spacing_->setValue(s.spacing_mm);
  diameter_->setValue(s.dot_diameter_mm);
}

bool IntrinsicsPage::writePatternPdf(const QString& path) {
  const Paper paper = kPapers[std::clamp(paper_->currentIndex(), 0, 2)];
  PatternPage page;
  std::string error;
  if (!layoutDotGridPage(spec(), paper, page, error)) {
    setRunStatus(tr("Pattern not written: InvalidPattern: %1").arg(QString::fromStdString(error)), true);
    return false;
  }
  if (!writeFileAtomically(path.toStdString(), patternPagePdf(page), error)) {
    setRunStatus(tr("Pattern not written: %1").arg(QString::fromStdString(error)), true);
    return false;
  }
  setRunStatus(tr("Wrote %1: %2 x %3 dots %4 mm apart on %5 landscape. Print it at actual size (100 %, no fitting "
                  "to the page) and check the 100 mm bar.")
                   .arg(path)
                   .arg(page.grid_columns)
                   .arg(page.grid_rows)
                   .arg(spec().spacing_mm)
                   .arg(QString::fromLatin1(paperName(paper))),
               false);
  return true;
}

void IntrinsicsPage::addImageFiles(const QStringList& paths) {
  QStringList failed;
  for (const QString& path : paths) {
    cv::Mat grey;
    QString error;
    const Status status = readCalibrationImage(path, grey, error);
    if (!ok(status)) {
      failed << QStringLiteral("%1 (%2)").arg(error, QString::fromUtf8(statusName(status).data()));
      continue;
    }
    addImage(grey, QFileInfo(path).fileName());
  }
  if (!failed.isEmpty()) setRunStatus(tr("Not read: %1").arg(failed.join(QStringLiteral("; "))), true);
}

void IntrinsicsPage::addImage(const cv::Mat& grey, const QString& origin) {
  if (grey.empty()) return;
  images_.push_back({grey, origin, ++next_id_});
  refreshImages();
  list_->setCurrentRow(imageCount() - 1);
  updateButtons();
}

void IntrinsicsPage::takeCapture(const cv::Mat& grey, const QString& origin) {
  if (grey.empty()) {
    setRunStatus(tr("Nothing to capture: no source is running and no image is open. Start the Camera source with the "
                    "grid in view (or add files) first."),
                 true);
    return;
  }
  addImage(grey, origin);
  setRunStatus(tr("%1 added.").arg(origin), false);
}

void IntrinsicsPage::removeImage(int index) {
  if (index < 0 || index >= imageCount()) return;
  images_.erase(images_.begin() + index);
  refreshImages();
  updateButtons();
}

void IntrinsicsPage::clearImages() {
  images_.clear();
  refreshImages();
  updateButtons();
}

const IntrinsicsView* IntrinsicsPage::runView(int index) const {
  if (!result_ || index < 0 || index >= imageCount()) return nullptr;
  for (size_t k = 0; k < run_ids_.size() && k < result_->views.size(); ++k)
    if (run_ids_[k] == images_[static_cast<size_t>(index)].id) return &result_->views[k];
  return nullptr;
}

QString IntrinsicsPage::imageStatus(int index) const {
  if (index < 0 || index >= imageCount()) return {};
  const Image& im = images_[static_cast<size_t>(index)];
  const QString head = tr("%1, %2 x %3 px").arg(im.origin).arg(im.grey.cols).arg(im.grey.rows);
  const IntrinsicsView* v = runView(index);
  if (!v) return tr("%1: not calibrated yet").arg(head);
  if (!ok(v->status)) return tr("%1: left out: %2").arg(head, statusInWords(v->status));
  return tr("%1: %2 dots%3, reprojection %4 px RMS, tilted %5 deg")
      .arg(head)
      .arg(v->dots)
      .arg(v->partial ? tr(" (part of the grid)") : QString())
      .arg(v->rms_px, 0, 'f', 3)
      .arg(v->tilt_deg, 0, 'f', 0);
}

void IntrinsicsPage::refreshImages() {
  const int current = list_->currentRow();
  list_->clear();
  for (int i = 0; i < imageCount(); ++i) {
    auto* item = new QListWidgetItem(imageStatus(i));
    const IntrinsicsView* v = runView(i);
    if (v && !ok(v->status)) item->setForeground(QColor(0xb0, 0x00, 0x20));
    list_->addItem(item);
  }
  list_->setCurrentRow(std::min(current, imageCount() - 1));
  showPreview();
}

void IntrinsicsPage::showPreview() {
  const int index = list_->currentRow();
  if (index < 0 || index >= imageCount()) {
    preview_->setImage({}, tr("No image selected"));
    return;
  }
  preview_->setImage(displayImage(images_[static_cast<size_t>(index)].grey));
  CalibrationOverlay overlay;
  if (const IntrinsicsView* v = runView(index))
    for (const FoundDot& d : v->found) overlay.spots.emplace_back(d.image_px.x(), d.image_px.y());
  preview_->setOverlay(std::move(overlay));
}

}  // namespace imagepro::app
