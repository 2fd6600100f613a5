#include "slam/datasets/dataset_identity.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "slam/io/synthetic_dataset.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

namespace fs = std::filesystem;

void Write(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// Rewrites one byte of the file in place: the same size, another content.
void FlipByte(const fs::path& path, size_t at) {
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  file.seekg(static_cast<std::streamoff>(at));
  const char byte = static_cast<char>(file.get() ^ 0x20);
  file.seekp(static_cast<std::streamoff>(at));
  file.put(byte);
}

// A synthetic-layout dataset of two sessions (no image is decoded: the
// identity reads bytes), session "2" in the folder "runs/two".
std::vector<SessionInfo> MakeDataset(const fs::path& root) {
  DatasetManifest manifest;
  manifest.sessions = {{"1", "1", "16:46", "mapping"}, {"2", "runs/two", "21:02", "mapping"}};
  fs::create_directories(root);
  WriteManifest(root.string(), manifest);
  for (const std::string folder : {"1", "runs/two"}) {
    Write(root / folder / "rgb.txt", "# rgb\n0.000000 rgb/0.000000.png\n");
    Write(root / folder / "rgb" / "0.000000.png", std::string(3000, 'c') + folder);
    Write(root / folder / "depth" / "0.000000.png", std::string(2000, 'd') + folder);
    Write(root / folder / "calibration.json", "{\"fx\": 525}");
  }
  std::vector<SessionInfo> sessions(2);
  sessions[0].name = "1";
  sessions[1].name = "2";
  return sessions;
}

nlohmann::json SessionContent(const nlohmann::json& identity, const std::string& session) {
  return identity["content"]["sessions"][session];
}

// An image, a depth map or a metadata file rewritten in place with the same
// size changes exactly its session's checksum (and the key of what depends on
// that session only); the files no session owns (manifest.json) change every
// session's identity; unchanged data gives the same identity.
TEST(DatasetIdentityTest, ContentChecksumsChangeExactlyWithTheSessionThatChanged) {
  const fs::path root = testing::ProcessTempDir("dataset_identity") + "/data";
  const std::vector<SessionInfo> sessions = MakeDataset(root);
  const nlohmann::json before = DatasetIdentity(root.string(), "synthetic", sessions);
  EXPECT_EQ(before["files"], 9);
  ASSERT_TRUE(before["content"]["shared"].is_string());
  EXPECT_EQ(DatasetIdentity(root.string(), "synthetic", sessions), before);
  EXPECT_EQ(DatasetIdentity(root.string(), "auto", sessions)["content"], before["content"])
      << "an auto-detected synthetic dataset reads its manifest's folders too";

  // Session 2's image (under the manifest's folder "runs/two").
  const auto size = fs::file_size(root / "runs/two/rgb/0.000000.png");
  FlipByte(root / "runs/two/rgb/0.000000.png", 1500);
  ASSERT_EQ(fs::file_size(root / "runs/two/rgb/0.000000.png"), size);
  nlohmann::json after = DatasetIdentity(root.string(), "synthetic", sessions);
  EXPECT_EQ(after["bytes"], before["bytes"]);
  EXPECT_NE(SessionContent(after, "2"), SessionContent(before, "2"));
  EXPECT_EQ(SessionContent(after, "1"), SessionContent(before, "1"));
  EXPECT_EQ(after["content"]["shared"], before["content"]["shared"]);
  EXPECT_EQ(SessionIdentity(after, "1"), SessionIdentity(before, "1"));
  EXPECT_NE(SessionIdentity(after, "2"), SessionIdentity(before, "2"));

  // Session 1's depth map, then its metadata.
  nlohmann::json last = after;
  FlipByte(root / "1/depth/0.000000.png", 0);
  after = DatasetIdentity(root.string(), "synthetic", sessions);
  EXPECT_NE(SessionContent(after, "1"), SessionContent(last, "1"));
  EXPECT_EQ(SessionContent(after, "2"), SessionContent(last, "2"));
  last = after;
  FlipByte(root / "1/calibration.json", 3);
  after = DatasetIdentity(root.string(), "synthetic", sessions);
  EXPECT_NE(SessionContent(after, "1"), SessionContent(last, "1"));
  EXPECT_EQ(SessionContent(after, "2"), SessionContent(last, "2"));

  // A file added to a session is a change of that session.
  last = after;
  Write(root / "runs/two/rgb/1.000000.png", "x");
  after = DatasetIdentity(root.string(), "synthetic", sessions);
  EXPECT_NE(SessionContent(after, "2"), SessionContent(last, "2"));
  EXPECT_EQ(SessionContent(after, "1"), SessionContent(last, "1"));

  // The manifest belongs to no session: every session's identity changes.
  last = after;
  const std::string manifest = (root / kManifestFileName).string();
  FlipByte(manifest, fs::file_size(manifest) / 2);
  after = DatasetIdentity(root.string(), "synthetic", sessions);
  EXPECT_NE(after["content"]["shared"], last["content"]["shared"]);
  EXPECT_NE(SessionIdentity(after, "1"), SessionIdentity(last, "1"));
  EXPECT_NE(SessionIdentity(after, "2"), SessionIdentity(last, "2"));
}

// A dataset of one session (a TUM folder) owns every file; a database named
// after its session ("<name>.db") is that session's.
TEST(DatasetIdentityTest, OneSessionOwnsEveryFileAndADatabaseItsSession) {
  const fs::path dir = testing::ProcessTempDir("dataset_identity_one");
  Write(dir / "tum/rgb.txt", "0.0 rgb/0.png\n");
  Write(dir / "tum/rgb/0.png", std::string(100, 'p'));
  std::vector<SessionInfo> one(1);
  one[0].name = "tum";
  const nlohmann::json tum = DatasetIdentity((dir / "tum").string(), "tum", one);
  FlipByte(dir / "tum/rgb/0.png", 10);
  const nlohmann::json changed = DatasetIdentity((dir / "tum").string(), "tum", one);
  EXPECT_NE(SessionContent(changed, "tum"), SessionContent(tum, "tum"));
  EXPECT_EQ(changed["content"]["shared"], tum["content"]["shared"]);

  Write(dir / "dbs/day.db", std::string(64, 'a'));
  Write(dir / "dbs/night.db", std::string(64, 'b'));
  std::vector<SessionInfo> two(2);
  two[0].name = "day";
  two[1].name = "night";
  const nlohmann::json dbs = DatasetIdentity((dir / "dbs").string(), "rtabmap-db", two);
  FlipByte(dir / "dbs/night.db", 5);
  const nlohmann::json night = DatasetIdentity((dir / "dbs").string(), "rtabmap-db", two);
  EXPECT_NE(SessionContent(night, "night"), SessionContent(dbs, "night"));
  EXPECT_EQ(SessionContent(night, "day"), SessionContent(dbs, "day"));
  EXPECT_EQ(SessionIdentity(night, "day"), SessionIdentity(dbs, "day"));
}

}  // namespace
}  // namespace duskmap
