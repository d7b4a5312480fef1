#include "app/main_window/dialog_folder.h"

#include <QDir>
#include <QFileInfo>
#include <QSettings>

namespace imagepro::app {

namespace {
const QString kKey = QStringLiteral("lastDirectory");
}

QString dialogFolder() {
  const QString last = QSettings().value(kKey).toString();
  if (!last.isEmpty() && QFileInfo(last).isDir()) return last;
  return QDir::homePath();
}

QString dialogFolderWith(const QString& file_name) { return dialogFolder() + QLatin1Char('/') + file_name; }

void rememberDialogFolder(const QString& path) {
  if (path.isEmpty()) return;
  const QFileInfo info(path);
  QSettings().setValue(kKey, info.isDir() ? info.absoluteFilePath() : info.absolutePath());
}

}  // namespace imagepro::app
