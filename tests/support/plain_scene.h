#pragma once
// The thesis's synthetic frame (2.2): the target's card on one flat grey. The default
// Virtual scene is a lit room (Backdrop::Room); tests whose ground truth counts on a
// uniform background and even light start from these instead.
#include "core/settings/options.h"
#include "core/settings/settings.h"

namespace imagepro::test {

inline VirtualSceneOptions plainScene() {
  VirtualSceneOptions scene;
  scene.backdrop = Backdrop::Plain;
  return scene;
}

inline Settings plainSettings() {
  Settings settings;
  settings.virtual_scene.backdrop = Backdrop::Plain;
  return settings;
}

}  // namespace imagepro::test
