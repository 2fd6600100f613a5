#include "slam/synthetic/assets/archive_path.h"

#include <gtest/gtest.h>

namespace duskmap {
namespace {

TEST(NormalizeArchivePath, DropsDotsAndEmptyPartsAndReadsBackslashes) {
  EXPECT_EQ(NormalizeArchivePath("a/b/c.obj"), "a/b/c.obj");
  EXPECT_EQ(NormalizeArchivePath("a//./b/../c.obj"), "a/c.obj");
  EXPECT_EQ(NormalizeArchivePath("a\\b\\c.jpg"), "a/b/c.jpg");
  EXPECT_EQ(NormalizeArchivePath("a/b/"), "a/b");
}

TEST(NormalizeArchivePath, RefusesAbsolutePathsAndEscapes) {
  for (const char* path : {"", "/etc/passwd", "\\x", "../x", "a/../../x", "C:/Documents and Settings/x.jpg",
                           "c:x.jpg", "file:/x", "http://host/x", ".", "a/.."}) {
    EXPECT_EQ(NormalizeArchivePath(path), std::nullopt) << path;
  }
}

TEST(ArchiveFolder, KeepsTheTrailingSlash) {
  EXPECT_EQ(ArchiveFolder("a/b/c.obj"), "a/b/");
  EXPECT_EQ(ArchiveFolder("c.obj"), "");
}

TEST(ResolveArchiveReference, ResolvesAgainstTheFolderAndStaysInside) {
  EXPECT_EQ(ResolveArchiveReference("a/b/", "c.mtl"), "a/b/c.mtl");
  EXPECT_EQ(ResolveArchiveReference("a/b/", "../shared/wood.jpg"), "a/shared/wood.jpg");
  EXPECT_EQ(ResolveArchiveReference("a/b/", "tex\\wood.jpg"), "a/b/tex/wood.jpg");
  EXPECT_EQ(ResolveArchiveReference("a/b/", "../../../etc/passwd"), std::nullopt);
  EXPECT_EQ(ResolveArchiveReference("a/b/", "/etc/passwd"), std::nullopt);
  EXPECT_EQ(ResolveArchiveReference("a/b/", "C:/x/wood.jpg"), std::nullopt);
  EXPECT_EQ(ResolveArchiveReference("", "x.jpg"), "x.jpg");
}

}  // namespace
}  // namespace duskmap
