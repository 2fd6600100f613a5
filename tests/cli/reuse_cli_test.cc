// End-to-end: content, not size, decides what `duskmap run` reuses. An image
// or depth map rewritten in place with the same byte size makes the feature
// cache kept across runs (--feature-cache) extract that session again (and
// only it), and makes a `--resume` of an earlier run refuse, naming the
// session; unchanged data is still restored. An h5 feature file rewritten
// the same way is not reused either.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "tests/testing/run_duskmap.h"
#include "tests/testing/temp_dir.h"

namespace {

namespace fs = std::filesystem;

using Result = duskmap::testing::CliResult;
using duskmap::testing::RunDuskmap;

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The first file of a session's image folder ("rgb" or "depth").
fs::path FirstImage(const fs::path& session, const std::string& folder) {
  std::vector<fs::path> images;
  for (const auto& entry : fs::directory_iterator(session / folder)) images.push_back(entry.path());
  std::sort(images.begin(), images.end());
  return images.front();
}

// Writes `image` as an uncompressed PNG (zlib stored blocks): its size then
// depends on the image's dimensions and type only, so that other pixels
// give a file of the same byte size.
void WriteUncompressedPng(const fs::path& path, const cv::Mat& image) {
  std::vector<uchar> bytes;
  ASSERT_TRUE(cv::imencode(".png", image, bytes, {cv::IMWRITE_PNG_COMPRESSION, 0}));
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

// Rewrites the image in place with a block of its pixels inverted (a depth
// map's set to 0, no measurement): the same byte size (checked), another
// content.
void ChangePixelsKeepingSize(const fs::path& path, bool depth = false) {
  const auto size = fs::file_size(path);
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(image.empty()) << path;
  cv::Mat block = image(cv::Rect(image.cols / 4, image.rows / 4, image.cols / 2, image.rows / 2));
  if (depth) {
    block.setTo(0);
  } else {
    cv::bitwise_not(block, block);
  }
  WriteUncompressedPng(path, image);
  ASSERT_EQ(fs::file_size(path), size) << path << ": the test needs a same-size rewrite";
}

class ReuseCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = duskmap::testing::ProcessTempDir("reuse_cli");
    const Result generated = duskmap::testing::GenerateSmallApartment(dir_.string(), 6, {"1", "A"});
    ASSERT_EQ(generated.exit_code, 0) << generated.output;
    const nlohmann::json experiment = {
        {"dataset", {{"path", (dir_ / "data").string()}, {"format", "synthetic"}}},
        {"features", {"OR"}},
        {"maps", {"1"}},
        {"localization_sessions", {"A"}}};
    std::ofstream(dir_ / "experiment.json") << experiment.dump(2);
    // The images the test rewrites, stored uncompressed first (the same
    // pixels): later rewrites keep their size.
    for (const fs::path& image : {FirstImage(dir_ / "data" / "A", "rgb"), FirstImage(dir_ / "data" / "A", "depth")}) {
      WriteUncompressedPng(image, cv::imread(image.string(), cv::IMREAD_UNCHANGED));
    }
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static std::string Run(const std::string& output, const std::string& extra = "") {
    return "run " + (dir_ / "experiment.json").string() + " --output " + (dir_ / output).string() +
           " --jobs 2 --no-figures " + extra;
  }
  static std::string Cached(const std::string& output) {
    return Run(output, "--feature-cache " + (dir_ / "shared_features").string());
  }
  // The extract job's "shared_cache" note: "stored <key>" or "restored <key>".
  static std::string CacheNote(const std::string& run, const std::string& session,
                               const std::string& extractor = "orb") {
    const auto summary = nlohmann::json::parse(
        std::ifstream(dir_ / run / "jobs" / "extract" / extractor / session / "summary.json"));
    return summary.value("shared_cache", std::string());
  }
  static bool Stored(const std::string& run, const std::string& session,
                     const std::string& extractor = "orb") {
    return CacheNote(run, session, extractor).rfind("stored ", 0) == 0;
  }
  static bool Restored(const std::string& run, const std::string& session,
                       const std::string& extractor = "orb") {
    return CacheNote(run, session, extractor).rfind("restored ", 0) == 0;
  }

  static fs::path dir_;
};

fs::path ReuseCli::dir_;

TEST_F(ReuseCli, SameSizeImageChangeReExtractsItsSessionAndRefusesAResume) {
  const Result first = RunDuskmap(Cached("first"));
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find(" GB checksummed in "), std::string::npos) << first.output;
  EXPECT_TRUE(Stored("first", "1") && Stored("first", "A"));

  // Unchanged data: every extraction is restored (the cache's purpose).
  const Result second = RunDuskmap(Cached("second"));
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_TRUE(Restored("second", "1") && Restored("second", "A"))
      << CacheNote("second", "1") << " / " << CacheNote("second", "A");

  // An rgb image of session A rewritten in place, same size, other pixels:
  // A is extracted again, from the new pixels; session 1 is still restored.
  ChangePixelsKeepingSize(FirstImage(dir_ / "data" / "A", "rgb"));
  const Result third = RunDuskmap(Cached("third"));
  ASSERT_EQ(third.exit_code, 0) << third.output;
  EXPECT_TRUE(Stored("third", "A")) << CacheNote("third", "A");
  EXPECT_TRUE(Restored("third", "1")) << CacheNote("third", "1");
  EXPECT_NE(ReadBytes(dir_ / "third/jobs/extract/orb/A/features.bin"),
            ReadBytes(dir_ / "first/jobs/extract/orb/A/features.bin"));

  // Resuming the first run would localize A from the old image's features
  // cached in its job folder: refused, naming session A, nothing touched.
  const std::string run_json = ReadBytes(dir_ / "first" / "run.json");
  fs::remove_all(dir_ / "first/jobs/localize/OR/1/A");
  const Result resumed = RunDuskmap(Cached("first") + " --resume");
  EXPECT_EQ(resumed.exit_code, 1) << resumed.output;
  EXPECT_NE(resumed.output.find((dir_ / "first" / "run.json").string() +
                                ": the files of session A (images, depth maps or metadata) changed "
                                "since the earlier run"),
            std::string::npos)
      << resumed.output;
  EXPECT_EQ(ReadBytes(dir_ / "first" / "run.json"), run_json);
  EXPECT_FALSE(fs::exists(dir_ / "first/jobs/localize/OR/1/A"));

  // A depth map changed the same way: A again, and only A.
  ChangePixelsKeepingSize(FirstImage(dir_ / "data" / "A", "depth"), /*depth=*/true);
  const Result fourth = RunDuskmap(Cached("fourth"));
  ASSERT_EQ(fourth.exit_code, 0) << fourth.output;
  EXPECT_TRUE(Stored("fourth", "A")) << CacheNote("fourth", "A");
  EXPECT_TRUE(Restored("fourth", "1")) << CacheNote("fourth", "1");

  // The fourth run resumes: its data have not changed since.
  fs::remove_all(dir_ / "fourth/jobs/localize/OR/1/A");
  const Result resumed_fourth = RunDuskmap(Cached("fourth") + " --resume");
  EXPECT_EQ(resumed_fourth.exit_code, 0) << resumed_fourth.output;
  EXPECT_NE(resumed_fourth.output.find(": 1 jobs run,"), std::string::npos) << resumed_fourth.output;
}

// A declared h5 column's file rewritten in place (one descriptor byte changed
// through h5py, the same size, the modification time put back): the feature
// cache extracts the column again instead of restoring the old features, and
// a resume is refused naming the file.
TEST_F(ReuseCli, SameSizeH5FileChangeIsNotReused) {
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  if (std::system((python + " -c 'import h5py, numpy' > /dev/null 2>&1").c_str()) != 0) {
    GTEST_SKIP() << "python3-h5py is not installed (scripts/setup.sh installs it)";
  }
  const fs::path h5 = dir_ / "orb.h5";
  const Result exported = RunDuskmap("features export --dataset " + (dir_ / "data").string() +
                                     " --type orb --output " + h5.string());
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  const nlohmann::json experiment = {
      {"dataset", {{"path", (dir_ / "data").string()}, {"format", "synthetic"}}},
      {"features", {{{"code", "XO"}, {"type", "h5"}, {"path", h5.string()}, {"descriptor_kind", "binary"}}}},
      {"maps", {"1"}},
      {"localization_sessions", {"A"}}};
  std::ofstream(dir_ / "h5_experiment.json") << experiment.dump(2);
  const auto run = [&](const std::string& output, const std::string& extra = "") {
    return RunDuskmap("run " + (dir_ / "h5_experiment.json").string() + " --output " +
                      (dir_ / output).string() + " --jobs 2 --no-figures --feature-cache " +
                      (dir_ / "h5_shared_features").string() + " " + extra);
  };
  const Result first = run("h5_first");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_TRUE(Stored("h5_first", "1", "h5-XO") && Stored("h5_first", "A", "h5-XO"));
  const Result second = run("h5_second");
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_TRUE(Restored("h5_second", "1", "h5-XO") && Restored("h5_second", "A", "h5-XO"));

  const auto size = fs::file_size(h5);
  std::ofstream(dir_ / "flip.py") << R"(import os, sys, h5py
path = sys.argv[1]
times = os.stat(path)
found = []
with h5py.File(path, "r+") as f:
    f.visititems(lambda name, item: found.append(name) if name.endswith("descriptors") and item.size > 0 and not found else None)
    d = f[found[0]]
    d[(0,) * d.ndim] = d[(0,) * d.ndim] ^ 1
os.utime(path, ns=(times.st_atime_ns, times.st_mtime_ns))
)";
  ASSERT_EQ(std::system((python + " " + (dir_ / "flip.py").string() + " " + h5.string()).c_str()), 0);
  ASSERT_EQ(fs::file_size(h5), size) << "the test needs a same-size rewrite";

  const Result third = run("h5_third");
  ASSERT_EQ(third.exit_code, 0) << third.output;
  EXPECT_TRUE(Stored("h5_third", "1", "h5-XO")) << CacheNote("h5_third", "1", "h5-XO");
  EXPECT_TRUE(Stored("h5_third", "A", "h5-XO")) << CacheNote("h5_third", "A", "h5-XO");
  const Result resumed = run("h5_first", "--resume");
  EXPECT_EQ(resumed.exit_code, 1) << resumed.output;
  EXPECT_NE(resumed.output.find("the feature file " + h5.string() + " changed since the earlier run"),
            std::string::npos)
      << resumed.output;
}

}  // namespace
