#include "slam/experiment/run_manifest.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "slam/experiment/feature_files.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

namespace fs = std::filesystem;

nlohmann::json Identity(const std::string& session_a, const std::string& shared) {
  return {{"format", "synthetic"},
          {"content", {{"shared", shared}, {"sessions", {{"1", "11"}, {"A", session_a}}}}}};
}

RunManifest Manifest(const nlohmann::json& identity, const nlohmann::json& feature_files) {
  RunManifest manifest;
  manifest.features = {"OR"};
  SetRunConfiguration({{"features", {"OR"}}}, nullptr, identity, feature_files, "1.0", &manifest);
  return manifest;
}

std::string ResumeError(const RunManifest& earlier, const RunManifest& now) {
  return testing::ErrorOf([&] { CheckResumable(earlier, now, "/results"); });
}

// A resume after a session's files, the shared files or a model/h5 file
// changed (content checksums) is refused naming what changed; the same data
// resumes.
TEST(RunManifestTest, ResumeAfterChangedDataIsRefusedNamingIt) {
  const RunManifest earlier = Manifest(Identity("aa", "ss"), {{"/m/x.h5", "01"}});
  EXPECT_EQ(ResumeError(earlier, Manifest(Identity("aa", "ss"), {{"/m/x.h5", "01"}})), "");
  const std::string session = ResumeError(earlier, Manifest(Identity("ab", "ss"), {{"/m/x.h5", "01"}}));
  EXPECT_EQ(session.rfind("/results/run.json: the files of session A (images, depth maps or metadata) "
                          "changed since the earlier run (first at dataset.content.sessions.A",
                          0),
            0u)
      << session;
  EXPECT_NE(session.find("--overwrite redoes it"), std::string::npos) << session;
  const std::string shared = ResumeError(earlier, Manifest(Identity("aa", "st"), {{"/m/x.h5", "01"}}));
  EXPECT_NE(shared.find("no one session owns (such as manifest.json) changed"), std::string::npos)
      << shared;
  const std::string file = ResumeError(earlier, Manifest(Identity("aa", "ss"), {{"/m/x.h5", "02"}}));
  EXPECT_NE(file.find("the feature file /m/x.h5 changed since the earlier run"), std::string::npos)
      << file;
  // Any other difference keeps naming the key.
  RunManifest other = Manifest(Identity("aa", "ss"), {{"/m/x.h5", "01"}});
  SetRunConfiguration({{"features", {"OR"}}, {"frame_step", 2}}, nullptr, Identity("aa", "ss"),
                      {{"/m/x.h5", "01"}}, "1.0", &other);
  EXPECT_NE(ResumeError(earlier, other).find("another configuration, first at experiment.frame_step"),
            std::string::npos);
}

// The files a run's columns read: a declared h5 column's file and an onnx
// column's model, by content (same size, other bytes: another checksum);
// built-in columns that read no file add nothing.
TEST(RunManifestTest, FeatureFileChecksumsFollowTheFilesContent) {
  const fs::path dir = testing::ProcessTempDir("feature_files");
  std::ofstream(dir / "orb.h5") << "h5 content 1";
  std::ofstream(dir / "net.onnx") << "onnx model";
  ExperimentOptions experiment;
  experiment.features = {"OR", "XO", "XN"};
  FeatureSetup h5;
  h5.label = "XO";
  h5.extractor = "h5";
  h5.matcher = "nndr";
  h5.h5.path = (dir / "orb.h5").string();
  FeatureSetup onnx;
  onnx.label = "XN";
  onnx.extractor = "onnx";
  onnx.matcher = "nndr";
  onnx.onnx.model_path = (dir / "net.onnx").string();
  experiment.declared_features = {h5, onnx};
  const EngineOptions engine;
  EXPECT_EQ(RunFeatureFileChecksums(experiment, engine, {"OR"}), nlohmann::json::object());
  // DN without a model_path runs the embedded model: its checksum is recorded.
  const nlohmann::json dusknet = RunFeatureFileChecksums(experiment, engine, {"DN"});
  ASSERT_EQ(dusknet.size(), 1u) << dusknet.dump();
  EXPECT_TRUE(dusknet["embedded:dusknet.onnx"].is_string()) << dusknet.dump();
  const nlohmann::json before = RunFeatureFileChecksums(experiment, engine, experiment.features);
  ASSERT_EQ(before.size(), 2u) << before.dump();
  EXPECT_TRUE(before[(dir / "orb.h5").string()].is_string());
  EXPECT_TRUE(before[(dir / "net.onnx").string()].is_string());
  std::ofstream(dir / "orb.h5", std::ios::trunc) << "h5 content 2";
  const nlohmann::json after = RunFeatureFileChecksums(experiment, engine, experiment.features);
  EXPECT_NE(after[(dir / "orb.h5").string()], before[(dir / "orb.h5").string()]);
  EXPECT_EQ(after[(dir / "net.onnx").string()], before[(dir / "net.onnx").string()]);
  fs::remove(dir / "net.onnx");
  EXPECT_TRUE(RunFeatureFileChecksums(experiment, engine, {"XN"})[(dir / "net.onnx").string()].is_null());
}

}  // namespace
}  // namespace duskmap
