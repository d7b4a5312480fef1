#include "app/main_window/message_banner.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QToolButton>

namespace imagepro::app {

MessageBanner::MessageBanner(QWidget* parent) : QFrame(parent), label_(new QLabel) {
  setObjectName(QStringLiteral("messageBanner"));
  label_->setWordWrap(true);
  label_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  auto* close = new QToolButton;
  close->setText(QStringLiteral("\u00d7"));
  close->setAutoRaise(true);
  close->setToolTip(tr("Dismiss"));
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(8, 4, 4, 4);
  layout->addWidget(label_, 1);
  layout->addWidget(close);
  connect(close, &QToolButton::clicked, this, &QWidget::hide);
  hide();
}

void MessageBanner::showError(const QString& text) {
  warning_ = false;
  setStyleSheet(QStringLiteral("#messageBanner { background: #f8d7da; border: 1px solid #e0a0a8; }"
                               "#messageBanner QLabel { color: #721c24; }"));
  label_->setText(text);
  show();
}

void MessageBanner::showWarning(const QString& text) {
  warning_ = true;
  setStyleSheet(QStringLiteral("#messageBanner { background: #fff3cd; border: 1px solid #e6c766; }"
                               "#messageBanner QLabel { color: #664d03; }"));
  label_->setText(text);
  show();
}

void MessageBanner::clearError() {
  if (!warning_) hide();
}

QString MessageBanner::text() const { return isVisible() ? label_->text() : QString(); }

}  // namespace imagepro::app
