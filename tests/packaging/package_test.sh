#!/usr/bin/env bash
# The Debian package as a user gets it: CPack builds it from the build tree, dpkg-deb
# unpacks it into a scratch root (no install, no source or build tree in reach), and
# from there the programs run, find their data and print the version; the package's
# name, dependencies and desktop entry are checked.
# usage: package_test.sh BUILD_DIR VERSION
set -euo pipefail
build_dir="$(cd "$1" && pwd)" version="$2"
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
echo "package: $(basename "$deb"), $(du -k "$deb" | cut -f1) KB, runs unpacked"
