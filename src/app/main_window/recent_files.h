#pragma once
// The File menu's recent files and folders, remembered between runs.
#include <QObject>
#include <QStringList>

class QMenu;

namespace imagepro::app {

class RecentFiles : public QObject {
  Q_OBJECT

 public:
  explicit RecentFiles(QMenu* menu, QObject* parent = nullptr);

  void add(const QString& path);
  void remove(const QString& path);  // a path that failed to load
  QStringList paths() const { return paths_; }

 signals:
  void chosen(const QString& path);

 private:
  void rebuild();

  QMenu* menu_;
  QStringList paths_;
};

}  // namespace imagepro::app
