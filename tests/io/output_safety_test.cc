#include "slam/io/output_safety.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

using testing::ProcessTempDir;

std::string Contents(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(OutputSafety, SameOrInsideResolvesDotsAndLinks) {
  const fs::path root = ProcessTempDir("safety_inside");
  fs::create_directories(root / "data" / "s1");
  fs::create_symlink(root / "data", root / "link");
  EXPECT_TRUE(IsSameOrInside(root / "data", root / "data/"));
  EXPECT_TRUE(IsSameOrInside(root / "data/s1/../manifest.json", root / "data"));
  EXPECT_TRUE(IsSameOrInside(root / "link/s1/new.txt", root / "data"));
  EXPECT_FALSE(IsSameOrInside(root / "data2", root / "data"));
  EXPECT_FALSE(IsSameOrInside(root, root / "data"));
}

TEST(OutputSafety, OutputMayNotBeOrLieInsideAnInput) {
  const fs::path root = ProcessTempDir("safety_inputs");
  fs::create_directories(root / "dataset");
  const std::string map = (root / "m.db").string();
  std::ofstream(map) << "map";
  const std::vector<NamedPath> inputs = {{"--map", map}, {"--dataset", (root / "dataset").string()}};
  std::string message = ErrorOf([&] { CheckOutputsApartFromInputs({{"--trajectory", map}}, inputs); });
  EXPECT_NE(message.find(map + ": --trajectory would write onto the input"), std::string::npos)
      << message;
  message = ErrorOf([&] {
    CheckOutputsApartFromInputs({{"--output", (root / "dataset/manifest.json").string()}}, inputs);
  });
  EXPECT_NE(message.find("inside the input"), std::string::npos) << message;
  message = ErrorOf([&] {
    CheckOutputsApartFromInputs({{"--records", "a.jsonl"}, {"--summary", "./a.jsonl"}}, {});
  });
  EXPECT_NE(message.find("given to both --records and --summary"), std::string::npos) << message;
  EXPECT_NO_THROW(CheckOutputsApartFromInputs(
      {{"--records", (root / "r.jsonl").string()}, {"--summary", ""}}, inputs));
}

TEST(OutputSafety, ReplaceNeedsOverwriteAndOwnership) {
  const fs::path root = ProcessTempDir("safety_replace");
  EXPECT_NO_THROW(CheckMayReplace({"--output", (root / "new").string()}, false, OwnedResultsFolder()));
  fs::create_directories(root / "user");
  std::string message =
      ErrorOf([&] { CheckMayReplace({"--output", (root / "user").string()}, false, OwnedResultsFolder()); });
  EXPECT_NE(message.find("already exists (--output; pass --overwrite"), std::string::npos) << message;
  message =
      ErrorOf([&] { CheckMayReplace({"--output", (root / "user").string()}, true, OwnedResultsFolder()); });
  EXPECT_NE(message.find("not a duskmap results folder"), std::string::npos) << message;
  std::ofstream((root / "user" / "run.json").string()) << "{}";
  EXPECT_NO_THROW(CheckMayReplace({"--output", (root / "user").string()}, true, OwnedResultsFolder()));
}

TEST(OutputSafety, LabelsStayOneComponent) {
  for (const std::string& bad : std::vector<std::string>{"", ".", "..", "../../escaped", "a/b",
                                                         ".hidden", "a\\b", "a\nb",
                                                         std::string(kMaxPathLabelBytes + 1, 'x')}) {
    EXPECT_THROW(CheckPathLabel(bad, "cfg.json: maps"), ConfigError) << bad;
  }
  for (const std::string& good : std::vector<std::string>{"1+6", "1-2-3-4-5-6", "1|2|3", "SI", "map_A.v2"}) {
    EXPECT_NO_THROW(CheckPathLabel(good, "cfg.json: maps")) << good;
  }
}

// The 48-session map of configs/lifelong_apartment.json (a1+...+h6, 143 bytes)
// is a valid label, and the longest label still names a folder while its job
// writes it as "<label>.partial".
TEST(OutputSafety, LongestLabelNamesAPartialFolder) {
  std::string merged_48;
  for (const char day : std::string("abcdefgh")) {
    for (int clock = 1; clock <= 6; ++clock) {
      merged_48 += (merged_48.empty() ? "" : "+") + std::string(1, day) + std::to_string(clock);
    }
  }
  ASSERT_EQ(merged_48.size(), 143u);
  EXPECT_NO_THROW(CheckPathLabel(merged_48, "cfg.json: maps"));
  const std::string longest(kMaxPathLabelBytes, 'x');
  EXPECT_NO_THROW(CheckPathLabel(longest, "cfg.json: maps"));
  const fs::path partial = fs::path(ProcessTempDir("safety_long_label")) / (longest + ".partial");
  EXPECT_TRUE(fs::create_directories(partial)) << partial;
}

TEST(OutputSafety, SecondProcessCannotLockTheFolder) {
  const fs::path root = ProcessTempDir("safety_lock");
  FolderLock lock(root);
  // flock locks belong to the open file description: another process (a
  // child, which opens the file anew) is refused while this one holds it.
  const pid_t child = ::fork();
  if (child == 0) {
    try {
      FolderLock second(root);
      ::_exit(0);
    } catch (const InputError& e) {
      const std::string message = e.what();
      ::_exit(message.find("another duskmap process (pid " + std::to_string(::getppid())) !=
                      std::string::npos
                  ? 7
                  : 1);
    }
    ::_exit(2);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 7);
}

TEST(OutputSafety, LockIsReleasedWithItsOwner) {
  const fs::path root = ProcessTempDir("safety_relock");
  { FolderLock first(root); }
  EXPECT_NO_THROW(FolderLock second(root));
}

TEST(OutputSafety, AtomicWriteReplacesWholeOrNothing) {
  const fs::path root = ProcessTempDir("safety_atomic");
  const std::string path = (root / "records.jsonl").string();
  std::ofstream(path) << "old\n";
  WriteFileAtomically(path, [](std::ostream& out) { out << "new\n"; });
  EXPECT_EQ(Contents(path), "new\n");
  EXPECT_THROW(WriteFileAtomically(path,
                                   [](std::ostream& out) {
                                     out << "half";
                                     throw InputError("simulated");
                                   }),
               InputError);
  EXPECT_EQ(Contents(path), "new\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(root), fs::directory_iterator()), 1);
}

TEST(OutputSafety, WriteCutShortLeavesTheOldFileAndNoPartialFile) {
  const fs::path root = ProcessTempDir("safety_cut");
  const std::string path = (root / "records.jsonl").string();
  std::ofstream(path) << "old\n";
  // A file-size limit makes write() fail part way, as a full disk does.
  const pid_t child = ::fork();
  if (child == 0) {
    ::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{100, 100};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    try {
      WriteFileAtomically(path, [](std::ostream& out) { out << std::string(100000, 'x'); });
    } catch (const InputError& e) {
      ::_exit(std::string(e.what()).find(path + ": cannot write: File too large") == 0 ? 7 : 1);
    }
    ::_exit(2);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 7);
  EXPECT_EQ(Contents(path), "old\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(root), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace duskmap
