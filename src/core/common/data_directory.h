#pragma once
// Where the shipped data is: the default settings (settings.json), the sample frames
// (samples/) and, once installed, the printable patterns (patterns/). An installed
// program finds it beside its own bin/ folder, at ../share/imagepro (the install
// layout of GNUInstallDirs), so neither the source nor the build tree is needed; a
// program run from a build tree falls back on the data/ folder of the sources it was
// built from.
#include <filesystem>

namespace imagepro {

// The data folder of the running program; empty when neither place holds the data.
std::filesystem::path dataDirectory();

// The same search for an executable at `executable`: its installed data folder if that
// holds settings.json, else the build's data folder if that does, else empty.
std::filesystem::path dataDirectoryFor(const std::filesystem::path& executable);

// The running program's own file, links resolved (/proc/self/exe); empty if unknown.
std::filesystem::path executablePath();

}  // namespace imagepro
