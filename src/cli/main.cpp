// imagepro-cli: the ImagePro pipeline without a window. Each subcommand is in its
// own cmd_<name>.cpp and registers itself; runCommands dispatches.
#include "cli/command.h"

int main(int argc, char** argv) {
  return imagepro::cli::runCommands("imagepro-cli", "headless ImagePro, monocular 3D pose of a circular target", argc,
                                    argv);
}
