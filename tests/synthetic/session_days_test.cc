// Sessions on successive days (SessionSpec::day, issue 46 item 3): the
// "day" key, the sun's path of the session's date, the timestamps a day
// apart, and configs/lifelong_apartment.json.
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "slam/core/check.h"
#include "slam/core/json_codec.h"
#include "slam/io/synthetic_dataset.h"
#include "slam/synthetic/generator.h"
#include "slam/synthetic/generator_config.h"
#include "slam/synthetic/generator_config_json.h"
#include "slam/synthetic/session_simulator.h"
#include "tests/synthetic/small_config.h"
#include "tests/synthetic/generator_config_files.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

using testing::GeneratorConfigError;
using testing::WriteGeneratorConfig;

std::string OneSession(const std::string& day) {
  return R"({"sessions": [{"name": "b5", "clock_time": "18:56", "day": )" + day + "}]}";
}

TEST(SessionDays, TheDayKeyIsReadAndValidatedNamingIt) {
  EXPECT_EQ(ReadGeneratorConfig(WriteGeneratorConfig("day3", OneSession("3"))).sessions.at(0).day, 3);
  EXPECT_EQ(ReadGeneratorConfig(WriteGeneratorConfig("day365", OneSession("365"))).sessions.at(0).day, 365);
  for (const std::string& bad : {"-1", "366"}) {
    const std::string path = WriteGeneratorConfig("bad" + bad, OneSession(bad));
    const std::string error = GeneratorConfigError(path);
    EXPECT_NE(error.find("sessions.b5.day must be in [0, 365], got " + bad), std::string::npos) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
  const std::string text = GeneratorConfigError(WriteGeneratorConfig("text", OneSession("\"monday\"")));
  EXPECT_NE(text.find("sessions[0].day"), std::string::npos) << text;
}

// A config that sets no day is the config it was: every session on
// lighting.day_of_year itself, with the same light and timestamps.
TEST(SessionDays, ASessionWithoutADayIsOnTheConfigsDate) {
  const GeneratorConfig only = ReadGeneratorConfig(WriteGeneratorConfig("none", R"({"max_frames": 3})"));
  for (const SessionSpec& s : only.sessions) EXPECT_EQ(s.day, 0) << s.name;
  for (const SessionSpec& s : GeneratorConfig::DefaultSessions()) EXPECT_EQ(s.day, 0) << s.name;
  EXPECT_EQ(ToJsonObject(LightingOnDay(only.lighting, 0)), ToJsonObject(only.lighting));
  const SessionSpec five{"5", "18:56", "mapping"};
  EXPECT_EQ(SessionStartTimestamp(five), (18 * 60 + 56) * 60.0);
}

TEST(SessionDays, DayOfYearAfterWrapsIntoTheNextYear) {
  EXPECT_EQ(DayOfYearAfter(87, 0), 87);
  EXPECT_EQ(DayOfYearAfter(87, 7), 94);
  EXPECT_EQ(DayOfYearAfter(360, 5), 365);
  EXPECT_EQ(DayOfYearAfter(360, 10), 5);
  EXPECT_EQ(DayOfYearAfter(365, 1), 1);
  EXPECT_EQ(DayOfYearAfter(366, 0), 366);  // a leap year's last day stays itself
  EXPECT_EQ(DayOfYearAfter(366, 1), 1);
  EXPECT_EQ(DayOfYearAfter(87, 365), 87);
  EXPECT_EQ(LightingOnDay(LightingOptions(), 7).site.day_of_year, 94);
}

// Late March the sun sets about 1.3 minutes later each day at Sherbrooke:
// at the paper's 18:56 it stands higher on each later day (1.5 degrees on
// day 0, 3.1 on day 7), further north of west.
TEST(SessionDays, ALaterDayAtTheSameClockTimeHasTheSunOfItsDate) {
  const SolarSite site;  // day 87, 28 March
  const double at = 18.0 + 56.0 / 60.0;
  double previous_elevation = -90.0, previous_azimuth = 0.0;
  for (int day = 0; day <= 11; ++day) {
    const SunPosition sun = ComputeSunPosition(LightingOnDay(LightingOptions(), day).site, at);
    EXPECT_GT(sun.elevation_deg, previous_elevation + 0.1) << "day " << day;
    EXPECT_GT(sun.azimuth_deg, previous_azimuth) << "day " << day;  // further north of west (270)
    previous_elevation = sun.elevation_deg;
    previous_azimuth = sun.azimuth_deg;
  }
  EXPECT_LT(ComputeSunsetTime(site), ComputeSunsetTime(LightingOnDay(LightingOptions(), 7).site));

  // The session simulator lights a day-7 session with day 94's sun, and its
  // lamps keep their clock-time schedule.
  const GeneratorConfig config = testing::SmallConfig(1);
  const Scene scene = BuildGeneratorScene(config);
  const SessionSimulator day0(config, scene, at, 1);
  const SessionSimulator day7(config, scene, at, 1, 7);
  EXPECT_EQ(day0.lighting().day_of_year, 87);
  EXPECT_EQ(day7.lighting().day_of_year, 94);
  EXPECT_EQ(day7.lighting_options().site.day_of_year, 94);
  EXPECT_EQ(day0.lighting().sun.elevation_deg, ComputeSunPosition(site, at).elevation_deg);
  EXPECT_GT(day7.lighting().sun.elevation_deg, day0.lighting().sun.elevation_deg + 1.0);
  EXPECT_NE(day7.lighting().sun.azimuth_deg, day0.lighting().sun.azimuth_deg);
  EXPECT_EQ(day7.lighting().lamp_on, day0.lighting().lamp_on);
}

TEST(SessionDays, ASessionStartsAtItsDayTimesADayPlusItsClockTime) {
  SessionSpec session{"d5", "18:56", "mapping"};
  session.day = 3;
  EXPECT_EQ(SessionStartTimestamp(session), 3 * 86400.0 + (18 * 60 + 56) * 60.0);
  session.day = 0;
  EXPECT_EQ(SessionStartTimestamp(session), (18 * 60 + 56) * 60.0);
}

nlohmann::json ReadJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// End to end: two sessions at 18:56, days 0 and 7: the later one's
// session.json has the day and its date, the later sun higher; frames are a week apart.
TEST(SessionDays, GeneratedSessionsOfTwoDaysHaveTheirDatesSunsAndTimestamps) {
  GeneratorConfig config = testing::SmallConfig(2);
  config.sessions = {{"a5", "18:56", "mapping"}, {"h5", "18:56", "mapping", 7}};
  GenerateOptions options;
  options.output_path = testing::ProcessTempDir("session_days") + "/data";
  GenerateDataset(config, options);
  const nlohmann::json a5 = ReadJson(options.output_path + "/a5/session.json");
  const nlohmann::json h5 = ReadJson(options.output_path + "/h5/session.json");
  EXPECT_FALSE(a5.contains("day"));  // a day-0 session's file is as one-day datasets write it
  EXPECT_FALSE(a5.contains("day_of_year"));
  EXPECT_EQ(h5.at("day"), 7);
  EXPECT_EQ(h5.at("day_of_year"), 94);
  EXPECT_GT(h5.at("sun_elevation_deg").get<double>(), a5.at("sun_elevation_deg").get<double>() + 1.0);
  const std::unique_ptr<DatasetReader> dataset = OpenSyntheticDataset(options.output_path);
  std::map<std::string, double> first;
  for (const std::string name : {"a5", "h5"}) {
    const std::unique_ptr<SessionReader> reader = dataset->OpenSession(name);
    const std::optional<RgbdFrame> frame = reader->Next();
    ASSERT_TRUE(frame.has_value());
    first[name] = frame->timestamp_s;
  }
  EXPECT_NEAR(first["a5"], (18 * 60 + 56) * 60.0, 1.0);
  EXPECT_NEAR(first["h5"] - first["a5"], 7 * 86400.0, 1e-3);
}

// The lifelong config: 48 mapping sessions, 8 successive days at the paper's
// 6 mapping clock times, and localization sessions held out on later days.
TEST(SessionDays, TheLifelongApartmentConfigHas48MappingSessionsOnEightDays) {
  const GeneratorConfig config =
      ReadGeneratorConfig(std::string(DUSKMAP_SOURCE_DIR) + "/configs/lifelong_apartment.json");
  std::map<int, std::vector<std::string>> mapping_times;
  std::set<int> localization_days;
  int localization = 0;
  for (const SessionSpec& s : config.sessions) {
    EXPECT_EQ(s.name.find_first_of("+-|"), std::string::npos) << s.name;  // usable in map labels
    EXPECT_EQ(s.name[0], static_cast<char>('a' + s.day)) << s.name;    // the documented scheme
    if (s.role == "mapping") {
      mapping_times[s.day].push_back(s.clock_time);
    } else {
      localization_days.insert(s.day);
      ++localization;
    }
  }
  std::vector<std::string> paper_mapping;
  for (const SessionSpec& s : GeneratorConfig::DefaultSessions()) {
    if (s.role == "mapping") paper_mapping.push_back(s.clock_time);
  }
  ASSERT_EQ(mapping_times.size(), 8u);
  for (const auto& [day, times] : mapping_times) {
    EXPECT_EQ(times, paper_mapping) << "day " << day;
    EXPECT_EQ(localization_days.count(day), 0u) << "day " << day;
  }
  EXPECT_EQ(mapping_times.begin()->first, 0);
  EXPECT_EQ(mapping_times.rbegin()->first, 7);
  EXPECT_EQ(localization, 6);
  EXPECT_EQ(localization_days, (std::set<int>{10, 11}));
}

}  // namespace
}  // namespace duskmap
