#include "slam/experiment/feature_cache.h"

#include <cerrno>
#include <cstring>
#include <system_error>
#include <utility>
#include <vector>

#include "slam/core/check.h"
#include "slam/core/system_error.h"
#include "slam/map/map_codec.h"

namespace duskmap {
namespace {

constexpr char kMagic[8] = {'D', 'U', 'S', 'K', 'F', 'C', '0', '1'};
constexpr char kFrameTag = 'F';
constexpr char kEndTag = 'E';
// Upper bound of one stored field; a larger length means a corrupt file.
constexpr uint64_t kMaxFieldBytes = uint64_t{1} << 32;

template <typename T>
void WritePod(std::ostream& out, const T& value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof(T));
}

void WriteBytes(std::ostream& out, const void* data, uint64_t size) {
  WritePod(out, size);
  if (size > 0) out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
}

void WriteString(std::ostream& out, const std::string& text) {
  WriteBytes(out, text.data(), text.size());
}

void WriteBlob(std::ostream& out, const Blob& blob) { WriteBytes(out, blob.data(), blob.size()); }

// Reads fields of one cache file, naming it in every error.
class FieldReader {
 public:
  FieldReader(std::istream& in, const std::filesystem::path& path) : in_(in), path_(path) {}

  template <typename T>
  T Pod(const char* what) {
    T value{};
    in_.read(reinterpret_cast<char*>(&value), sizeof(T));
    Check(what);
    return value;
  }

  Blob Bytes(const char* what) {
    const uint64_t size = Pod<uint64_t>(what);
    SLAM_THROW_IF_NOT(InputError, size <= kMaxFieldBytes)
        << path_.string() << ": corrupt feature cache (" << what << " claims " << size << " bytes)";
    Blob blob(size);
    if (size > 0) in_.read(reinterpret_cast<char*>(blob.data()), static_cast<std::streamsize>(size));
    Check(what);
    return blob;
  }

  std::string String(const char* what) {
    const Blob blob = Bytes(what);
    return std::string(blob.begin(), blob.end());
  }

  std::string What(const std::string& field) const {
    return path_.string() + ": " + field;
  }

 private:
  void Check(const char* what) {
    SLAM_THROW_IF_NOT(InputError, in_.good())
        << path_.string() << ": truncated feature cache (while reading " << what << ")";
  }

  std::istream& in_;
  const std::filesystem::path& path_;
};

// `path` removed first, so that a file hard-linked to it elsewhere (a shared
// feature cache's entry, shared_feature_cache.h) is replaced, never truncated.
const std::filesystem::path& FreshPath(const std::filesystem::path& path) {
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  return path;
}

}  // namespace

FeatureCacheWriter::FeatureCacheWriter(const std::filesystem::path& path,
                                       const std::string& extractor, const SessionInfo& session)
    : path_(path), out_(FreshPath(path), std::ios::out | std::ios::binary | std::ios::trunc) {
  SLAM_THROW_IF_NOT(InputError, out_.is_open()) << path.string() << ": cannot write: " << LastSystemError();
  errno = 0;
  out_.write(kMagic, sizeof(kMagic));
  WriteString(out_, extractor);
  WriteString(out_, session.name);
  WritePod(out_, static_cast<uint8_t>(session.clock_time.has_value()));
  WriteString(out_, session.clock_time.value_or(""));
  WritePod(out_, static_cast<uint8_t>(session.has_ground_truth));
  count_position_ = out_.tellp();
  WritePod(out_, int64_t{0});  // patched by Close()
  ThrowIfWriteFailed();
}

void FeatureCacheWriter::ThrowIfWriteFailed() const {
  // errno is cleared before each step's writes and read right after them:
  // a full disk reads "No space left on device", not a later call's reason.
  SLAM_THROW_IF_NOT(InputError, out_.good()) << path_.string() << ": write failed: " << LastSystemError();
}

void FeatureCacheWriter::Append(const RgbdFrame& frame, const FrameFeatures& features) {
  SLAM_CHECK(!closed_);
  SLAM_THROW_IF_NOT(InputError, features.points_in_camera.size() == features.size() &&
                                    features.descriptors.rows == static_cast<int>(features.size()))
      << path_.string() << ": frame " << frame.frame_index
      << " has inconsistent features (keypoints, descriptors and points differ in count)";
  errno = 0;
  out_.put(kFrameTag);
  WritePod(out_, frame.frame_index);
  WritePod(out_, frame.timestamp_s);
  WriteBlob(out_, EncodeCamera(frame.camera));
  WriteBlob(out_, EncodePose(frame.body_from_camera));
  WriteBlob(out_, EncodePose(frame.odom_from_body));
  WritePod(out_, static_cast<uint8_t>(frame.world_from_camera.has_value()));
  if (frame.world_from_camera) WriteBlob(out_, EncodePose(*frame.world_from_camera));
  WritePod(out_, static_cast<uint8_t>(features.kind));
  WritePod(out_, static_cast<int32_t>(features.descriptors.rows));
  WritePod(out_, static_cast<int32_t>(features.descriptors.cols));
  WritePod(out_, static_cast<int32_t>(features.descriptors.type()));
  WriteBlob(out_, EncodeKeypoints(features.keypoints));
  WriteBlob(out_, features.descriptors.empty() ? Blob() : EncodeMatrix(features.descriptors));
  WriteBlob(out_, EncodePoints(features.points_in_camera));
  ThrowIfWriteFailed();
  ++num_frames_;
}

void FeatureCacheWriter::Close() {
  SLAM_CHECK(!closed_);
  errno = 0;
  out_.put(kEndTag);
  out_.flush();  // before the seek, whose own flush would not keep the reason
  ThrowIfWriteFailed();
  out_.seekp(count_position_);
  WritePod(out_, num_frames_);
  out_.flush();
  ThrowIfWriteFailed();
  out_.close();
  SLAM_THROW_IF_NOT(InputError, !out_.fail()) << path_.string() << ": write failed: " << LastSystemError();
  closed_ = true;
}

FeatureCacheReader::FeatureCacheReader(const std::filesystem::path& path)
    : path_(path), in_(path, std::ios::in | std::ios::binary) {
  SLAM_THROW_IF_NOT(InputError, in_.is_open()) << path.string() << ": cannot open feature cache";
  char magic[sizeof(kMagic)] = {};
  in_.read(magic, sizeof(magic));
  SLAM_THROW_IF_NOT(InputError, in_.good() && std::memcmp(magic, kMagic, sizeof(kMagic)) == 0)
      << path.string() << ": not a duskmap feature cache (or of another version)";
  FieldReader read(in_, path_);
  extractor_ = read.String("extractor");
  info_.name = read.String("session name");
  const bool has_clock = read.Pod<uint8_t>("clock flag") != 0;
  const std::string clock = read.String("clock time");
  if (has_clock) info_.clock_time = clock;
  info_.has_ground_truth = read.Pod<uint8_t>("ground-truth flag") != 0;
  info_.num_frames = read.Pod<int64_t>("frame count");
}

std::optional<RgbdFrame> FeatureCacheReader::Next(std::optional<FrameFeatures>* features) {
  features->reset();
  if (done_) return std::nullopt;
  FieldReader read(in_, path_);
  const char tag = read.Pod<char>("frame tag");
  if (tag == kEndTag) {
    done_ = true;
    SLAM_THROW_IF_NOT(InputError, frames_read_ == info_.num_frames)
        << path_.string() << ": feature cache holds " << frames_read_ << " frames, header says "
        << info_.num_frames;
    return std::nullopt;
  }
  SLAM_THROW_IF_NOT(InputError, tag == kFrameTag)
      << path_.string() << ": corrupt feature cache (bad tag after frame " << frames_read_ << ")";
  RgbdFrame frame;
  frame.frame_index = read.Pod<int64_t>("frame index");
  frame.timestamp_s = read.Pod<double>("timestamp");
  const std::string what = read.What("frame " + std::to_string(frame.frame_index));
  frame.camera = DecodeCamera(read.Bytes("camera"), what + " camera");
  frame.body_from_camera = DecodePose(read.Bytes("extrinsics"), what + " body_from_camera");
  frame.odom_from_body = DecodePose(read.Bytes("odometry"), what + " odom_from_body");
  if (read.Pod<uint8_t>("truth flag") != 0) {
    frame.world_from_camera = DecodePose(read.Bytes("truth"), what + " world_from_camera");
  }
  FrameFeatures f;
  const uint8_t kind = read.Pod<uint8_t>("descriptor kind");
  SLAM_THROW_IF_NOT(InputError, kind <= static_cast<uint8_t>(DescriptorKind::kBinary))
      << what << ": unknown descriptor kind " << int(kind);
  f.kind = static_cast<DescriptorKind>(kind);
  const int32_t rows = read.Pod<int32_t>("descriptor rows");
  const int32_t cols = read.Pod<int32_t>("descriptor cols");
  const int32_t type = read.Pod<int32_t>("descriptor type");
  f.keypoints = DecodeKeypoints(read.Bytes("keypoints"), what + " keypoints");
  const Blob descriptors = read.Bytes("descriptors");
  if (rows > 0) f.descriptors = DecodeMatrix(descriptors, rows, cols, type, what + " descriptors");
  f.points_in_camera = DecodePoints(read.Bytes("points"), what + " points");
  SLAM_THROW_IF_NOT(InputError, f.points_in_camera.size() == f.keypoints.size() &&
                                    static_cast<size_t>(rows) == f.keypoints.size())
      << what << ": keypoints, descriptors and points differ in count";
  ++frames_read_;
  *features = std::move(f);
  return frame;
}

}  // namespace duskmap
