#include "app/panels/collapsible_group.h"

#include <QFrame>
#include <QToolButton>
#include <QVBoxLayout>

namespace imagepro::app {

CollapsibleGroup::CollapsibleGroup(const QString& title, QWidget* content, QWidget* parent)
    : QWidget(parent), header_(new QToolButton), content_(content) {
  header_->setText(title);
  header_->setCheckable(true);
  header_->setChecked(true);
  header_->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
  header_->setArrowType(Qt::DownArrow);
  header_->setAutoRaise(true);
  header_->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
  QFont bold = header_->font();
  bold.setBold(true);
  header_->setFont(bold);

  auto* frame = new QFrame;
  frame->setFrameShape(QFrame::StyledPanel);
  auto* frame_layout = new QVBoxLayout(frame);
  frame_layout->setContentsMargins(8, 4, 8, 6);
  frame_layout->addWidget(content_);

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(0);
  layout->addWidget(header_);
  layout->addWidget(frame);

  connect(header_, &QToolButton::toggled, this, [this, frame](bool on) {
    header_->setArrowType(on ? Qt::DownArrow : Qt::RightArrow);
    frame->setVisible(on);
  });
}

QString CollapsibleGroup::title() const { return header_->text(); }
bool CollapsibleGroup::isExpanded() const { return header_->isChecked(); }
void CollapsibleGroup::setExpanded(bool expanded) { header_->setChecked(expanded); }

}  // namespace imagepro::app
