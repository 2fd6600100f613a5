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
  rejected.search_distance_m = 0.4;
  CandidateAttempt accepted;
  accepted.node = 7;
  accepted.session = 1;
  accepted.status = RegistrationStatus::kAccepted;
  accepted.inliers = 42;
  accepted.truth_distance_m = 0.2;
  accepted.truth_angle_deg = 3.0;
  accepted.estimate_distance_m = 0.25;
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
  EXPECT_DOUBLE_EQ(second["attempts"][0]["search_distance_m"].get<double>(), 0.4);
  EXPECT_TRUE(second["attempts"][0]["estimate_distance_m"].is_null());
  EXPECT_DOUBLE_EQ(second["attempts"][1]["estimate_distance_m"].get<double>(), 0.25);
  EXPECT_TRUE(second["attempts"][1]["search_distance_m"].is_null());
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

// Every branch of both record writers: nulls and values, a check, a cache
// validation, an optimisation or none.
std::string AllRecordsAsText() {
  std::vector<LocalizationRecord> records = TwoRecords();
  LocalizationRecord c = records[1];
  c.frame_index = 2;
  c.timestamp_s = 12.25;
  c.outcome = LocalizationOutcome::kOdometryCacheRejected;
  c.lcd_status = LcdStatus::kAccepted;
  c.lcd_score = 0.875;
  c.matched_by = LinkType::kProximity;
  c.cache_validation = CacheValidation::kRejected;
  c.cache_max_error_ratio = 4.5;
  c.num_features = 480;
  c.proximity_candidates = 2;
  c.candidates_tried = 2;
  c.distance_since_last_m = 1.5;
  c.timings = {9.5, 3.25, 0.125, 4.0, 17.0};
  c.check = RelocalizationCheck();
  c.check->correct = true;
  c.check->error.translation_m = 0.03125;
  c.check->error.rotation_deg = 1.5;
  c.map_from_camera = Rigid3d(Eigen::Quaterniond(0.5, 0.5, -0.5, 0.5), {-1.5, 0.25, 2});
  records.push_back(c);
  std::vector<nlohmann::json> localization;
  for (const auto& r : records) localization.push_back(LocalizationRecordToJson(r));
  MappingFrameResult first;
  first.node = 1;
  first.session = 0;
  first.num_features = 500;
  first.timings = {10.5, 2.0, 0.0, 0.0, 0.0, 0.0, 12.5};
  MappingFrameResult second;
  second.node = 2;
  second.session = 1;
  second.num_features = 450;
  second.lcd_status = LcdStatus::kAccepted;
  second.lcd_hypothesis = 1;
  second.registrations = 3;
  second.loop_closures_added = 1;
  second.proximity_links_added = 2;
  second.optimized = true;
  second.optimization_status = OptimizationStatus::kRejectedMaxError;
  second.links_rejected = 1;
  second.nodes_reduced = 4;
  second.timings = {11.0, 2.5, 0.5, 6.0, 20.0, 1.0, 41.0};
  std::vector<nlohmann::json> mapping = {MappingResultToJson(first), MappingResultToJson(second)};
  std::ostringstream out;
  WriteJsonLines(out, localization);
  WriteCsv(out, localization);
  WriteJsonLines(out, mapping);
  WriteCsv(out, mapping);
  return out.str();
}

// The records as duskmap wrote them before their fields went through codecs
// (issue 20), byte for byte: keys, values, nulls and column order.
TEST(RecordIo, RecordsAreWrittenByteForByteAsBefore) {
  const char kExpected[] = R"golden({"attempts":[],"cache_validation":null,"candidates_tried":0,"correct":null,"distance_since_last_m":0.0,"error_deg":null,"error_m":null,"features":0,"frame":0,"inliers":0,"jump_mm":null,"lcd_hypothesis":null,"lcd_score":0.0,"lcd_status":"no_candidates","lcd_top":[],"matched_by":null,"matched_node":null,"matched_session":null,"outcome":"no_candidate","pose":null,"proximity_candidates":0,"registration_status":null,"relocalized":false,"timestamp_s":10.0,"timings_ms":{"features":0.0,"lcd":0.0,"proximity":0.0,"registration":0.0,"total":0.0}}
{"attempts":[{"estimate_distance_m":null,"inliers":12,"matches":30,"node":5,"search_distance_m":0.4,"session":0,"source":"proximity","status":"too_few_inliers","truth_angle_deg":null,"truth_distance_m":null},{"estimate_distance_m":0.25,"inliers":42,"matches":0,"node":7,"search_distance_m":null,"session":1,"source":"loop_closure","status":"accepted","truth_angle_deg":3.0,"truth_distance_m":0.2}],"cache_validation":null,"candidates_tried":0,"correct":null,"distance_since_last_m":0.0,"error_deg":null,"error_m":null,"features":0,"frame":1,"inliers":42,"jump_mm":12.5,"lcd_hypothesis":7,"lcd_score":0.0,"lcd_status":"no_candidates","lcd_top":[{"likelihood":1.5,"node":7,"posterior":0.6}],"matched_by":"loop_closure","matched_node":7,"matched_session":1,"outcome":"relocalized","pose":{"q_xyzw":[0.0,0.0,0.0,1.0],"t":[1.0,2.0,3.0]},"proximity_candidates":0,"registration_status":"accepted","relocalized":true,"timestamp_s":11.0,"timings_ms":{"features":0.0,"lcd":0.0,"proximity":0.0,"registration":0.0,"total":0.0}}
{"attempts":[{"estimate_distance_m":null,"inliers":12,"matches":30,"node":5,"search_distance_m":0.4,"session":0,"source":"proximity","status":"too_few_inliers","truth_angle_deg":null,"truth_distance_m":null},{"estimate_distance_m":0.25,"inliers":42,"matches":0,"node":7,"search_distance_m":null,"session":1,"source":"loop_closure","status":"accepted","truth_angle_deg":3.0,"truth_distance_m":0.2}],"cache_validation":"rejected","candidates_tried":2,"correct":true,"distance_since_last_m":1.5,"error_deg":1.5,"error_m":0.03125,"features":480,"frame":2,"inliers":42,"jump_mm":12.5,"lcd_hypothesis":7,"lcd_score":0.875,"lcd_status":"accepted","lcd_top":[{"likelihood":1.5,"node":7,"posterior":0.6}],"matched_by":"proximity","matched_node":7,"matched_session":1,"outcome":"odometry_cache_rejected","pose":{"q_xyzw":[0.5,-0.5,0.5,0.5],"t":[-1.5,0.25,2.0]},"proximity_candidates":2,"registration_status":"accepted","relocalized":true,"timestamp_s":12.25,"timings_ms":{"features":9.5,"lcd":3.25,"proximity":0.125,"registration":4.0,"total":17.0}}
attempts,cache_validation,candidates_tried,correct,distance_since_last_m,error_deg,error_m,features,frame,inliers,jump_mm,lcd_hypothesis,lcd_score,lcd_status,lcd_top,matched_by,matched_node,matched_session,outcome,pose,proximity_candidates,registration_status,relocalized,timestamp_s,timings_ms.features,timings_ms.lcd,timings_ms.proximity,timings_ms.registration,timings_ms.total,pose.q_xyzw,pose.t
,,0,,0.0,,,0,0,0,,,0.0,no_candidates,,,,,no_candidate,,0,,false,10.0,0.0,0.0,0.0,0.0,0.0,,
"{""estimate_distance_m"":null,""inliers"":12,""matches"":30,""node"":5,""search_distance_m"":0.4,""session"":0,""source"":""proximity"",""status"":""too_few_inliers"",""truth_angle_deg"":null,""truth_distance_m"":null} {""estimate_distance_m"":0.25,""inliers"":42,""matches"":0,""node"":7,""search_distance_m"":null,""session"":1,""source"":""loop_closure"",""status"":""accepted"",""truth_angle_deg"":3.0,""truth_distance_m"":0.2}",,0,,0.0,,,0,1,42,12.5,7,0.0,no_candidates,"{""likelihood"":1.5,""node"":7,""posterior"":0.6}",loop_closure,7,1,relocalized,,0,accepted,true,11.0,0.0,0.0,0.0,0.0,0.0,0.0 0.0 0.0 1.0,1.0 2.0 3.0
"{""estimate_distance_m"":null,""inliers"":12,""matches"":30,""node"":5,""search_distance_m"":0.4,""session"":0,""source"":""proximity"",""status"":""too_few_inliers"",""truth_angle_deg"":null,""truth_distance_m"":null} {""estimate_distance_m"":0.25,""inliers"":42,""matches"":0,""node"":7,""search_distance_m"":null,""session"":1,""source"":""loop_closure"",""status"":""accepted"",""truth_angle_deg"":3.0,""truth_distance_m"":0.2}",rejected,2,true,1.5,1.5,0.03125,480,2,42,12.5,7,0.875,accepted,"{""likelihood"":1.5,""node"":7,""posterior"":0.6}",proximity,7,1,odometry_cache_rejected,,2,accepted,true,12.25,9.5,3.25,0.125,4.0,17.0,0.5 -0.5 0.5 0.5,-1.5 0.25 2.0
{"features":500,"lcd_hypothesis":0,"lcd_status":"no_candidates","links_rejected":0,"loop_closures_added":0,"node":1,"nodes_reduced":0,"optimization":"none","proximity_links_added":0,"registrations":0,"session":0,"timings_ms":{"features":10.5,"lcd":2.0,"optimization":0.0,"proximity":0.0,"reduction":0.0,"registration":0.0,"total":12.5}}
{"features":450,"lcd_hypothesis":1,"lcd_status":"accepted","links_rejected":1,"loop_closures_added":1,"node":2,"nodes_reduced":4,"optimization":"rejected_max_error","proximity_links_added":2,"registrations":3,"session":1,"timings_ms":{"features":11.0,"lcd":2.5,"optimization":20.0,"proximity":0.5,"reduction":1.0,"registration":6.0,"total":41.0}}
features,lcd_hypothesis,lcd_status,links_rejected,loop_closures_added,node,nodes_reduced,optimization,proximity_links_added,registrations,session,timings_ms.features,timings_ms.lcd,timings_ms.optimization,timings_ms.proximity,timings_ms.reduction,timings_ms.registration,timings_ms.total
500,0,no_candidates,0,0,1,0,none,0,0,0,10.5,2.0,0.0,0.0,0.0,0.0,12.5
450,1,accepted,1,1,2,4,rejected_max_error,2,3,1,11.0,2.5,20.0,0.5,1.0,6.0,41.0
)golden";
  EXPECT_EQ(AllRecordsAsText(), kExpected);
}

}  // namespace
}  // namespace duskmap
