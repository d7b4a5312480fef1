#pragma once
// A dismissable error (red) or warning (amber) line at the top of the results area, so a problem (an
// unreadable file, malformed settings) is seen where the user is looking.
#include <QFrame>

class QLabel;

namespace imagepro::app {

class MessageBanner : public QFrame {
  Q_OBJECT

 public:
  explicit MessageBanner(QWidget* parent = nullptr);
  void showError(const QString& text);
  void showWarning(const QString& text);  // done, with something to know (a renamed key)
  // Hides an error, which the next step's success ends; a warning stays until dismissed.
  void clearError();
  QString text() const;

 private:
  QLabel* label_;
  bool warning_ = false;
};

}  // namespace imagepro::app
