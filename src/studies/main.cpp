// imagepro-studies: the evaluation harness that regenerates the docs' tables (accuracy
// against a reference marker, the calibration and tracking studies, the peers' speed).
// Each study is in its own cmd_<name>.cpp and registers itself; runCommands dispatches.
#include "cli/command.h"

int main(int argc, char** argv) {
  return imagepro::cli::runCommands("imagepro-studies", "ImagePro's studies, which regenerate the tables of docs/",
                                    argc, argv);
}
