#include "slam/experiment/map_spec.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

using ::testing::ElementsAre;

TEST(ParseMapSpec, PaperNotation) {
  EXPECT_EQ(ParseMapSpec("3").kind, MapKind::kSingle);
  EXPECT_THAT(ParseMapSpec("3").sessions, ElementsAre("3"));
  const MapSpec merged = ParseMapSpec("1+3+5");
  EXPECT_EQ(merged.kind, MapKind::kMerged);
  EXPECT_THAT(merged.sessions, ElementsAre("1", "3", "5"));
  EXPECT_EQ(ParseMapSpec("1-2-3-4-5-6").kind, MapKind::kReduced);
  const MapSpec closest = ParseMapSpec("1|2|3");
  EXPECT_EQ(closest.kind, MapKind::kClosestInTime);
  EXPECT_FALSE(closest.BuildsItsOwnMap());
  EXPECT_THAT(ParseMapSpec("day+night").sessions, ElementsAre("day", "night"));
}

TEST(ParseMapSpec, RejectsMalformedLabels) {
  EXPECT_THROW(ParseMapSpec(""), ConfigError);
  EXPECT_THROW(ParseMapSpec("1+"), ConfigError);
  EXPECT_THROW(ParseMapSpec("1+2-3"), ConfigError);
  EXPECT_THROW(ParseMapSpec("1+1"), ConfigError);
}

}  // namespace
}  // namespace duskmap
