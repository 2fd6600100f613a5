#include "slam/features/h5_feature_file.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "slam/features/feature_factory.h"
#include "slam/features/h5_extractor.h"
#include "tests/features/test_images.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

std::string TempPath(const std::string& name) {
  return testing::ProcessTempPath("h5_" + name);
}

using testing::ErrorOf;

std::vector<cv::KeyPoint> SomeKeypoints(int n) {
  std::vector<cv::KeyPoint> keypoints;
  for (int i = 0; i < n; ++i) {
    keypoints.emplace_back(cv::Point2f(10.25f + 3.0f * i, 20.5f + 2.0f * i), 4.0f + i,
                           i % 2 ? -1.0f : 30.0f * i, 1.0f / (1 + i), i % 3);
  }
  return keypoints;
}

cv::Mat SomeDescriptors(int n, int cols, int type) {
  cv::Mat d(n, cols, type);
  cv::randu(d, 0, type == CV_8U ? 256 : 1);
  return d;
}

// Runs Debian's python3 with h5py; false when either is missing.
bool RunPython(const std::string& script) {
  const std::string file = TempPath("script.py");
  std::ofstream(file) << script;
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  return std::system((python + " " + file + " > /dev/null 2>&1").c_str()) == 0;
}

bool HasH5py() { return RunPython("import h5py\n"); }

TEST(H5FeatureFile, RoundTripOfFloatAndBinaryFeaturesInNestedGroups) {
  const std::string path = TempPath("round_trip.h5");
  const std::vector<cv::KeyPoint> keypoints = SomeKeypoints(7);
  const cv::Mat floats = SomeDescriptors(7, 128, CV_32F);
  const cv::Mat bytes = SomeDescriptors(7, 61, CV_8U);
  {
    H5FeatureFile file(path, H5FeatureFile::Mode::kCreate);
    file.Write("1/rgb/60000.000000.png", keypoints, floats, DescriptorKind::kFloat);
    file.Write("1/rgb/60001.000000.png", keypoints, bytes, DescriptorKind::kBinary);
    file.Write("A/rgb/60000.000000.png", {}, cv::Mat(), DescriptorKind::kFloat);
    EXPECT_NE(ErrorOf([&] { file.Write("1/rgb/60000.000000.png", keypoints, floats, DescriptorKind::kFloat); })
                  .find("the image group exists already"),
              std::string::npos);
    file.Close();
  }
  const H5FeatureFile file(path, H5FeatureFile::Mode::kRead);
  EXPECT_TRUE(file.HasImage("1/rgb/60000.000000.png"));
  EXPECT_FALSE(file.HasImage("1/rgb/60002.000000.png"));
  EXPECT_FALSE(file.HasImage("B/rgb/60000.000000.png"));
  const H5ImageFeatures f = file.Read("1/rgb/60000.000000.png", DescriptorKind::kFloat);
  const H5ImageFeatures b = file.Read("1/rgb/60001.000000.png", DescriptorKind::kBinary);
  ASSERT_EQ(f.keypoints.size(), 7u);
  EXPECT_TRUE(f.has_scores);
  for (size_t i = 0; i < keypoints.size(); ++i) {
    EXPECT_EQ(f.keypoints[i].pt, keypoints[i].pt);
    EXPECT_EQ(f.keypoints[i].size, keypoints[i].size);
    EXPECT_EQ(f.keypoints[i].angle, keypoints[i].angle);
    EXPECT_EQ(f.keypoints[i].response, keypoints[i].response);
    EXPECT_EQ(f.keypoints[i].octave, keypoints[i].octave);
  }
  EXPECT_EQ(cv::norm(f.descriptors, floats, cv::NORM_INF), 0.0);
  EXPECT_EQ(b.descriptors.type(), CV_8U);
  EXPECT_EQ(cv::norm(b.descriptors, bytes, cv::NORM_INF), 0.0);
  const H5ImageFeatures none = file.Read("A/rgb/60000.000000.png", DescriptorKind::kFloat);
  EXPECT_TRUE(none.keypoints.empty());
  EXPECT_TRUE(none.descriptors.empty());
}

// A disk that fills up: a file-size limit (RLIMIT_FSIZE, SIGXFSZ ignored)
// refuses writes past 64 KiB with EFBIG, as a full disk refuses them with
// ENOSPC. The error says so; and the process exits cleanly afterwards (HDF5's
// shutdown at exit used to close the failed file again and crash).
TEST(H5FeatureFile, AFailedWriteNamesTheFileAndTheReasonAndTheProcessSurvives) {
  const std::string path = TempPath("size_limited.h5");
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit limited = saved;
  limited.rlim_cur = 64 * 1024;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &limited), 0);
  // Past the limit the descriptors' write fails (or, for data HDF5 holds back,
  // the close); either names the file and the system's reason.
  const std::string error = ErrorOf([&] {
    H5FeatureFile file(path, H5FeatureFile::Mode::kCreate);
    file.Write("1/rgb/60000.000000.png", SomeKeypoints(500), SomeDescriptors(500, 128, CV_32F),
               DescriptorKind::kFloat);
    file.Close();
  });
  setrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_EQ(error.rfind(path + ":", 0), 0u) << error;
  EXPECT_NE(error.find(": File too large"), std::string::npos) << error;
}

TEST(H5FeatureFile, PixelCornerKeypointsAreShiftedToOpenCVsConvention) {
  const std::string path = TempPath("corner.h5");
  {
    H5FeatureFile file(path, H5FeatureFile::Mode::kCreate);
    file.Write("x.png", SomeKeypoints(2), SomeDescriptors(2, 8, CV_32F), DescriptorKind::kFloat);
    file.Close();
  }
  const H5FeatureFile file(path, H5FeatureFile::Mode::kRead);
  const H5ImageFeatures f = file.Read("x.png", DescriptorKind::kFloat, KeypointOrigin::kPixelCorner);
  EXPECT_EQ(f.keypoints[1].pt, cv::Point2f(12.75f, 22.0f));
  EXPECT_EQ(ParseKeypointOrigin("pixel_corner", "f"), KeypointOrigin::kPixelCorner);
  EXPECT_NE(ErrorOf([] { ParseKeypointOrigin("colmap", "features.h5.keypoint_origin"); })
                .find("features.h5.keypoint_origin: 'colmap' unknown"),
            std::string::npos);
}

// A file as hloc's extract_features.py writes it with as_half (float16
// descriptors D x N, float32 keypoints, scores), written by h5py.
TEST(H5FeatureFile, ReadsAFileWrittenByH5pyInHlocsLayout) {
  if (!HasH5py()) GTEST_SKIP() << "python3-h5py is not installed (scripts/setup.sh installs it)";
  const std::string path = TempPath("hloc.h5");
  ASSERT_TRUE(RunPython(
      "import h5py, numpy as np\n"
      "with h5py.File('" + path + "', 'w') as f:\n"
      "    g = f.create_group('1/rgb/60000.000000.png')\n"
      "    g['keypoints'] = np.array([[1.5, 2.0], [100.0, 50.25], [3.0, 4.0]], np.float32)\n"
      "    d = np.arange(3 * 4, dtype=np.float32).reshape(4, 3) / 8.0\n"
      "    g['descriptors'] = d.astype(np.float16)\n"
      "    g['scores'] = np.array([0.5, 0.9, 0.1], np.float32)\n"
      "    g['image_size'] = np.array([640, 480])\n"
      "    b = f.create_group('2/rgb/60000.000000.png')\n"
      "    b['keypoints'] = np.zeros((2, 2), np.float64)\n"
      "    b['descriptors'] = np.array([[1, 2], [255, 0]], np.uint8)\n"));
  const H5FeatureFile file(path, H5FeatureFile::Mode::kRead);
  const H5ImageFeatures f = file.Read("1/rgb/60000.000000.png", DescriptorKind::kFloat);
  ASSERT_EQ(f.keypoints.size(), 3u);
  EXPECT_EQ(f.keypoints[1].pt, cv::Point2f(100.0f, 50.25f));
  EXPECT_FLOAT_EQ(f.keypoints[1].response, 0.9f);
  EXPECT_EQ(f.keypoints[1].angle, -1.0f);  // cv::KeyPoint's defaults without duskmap's fields
  EXPECT_EQ(f.keypoints[1].size, 0.0f);
  ASSERT_EQ(f.descriptors.size(), cv::Size(4, 3));  // N x D
  EXPECT_FLOAT_EQ(f.descriptors.at<float>(1, 2), (2 * 3 + 1) / 8.0f);  // stored d[2][1]
  const H5ImageFeatures b = file.Read("2/rgb/60000.000000.png", DescriptorKind::kBinary);
  ASSERT_EQ(b.descriptors.size(), cv::Size(2, 2));
  EXPECT_EQ(b.descriptors.at<uint8_t>(0, 1), 255);
  EXPECT_FALSE(b.has_scores);
  EXPECT_EQ(b.keypoints[0].response, 0.0f);
}

TEST(H5FeatureFile, BadFilesAndGroupsAreNamedInOneLine) {
  if (!HasH5py()) GTEST_SKIP() << "python3-h5py is not installed (scripts/setup.sh installs it)";
  const std::string path = TempPath("bad.h5");
  ASSERT_TRUE(RunPython(
      "import h5py, numpy as np\n"
      "with h5py.File('" + path + "', 'w') as f:\n"
      "    def add(name, k, d, **extra):\n"
      "        g = f.create_group(name)\n"
      "        g['keypoints'] = k\n"
      "        g['descriptors'] = d\n"
      "        for key, value in extra.items(): g[key] = value\n"
      "    k = np.ones((3, 2), np.float32)\n"
      "    add('n_mismatch', k, np.ones((8, 4), np.float32))\n"
      "    add('wrong_dtype', k, np.ones((8, 3), np.uint8))\n"
      "    add('nan_keypoint', np.array([[1, 1], [np.nan, 2], [3, 3]], np.float32), np.ones((8, 3), np.float32))\n"
      "    add('nan_descriptor', k, np.full((8, 3), np.nan, np.float32))\n"
      "    add('three_columns', np.ones((3, 3), np.float32), np.ones((8, 3), np.float32))\n"
      "    add('short_scores', k, np.ones((8, 3), np.float32), scores=np.ones(2, np.float32))\n"
      "    g = f.create_group('no_descriptors')\n"
      "    g['keypoints'] = k\n"));
  const H5FeatureFile file(path, H5FeatureFile::Mode::kRead);
  const auto read = [&](const std::string& group, DescriptorKind kind = DescriptorKind::kFloat) {
    return ErrorOf([&] { file.Read(group, kind); });
  };
  EXPECT_EQ(read("missing/rgb/1.png"), path + ": missing/rgb/1.png: no such image group");
  EXPECT_EQ(read("no_descriptors"), path + ": no_descriptors: no 'descriptors' dataset");
  EXPECT_EQ(read("n_mismatch"), path + ": n_mismatch/descriptors: must be D x N with N = 3 (the keypoints), got 8 x 4");
  EXPECT_EQ(read("wrong_dtype"), path + ": wrong_dtype/descriptors: descriptor_kind float needs float32 or float16, got uint8");
  EXPECT_EQ(read("n_mismatch", DescriptorKind::kBinary), path + ": n_mismatch/descriptors: must be D x N with N = 3 (the keypoints), got 8 x 4");
  EXPECT_EQ(read("nan_descriptor", DescriptorKind::kBinary), path + ": nan_descriptor/descriptors: descriptor_kind binary needs uint8, got float32");
  EXPECT_EQ(read("nan_keypoint"), path + ": nan_keypoint/keypoints: value 2 is nan");
  EXPECT_EQ(read("nan_descriptor"), path + ": nan_descriptor/descriptors: value 0 is nan");
  EXPECT_EQ(read("three_columns"), path + ": three_columns/keypoints: must be N x 2 (x, y), got 3 x 3");
  EXPECT_EQ(read("short_scores"), path + ": short_scores/scores: scores must have 3 values (one per keypoint), got 2");
}

// Numbers are checked where they enter: infinity in any dataset, float64
// descriptors (the docs name float32 and float16; they were narrowed
// silently), and declared shapes that no file of this size holds (10^11 rows
// made the reader throw bad_alloc) are one-line errors naming the file, the
// dataset and the problem.
TEST(H5FeatureFile, InfiniteValuesFloat64DescriptorsAndImpossibleShapesAreRefused) {
  if (!HasH5py()) GTEST_SKIP() << "python3-h5py is not installed (scripts/setup.sh installs it)";
  const std::string path = TempPath("numbers.h5");
  ASSERT_TRUE(RunPython(
      "import h5py, numpy as np\n"
      "with h5py.File('" + path + "', 'w') as f:\n"
      "    k = np.ones((3, 2), np.float32)\n"
      "    d = np.ones((8, 3), np.float32)\n"
      "    def add(name, **datasets):\n"
      "        g = f.create_group(name)\n"
      "        for key, value in datasets.items(): g[key] = value\n"
      "    add('inf_keypoint', keypoints=np.array([[1, 1], [2, 2], [3, -np.inf]], np.float32), descriptors=d)\n"
      "    add('inf_score', keypoints=k, descriptors=d, scores=np.array([0.5, np.inf, 1], np.float32))\n"
      "    add('nan_size', keypoints=k, descriptors=d, keypoint_sizes=np.array([1, 2, np.nan], np.float32))\n"
      "    add('inf_descriptor', keypoints=k, descriptors=np.full((8, 3), np.inf, np.float16))\n"
      "    add('float64_nan_keypoint', keypoints=np.array([[1, 1], [np.nan, 2], [3, 3]]), descriptors=d)\n"
      "    add('float64_descriptors', keypoints=k, descriptors=np.ones((8, 3), np.float64))\n"
      "    add('float16_descriptors', keypoints=k, descriptors=np.ones((8, 3), np.float16))\n"
      "    g = f.create_group('huge_rows')\n"
      "    g.create_dataset('keypoints', shape=(10**11, 2), dtype='f4')\n"
      "    g['descriptors'] = d\n"
      "    g = f.create_group('huge_descriptors')\n"
      "    g['keypoints'] = k\n"
      "    g.create_dataset('descriptors', shape=(10**9, 3), dtype='f4')\n"
      "    g = f.create_group('huge_compressed')\n"
      "    g.create_dataset('keypoints', shape=(10**11, 2), dtype='f4', chunks=(4096, 2), compression='gzip')\n"
      "    g['descriptors'] = d\n"));
  const H5FeatureFile file(path, H5FeatureFile::Mode::kRead);
  const auto read = [&](const std::string& group) {
    return ErrorOf([&] { file.Read(group, DescriptorKind::kFloat); });
  };
  EXPECT_EQ(read("inf_keypoint"), path + ": inf_keypoint/keypoints: value 5 is -inf");
  EXPECT_EQ(read("inf_score"), path + ": inf_score/scores: value 1 is inf");
  EXPECT_EQ(read("nan_size"), path + ": nan_size/keypoint_sizes: value 2 is nan");
  EXPECT_EQ(read("inf_descriptor"), path + ": inf_descriptor/descriptors: value 0 is inf");
  EXPECT_EQ(read("float64_nan_keypoint"), path + ": float64_nan_keypoint/keypoints: value 2 is nan");
  EXPECT_EQ(read("float64_descriptors"),
            path + ": float64_descriptors/descriptors: descriptor_kind float needs float32 or "
                   "float16, got float64");
  EXPECT_EQ(read("float16_descriptors"), "");
  const std::string huge = read("huge_rows");
  EXPECT_EQ(huge.rfind(path + ": huge_rows/keypoints: declares 100000000000 x 2 values, more than "
                              "an image's features could need", 0),
            0u)
      << huge;
  EXPECT_EQ(read("huge_compressed").rfind(path + ": huge_compressed/keypoints: declares "
                                                 "100000000000 x 2 values",
                                          0),
            0u)
      << read("huge_compressed");
  const std::string descriptors = read("huge_descriptors");
  EXPECT_EQ(descriptors.rfind(path + ": huge_descriptors/descriptors: declares 1000000000 x 3 "
                                     "values, more than an image's features could need",
                              0),
            0u)
      << descriptors;
}

TEST(H5FeatureFile, DeclaredShapesBeyondTheFileSizeAreRefusedBeforeAllocating) {
  if (!HasH5py()) GTEST_SKIP() << "python3-h5py is not installed (scripts/setup.sh installs it)";
  const std::string path = TempPath("unwritten.h5");
  // 10^7 x 2 float32 keypoints (80 MB) declared, never written: the file is a few kB.
  ASSERT_TRUE(RunPython(
      "import h5py, numpy as np\n"
      "with h5py.File('" + path + "', 'w') as f:\n"
      "    g = f.create_group('img')\n"
      "    g.create_dataset('keypoints', shape=(10**7, 2), dtype='f4')\n"
      "    g['descriptors'] = np.ones((8, 1), np.float32)\n"));
  const H5FeatureFile file(path, H5FeatureFile::Mode::kRead);
  const std::string error = ErrorOf([&] { file.Read("img", DescriptorKind::kFloat); });
  EXPECT_EQ(error.rfind(path + ": img/keypoints: declares 10000000 x 2 values of float32 (80000000 "
                               "bytes), more than the whole file holds (",
                        0),
            0u)
      << error;
  EXPECT_NE(error.find(" bytes); the file is damaged or was not written to the end"), std::string::npos)
      << error;
}

TEST(H5FeatureFile, MissingTruncatedAndForeignFilesAreRefused) {
  const std::string missing = TempPath("missing.h5");
  EXPECT_EQ(ErrorOf([&] { H5FeatureFile(missing, H5FeatureFile::Mode::kRead); }),
            missing + ": feature file not found");
  const std::string text = TempPath("text.h5");
  std::ofstream(text) << "keypoints,descriptors\n1,2\n";
  EXPECT_EQ(ErrorOf([&] { H5FeatureFile(text, H5FeatureFile::Mode::kRead); }), text + ": not an HDF5 file");
  const std::string whole = TempPath("whole.h5");
  {
    H5FeatureFile file(whole, H5FeatureFile::Mode::kCreate);
    for (int i = 0; i < 20; ++i) {
      file.Write("rgb/" + std::to_string(i) + ".png", SomeKeypoints(50), SomeDescriptors(50, 128, CV_32F),
                 DescriptorKind::kFloat);
    }
    file.Close();
  }
  const std::string cut = TempPath("cut.h5");
  fs::copy_file(whole, cut, fs::copy_options::overwrite_existing);
  fs::resize_file(cut, fs::file_size(whole) / 2);
  const std::string error = ErrorOf([&] {
    const H5FeatureFile file(cut, H5FeatureFile::Mode::kRead);
    for (int i = 0; i < 20; ++i) file.Read("rgb/" + std::to_string(i) + ".png", DescriptorKind::kFloat);
  });
  EXPECT_EQ(error, cut + ": cannot be opened as HDF5 (truncated or damaged)");
}

RgbdFrame FrameOf(const std::string& session, const std::string& image_name) {
  RgbdFrame frame;
  frame.bgr = testing::TexturedImage(160, 120, 3);
  cv::cvtColor(frame.bgr, frame.bgr, cv::COLOR_GRAY2BGR);
  frame.depth_m = cv::Mat(120, 160, CV_32F, cv::Scalar(2.0f));
  frame.camera.width = 160;
  frame.camera.height = 120;
  frame.camera.fx = frame.camera.fy = 100.0;
  frame.camera.cx = 79.5;
  frame.camera.cy = 59.5;
  frame.session = session;
  frame.image_name = image_name;
  return frame;
}

// Features written from a built-in type and imported back are that type's
// features, bit for bit, 3D points included; max_features keeps the best scores.
TEST(H5FeatureExtractor, ImportsExactlyWhatABuiltInTypeExported) {
  FeatureOptions sift;
  sift.type = "sift";
  const std::unique_ptr<FeatureExtractor> builtin = CreateFeatureExtractor(sift);
  const RgbdFrame frame = FrameOf("1", "rgb/60000.000000.png");
  const FrameFeatures expected = builtin->ExtractFrame(frame);
  ASSERT_GT(expected.size(), 20u);
  const std::string path = TempPath("exported.h5");
  {
    H5FeatureFile file(path, H5FeatureFile::Mode::kCreate);
    file.Write("1/rgb/60000.000000.png", expected.keypoints, expected.descriptors, expected.kind);
    file.Close();
  }
  FeatureOptions h5;
  h5.type = "h5";
  h5.h5.path = path;
  const FrameFeatures imported = CreateFeatureExtractor(h5)->ExtractFrame(frame);
  ASSERT_EQ(imported.size(), expected.size());
  EXPECT_EQ(imported.kind, DescriptorKind::kFloat);
  EXPECT_EQ(cv::norm(imported.descriptors, expected.descriptors, cv::NORM_INF), 0.0);
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(imported.keypoints[i].pt, expected.keypoints[i].pt);
    EXPECT_EQ(imported.keypoints[i].response, expected.keypoints[i].response);
    EXPECT_EQ(imported.keypoints[i].angle, expected.keypoints[i].angle);
    EXPECT_EQ(imported.points_in_camera[i], expected.points_in_camera[i]);
  }
  h5.max_features = 10;
  h5.vocabulary_features = 10;
  const FrameFeatures strongest = CreateFeatureExtractor(h5)->ExtractFrame(frame);
  ASSERT_EQ(strongest.size(), 10u);
  EXPECT_EQ(strongest.keypoints[9].pt, expected.keypoints[9].pt);
}

TEST(H5FeatureExtractor, PerSessionFilesInAFolder) {
  const std::string folder = TempPath("per_session");
  fs::create_directories(folder);
  {
    H5FeatureFile file(folder + "/A.h5", H5FeatureFile::Mode::kCreate);
    file.Write("rgb/1.png", SomeKeypoints(3), SomeDescriptors(3, 32, CV_8U), DescriptorKind::kBinary);
    file.Close();
  }
  FeatureOptions o;
  o.type = "h5";
  o.h5.path = folder;
  o.h5.descriptor_kind = "binary";
  const std::unique_ptr<FeatureExtractor> extractor = CreateFeatureExtractor(o);
  const FrameFeatures f = extractor->ExtractFrame(FrameOf("A", "rgb/1.png"));
  EXPECT_EQ(f.size(), 3u);
  EXPECT_EQ(f.kind, DescriptorKind::kBinary);
  EXPECT_TRUE(f.HasPoint(0));
  EXPECT_EQ(ErrorOf([&] { extractor->ExtractFrame(FrameOf("B", "rgb/1.png")); }),
            folder + "/B.h5: feature file not found");
}

TEST(H5FeatureExtractor, RefusesKeypointsOutsideTheImageFramesWithoutNamesAndBareImages) {
  const std::string path = TempPath("outside.h5");
  {
    H5FeatureFile file(path, H5FeatureFile::Mode::kCreate);
    std::vector<cv::KeyPoint> keypoints = SomeKeypoints(3);
    keypoints[2].pt = cv::Point2f(160.0f, 5.0f);
    file.Write("1/rgb/1.png", keypoints, SomeDescriptors(3, 16, CV_32F), DescriptorKind::kFloat);
    file.Close();
  }
  FeatureOptions o;
  o.type = "h5";
  o.h5.path = path;
  const std::unique_ptr<FeatureExtractor> extractor = CreateFeatureExtractor(o);
  EXPECT_EQ(ErrorOf([&] { extractor->ExtractFrame(FrameOf("1", "rgb/1.png")); }),
            path + ": 1/rgb/1.png/keypoints: keypoint 2 at (160, 5) is outside the 160x120 image "
                   "(pixel_centre convention)");
  EXPECT_NE(ErrorOf([&] { extractor->ExtractFrame(FrameOf("1", "")); }).find("has no image name"),
            std::string::npos);
  EXPECT_EQ(ErrorOf([&] { extractor->Extract(testing::TexturedImage(160, 120, 3)); }),
            "features.type h5: its features are read per dataset frame (session and image name), "
            "not from an image");
  o.h5.descriptor_kind = "binary";
  EXPECT_EQ(ErrorOf([&] { CreateFeatureExtractor(o)->ExtractFrame(FrameOf("1", "rgb/1.png")); }),
            path + ": 1/rgb/1.png/descriptors: descriptor_kind binary needs uint8, got float32");
  o.h5.path = "";
  EXPECT_NE(ErrorOf([&] { CreateFeatureExtractor(o); }).find("features.h5.path:"), std::string::npos);
  o.h5.path = path;
  o.h5.descriptor_kind = "half";
  EXPECT_NE(ErrorOf([&] { CreateFeatureExtractor(o); }).find("features.h5.descriptor_kind: 'half' unknown"),
            std::string::npos);
}

}  // namespace
}  // namespace duskmap
