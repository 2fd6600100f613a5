#include "slam/engine/record_io.h"

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

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
  CandidateAttempt rejected;
  rejected.node = 5;
  rejected.session = 0;
  rejected.source = LinkType::kProximity;
  rejected.status = RegistrationStatus::kTooFewInliers;
  rejected.matches = 30;
  rejected.inliers = 12;
  CandidateAttempt accepted;
  accepted.node = 7;
  accepted.session = 1;
  accepted.status = RegistrationStatus::kAccepted;
  accepted.inliers = 42;
  accepted.truth_distance_m = 0.2;
  accepted.truth_angle_deg = 3.0;
  b.attempts = {rejected, accepted};
  b.lcd_hypothesis = 7;
  b.lcd_top = {{7, 0.6, 2.0f, 1.5f}};
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
  ASSERT_EQ(second["attempts"].size(), 2u);
  EXPECT_EQ(second["attempts"][0]["node"], 5);
  EXPECT_EQ(second["attempts"][0]["source"], "proximity");
  EXPECT_EQ(second["attempts"][0]["status"], "too_few_inliers");
  EXPECT_TRUE(second["attempts"][0]["truth_distance_m"].is_null());
  EXPECT_DOUBLE_EQ(second["attempts"][1]["truth_distance_m"].get<double>(), 0.2);
  EXPECT_EQ(second["lcd_hypothesis"], 7);
  EXPECT_EQ(second["lcd_top"][0]["node"], 7);
  EXPECT_TRUE(first["lcd_hypothesis"].is_null());
  EXPECT_TRUE(first["attempts"].empty());
}

// Splits a CSV line honouring RFC 4180 quotes.
std::vector<std::string> SplitCsvLine(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
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
  const std::vector<std::string> columns = SplitCsvLine(header);
  EXPECT_EQ(SplitCsvLine(row1).size(), columns.size());
  const std::vector<std::string> second = SplitCsvLine(row2);
  ASSERT_EQ(second.size(), columns.size());
  // The attempts list is JSON with commas: quoted, and it parses back.
  const auto at = std::find(columns.begin(), columns.end(), "attempts");
  ASSERT_NE(at, columns.end());
  const std::string attempts = second[static_cast<size_t>(at - columns.begin())];
  EXPECT_NE(attempts.find("too_few_inliers"), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(attempts.substr(0, attempts.find("} {") + 1))["node"], 5);
}

}  // namespace
}  // namespace duskmap
