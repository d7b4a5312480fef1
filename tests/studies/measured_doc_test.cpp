// The measured places of a study's doc: values replace only their places, blocks stand between
// blank lines, and a doc that disagrees with its study is refused with the place named.
#include "studies/measured_doc.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/common/atomic_file.h"
#include "support/test_dirs.h"

namespace imagepro::studies {
namespace {

TEST(MeasuredDoc, InlineValuesReplaceOnlyTheirPlaces) {
  std::string doc = "Status <!--m:status-->old<!--/m--> after <!--m:n-->3<!--/m--> steps; <!--m:n-->9<!--/m--> again.\n";
  std::string error;
  ASSERT_TRUE(fillMeasuredPlaces(doc, {{"status", "Ok"}, {"n", "4"}}, {}, error)) << error;
  EXPECT_EQ(doc, "Status <!--m:status-->Ok<!--/m--> after <!--m:n-->4<!--/m--> steps; <!--m:n-->4<!--/m--> again.\n");
  // Filling again gives the same doc: the places survive their values.
  const std::string once = doc;
  ASSERT_TRUE(fillMeasuredPlaces(doc, {{"status", "Ok"}, {"n", "4"}}, {}, error)) << error;
  EXPECT_EQ(doc, once);
}

TEST(MeasuredDoc, ABlockStandsBetweenBlankLines) {
  std::string doc = "Before.\n<!--m:table-->\n| old |\n<!--/m-->\nAfter.\n";
  std::string error;
  ASSERT_TRUE(fillMeasuredPlaces(doc, {{"table", "| a |\n| --- |\n| 1 |\n"}}, {}, error)) << error;
  EXPECT_EQ(doc, "Before.\n<!--m:table-->\n\n| a |\n| --- |\n| 1 |\n\n<!--/m-->\nAfter.\n");
  // An empty value leaves the markers alone on their lines.
  ASSERT_TRUE(fillMeasuredPlaces(doc, {{"table", ""}}, {}, error)) << error;
  EXPECT_EQ(doc, "Before.\n<!--m:table-->\n<!--/m-->\nAfter.\n");
}

TEST(MeasuredDoc, PlacesOfPartsNotRunKeepTheirText) {
  std::string doc = "Rotation <!--m:virtual.rot-->0.1<!--/m--> and <!--m:real.rot-->0.2<!--/m-->\n";
  std::string error;
  ASSERT_TRUE(fillMeasuredPlaces(doc, {{"virtual.rot", "0.05"}}, {"virtual."}, error)) << error;
  EXPECT_EQ(doc, "Rotation <!--m:virtual.rot-->0.05<!--/m--> and <!--m:real.rot-->0.2<!--/m-->\n");
  // The part that ran must fill every place of its own.
  std::string same = doc;
  EXPECT_FALSE(fillMeasuredPlaces(same, {}, {"real."}, error));
  EXPECT_NE(error.find("no value for 'real.rot'"), std::string::npos) << error;
  EXPECT_EQ(same, doc);
}

TEST(MeasuredDoc, ADocThatDisagreesWithItsStudyIsRefusedNamingThePlace) {
  std::string error;
  std::string noPlace = "No places here.\n";
  EXPECT_FALSE(fillMeasuredPlaces(noPlace, {{"median", "0.1"}}, {}, error));
  EXPECT_NE(error.find("'median'"), std::string::npos) << error;
  std::string unterminated = "a\n<!--m:median-->0.1 and <!--m:p95-->0.2<!--/m-->\n";
  EXPECT_FALSE(fillMeasuredPlaces(unterminated, {{"median", "0.1"}, {"p95", "1"}}, {}, error));
  EXPECT_NE(error.find("line 2"), std::string::npos) << error;
  EXPECT_NE(error.find("'median'"), std::string::npos) << error;
  std::string badName = "A <!--m:two words-->x<!--/m-->";
  EXPECT_FALSE(fillMeasuredPlaces(badName, {}, {}, error));
  EXPECT_NE(error.find("valid name"), std::string::npos) << error;
  std::string startsALine = "Prose\n<!--m:median-->0.1<!--/m--> deg.\n";
  EXPECT_FALSE(fillMeasuredPlaces(startsALine, {{"median", "0.2"}}, {}, error));
  EXPECT_NE(error.find("begins its line"), std::string::npos) << error;
  std::string tableInline = "See <!--m:table-->here<!--/m-->.\n";
  EXPECT_FALSE(fillMeasuredPlaces(tableInline, {{"table", "| a |\n| 1 |"}}, {}, error));
  EXPECT_NE(error.find("inline"), std::string::npos) << error;
  EXPECT_EQ(tableInline, "See <!--m:table-->here<!--/m-->.\n");
}

TEST(MeasuredDoc, AFailedFillLeavesTheFileAsItWas) {
  const std::filesystem::path dir = test::freshDir("measured_doc");
  const std::string path = (dir / "report.md").string();
  std::string error;
  const std::string before = "Median <!--m:median-->0.1<!--/m-->.\n";
  ASSERT_TRUE(writeFileAtomically(path, before, error)) << error;
  EXPECT_FALSE(fillMeasuredDoc(path, path, {{"median", "0.2"}, {"stray", "1"}}, {}, error));
  EXPECT_NE(error.find(path), std::string::npos) << error;
  std::string after;
  ASSERT_TRUE(readWholeFile(path, after, error)) << error;
  EXPECT_EQ(after, before);
  ASSERT_TRUE(fillMeasuredDoc(path, path, {{"median", "0.2"}}, {}, error)) << error;
  ASSERT_TRUE(readWholeFile(path, after, error)) << error;
  EXPECT_EQ(after, "Median <!--m:median-->0.2<!--/m-->.\n");
  EXPECT_FALSE(fillMeasuredDoc((dir / "missing.md").string(), path, {}, {}, error));
  EXPECT_NE(error.find("missing.md"), std::string::npos) << error;
  EXPECT_NE(error.find("--template"), std::string::npos) << error;
}

}  // namespace
}  // namespace imagepro::studies
