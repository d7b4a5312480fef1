#pragma once
// The main window's tool windows (the calibration wizard, the d0 dialog): one of each,
// made on first use as the window's child and kept while closed, shown and raised.
#include <QString>

namespace imagepro::app {

template <class Dialog, class Window>
Dialog& showOwnedDialog(Window& window) {
  auto* dialog = window.template findChild<Dialog*>(QString(), Qt::FindDirectChildrenOnly);
  if (!dialog) dialog = new Dialog(window);
  dialog->show();
  dialog->raise();
  dialog->activateWindow();
  return *dialog;
}

}  // namespace imagepro::app
