// The frame record: every output's columns come from one table, and the outputs agree.
#include "core/pipeline/frame_record.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <set>

#include "core/pipeline/data_out.h"
#include "core/pipeline/pose_stream.h"

namespace imagepro {
namespace {

FrameResult tracked() {
  FrameResult r;
  r.index = 12;
  r.timestamp_s = 0.48;
  r.status = Status::Ok;
  r.reached = ApplicationLevel::Reconstruction;
  r.pose = Pose{1.5, -2.25, 30.125, 10.0, -20.5, 812.75};
  r.truth = Pose{1.5, -2.0, 30.0, 10.0, -20.0, 812.0};
  r.search_region = {10, 20, 300, 200};
  r.detected_region = {40, 50, 100, 90};
  r.rim_seen = 0.8125;
  r.spot_error_px = 0.2504;
  r.rim_error_px = 0.0626;
  r.lens_inverse = LensInverse::ExactWideLens;
  for (std::size_t s = 0; s < kStageCount; ++s) r.times.us[s] = 10.25 * static_cast<double>(s + 1);
  r.target_id = 2;
  return r;
}

// The poses in the chosen frames and the pair's readout (settings "frames"), added last.
constexpr const char* kFramed =
    ",world_Rx_deg,world_Ry_deg,world_Rz_deg,world_Tx_mm,world_Ty_mm,world_Tz_mm,ref_Rx_deg,ref_Ry_deg,ref_Rz_deg,"
    "ref_Tx_mm,ref_Ty_mm,ref_Tz_mm,pair_distance_mm,pair_angle_deg";
constexpr const char* kNoFrames = ",,,,,,,,,,,,,,";

// The CSVs' columns are a contract with users' scripts: these are the columns of the
// versions before, to the character, with the fields added since at the end (`target`,
// then, in data out, the frames').
TEST(FrameRecord, TheCsvColumnsAreTheContractsOnes) {
  EXPECT_EQ(recordCsvHeader(kReconstructCsv),
            "frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm,rim_seen,target");
  EXPECT_EQ(recordCsvHeader(kReconstructCsv | kTruthCsv),
            "frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm,true_Rx_deg,true_Ry_deg,true_Rz_deg,true_Tx_mm,"
            "true_Ty_mm,true_Tz_mm,rim_seen,target");
  EXPECT_EQ(DataOut::header(),
            "frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm,timestamp_s,search_x,search_y,search_w,search_h,"
            "target_x,target_y,target_w,target_h,grab_us,crop_us,threshold_us,edges_us,connectivity_us,ellipse_us,"
            "reconstruction_us,tracking_us,rim_seen,target" + std::string(kFramed));
}

TEST(FrameRecord, RowsHaveACellForEveryColumn) {
  const FrameResult r = tracked();
  EXPECT_EQ(recordCsvRow(r, kReconstructCsv | kTruthCsv),
            "12,ok,1.500000,-2.250000,30.125000,10.000000,-20.500000,812.750000,1.500000,-2.000000,30.000000,"
            "10.000000,-20.000000,812.000000,0.812,2");
  EXPECT_EQ(DataOut::row(r),
            "12,ok,1.500000,-2.250000,30.125000,10.000000,-20.500000,812.750000,0.480000,10,20,300,200,40,50,100,90,"
            "10.2,20.5,30.8,41.0,51.2,61.5,71.8,82.0,0.812,2" + std::string(kNoFrames));
  FrameResult miss;
  miss.index = 3;
  miss.name = "a,b.png";  // quoted: it holds a comma
  miss.status = Status::NoTarget;
  EXPECT_EQ(recordCsvRow(miss, kReconstructCsv), "\"a,b.png\",NoTarget,,,,,,,,");
  const std::string header = recordCsvHeader(kDataOutCsv);
  const std::string row = DataOut::row(miss);
  EXPECT_EQ(std::count(row.begin(), row.end(), ','), std::count(header.begin(), header.end(), ',') + 1);  // the name's comma
}

// The stream and reconstruct's JSON carry the same digits as the CSV; a field without a
// value is null in the stream and left out of reconstruct's JSON.
TEST(FrameRecord, JsonOutputsAgreeWithTheCsv) {
  const FrameResult r = tracked();
  const auto stream = nlohmann::json::parse(poseStreamJson(r));
  EXPECT_EQ(stream["frame"], 12);
  EXPECT_EQ(stream["status"], "ok");
  EXPECT_DOUBLE_EQ(stream["Tz_mm"].get<double>(), 812.75);
  EXPECT_DOUBLE_EQ(stream["timestamp_s"].get<double>(), 0.48);
  EXPECT_DOUBLE_EQ(stream["rim_seen"].get<double>(), 0.812);
  EXPECT_TRUE(stream["name"].is_null());
  const auto members = nlohmann::json::parse("{" + recordJsonMembers(r, kReconstructJson) + "}");
  EXPECT_EQ(members["frame"], "12");
  EXPECT_EQ(members["lens_inverse"], "exact-wide-lens");
  EXPECT_DOUBLE_EQ(members["rim_seen"].get<double>(), 0.812);
  // The self-check's measures: reconstruct's JSON only, the CSVs keep their columns.
  EXPECT_DOUBLE_EQ(members["spot_error_px"].get<double>(), 0.250);
  EXPECT_DOUBLE_EQ(members["rim_error_px"].get<double>(), 0.063);
  EXPECT_FALSE(stream.contains("rim_error_px"));

  FrameResult miss;
  miss.index = 4;
  miss.status = Status::NoTarget;
  const auto missed = nlohmann::json::parse(poseStreamJson(miss));
  EXPECT_TRUE(missed["Rx_deg"].is_null());
  EXPECT_TRUE(missed["rim_seen"].is_null());
  const auto left = nlohmann::json::parse("{" + recordJsonMembers(miss, kReconstructJson) + "}");
  EXPECT_FALSE(left.contains("Rx_deg"));
  EXPECT_FALSE(left.contains("rim_seen"));
  EXPECT_FALSE(left.contains("spot_error_px"));
  EXPECT_FALSE(left.contains("rim_error_px"));
  EXPECT_FALSE(left.contains("lens_inverse"));  // the reconstruction stage did not run
}

TEST(FrameRecord, EveryFieldIsDescribedAndCarried) {
  std::set<std::pair<std::string_view, std::uint16_t>> seen;
  for (const FrameField& f : frameFields()) {
    EXPECT_FALSE(f.name.empty());
    EXPECT_FALSE(f.description.empty()) << f.name;
    EXPECT_NE(f.outputs, 0) << f.name;
    EXPECT_NE(f.value, nullptr) << f.name;
    EXPECT_EQ(!f.label.empty(), (f.outputs & kResultsText) != 0) << f.name;  // a text line needs a label
    for (std::uint16_t bit = 1; bit <= kResultsText; bit <<= 1) {
      if (f.outputs & bit) {
        EXPECT_TRUE(seen.insert({f.name, bit}).second) << f.name << " twice in one output";
      }
    }
  }
}

}  // namespace
}  // namespace imagepro
