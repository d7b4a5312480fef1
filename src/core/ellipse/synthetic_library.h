#pragma once
// The synthetic image library of thesis appendix B (tables B.1 and B.2): 67 binary
// images of one white rectangle and 70 of one white ellipse on black, 640x480, the
// shape centred on the image centre (319.5, 239.5). The library measures how well an
// ellipse detector accepts ellipses and rejects rectangles (thesis 2.6.1-2.6.2).
//
// Table columns: for a rectangle the width (its longer side) in pixels, the rotation
// and width / height; for an ellipse the major length (the full major axis) in pixels,
// the rotation and major / minor length. Rotations turn the long side from +u towards
// +v, the same sense as Ellipse::angle_deg. The tables list some rows twice (ellipses
// 3-4, 9-10, 61-62, 67-68); they are kept, so the numbering matches the thesis.
#include <opencv2/core.hpp>

#include <span>
#include <string>

#include "core/ellipse/ellipse.h"

namespace imagepro {

enum class LibraryShape : unsigned char { Rectangle, Ellipse };

struct LibraryEntry {
  LibraryShape shape = LibraryShape::Ellipse;
  int number = 0;             // the thesis's image number within its table
  double length_px = 0.0;     // rectangle width / ellipse major length
  double rotation_deg = 0.0;
  double aspect = 1.0;        // width / height, major / minor

  double semiMajor() const { return 0.5 * length_px; }
  double semiMinor() const { return 0.5 * length_px / aspect; }
  // The exact shape as an ellipse (for a rectangle: its inscribed ellipse), centred.
  Ellipse ellipse(cv::Size image = {640, 480}) const;
};

// Table B.1 (67 rectangles) followed by table B.2 (70 ellipses).
std::span<const LibraryEntry> syntheticLibrary();

// Binary 0/255 image of `size` with the shape centred at ((w-1)/2, (h-1)/2): a pixel is
// white when its centre lies inside the shape (boundary included).
void renderLibraryImage(const LibraryEntry& entry, cv::Mat& out, cv::Size size = {640, 480});

// Grey versions of the library for robustness measurements: the shape's area coverage of
// each pixel (supersampling x supersampling points) between black_level and white_level,
// then a Gaussian blur and additive Gaussian noise (clipped to 0..255).
struct LibraryGreyOptions {
  int supersampling = 8;
  int black_level = 20;
  int white_level = 230;
  double blur_sigma_px = 0.0;
  double noise_sigma = 0.0;  // grey levels
  unsigned seed = 1;
};
void renderLibraryImageGrey(const LibraryEntry& entry, const LibraryGreyOptions& options, cv::Mat& out,
                            cv::Size size = {640, 480});

// "rectangle_01.png" ... "ellipse_70.png".
std::string libraryFileName(const LibraryEntry& entry);

}  // namespace imagepro
