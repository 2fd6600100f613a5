#include "slam/io/publish.h"

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/testing/read_text.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

using testing::ProcessTempDir;
using testing::ReadText;


std::set<std::string> Names(const fs::path& folder) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.insert(entry.path().filename().string());
  return names;
}

std::string MessageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A file whose first line is "mine": what the tests' --overwrite may replace.
OwnedOutput Mine() {
  return {"a file of mine", [](const fs::path& p) { return ReadText(p).rfind("mine", 0) == 0; }};
}

PublishTarget Target(const fs::path& path, bool overwrite) {
  return {{"--output", path.string()}, overwrite, Mine()};
}

// The hook makes a file appear at the final path right before the publish.
class AppearsBeforePublish {
 public:
  explicit AppearsBeforePublish(std::function<void(const std::string&)> make) {
    SetBeforePublishHookForTesting(std::move(make));
  }
  ~AppearsBeforePublish() { SetBeforePublishHookForTesting(nullptr); }
};

// A pid that was this process's child and is gone.
pid_t DeadPid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

TEST(Publish, NoClobberPublishesAFreeName) {
  const fs::path root = ProcessTempDir("publish_free");
  WriteAndPublish(Target(root / "out.txt", false), [](std::ostream& out) { out << "new\n"; });
  EXPECT_EQ(ReadText(root / "out.txt"), "new\n");
  EXPECT_EQ(Names(root), std::set<std::string>{"out.txt"});  // the temporary file is gone
}

TEST(Publish, NoClobberRefusesAFileThatAppeared) {
  const fs::path root = ProcessTempDir("publish_appeared");
  const fs::path path = root / "out.txt";
  const AppearsBeforePublish hook([&](const std::string& final_path) {
    EXPECT_EQ(final_path, path.string());
    std::ofstream(final_path) << "notes";
  });
  const std::string message = MessageOf([&] {
    WriteAndPublish(Target(path, false), [](std::ostream& out) { out << "new\n"; });
  });
  EXPECT_EQ(message, path.string() +
                         ": appeared while this command ran (--output); nothing was replaced "
                         "(pass --overwrite to replace it)");
  EXPECT_EQ(ReadText(path), "notes");
  EXPECT_EQ(Names(root), std::set<std::string>{"out.txt"});
}

TEST(Publish, OverwriteReplacesOnlyWhatTheOwnerRecognises) {
  const fs::path root = ProcessTempDir("publish_overwrite");
  const fs::path path = root / "out.txt";
  std::ofstream(path) << "mine, old";
  WriteAndPublish(Target(path, true), [](std::ostream& out) { out << "mine, new"; });
  EXPECT_EQ(ReadText(path), "mine, new");
  EXPECT_EQ(Names(root), std::set<std::string>{"out.txt"});
  // The owner is tested right before the replace: what appeared is kept.
  const AppearsBeforePublish hook([&](const std::string&) { std::ofstream(path) << "notes"; });
  const std::string message = MessageOf([&] {
    WriteAndPublish(Target(path, true), [](std::ostream& out) { out << "mine, newer"; });
  });
  EXPECT_NE(message.find(path.string() + ": not a file of mine, so --overwrite will not replace it"),
            std::string::npos)
      << message;
  EXPECT_EQ(ReadText(path), "notes");
  EXPECT_EQ(Names(root), std::set<std::string>{"out.txt"});
}

TEST(Publish, FailedWriteRemovesTheTemporaryFile) {
  const fs::path root = ProcessTempDir("publish_failed");
  EXPECT_THROW(WriteAndPublishAt(Target(root / "out.h5", false),
                                 [](const std::string& temp) {
                                   std::ofstream(temp) << "half";
                                   throw InputError("simulated");
                                 }),
               InputError);
  EXPECT_TRUE(Names(root).empty());
}

// Processes publishing to one path at once: exactly one wins, the file is
// whole and is the winner's.
TEST(Publish, ConcurrentPublishersExactlyOneWins) {
  const fs::path root = ProcessTempDir("publish_concurrent");
  const fs::path path = root / "out.txt";
  constexpr int kWriters = 8;
  std::vector<pid_t> children;
  for (int i = 0; i < kWriters; ++i) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      try {
        WriteAndPublish(Target(path, false), [i](std::ostream& out) {
          out << "writer " << i << std::string(100000, 'x');
        });
      } catch (const InputError&) {
        ::_exit(1);
      }
      ::_exit(0);
    }
    children.push_back(child);
  }
  int winners = 0;
  int winner = -1;
  for (int i = 0; i < kWriters; ++i) {
    int status = 0;
    ASSERT_EQ(::waitpid(children[i], &status, 0), children[i]);
    ASSERT_TRUE(WIFEXITED(status));
    if (WEXITSTATUS(status) == 0) {
      ++winners;
      winner = i;
    }
  }
  EXPECT_EQ(winners, 1);
  EXPECT_EQ(ReadText(path), "writer " + std::to_string(winner) + std::string(100000, 'x'));
  EXPECT_EQ(Names(root), std::set<std::string>{"out.txt"});
}

TEST(Publish, FolderNoClobberRefusesAFolderThatAppeared) {
  const fs::path root = ProcessTempDir("publish_folder");
  const fs::path path = root / "out";
  const fs::path staging = root / "out.tmp-1";
  fs::create_directories(staging);
  std::ofstream(staging / "new.txt") << "new";
  // Even an empty folder, which rename(2) would silently replace.
  {
    const AppearsBeforePublish hook([&](const std::string&) { fs::create_directories(path); });
    EXPECT_NE(MessageOf([&] { PublishFolder(staging.string(), Target(path, false)); })
                  .find("appeared while this command ran"),
              std::string::npos);
  }
  EXPECT_TRUE(fs::is_empty(path));
  EXPECT_TRUE(fs::exists(staging / "new.txt"));  // kept: its owner removes it
  fs::remove(path);
  PublishFolder(staging.string(), Target(path, false));
  EXPECT_EQ(ReadText(path / "new.txt"), "new");
  EXPECT_EQ(Names(root), std::set<std::string>{"out"});
}

TEST(Publish, FolderOverwriteTestsTheOwnerOfWhatIsThere) {
  const fs::path root = ProcessTempDir("publish_folder_overwrite");
  const fs::path path = root / "out";
  const fs::path staging = root / "out.tmp-1";
  fs::create_directories(path);
  std::ofstream(path / "thesis.tex") << "years of work";
  fs::create_directories(staging);
  std::ofstream(staging / "new.txt") << "new";
  const OwnedOutput has_old = {"an output", [](const fs::path& p) { return fs::exists(p / "old.txt"); }};
  const PublishTarget target{{"--output", path.string()}, true, has_old};
  EXPECT_NE(MessageOf([&] { PublishFolder(staging.string(), target); })
                .find(path.string() + ": not an output, so --overwrite will not replace it (left as it was)"),
            std::string::npos);
  EXPECT_EQ(ReadText(path / "thesis.tex"), "years of work");
  EXPECT_EQ(Names(root), (std::set<std::string>{"out", "out.tmp-1"}));
  fs::remove_all(path);
  fs::create_directories(path);
  std::ofstream(path / "old.txt") << "old";
  PublishFolder(staging.string(), target);
  EXPECT_EQ(Names(path), std::set<std::string>{"new.txt"});
  EXPECT_EQ(Names(root), std::set<std::string>{"out"});  // no old folder left aside
}

TEST(Publish, StaleSiblingsOfGoneProcessesAreRemoved) {
  const fs::path root = ProcessTempDir("publish_stale");
  const pid_t dead = DeadPid();
  const std::string gone = "report.tmp-" + std::to_string(dead);
  const std::string alive = "report.tmp-" + std::to_string(::getppid()) + "-0";
  fs::create_directories(root / gone / "tables");
  fs::create_directories(root / alive);
  std::ofstream(root / ("report.tmp-" + std::to_string(dead) + "-3")) << "half";
  std::ofstream(root / "report.tmp-notes") << "not a temporary name";
  fs::create_directories(root / "report");
  EXPECT_EQ(RemoveStaleSiblings((root / "report").string(), "tmp"), 2);
  EXPECT_EQ(Names(root), (std::set<std::string>{alive, "report.tmp-notes", "report"}));
}

TEST(Publish, AFolderMovedAsideByAKilledRunIsPutBack) {
  const fs::path root = ProcessTempDir("publish_aside");
  const std::string aside = "out.old-" + std::to_string(DeadPid()) + "-0";
  fs::create_directories(root / aside);
  std::ofstream(root / aside / "data.txt") << "earlier output";
  RecoverStaleAside((root / "out").string());
  EXPECT_EQ(ReadText(root / "out" / "data.txt"), "earlier output");
  EXPECT_EQ(Names(root), std::set<std::string>{"out"});
  // Once replaced (the new one is in place), a stale old folder is removed.
  fs::create_directories(root / aside);
  RecoverStaleAside((root / "out").string());
  EXPECT_EQ(Names(root), std::set<std::string>{"out"});
}

}  // namespace
}  // namespace duskmap
