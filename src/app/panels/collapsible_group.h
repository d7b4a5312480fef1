#pragma once
// One panel of the control panel: a title bar that folds its content away.
#include <QWidget>

class QToolButton;

namespace imagepro::app {

class CollapsibleGroup : public QWidget {
  Q_OBJECT

 public:
  CollapsibleGroup(const QString& title, QWidget* content, QWidget* parent = nullptr);

  QString title() const;
  QWidget* content() const { return content_; }
  bool isExpanded() const;
  void setExpanded(bool expanded);

 private:
  QToolButton* header_;
  QWidget* content_;
};

}  // namespace imagepro::app
