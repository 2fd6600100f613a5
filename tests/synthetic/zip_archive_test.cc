#include "slam/synthetic/assets/zip_archive.h"

#include <gtest/gtest.h>

#include "mesh_test_files.h"
#include "slam/core/check.h"

namespace duskmap {
namespace {

TEST(ZipArchive, ListsAndReadsFilesByArchivePath) {
  const ScratchFolder scratch("zip_read");
  const std::string path = scratch.File("a.zip");
  const std::string big(100000, 'x');
  WriteZip(path, {{"a/b.txt", "hello"}, {"big.bin", big}, {"../evil.txt", "no"}, {"/abs.txt", "no"}});
  const ZipArchive archive = ZipArchive::Open(path);
  EXPECT_EQ(archive.path(), path);
  EXPECT_EQ(archive.FilePaths(), (std::vector<std::string>{"a/b.txt", "big.bin"}));
  EXPECT_TRUE(archive.Contains("a/b.txt"));
  EXPECT_FALSE(archive.Contains("a/./b.txt"));
  EXPECT_FALSE(archive.Contains("../evil.txt"));
  EXPECT_FALSE(archive.Contains("/abs.txt"));
  EXPECT_EQ(archive.Read("a/b.txt", 100), "hello");
  EXPECT_EQ(archive.Read("a/x/../b.txt", 100), "hello");
  EXPECT_EQ(archive.Read("big.bin", 1 << 20), big);
  EXPECT_EQ(InputErrorOf([&] { archive.Read("big.bin", 1000); }),
            path + "!/big.bin: 100000 bytes uncompressed, over the limit of 1000");
  EXPECT_EQ(InputErrorOf([&] { archive.Read("../evil.txt", 100); }),
            path + "!/../evil.txt: path leaves the archive (absolute or '..')");
  EXPECT_EQ(InputErrorOf([&] { archive.Read("/abs.txt", 100); }),
            path + "!//abs.txt: path leaves the archive (absolute or '..')");
  EXPECT_EQ(InputErrorOf([&] { archive.Read("a/c.txt", 100); }), path + "!/a/c.txt: no such file in the archive");
}

TEST(ZipArchive, RefusesMissingNonZipAndTruncatedFiles) {
  const ScratchFolder scratch("zip_bad");
  EXPECT_EQ(InputErrorOf([&] { ZipArchive::Open(scratch.File("none.zip")); }),
            scratch.File("none.zip") + ": no such file");
  WriteBytes(scratch.File("text.zip"), "this is not a zip archive at all\n");
  EXPECT_EQ(InputErrorOf([&] { ZipArchive::Open(scratch.File("text.zip")); }),
            scratch.File("text.zip") + ": not a ZIP archive");
  WriteZip(scratch.File("whole.zip"), {{"a.txt", std::string(5000, 'a')}, {"b.txt", "b"}});
  const std::string whole = ReadBytes(scratch.File("whole.zip"));
  WriteBytes(scratch.File("cut.zip"), whole.substr(0, whole.size() - 40));
  const std::string cut = InputErrorOf([&] { ZipArchive::Open(scratch.File("cut.zip")); });
  EXPECT_EQ(cut.rfind(scratch.File("cut.zip") + ": ", 0), 0u) << cut;
  EXPECT_NE(cut.find("ZIP archive"), std::string::npos) << cut;
}

TEST(ZipArchive, RefusesDataThatFailTheirChecksum) {
  const ScratchFolder scratch("zip_crc");
  const std::string content = "SOME-STORED-CONTENT-0123456789";
  WriteZip(scratch.File("ok.zip"), {{"data.txt", content}}, /*store=*/true);
  std::string bytes = ReadBytes(scratch.File("ok.zip"));
  const size_t at = bytes.find(content);
  ASSERT_NE(at, std::string::npos);
  bytes[at + 5] = '#';
  WriteBytes(scratch.File("damaged.zip"), bytes);
  const ZipArchive archive = ZipArchive::Open(scratch.File("damaged.zip"));
  const std::string message = InputErrorOf([&] { archive.Read("data.txt", 1000); });
  EXPECT_EQ(message.rfind(scratch.File("damaged.zip") + "!/data.txt: corrupt data (", 0), 0u) << message;
  EXPECT_NE(message.find("CRC"), std::string::npos) << message;
}

}  // namespace
}  // namespace duskmap
