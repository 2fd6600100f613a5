#include "slam/engine/record_io.h"

#include <sstream>

#include <gtest/gtest.h>

namespace duskmap {
namespace {

std::vector<LocalizationRecord> TwoRecords() {
  LocalizationRecord a;
  a.frame_index = 0;
  a.timestamp_s = 10.0;
  a.outcome = LocalizationOutcome::kNoCandidate;
  LocalizationRecord b;
  b.frame_index = 1;
  b.timestamp_s = 11.0;
  b.relocalized = true;
  b.outcome = LocalizationOutcome::kRelocalized;
  b.registration_status = RegistrationStatus::kAccepted;
  b.matched_node = 7;
  b.matched_session = 1;
  b.inliers = 42;
  b.jump_mm = 12.5;
  b.map_from_camera = Rigid3d(Eigen::Quaterniond::Identity(), {1, 2, 3});
  return {a, b};
}

TEST(RecordIo, JsonLinesHaveOneObjectPerFrame) {
  std::vector<nlohmann::json> rows;
  for (const auto& r : TwoRecords()) rows.push_back(LocalizationRecordToJson(r));
  std::ostringstream out;
  WriteJsonLines(out, rows);
  std::istringstream in(out.str());
  std::string line;
  std::getline(in, line);
  const auto first = nlohmann::json::parse(line);
  EXPECT_EQ(first["outcome"], "no_candidate");
  EXPECT_TRUE(first["pose"].is_null());
  std::getline(in, line);
  const auto second = nlohmann::json::parse(line);
  EXPECT_EQ(second["matched_node"], 7);
  EXPECT_EQ(second["registration_status"], "accepted");
  EXPECT_DOUBLE_EQ(second["jump_mm"].get<double>(), 12.5);
  EXPECT_DOUBLE_EQ(second["pose"]["t"][2].get<double>(), 3.0);
}

TEST(RecordIo, CsvHasUnionOfColumns) {
  std::vector<nlohmann::json> rows;
  for (const auto& r : TwoRecords()) rows.push_back(LocalizationRecordToJson(r));
  std::ostringstream out;
  WriteCsv(out, rows);
  std::istringstream in(out.str());
  std::string header, row1, row2;
  std::getline(in, header);
  std::getline(in, row1);
  std::getline(in, row2);
  EXPECT_NE(header.find("pose.t"), std::string::npos);
  EXPECT_NE(header.find("timings_ms.lcd"), std::string::npos);
  const auto count = [](const std::string& s) { return std::count(s.begin(), s.end(), ','); };
  EXPECT_EQ(count(header), count(row1));
  EXPECT_EQ(count(header), count(row2));
}

}  // namespace
}  // namespace duskmap
