#!/usr/bin/env bash
# ImagePro set-up: installs the Debian packages that are missing, configures and
# builds, then either starts the application or runs the whole test suite.
#
#   tools/setup.sh run    build, then start ImagePro on the Virtual source
#                         (without a display: a headless demo that prints poses)
#   tools/setup.sh test   build, then run every test through ctest
#   tools/setup.sh build  build only
#
# Environment: BUILD_DIR (default: build), JOBS (default: 2), IMAGEPRO_WERROR (ON in CI).
set -euo pipefail

mode="${1:-run}"
case "$mode" in run|test|build) ;; *) echo "usage: tools/setup.sh run|test|build" >&2; exit 2 ;; esac

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$root/build}"
jobs="${JOBS:-2}"

# libqt6opengl6-dev is only recommended by qt6-base-dev, but Qt6Charts' CMake package
# needs Qt6OpenGL, and recommends are not installed here.
# opencv-doc (~96 MB) ships the photographs that real-scene frames are drawn over
# (its examples/data folder); without it the real-scene tests skip.
packages=(
  build-essential cmake pkg-config ccache
  qt6-base-dev qt6-charts-dev libqt6opengl6-dev libgl-dev
  libopencv-dev libopencv-contrib-dev libeigen3-dev nlohmann-json3-dev
  libv4l-dev libapriltag-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  opencv-doc
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "== installing: ${missing[*]}"
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "error: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
    sudo_cmd=(sudo)
  fi
  "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

werror="${IMAGEPRO_WERROR:-OFF}"
[ "${CI:-}" = "true" ] && werror=ON

echo "== configuring $build_dir"
cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DIMAGEPRO_WERROR="$werror" >/dev/null
echo "== building with $jobs jobs"
cmake --build "$build_dir" -j "$jobs"

case "$mode" in
  build) ;;
  test)
    echo "== running the test suite"
    cd "$build_dir"
    QT_QPA_PLATFORM=offscreen ctest --output-on-failure -j "$jobs" --timeout 900
    ;;
  run)
    if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
      exec "$build_dir/src/app/imagepro" --source virtual
    else
      echo "== no display: headless demo on the Virtual source (the GUI needs a display)"
      exec "$build_dir/src/cli/imagepro-cli" demo --frames 100
    fi
    ;;
esac
