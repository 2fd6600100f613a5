#include "slam/engine/localization_record_json.h"

#include <gtest/gtest.h>

#include <iterator>

#include "slam/engine/mapper_json.h"

namespace duskmap {
namespace {

// The records name each value through JsonEnumNames; the rest of duskmap
// through the enum's name function: both must spell every value alike.
template <typename E, typename NameFunction>
void ExpectNamedAlike(NameFunction name_of, size_t values) {
  EXPECT_EQ(std::size(JsonEnumNames<E>::kNames), values);
  for (const auto& [value, name] : JsonEnumNames<E>::kNames) {
    EXPECT_STREQ(name, name_of(value));
    EXPECT_EQ(ParseJsonEnum<E>(name, "x"), value);
  }
}

TEST(LocalizationRecordJson, EnumsAreNamedAsTheirNameFunctionsNameThem) {
  ExpectNamedAlike<LocalizationOutcome>(LocalizationOutcomeName, 6);
  ExpectNamedAlike<LcdStatus>(LcdStatusName, 6);
  ExpectNamedAlike<RegistrationStatus>(RegistrationStatusName, 12);
  ExpectNamedAlike<CacheValidation>(CacheValidationName, 3);
  ExpectNamedAlike<LinkType>(LinkTypeName, 5);
}

TEST(LocalizationRecordJson, AttemptsWriteUnknownTruthAsNullAndReadBack) {
  CandidateAttempt a;
  a.node = 5;
  a.session = 1;
  a.source = LinkType::kProximity;
  a.status = RegistrationStatus::kTooFewInliers;
  a.matches = 30;
  a.inliers = 12;
  a.truth_angle_deg = 2.5;
  a.search_distance_m = 0.5;
  const nlohmann::json json = ToJsonObject(a);
  EXPECT_EQ(json.dump(),
            R"({"estimate_distance_m":null,"inliers":12,"matches":30,"node":5,)"
            R"("search_distance_m":0.5,"session":1,"source":"proximity",)"
            R"("status":"too_few_inliers","truth_angle_deg":2.5,"truth_distance_m":null})");
  const CandidateAttempt back = ReadJsonOptions<CandidateAttempt>(json, "attempt");
  EXPECT_EQ(ToJsonObject(back), json);
  EXPECT_FALSE(back.truth_distance_m.has_value());
}

TEST(LocalizationRecordJson, TimingsUseTheRecordsShortKeys) {
  EXPECT_EQ(ToJsonObject(LocalizationTimings{1, 2, 3, 4, 10}).dump(),
            R"({"features":1.0,"lcd":2.0,"proximity":3.0,"registration":4.0,"total":10.0})");
  EXPECT_EQ(ToJsonObject(MappingTimings{1, 2, 3, 4, 5, 6, 21}).dump(),
            R"({"features":1.0,"lcd":2.0,"optimization":5.0,"proximity":3.0,)"
            R"("reduction":6.0,"registration":4.0,"total":21.0})");
}

}  // namespace
}  // namespace duskmap
