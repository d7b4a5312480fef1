#include "app/main_window/recent_files.h"

#include <QAction>
#include <QDir>
#include <QFileInfo>
#include <QMenu>
#include <QSettings>

namespace imagepro::app {

namespace {
constexpr int kMaxRecent = 10;
const QString kKey = QStringLiteral("recentFiles");
}  // namespace

RecentFiles::RecentFiles(QMenu* menu, QObject* parent) : QObject(parent), menu_(menu) {
  paths_ = QSettings().value(kKey).toStringList();
  rebuild();
}

namespace {
QString cleanPath(const QString& path) { return QDir::cleanPath(QFileInfo(path).absoluteFilePath()); }
}  // namespace

void RecentFiles::add(const QString& path) {
  const QString clean = cleanPath(path);
  paths_.removeAll(clean);
  paths_.prepend(clean);
  while (paths_.size() > kMaxRecent) paths_.removeLast();
  QSettings().setValue(kKey, paths_);
  rebuild();
}

void RecentFiles::remove(const QString& path) {
  if (paths_.removeAll(cleanPath(path)) == 0) return;
  QSettings().setValue(kKey, paths_);
  rebuild();
}

void RecentFiles::rebuild() {
  menu_->clear();
  for (int i = 0; i < paths_.size(); ++i) {
    const QString path = paths_[i];
    QAction* action = menu_->addAction(QStringLiteral("&%1 %2").arg((i + 1) % 10).arg(QFileInfo(path).fileName()));
    action->setToolTip(path);
    action->setStatusTip(path);
    connect(action, &QAction::triggered, this, [this, path] { emit chosen(path); });
  }
  if (paths_.isEmpty()) menu_->addAction(tr("(none)"))->setEnabled(false);
  menu_->addSeparator();
  connect(menu_->addAction(tr("Clear list")), &QAction::triggered, this, [this] {
    paths_.clear();
    QSettings().setValue(kKey, paths_);
    rebuild();
  });
}

}  // namespace imagepro::app
