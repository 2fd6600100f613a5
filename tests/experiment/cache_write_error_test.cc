// A feature cache that cannot be written whole says why, naming the file: a
// full cache disk read "Input/output error" (issue 48), std::filesystem's
// word for any failed copy. The limit on a file's size (RLIMIT_FSIZE) makes
// the write fail here as a full disk would, with the system's own reason.
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "slam/core/check.h"
#include "slam/experiment/feature_cache.h"
#include "slam/experiment/shared_feature_cache.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

// Lowers this process's file-size limit (a write past it fails with EFBIG,
// "File too large", instead of raising SIGXFSZ) and restores it.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    ::getrlimit(RLIMIT_FSIZE, &saved_);
    previous_signal_ = ::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    ::setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &saved_);
    ::signal(SIGXFSZ, previous_signal_);
  }

 private:
  rlimit saved_{};
  sighandler_t previous_signal_ = SIG_DFL;
};

FrameFeatures ManyFeatures(int n) {
  FrameFeatures f;
  f.kind = DescriptorKind::kBinary;
  f.descriptors = cv::Mat(n, 32, CV_8U, cv::Scalar(7));
  for (int i = 0; i < n; ++i) {
    f.keypoints.emplace_back(10.f + i, 20.f, 7.f, 45.f, 1.0f, 0, -1);
    f.points_in_camera.push_back(Eigen::Vector3f(0.1f, 0.2f, 1.5f));
  }
  return f;
}

TEST(FeatureCacheWriteError, AFailedWriteNamesTheFileAndTheSystemsReason) {
  const fs::path path = testing::ProcessTempPath("limited_features.bin");
  RgbdFrame frame;
  frame.camera = PinholeCamera{640, 480, 525.0, 526.0, 319.5, 239.5};
  SessionInfo session;
  session.name = "1";
  std::string error;
  {
    const FileSizeLimit limit(16 * 1024);
    FeatureCacheWriter writer(path, "orb", session);
    error = testing::ErrorOf([&] {
      for (int i = 0; i < 20; ++i) writer.Append(frame, ManyFeatures(500));
      writer.Close();
    });
  }
  EXPECT_EQ(error, path.string() + ": write failed: File too large");
}

// Storing into a shared cache on another file system copies the file: the
// copy's failure names the file it wrote and the reason. Needs /dev/shm on
// another device than the tests' temporary folder.
TEST(FeatureCacheWriteError, ACopyIntoTheSharedCacheNamesTheFileAndTheReason) {
  const fs::path root = testing::ProcessTempDir("shared_copy");
  struct stat temp_info, shm_info;
  if (::stat(root.c_str(), &temp_info) != 0 || ::stat("/dev/shm", &shm_info) != 0 ||
      temp_info.st_dev == shm_info.st_dev) {
    GTEST_SKIP() << "/dev/shm is absent or on the temporary folder's device: no copy to fail";
  }
  const fs::path folder = "/dev/shm/duskmap_cache_copy_test_" + std::to_string(::getpid());
  const fs::path cache_file = root / "features.bin";
  std::ofstream(cache_file, std::ios::binary) << std::string(256 * 1024, 'x');
  SharedFeatureCacheOptions options;
  options.folder = folder;
  const SharedFeatureCache cache(options);
  std::string error;
  {
    const FileSizeLimit limit(64 * 1024);
    error = testing::ErrorOf([&] { cache.Store("key", cache_file, ExtractJobSummary{}); });
  }
  const std::string partial = (folder / ("key.partial-" + std::to_string(::getpid())) / "features.bin").string();
  EXPECT_EQ(error, partial + ": write failed: File too large");
  EXPECT_FALSE(fs::exists(folder / "key"));  // nothing half-stored
  EXPECT_FALSE(fs::exists(fs::path(partial).parent_path()));
  fs::remove_all(folder);
}

}  // namespace
}  // namespace duskmap
