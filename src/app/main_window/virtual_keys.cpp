#include "app/main_window/virtual_keys.h"

#include <Qt>

namespace imagepro::app {

std::optional<VirtualKey> virtualKeyFor(int qt_key) {
  switch (qt_key) {
    case Qt::Key_4: return VirtualKey::TxMinus;
    case Qt::Key_6: return VirtualKey::TxPlus;
    case Qt::Key_2: return VirtualKey::TyMinus;
    case Qt::Key_8: return VirtualKey::TyPlus;
    case Qt::Key_Insert: return VirtualKey::TzMinus;
    case Qt::Key_Delete: return VirtualKey::TzPlus;
    case Qt::Key_Up: return VirtualKey::RxMinus;
    case Qt::Key_Down: return VirtualKey::RxPlus;
    case Qt::Key_Left: return VirtualKey::RyMinus;
    case Qt::Key_Right: return VirtualKey::RyPlus;
    case Qt::Key_Home: return VirtualKey::RzMinus;
    case Qt::Key_End: return VirtualKey::RzPlus;
    default: return std::nullopt;
  }
}

}  // namespace imagepro::app
