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

TEST_F(LocalizerTest, AMapOfAnotherFeatureTypeIsRefused) {
  EngineOptions options = PaperOptions();
  options.features.type = "orb";
  const std::string error = testing::ErrorOf([&] { Localizer localizer(*map_, options); });
  EXPECT_NE(error.find("the map was built with feature type 'surf'"), std::string::npos) << error;
}

}  // namespace
}  // namespace duskmap
