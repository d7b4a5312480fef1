#!/usr/bin/env bash
# ImagePro set-up: installs the Debian packages that are missing, configures and
# builds, then either starts the application or runs the whole test suite.
#
#   tools/setup.sh run    build only what it starts, then start ImagePro on the Virtual source
#                         (without a display: imagepro-cli's headless demo, which prints poses)
#   tools/setup.sh test   build, then run every test through ctest
#   tools/setup.sh build  build only
#   tools/setup.sh package  build what the Debian package holds, then the package itself:
#                         BUILD_DIR/package/imagepro_<version>_<arch>.deb (packaging/)
#   tools/setup.sh sanitize  AddressSanitizer + UndefinedBehaviorSanitizer build (build-sanitize),
#                         preconditions checked, then the test suite; SANITIZE_TESTS=core-cli
#                         leaves out the application and its tests (docs/reliability.md)
#   tools/setup.sh tsan   ThreadSanitizer build (build-tsan), then the tests of the threads:
#                         the worker and the GUI (test_app), the engine, data out
#   tools/setup.sh fuzz   clang build of the libFuzzer targets of tests/fuzz (build-fuzz);
#                         tools/fuzz.sh runs them
#
# Environment: BUILD_DIR (default: build, or the mode's own), JOBS (default: 2),
# IMAGEPRO_WERROR (ON in CI).
set -euo pipefail

mode="${1:-run}"
case "$mode" in run|test|build|package|sanitize|tsan|fuzz) ;; *) echo "usage: tools/setup.sh run|test|build|package|sanitize|tsan|fuzz" >&2; exit 2 ;; esac

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
case "$mode" in
  sanitize) default_build="$root/build-sanitize" ;;
  tsan) default_build="$root/build-tsan" ;;
  fuzz) default_build="$root/build-fuzz" ;;
  *) default_build="$root/build" ;;
esac
build_dir="${BUILD_DIR:-$default_build}"
jobs="${JOBS:-2}"

# libqt6opengl6-dev is only recommended by qt6-base-dev, but Qt6Charts' CMake package
# needs Qt6OpenGL, and recommends are not installed here.
# The studies (src/studies) measure against AprilTag and OpenCV's aruco (contrib).
# The Python module (src/python) and its tests: pybind11, the system's python3 with numpy
# and pytest.
# The package (packaging/, its test): help2man writes imagepro-cli's man page, CPack's DEB
# generator asks file and dpkg-shlibdeps (dpkg-dev) for the dependencies, and
# desktop-file-validate checks the desktop entry.
# What the application itself is built from: all that `run` installs.
packages=(
  build-essential cmake pkg-config ccache
  qt6-base-dev qt6-charts-dev libqt6opengl6-dev libgl-dev
  libopencv-dev libeigen3-dev nlohmann-json3-dev libv4l-dev
)
# The rest serves the tests, the studies, the Python module and the package: run, which
# builds none of them, goes without. The photographs (opencv-doc) are the real-scene
# tests' backgrounds; without them those tests skip.
if [ "$mode" != run ]; then
  packages+=(
    libopencv-contrib-dev libapriltag-dev
    libgtest-dev libgmock-dev libbenchmark-dev
    pybind11-dev python3-dev python3-numpy python3-pytest
    help2man dpkg-dev file desktop-file-utils
    opencv-doc
  )
fi
# libFuzzer comes with clang's runtime libraries.
[ "$mode" = fuzz ] && packages+=(clang libclang-rt-14-dev libfuzzer-14-dev)

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

# The sanitizer modes' options and what they build and test (CMakeLists.txt: IMAGEPRO_SANITIZE).
mode_options=()
targets=()
# The sanitizers' runs need no more than -O1; Release's -O3 would only lengthen these builds.
sanitizer_release_flags="-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG"
case "$mode" in
  sanitize) mode_options=(-DIMAGEPRO_SANITIZE=address,undefined "$sanitizer_release_flags") ;;
  tsan)
    mode_options=(-DIMAGEPRO_SANITIZE=thread "$sanitizer_release_flags")
    targets=(--target test_app test_pipeline)
    ;;
  package) targets=(--target imagepro_package_contents) ;;
  fuzz)
    # The vector code's GCC target pragmas mean nothing to clang: the whole build takes
    # the AVX2 instructions they ask for (the fuzzing machine has them), and clang's
    # warnings about them are no error here (the gcc builds keep -Werror).
    mode_options=(-DCMAKE_CXX_COMPILER=clang++ "-DCMAKE_CXX_FLAGS=-mavx2 -mbmi -mbmi2" -DIMAGEPRO_WERROR=OFF
                  -DIMAGEPRO_SANITIZE=address,undefined,fuzzer-no-link -DIMAGEPRO_FUZZ=ON
                  -DIMAGEPRO_BUILD_APP=OFF -DIMAGEPRO_BUILD_TESTS=OFF)
    targets=(--target imagepro_fuzz_targets)
    ;;
esac
# run builds only the program it starts: the window, or without a display the headless demo,
# and configures without the tests and studies, whose packages it did not install. Every
# other mode asks for them back, so a later test or build in the same folder has them.
has_display=false
if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then has_display=true; fi
if [ "$mode" = run ]; then
  if $has_display; then targets=(--target imagepro); else targets=(--target imagepro-cli); fi
  mode_options+=(-DIMAGEPRO_BUILD_TESTS=OFF -DIMAGEPRO_BUILD_STUDIES=OFF -DIMAGEPRO_PYTHON=OFF)
elif [ "$mode" != fuzz ]; then
  mode_options+=(-DIMAGEPRO_BUILD_TESTS=ON -DIMAGEPRO_BUILD_STUDIES=ON)
  # The module's own default: on where pybind11 and numpy are (not in a sanitizer build).
  mode_options+=(-UIMAGEPRO_PYTHON)
fi
sanitize_tests="${SANITIZE_TESTS:-all}"
# The sanitizer builds keep line numbers for their reports (-g1), for which ccache also
# keys each object on its build folder by default; leaving the folder out lets a fresh
# clone (CI) reuse what was compiled anywhere under ccache's base_dir.
case "$mode" in sanitize|tsan|fuzz) export CCACHE_NOHASHDIR=1 ;; esac
if [ "$mode" = sanitize ] && [ "$sanitize_tests" = core-cli ]; then
  mode_options+=(-DIMAGEPRO_BUILD_APP=OFF)
fi

echo "== configuring $build_dir"
cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DIMAGEPRO_WERROR="$werror" "${mode_options[@]}" >/dev/null
echo "== building with $jobs jobs"
cmake --build "$build_dir" -j "$jobs" "${targets[@]}"

case "$mode" in
  build) ;;
  package)
    echo "== making the Debian package"
    (cd "$build_dir" && cpack --config CPackConfig.cmake)
    ;;
  test)
    echo "== running the test suite"
    cd "$build_dir"
    QT_QPA_PLATFORM=offscreen ctest --output-on-failure -j "$jobs" --timeout 900
    ;;
  sanitize)
    echo "== running the test suite under AddressSanitizer and UndefinedBehaviorSanitizer ($sanitize_tests)"
    cd "$build_dir"
    # The soak's memory slope means nothing under ASan (freed memory waits in quarantine).
    # halt_on_error: any report fails its test; Qt's and fontconfig's caches live to
    # the process's end, which LeakSanitizer would take for leaks. QtTest would answer
    # the abort of a report at exit by running gdb on itself over and over, until
    # ctest's time-out: without its stack dump the test fails at once with the report.
    QTEST_DISABLE_STACK_DUMP=1 ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:abort_on_error=1:detect_stack_use_after_return=1" \
      LSAN_OPTIONS="suppressions=$root/tools/sanitizer/lsan.supp:print_suppressions=0" \
      UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
      QT_QPA_PLATFORM=offscreen ctest --output-on-failure -j "$jobs" --timeout 1800 -LE soak
    ;;
  tsan)
    echo "== running the threads' tests under ThreadSanitizer"
    cd "$build_dir"
    TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$root/tools/sanitizer/tsan.supp" \
      QT_QPA_PLATFORM=offscreen ctest --output-on-failure -j "$jobs" --timeout 1800 -R '^(test_app|Engine|DataOut|FrameClock|StageChain)'
    ;;
  fuzz) echo "== fuzz targets in $build_dir/tests/fuzz (tools/fuzz.sh runs them)" ;;
  run)
    if $has_display; then
      exec "$build_dir/src/app/imagepro" --source virtual
    else
      echo "== no display: headless demo on the Virtual source (the GUI needs a display)"
      exec "$build_dir/src/cli/imagepro-cli" demo --frames 100
    fi
    ;;
esac
