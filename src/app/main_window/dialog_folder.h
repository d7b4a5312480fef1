#pragma once
// Where every file dialog of the application starts: the folder the user last opened
// or saved in, in any window (kept across runs), or the home folder.
#include <QString>

namespace imagepro::app {

// The folder to start a dialog in: the last one remembered, while it still exists, else home.
QString dialogFolder();
// The start of a save dialog: dialogFolder() with a suggested file name.
QString dialogFolderWith(const QString& file_name);
// Remembers the folder of a chosen path (a file's folder, or the folder itself).
void rememberDialogFolder(const QString& path);

}  // namespace imagepro::app
