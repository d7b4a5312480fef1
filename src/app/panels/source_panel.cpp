#include "app/panels/source_panel.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QToolButton>
#include <QVBoxLayout>

namespace imagepro::app {

SourcePanel::SourcePanel(QWidget* parent)
    : QWidget(parent),
      combo_(new QComboBox),
      button_(new QPushButton),
      file_row_(new QWidget),
      position_(new QLabel),
      description_(new QLabel) {
  combo_->setObjectName(QStringLiteral("sourceCombo"));
  button_->setObjectName(QStringLiteral("sourceButton"));
  for (SourceKind k : kSourceKinds) combo_->addItem(sourceKindLabel(k), static_cast<int>(k));
  combo_->setItemData(0, tr("Still images: a file, several files or a folder (thesis 2.2)"), Qt::ToolTipRole);
  combo_->setItemData(1, tr("A V4L2 camera, frame by frame (thesis 2.2)"), Qt::ToolTipRole);
  combo_->setItemData(2, tr("Virtual perspective projection of the target; move it with the keys (thesis 2.2, appendix A)"),
                      Qt::ToolTipRole);
  description_->setObjectName(QStringLiteral("sourceDescription"));
  description_->setWordWrap(true);
  description_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  position_->setObjectName(QStringLiteral("filePosition"));
  position_->setAlignment(Qt::AlignCenter);

  auto* open = new QToolButton;
  open->setObjectName(QStringLiteral("fileOpen"));
  open->setText(tr("Open..."));
  open->setToolTip(tr("Choose other image files or a folder (Ctrl+O)"));
  connect(open, &QToolButton::clicked, this, &SourcePanel::openFileRequested);
  auto* steps = new QHBoxLayout(file_row_);
  steps->setContentsMargins(0, 0, 0, 0);
  steps->addWidget(stepButton(FileStep::First, QStringLiteral("|\u25c0"), "fileFirst", tr("The first image (Home)")));
  steps->addWidget(stepButton(FileStep::Previous, QStringLiteral("\u25c0"), "filePrevious",
                              tr("The previous image (Left or Page Up)")));
  steps->addWidget(position_, 1);
  steps->addWidget(stepButton(FileStep::Next, QStringLiteral("\u25b6"), "fileNext", tr("The next image (Right or Page Down)")));
  steps->addWidget(stepButton(FileStep::Last, QStringLiteral("\u25b6|"), "fileLast", tr("The last image (End)")));
  steps->addWidget(open);

  auto* row = new QHBoxLayout;
  row->addWidget(combo_, 1);
  row->addWidget(button_);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addLayout(row);
  layout->addWidget(file_row_);
  layout->addWidget(description_);

  connect(combo_, &QComboBox::currentIndexChanged, this, [this] {
    if (running_) emit stopRequested();
    updateButton();
    emit kindChanged(kind());
  });
  connect(button_, &QPushButton::clicked, this, [this] {
    if (running_) emit stopRequested();
    else if (!canStart()) emit openFileRequested();
    else emit startRequested(kind());
  });
  setKind(SourceKind::Virtual);
  updateButton();
}

QToolButton* SourcePanel::stepButton(FileStep step, const QString& text, const char* name, const QString& tooltip) {
  auto* b = new QToolButton;
  b->setObjectName(QLatin1String(name));
  b->setText(text);
  b->setToolTip(tooltip);
  connect(b, &QToolButton::clicked, this, [this, step] { emit stepRequested(step); });
  return b;
}

SourceKind SourcePanel::kind() const { return static_cast<SourceKind>(combo_->currentData().toInt()); }

void SourcePanel::setKind(SourceKind kind) { combo_->setCurrentIndex(combo_->findData(static_cast<int>(kind))); }

void SourcePanel::setRunning(bool running) {
  running_ = running;
  updateButton();
}

void SourcePanel::setDescription(const QString& text) { description_->setText(text); }

QString SourcePanel::description() const { return description_->text(); }

void SourcePanel::setFileCount(int count) {
  file_count_ = count;
  if (count <= 0) file_index_ = -1;
  updateButton();
}

void SourcePanel::setFileIndex(int index) {
  file_index_ = index;
  updateButton();
}

bool SourcePanel::canStart() const {
  // One still image has nothing to play: Start would only show it again.
  return kind() != SourceKind::File || file_count_ == 0 || file_count_ > 1;
}

void SourcePanel::updateButton() {
  const bool file = kind() == SourceKind::File;
  if (file && !canStart()) {
    button_->setText(running_ ? tr("Stop") : tr("Open File..."));
    button_->setToolTip(tr("Choose image files or a folder to process (Ctrl+O)"));
  } else if (file) {
    button_->setText(running_ ? tr("Stop") : tr("Start"));
    button_->setToolTip(file_count_ > 1 ? tr("Play the images from the one shown to the last; Stop halts at the one "
                                             "shown (F5)")
                                        : tr("Play or stop the video (F5)"));
  } else {
    button_->setText(running_ ? tr("Stop") : tr("Start"));
    button_->setToolTip(tr("Start or stop processing (F5)"));
  }
  file_row_->setVisible(file && file_count_ > 1);
  position_->setText(file_count_ > 1 && file_index_ >= 0 ? tr("%1 of %2").arg(file_index_ + 1).arg(file_count_)
                                                         : QString());
}

}  // namespace imagepro::app
