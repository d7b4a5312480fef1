#include "core/source/image_inputs.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <fstream>

#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;

void writeBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

std::vector<std::string> paths(const std::vector<ImageInput>& inputs) {
  std::vector<std::string> out;
  for (const ImageInput& i : inputs) {
    EXPECT_EQ(i.status, Status::Ok) << i.path << ": " << i.error;
    out.push_back(fs::path(i.path).filename().string());
  }
  return out;
}

// Images stay themselves, folders become their images in natural order, and a list
// file the images it names, whatever the list's name ends in (.txt, .lst, none).
TEST(ImageInputs, FoldersAndListsOfAnyNameExpand) {
  const fs::path dir = test::freshDir("source/inputs");
  fs::create_directories(dir / "seq");
  const cv::Mat img(8, 8, CV_8UC1, cv::Scalar(100));
  for (const char* name : {"f10.png", "f2.png", "f1.png"}) cv::imwrite((dir / "seq" / name).string(), img);
  cv::imwrite((dir / "single.png").string(), img);
  writeBytes(dir / "frames.txt", "seq/f2.png\nsingle.png\n");
  writeBytes(dir / "frames.lst", "# comment\nseq/f10.png\n");
  writeBytes(dir / "frames", "seq/f1.png\n");
  const auto out = expandImageInputs({(dir / "seq").string(), (dir / "single.png").string(),
                                      (dir / "frames.txt").string(), (dir / "frames.lst").string(),
                                      (dir / "frames").string()});
  EXPECT_EQ(paths(out), (std::vector<std::string>{"f1.png", "f2.png", "f10.png", "single.png", "f2.png", "single.png",
                                                  "f10.png", "f1.png"}));
  EXPECT_EQ(fs::path(out[4].path), dir / "seq" / "f2.png");  // relative to the list's folder
}

// An image's name is an image even when missing or corrupt: the reader names it in
// its own frame, the other inputs go on.
TEST(ImageInputs, MissingOrCorruptImagesAreLeftToTheReader) {
  const fs::path dir = test::freshDir("source/inputs_images");
  writeBytes(dir / "corrupt.png", "not a png");
  const auto out = expandImageInputs({(dir / "missing.png").string(), (dir / "corrupt.png").string()});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].status, Status::Ok);
  EXPECT_EQ(out[1].status, Status::Ok);
}

// A file of another name that is not text (a video, a raw dump) is neither an image
// nor a list, and says so; a missing list or folder, or one that names no image, is
// FileNotFound naming it.
TEST(ImageInputs, WhatIsNeitherIsNamed) {
  const fs::path dir = test::freshDir("source/inputs_errors");
  writeBytes(dir / "clip.mp4", std::string("\0\0\0\x18" "ftypmp42", 12));
  writeBytes(dir / "empty.txt", "# nothing listed\n");
  fs::create_directories(dir / "no_images");
  const auto out = expandImageInputs({(dir / "clip.mp4").string(), (dir / "absent.txt").string(),
                                      (dir / "absent").string(), (dir / "empty.txt").string(),
                                      (dir / "no_images").string()});
  ASSERT_EQ(out.size(), 5u);
  EXPECT_EQ(out[0].status, Status::FileUnreadable);
  EXPECT_NE(out[0].error.find("clip.mp4: neither an image file"), std::string::npos) << out[0].error;
  for (std::size_t i = 1; i < out.size(); ++i) {
    EXPECT_EQ(out[i].status, Status::FileNotFound) << out[i].path;
    EXPECT_NE(out[i].error.find(out[i].path), std::string::npos) << out[i].error;
  }
}

}  // namespace
}  // namespace imagepro
