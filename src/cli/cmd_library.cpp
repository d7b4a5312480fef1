// imagepro-cli library: writes the synthetic image library of thesis appendix B
// (tables B.1 and B.2) as PNG files with a CSV of each image's parameters.
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "cli/command.h"
#include "core/common/atomic_file.h"
#include "core/ellipse/synthetic_library.h"

namespace imagepro::cli {
namespace {

int run(const Args& args) {
  args.rejectUnknown({"grey", "blur", "noise", "seed"});
  if (args.positionals().size() != 1) throw UsageError("give exactly one output folder");
  const std::filesystem::path dir = args.positionals()[0];
  LibraryGreyOptions grey;
  grey.blur_sigma_px = args.number("blur", 0.0);
  grey.noise_sigma = args.number("noise", 0.0);
  grey.seed = static_cast<unsigned>(args.integer("seed", 1));
  if (grey.blur_sigma_px < 0.0 || grey.blur_sigma_px > 50.0) throw UsageError("--blur must be 0..50");
  if (grey.noise_sigma < 0.0 || grey.noise_sigma > 255.0) throw UsageError("--noise must be 0..255");
  const bool binary = !args.has("grey") && !args.has("blur") && !args.has("noise");

  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) throw InputError("cannot create folder \"" + dir.string() + "\"");
  // library.csv is written whole after the images, atomically: a run that fails or is
  // killed part-way leaves the previous library.csv as it was, never a truncated one.
  const std::filesystem::path csvPath = dir / "library.csv";
  std::string csv = "file,shape,number,length_px,rotation_deg,aspect,centre_u,centre_v,semi_major_px,semi_minor_px\n";

  cv::Mat image;
  for (const LibraryEntry& e : syntheticLibrary()) {
    if (binary) renderLibraryImage(e, image);
    else renderLibraryImageGrey(e, grey, image);
    const std::string name = libraryFileName(e);
    bool written = false;
    try {
      written = cv::imwrite((dir / name).string(), image);
    } catch (const cv::Exception&) {
      written = false;
    }
    if (!written) throw InputError("cannot write \"" + (dir / name).string() + "\"");
    const Ellipse shape = e.ellipse(image.size());
    char row[256];
    std::snprintf(row, sizeof row, "%s,%s,%d,%g,%g,%g,%g,%g,%g,%g\n", name.c_str(),
                  e.shape == LibraryShape::Rectangle ? "rectangle" : "ellipse", e.number, e.length_px,
                  e.rotation_deg, e.aspect, shape.cx, shape.cy, shape.a, shape.b);
    csv += row;
  }
  std::string error;
  if (!writeFileAtomically(csvPath.string(), csv, error)) throw InputError(error);
  std::fprintf(stderr, "wrote %zu images and library.csv to %s\n", syntheticLibrary().size(), dir.string().c_str());
  return 0;
}

const CommandRegistration kRegistration{{
    "library",
    "write the synthetic image library of appendix B (67 rectangles, 70 ellipses)",
    "usage: imagepro-cli library [--grey] [--blur S] [--noise S] [--seed N] OUTDIR\n\n"
    "Writes the images of thesis tables B.1 (rectangle_01.png ... rectangle_67.png)\n"
    "and B.2 (ellipse_01.png ... ellipse_70.png): 640x480, one white shape centred at\n"
    "(319.5, 239.5) on black, and library.csv with each image's parameters: the\n"
    "table's length (rectangle width or ellipse major length, pixels), rotation (long\n"
    "axis from +u towards +v, degrees) and aspect ratio, and the shape's centre and\n"
    "semi-axes (half sides of a rectangle) in pixels. library.csv is written last and\n"
    "atomically: an earlier one stays whole until the new one replaces it.\n"
    "By default the images are binary (0/255, a pixel is white when its centre is\n"
    "inside the shape), exactly as in the thesis. For robustness measurements:\n"
    "  --grey       anti-aliased grey (8x8 samples per pixel), black 20, white 230\n"
    "  --blur S     grey, then a Gaussian blur of S pixels\n"
    "  --noise S    grey, then Gaussian noise of S grey levels (seed --seed N, default 1)",
    {"grey"},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
