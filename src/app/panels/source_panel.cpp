#include "app/panels/source_panel.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QVBoxLayout>

namespace imagepro::app {

SourcePanel::SourcePanel(QWidget* parent)
    : QWidget(parent), combo_(new QComboBox), button_(new QPushButton), description_(new QLabel) {
  combo_->setObjectName(QStringLiteral("sourceCombo"));
  button_->setObjectName(QStringLiteral("sourceButton"));
  for (SourceKind k : kSourceKinds) combo_->addItem(sourceKindLabel(k), static_cast<int>(k));
  combo_->setItemData(0, tr("Still images: a file, several files or a folder (thesis 2.2)"), Qt::ToolTipRole);
  combo_->setItemData(1, tr("A V4L2 camera, frame by frame (thesis 2.2)"), Qt::ToolTipRole);
  combo_->setItemData(2, tr("Virtual perspective projection of the target; move it with the keys (thesis 2.2, appendix A)"),
                      Qt::ToolTipRole);
  description_->setWordWrap(true);
  description_->setTextInteractionFlags(Qt::TextSelectableByMouse);

  auto* row = new QHBoxLayout;
  row->addWidget(combo_, 1);
  row->addWidget(button_);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addLayout(row);
  layout->addWidget(description_);

  connect(combo_, &QComboBox::currentIndexChanged, this, [this] {
    if (running_) emit stopRequested();
    updateButton();
    emit kindChanged(kind());
  });
  connect(button_, &QPushButton::clicked, this, [this] {
    if (running_) emit stopRequested();
    else if (kind() == SourceKind::File) emit openFileRequested();
    else emit startRequested(kind());
  });
  setKind(SourceKind::Virtual);
  updateButton();
}

SourceKind SourcePanel::kind() const { return static_cast<SourceKind>(combo_->currentData().toInt()); }

void SourcePanel::setKind(SourceKind kind) { combo_->setCurrentIndex(combo_->findData(static_cast<int>(kind))); }

void SourcePanel::setRunning(bool running) {
  running_ = running;
  updateButton();
}

void SourcePanel::setDescription(const QString& text) { description_->setText(text); }

void SourcePanel::updateButton() {
  if (kind() == SourceKind::File) {
    button_->setText(running_ ? tr("Stop") : tr("Open File..."));
    button_->setToolTip(tr("Choose image files or a folder to process (Ctrl+O)"));
  } else {
    button_->setText(running_ ? tr("Stop") : tr("Start"));
    button_->setToolTip(tr("Start or stop processing (F5)"));
  }
}

}  // namespace imagepro::app
