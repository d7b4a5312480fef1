#!/usr/bin/env bash
# The Debian package as a user gets it: CPack builds it from the build tree, dpkg-deb
# unpacks it into a scratch root (no install, no source or build tree in reach), and
# from there the programs run, find their data and print the version, and Debian's
# python3 imports the Python module from where the package puts it; the package's
# name, dependencies and desktop entry are checked.
# usage: package_test.sh BUILD_DIR VERSION [python|no-python]
set -euo pipefail
build_dir="$(cd "$1" && pwd)" version="$2" python="${3:-no-python}"
fail() { echo "FAILED: $*" >&2; exit 1; }
for tool in cpack:cmake dpkg-deb:dpkg dpkg-shlibdeps:dpkg-dev desktop-file-validate:desktop-file-utils; do
  command -v "${tool%%:*}" >/dev/null || fail "${tool%%:*} is missing (Debian package ${tool##*:}; tools/setup.sh installs it)"
done
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT

# The package, in a folder of its own: a `tools/setup.sh package` at the same time
# writes to the build's package/ folder, not here.
(cd "$build_dir" && cpack --config CPackConfig.cmake -B "$scratch/out" >"$scratch/cpack.log" 2>&1) ||
  fail "cpack: $(tail -20 "$scratch/cpack.log")"
deb="$scratch/out/imagepro_${version}_$(dpkg --print-architecture).deb"
[ -f "$deb" ] || fail "no $(basename "$deb"); cpack made: $(ls "$scratch/out")"

# dpkg-shlibdeps named the libraries the programs link.
depends="$(dpkg-deb -f "$deb" Depends)"
for lib in libqt6widgets6 libopencv-core libstdc++6; do
  [[ "$depends" == *"$lib"* ]] || fail "Depends lacks $lib: $depends"
done
if [ "$python" = python ]; then
  # The Python version the module was built for, and numpy.
  for dep in "python3 (>= " "python3 (<< " python3-numpy; do
    [[ "$depends" == *"$dep"* ]] || fail "Depends lacks $dep: $depends"
  done
fi
[ "$(dpkg-deb -f "$deb" Section)" = science ] || fail "Section: $(dpkg-deb -f "$deb" Section)"
[ -n "$(dpkg-deb -f "$deb" Maintainer)" ] || fail "no Maintainer"

root="$scratch/root"
dpkg-deb -x "$deb" "$root"
usr="$root/usr"
for program in imagepro imagepro-cli; do
  [ -x "$usr/bin/$program" ] || fail "no usr/bin/$program"
  missing="$(ldd "$usr/bin/$program" | grep 'not found' || true)"
  [ -z "$missing" ] || fail "$program: libraries not found: $missing"
done

# Run from a folder that is neither the source nor the build tree.
cd "$scratch"
cli="$usr/bin/imagepro-cli"
[ "$("$cli" --version)" = "imagepro-cli $version" ] || fail "imagepro-cli --version: $("$cli" --version)"
[ "$(QT_QPA_PLATFORM=offscreen "$usr/bin/imagepro" --version 2>/dev/null)" = "ImagePro $version" ] ||
  fail "imagepro --version: $(QT_QPA_PLATFORM=offscreen "$usr/bin/imagepro" --version 2>&1)"
data="$("$cli" --data-dir)"
[ "$data" = "$usr/share/imagepro" ] || fail "imagepro-cli --data-dir: $data, not the unpacked $usr/share/imagepro"

"$cli" demo --frames 10 >"$scratch/demo.txt" || fail "demo --frames 10 exited $?: $(tail -5 "$scratch/demo.txt")"
grep -q '^10 of 10 frames reconstructed' "$scratch/demo.txt" || fail "demo: $(tail -3 "$scratch/demo.txt")"
# The shipped settings and samples, from the unpacked data folder.
"$cli" reconstruct --config "$data/settings.json" "$data/samples" >"$scratch/poses.csv" ||
  fail "reconstruct on the shipped samples exited $?"
grep -q '^sample01_facing.png,ok,' "$scratch/poses.csv" || fail "reconstruct: $(head -3 "$scratch/poses.csv")"
for pattern in thesis-a4 thesis-letter thesis-a3; do
  [ "$(head -c 5 "$data/patterns/$pattern.pdf")" = "%PDF-" ] || fail "no PDF patterns/$pattern.pdf"
done

# The man page holds every command's help; the desktop entry validates and its icon is there.
man_page="$usr/share/man/man1/imagepro-cli.1.gz"
[ -f "$man_page" ] || fail "no man page"
# Unpacked once into a file: piped into grep -q, gzip can be cut off by grep's early exit
# (SIGPIPE), which pipefail reports as a failure of the whole pipe.
gzip -dc "$man_page" >"$scratch/imagepro-cli.1" || fail "man page does not decompress"
for section in '^\.SH SYNOPSIS' '^\.SH COMMANDS' '^\.SS demo' '^\.SS reconstruct'; do
  grep -q "$section" "$scratch/imagepro-cli.1" || fail "man page lacks $section"
done
desktop="$usr/share/applications/imagepro.desktop"
desktop-file-validate "$desktop" || fail "desktop-file-validate $desktop"
grep -qx 'Exec=imagepro %F' "$desktop" || fail "Exec: $(grep ^Exec "$desktop")"
[ -f "$usr/share/icons/hicolor/scalable/apps/imagepro.svg" ] || fail "no scalable icon"
# The Python module: in the folder Debian's python3 searches, and imported from there by
# that python3 (the unpacked copy of the folder put first on its path), outside the
# build tree; a pose reconstructed through it.
if [ "$python" = python ]; then
  dist="$usr/lib/python3/dist-packages"
  set -- "$dist"/imagepro.*.so
  [ -f "$1" ] || fail "no imagepro module in usr/lib/python3/dist-packages: $(dpkg-deb -c "$deb" | grep -i python || true)"
  /usr/bin/python3 -c 'import sys; sys.exit("/usr/lib/python3/dist-packages" not in sys.path)' ||
    fail "Debian's python3 does not search /usr/lib/python3/dist-packages"
  missing="$(ldd "$1" | grep 'not found' || true)"
  [ -z "$missing" ] || fail "$(basename "$1"): libraries not found: $missing"
  env -u PYTHONHOME PYTHONPATH="$dist" /usr/bin/python3 -c '
import sys, imagepro
assert imagepro.__file__.startswith(sys.argv[1]), imagepro.__file__
assert imagepro.__version__ == sys.argv[2], imagepro.__version__
settings = imagepro.Settings()
truth = imagepro.Pose(rx_deg=10, ry_deg=-20, rz_deg=30, tx_mm=20, ty_mm=-10, tz_mm=900)
result = imagepro.reconstruct(imagepro.render(truth, settings), settings)
assert result.pose is not None and result.pose.rotation_error_deg(truth) < 1.0, result
' "$dist/" "$version" >"$scratch/python.txt" 2>&1 || fail "import imagepro from the package: $(tail -5 "$scratch/python.txt")"
fi
echo "package: $(basename "$deb"), $(du -k "$deb" | cut -f1) KB, runs unpacked"
