// The Localizer on its own, frame by frame, against a map of the tiny
// synthetic dataset: same-light frames re-localize on a map node, refused
// transforms say why, the map is never changed, and a map of another feature
// type is refused.
#include "slam/engine/localizer.h"

#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "slam/engine/session_runs.h"
#include "slam/io/synthetic_dataset.h"
#include "slam/map/map_store.h"
#include "tests/engine/tiny_dataset.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

EngineOptions PaperOptions() {
  return ReadEngineOptionsFile(std::string(DUSKMAP_SOURCE_DIR) + "/configs/engine_paper.json");
}

class LocalizerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dataset_ = OpenSyntheticDataset(testing::TinyDatasetPath()).release();
    map_ = new Map(BuildMap(*dataset_, {"1"}, PaperOptions()).map);
  }
  static void TearDownTestSuite() {
    delete map_;
    delete dataset_;
  }
  static std::vector<LocalizationRecord> Localize(Localizer* localizer, const std::string& session) {
    std::vector<LocalizationRecord> records;
    std::unique_ptr<SessionReader> reader = dataset_->OpenSession(session);
    while (std::optional<RgbdFrame> frame = reader->Next()) records.push_back(localizer->ProcessFrame(*frame));
    return records;
  }
  static DatasetReader* dataset_;
  static Map* map_;
};

DatasetReader* LocalizerTest::dataset_ = nullptr;
Map* LocalizerTest::map_ = nullptr;

std::string FileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST_F(LocalizerTest, SameLightFramesRelocalizeOnMapNodesAndTheMapIsUntouched) {
  const std::string dir = testing::ProcessTempDir("localizer_test");
  SaveMap(*map_, dir + "/before.db");
  Localizer localizer(*map_, PaperOptions());
  EXPECT_FALSE(localizer.map_from_odom().has_value());
  const std::vector<LocalizationRecord> records = Localize(&localizer, "A");
  ASSERT_EQ(records.size(), 25u);
  int relocalized = 0;
  for (const LocalizationRecord& r : records) {
    if (!r.relocalized) continue;
    ++relocalized;
    EXPECT_EQ(r.outcome, LocalizationOutcome::kRelocalized);
    EXPECT_TRUE(map_->HasNode(r.matched_node));
    EXPECT_EQ(r.registration_status, RegistrationStatus::kAccepted);
    EXPECT_GE(r.inliers, PaperOptions().registration.min_inliers);
    ASSERT_FALSE(r.attempts.empty());
    EXPECT_EQ(r.attempts.back().status, RegistrationStatus::kAccepted);
  }
  EXPECT_GE(relocalized, 20);  // same light, ten minutes apart
  EXPECT_TRUE(localizer.map_from_odom().has_value());
  SaveMap(*map_, dir + "/after.db");
  EXPECT_EQ(FileBytes(dir + "/before.db"), FileBytes(dir + "/after.db")) << "localization changed the map";
  std::filesystem::remove_all(dir);
}

TEST_F(LocalizerTest, RefusedTransformsSayWhy) {
  EngineOptions options = PaperOptions();
  options.registration.min_inliers = 5000;  // more than a frame has features
  Localizer localizer(*map_, options);
  const std::vector<LocalizationRecord> records = Localize(&localizer, "A");
  int refused = 0;
  for (const LocalizationRecord& r : records) {
    EXPECT_FALSE(r.relocalized);
    if (r.outcome != LocalizationOutcome::kRegistrationRejected) continue;
    ++refused;
    ASSERT_TRUE(r.registration_status.has_value());
    EXPECT_NE(*r.registration_status, RegistrationStatus::kAccepted);
    ASSERT_FALSE(r.attempts.empty());
    for (const CandidateAttempt& attempt : r.attempts) {
      EXPECT_NE(attempt.status, RegistrationStatus::kAccepted);
      EXPECT_TRUE(map_->HasNode(attempt.node));
    }
  }
  EXPECT_GT(refused, 10);
  EXPECT_FALSE(localizer.map_from_odom().has_value());
}

// Loop closure detection off: only proximity proposes candidates.
EngineOptions ProximityOnly() {
  EngineOptions options = PaperOptions();
  options.loop_closure.loop_threshold = 1.0;  // 1 - P(new place) never exceeds it
  return options;
}

// The reference with -loc_null searches proximity before any re-localization,
// around the odometry pose taken as a map pose (spec §5, §9.1): session A starts
// where map 1 starts, so its first frame re-localizes by proximity alone.
TEST_F(LocalizerTest, ProximitySearchesBeforeTheFirstRelocalization) {
  EngineOptions options = ProximityOnly();
  ASSERT_TRUE(options.localization.proximity_before_relocalized);  // the paper's runs
  Localizer localizer(*map_, options);
  const std::vector<LocalizationRecord> records = Localize(&localizer, "A");
  ASSERT_FALSE(records.empty());
  EXPECT_TRUE(records[0].relocalized);
  int relocalized = 0;
  for (const LocalizationRecord& r : records) {
    EXPECT_EQ(r.lcd_hypothesis, 0u);
    for (const CandidateAttempt& attempt : r.attempts) {
      EXPECT_EQ(attempt.source, LinkType::kProximity);
      ASSERT_TRUE(attempt.search_distance_m.has_value());
      EXPECT_LE(*attempt.search_distance_m, options.proximity.path_filtering_radius_m);
    }
    if (!r.relocalized) continue;
    ++relocalized;
    EXPECT_EQ(r.matched_by, LinkType::kProximity);
  }
  EXPECT_GE(relocalized, 20);

  // Without it, nothing proposes a candidate until a loop closure, which never comes.
  options.localization.proximity_before_relocalized = false;
  Localizer waiting(*map_, options);
  for (const LocalizationRecord& r : Localize(&waiting, "A")) {
    EXPECT_FALSE(r.relocalized);
    EXPECT_TRUE(r.attempts.empty());
  }
}

// A proximity link is accepted only when the estimated translation is within
// RGBD/ProximityPathFilteringRadius (spec §5.4): with the odometry shifted
// 0.45 m from where the frames were taken, candidates near the shifted pose lie
// up to about a metre from the true one and registration says so.
TEST_F(LocalizerTest, AProximityLinkLongerThanTheFilteringRadiusIsRefused) {
  EngineOptions options = ProximityOnly();
  options.proximity.path_filtering_radius_m = 0.3;
  Localizer localizer(*map_, options);
  const Rigid3d shift(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.45, 0.0, 0.0));
  std::unique_ptr<SessionReader> reader = dataset_->OpenSession("A");
  int too_long = 0, accepted = 0;
  while (std::optional<RgbdFrame> frame = reader->Next()) {
    frame->odom_from_body = shift * frame->odom_from_body;
    const LocalizationRecord r = localizer.ProcessFrame(*frame);
    for (const CandidateAttempt& attempt : r.attempts) {
      if (attempt.status == RegistrationStatus::kTranslationTooLong) {
        ++too_long;
        ASSERT_TRUE(attempt.estimate_distance_m.has_value());
        EXPECT_GT(*attempt.estimate_distance_m, 0.3);
      } else if (attempt.status == RegistrationStatus::kAccepted) {
        ++accepted;
        ASSERT_TRUE(attempt.estimate_distance_m.has_value());
        EXPECT_LE(*attempt.estimate_distance_m, 0.3);
      }
    }
    if (r.relocalized) EXPECT_EQ(r.registration_status, RegistrationStatus::kAccepted);
  }
  EXPECT_GE(too_long, 1);
  EXPECT_GE(accepted, 1);
}

TEST_F(LocalizerTest, AMapOfAnotherFeatureTypeIsRefused) {
  EngineOptions options = PaperOptions();
  options.features.type = "orb";
  const std::string error = testing::ErrorOf([&] { Localizer localizer(*map_, options); });
  EXPECT_NE(error.find("the map was built with feature type 'surf'"), std::string::npos) << error;
}

}  // namespace
}  // namespace duskmap
