#include "slam/core/file_checksum.h"

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

namespace fs = std::filesystem;

void WriteBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// Every byte counts: one byte changed anywhere in a file of several 1 MiB
// blocks (the first, a middle block's, the last) gives another checksum, at
// the same size; the same bytes give the same checksum.
TEST(FileChecksumTest, AnyByteChangedAtTheSameSizeChangesTheChecksum) {
  const fs::path dir = testing::ProcessTempDir("file_checksum");
  std::string bytes((size_t{5} << 19) + 17, '\0');  // 2.5 MiB and a tail
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 131 % 251);
  WriteBytes(dir / "a.bin", bytes);
  const uint64_t original = FileChecksum64(dir / "a.bin");
  EXPECT_EQ(FileChecksum64Hex(dir / "a.bin").size(), 16u);
  WriteBytes(dir / "b.bin", bytes);
  EXPECT_EQ(FileChecksum64(dir / "b.bin"), original);
  for (const size_t at : {size_t{0}, size_t{1} << 20, bytes.size() - 1}) {
    std::string changed = bytes;
    changed[at] = static_cast<char>(changed[at] ^ 0x01);
    WriteBytes(dir / "b.bin", changed);
    ASSERT_EQ(fs::file_size(dir / "b.bin"), bytes.size());
    EXPECT_NE(FileChecksum64(dir / "b.bin"), original) << "byte " << at;
  }
  // A shorter file, and an empty one, differ too.
  WriteBytes(dir / "b.bin", bytes.substr(0, bytes.size() - 1));
  EXPECT_NE(FileChecksum64(dir / "b.bin"), original);
  WriteBytes(dir / "empty.bin", "");
  WriteBytes(dir / "zero.bin", std::string(1, '\0'));
  EXPECT_NE(FileChecksum64(dir / "empty.bin"), FileChecksum64(dir / "zero.bin"));
}

// Bytes in memory (an embedded model) get the checksum a file of them gets,
// at any size: empty, within one block, exactly one block, several and a tail.
TEST(FileChecksumTest, BytesInMemoryChecksumAsTheirFile) {
  const fs::path dir = testing::ProcessTempDir("bytes_checksum");
  for (const size_t size : {size_t{0}, size_t{100}, size_t{1} << 20, (size_t{5} << 19) + 17}) {
    std::string bytes(size, '\0');
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 131 % 251);
    WriteBytes(dir / "b.bin", bytes);
    EXPECT_EQ(BytesChecksum64(bytes.data(), bytes.size()), FileChecksum64(dir / "b.bin")) << size;
  }
  EXPECT_NE(BytesChecksum64("ab", 2), BytesChecksum64("ba", 2));
  fs::remove_all(dir);
}

TEST(FileChecksumTest, UnreadableInputsAreOneLineErrorsNamingThem) {
  const fs::path dir = testing::ProcessTempDir("file_checksum_errors");
  const std::string missing = testing::ErrorOf([&] { FileChecksum64(dir / "none.bin"); });
  EXPECT_EQ(missing, (dir / "none.bin").string() + ": cannot read (No such file or directory)");
  EXPECT_EQ(testing::ErrorOf([&] { FileChecksum64(dir); }), dir.string() + ": not a regular file");
  // A FIFO is refused at once, not waited on.
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0600), 0);
  EXPECT_EQ(testing::ErrorOf([&] { FileChecksum64(dir / "fifo"); }),
            (dir / "fifo").string() + ": not a regular file");
}

}  // namespace
}  // namespace duskmap
