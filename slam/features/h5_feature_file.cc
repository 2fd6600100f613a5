#include "slam/features/h5_feature_file.h"

#include <hdf5.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <sstream>
#include <system_error>
#include <type_traits>

#include "slam/core/check.h"
#include "slam/core/system_error.h"

namespace duskmap {
namespace {

static_assert(std::is_same_v<hid_t, int64_t>, "H5FeatureFile stores hid_t as int64_t");

std::mutex& H5Mutex() {
  // Before any other HDF5 call: no library shutdown at process exit. A file
  // whose close failed (a full disk) stays in HDF5's tables, and the shutdown
  // closing it again crashed the process after its error message; the
  // operating system releases what is left instead.
  static std::mutex* mutex = [] {
    H5dont_atexit();
    return new std::mutex;
  }();
  return *mutex;
}

// Every entry point holds the lock and silences HDF5's printing of its error
// stack (the library never prints; errors become InputError messages).
class H5Guard {
 public:
  H5Guard() : lock_(H5Mutex()) { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

 private:
  std::lock_guard<std::mutex> lock_;
};

// Closes an HDF5 object when it goes out of scope.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  ~Handle() {
    if (id_ >= 0) closer_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  Closer closer_;
};

// Whether the link `name` ("a/b/c") resolves, checking each parent first (HDF5
// reports an error, not "absent", when a parent is missing).
bool LinkExists(hid_t file, const std::string& name) {
  if (name.empty() || name.front() == '/') return false;
  size_t end = 0;
  while (end != std::string::npos) {
    end = name.find('/', end + 1);
    const std::string prefix = name.substr(0, end);
    if (H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
  }
  return true;
}

std::string TypeText(hid_t type) {
  const size_t bytes = H5Tget_size(type);
  switch (H5Tget_class(type)) {
    case H5T_FLOAT: return "float" + std::to_string(8 * bytes);
    case H5T_INTEGER:
      return (H5Tget_sign(type) == H5T_SGN_NONE ? "uint" : "int") + std::to_string(8 * bytes);
    case H5T_STRING: return "string";
    default: return "a non-numeric type";
  }
}

// One dataset of an image group, opened and described.
class DatasetReader {
 public:
  DatasetReader(hid_t group, const std::string& name, std::string where)
      : where_(std::move(where) + "/" + name),
        id_(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose),
        type_(id_.ok() ? H5Dget_type(id_.get()) : -1, H5Tclose),
        space_(id_.ok() ? H5Dget_space(id_.get()) : -1, H5Sclose) {
    SLAM_THROW_IF_NOT(InputError, id_.ok() && type_.ok() && space_.ok())
        << where_ << ": dataset cannot be opened";
    const int rank = H5Sget_simple_extent_ndims(space_.get());
    SLAM_THROW_IF_NOT(InputError, rank >= 0 && rank <= 2) << where_ << ": has " << rank << " dimensions";
    dims_.resize(rank);
    if (rank > 0) H5Sget_simple_extent_dims(space_.get(), dims_.data(), nullptr);
    RequirePlausibleSize();
  }

  const std::string& where() const { return where_; }
  const std::vector<hsize_t>& dims() const { return dims_; }
  H5T_class_t type_class() const { return H5Tget_class(type_.get()); }
  bool IsUnsignedByte() const {
    return type_class() == H5T_INTEGER && H5Tget_size(type_.get()) == 1 &&
           H5Tget_sign(type_.get()) == H5T_SGN_NONE;
  }
  std::string type_text() const { return TypeText(type_.get()); }
  size_t type_bytes() const { return H5Tget_size(type_.get()); }
  std::string shape_text() const {
    std::ostringstream text;
    for (size_t i = 0; i < dims_.size(); ++i) text << (i ? " x " : "") << dims_[i];
    return dims_.empty() ? "a scalar" : text.str();
  }
  size_t elements() const {
    size_t n = 1;
    for (hsize_t d : dims_) n *= static_cast<size_t>(d);
    return n;
  }

  // Reads every element converted to `memory_type` into `out`.
  void ReadAll(hid_t memory_type, void* out) const {
    if (elements() == 0) return;
    SLAM_THROW_IF_NOT(InputError, H5Dread(id_.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) >= 0)
        << where_ << ": cannot be read (file truncated or damaged)";
  }

  // A numeric dataset of `n` elements, as floats; throws on NaN/infinity.
  std::vector<float> ReadFloats(size_t n, const char* what) const {
    SLAM_THROW_IF_NOT(InputError, dims_.size() == 1 && dims_[0] == n)
        << where_ << ": " << what << " must have " << n << " values (one per keypoint), got "
        << shape_text();
    SLAM_THROW_IF_NOT(InputError, type_class() == H5T_FLOAT || type_class() == H5T_INTEGER)
        << where_ << ": must be numeric, got " << type_text();
    std::vector<float> values(n);
    ReadAll(H5T_NATIVE_FLOAT, values.data());
    RequireFinite(values.data(), n);
    return values;
  }

  // The declared shape is checked before anything is allocated for it: a
  // dataset declaring 10^11 rows made the reader throw bad_alloc. Without
  // compression, the values must fit in the file; with it, in what one
  // image's features could need (kMaxValues).
  void RequirePlausibleSize() const {
    long double values = 1;
    for (hsize_t d : dims_) values *= static_cast<long double>(d);
    SLAM_THROW_IF_NOT(InputError, values <= kMaxValues)
        << where_ << ": declares " << shape_text() << " values, more than an image's features "
        << "could need (at most " << kMaxValues << "); the file is damaged or not hloc's layout";
    hsize_t file_bytes = 0;
    const Handle file(H5Iget_file_id(id_.get()), H5Fclose);
    const Handle create(H5Dget_create_plist(id_.get()), H5Pclose);
    const bool compressed = !create.ok() || H5Pget_nfilters(create.get()) != 0;
    if (compressed || !file.ok() || H5Fget_filesize(file.get(), &file_bytes) < 0) return;
    const long double bytes = values * static_cast<long double>(type_bytes());
    SLAM_THROW_IF_NOT(InputError, bytes <= static_cast<long double>(file_bytes))
        << where_ << ": declares " << shape_text() << " values of " << type_text() << " ("
        << static_cast<uint64_t>(bytes) << " bytes), more than the whole file holds ("
        << file_bytes << " bytes); the file is damaged or was not written to the end";
  }

  // 2^27 values (512 MiB as float32): 500,000 keypoints of 256 dimensions.
  static constexpr size_t kMaxValues = size_t{1} << 27;

  void RequireFinite(const float* values, size_t n) const {
    for (size_t i = 0; i < n; ++i) {
      SLAM_THROW_IF_NOT(InputError, std::isfinite(values[i]))
          << where_ << ": value " << i << " is " << values[i];
    }
  }

 private:
  std::string where_;
  Handle id_;
  Handle type_;
  Handle space_;
  std::vector<hsize_t> dims_;
};

void WriteDataset(hid_t group, const char* name, hid_t file_type, hid_t memory_type,
                  std::vector<hsize_t> dims, const void* data, const std::string& where) {
  errno = 0;  // a failure's reason is the system's only if a system call set it here
  const Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
  const Handle dataset(space.ok() ? H5Dcreate2(group, name, file_type, space.get(), H5P_DEFAULT,
                                               H5P_DEFAULT, H5P_DEFAULT)
                                  : -1,
                       H5Dclose);
  bool empty = false;
  for (hsize_t d : dims) empty = empty || d == 0;
  SLAM_THROW_IF_NOT(InputError, dataset.ok() &&
                                    (empty || H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL,
                                                       H5P_DEFAULT, data) >= 0))
      << where << "/" << name << ": cannot be written: " << LastSystemError();
}

// The descriptors of an image's `n` keypoints, one row each: its D x N
// "descriptors" dataset read as `kind` (float32 or float16 as CV_32F, uint8
// as CV_8U); empty without keypoints.
cv::Mat ReadDescriptorRows(hid_t group, const std::string& where, DescriptorKind kind, size_t n) {
  const DatasetReader descriptors(group, "descriptors", where);
  SLAM_THROW_IF_NOT(InputError, descriptors.dims().size() == 2 && descriptors.dims()[1] == n &&
                                    (descriptors.dims()[0] >= 1 || n == 0))
      << descriptors.where() << ": must be D x N with N = " << n << " (the keypoints), got "
      << descriptors.shape_text();
  const int d = static_cast<int>(descriptors.dims()[0]);
  cv::Mat by_column;  // D x N, as stored
  if (kind == DescriptorKind::kFloat) {
    // float64 is refused, not narrowed: the docs and hloc's layout name
    // float32 and float16, and silently narrowing hid a file's wrong type.
    SLAM_THROW_IF_NOT(InputError, descriptors.type_class() == H5T_FLOAT &&
                                      (descriptors.type_bytes() == 4 || descriptors.type_bytes() == 2))
        << descriptors.where() << ": descriptor_kind float needs float32 or float16, got "
        << descriptors.type_text();
    by_column.create(d, static_cast<int>(n), CV_32F);
    descriptors.ReadAll(H5T_NATIVE_FLOAT, by_column.data);
    descriptors.RequireFinite(by_column.ptr<float>(), by_column.total());
  } else {
    SLAM_THROW_IF_NOT(InputError, descriptors.IsUnsignedByte())
        << descriptors.where() << ": descriptor_kind binary needs uint8, got "
        << descriptors.type_text();
    by_column.create(d, static_cast<int>(n), CV_8U);
    descriptors.ReadAll(H5T_NATIVE_UINT8, by_column.data);
  }
  if (n == 0) return cv::Mat();
  return by_column.t();
}

}  // namespace

const char* KeypointOriginName(KeypointOrigin origin) {
  return origin == KeypointOrigin::kPixelCorner ? "pixel_corner" : "pixel_centre";
}

KeypointOrigin ParseKeypointOrigin(const std::string& name, const std::string& field) {
  if (name == "pixel_centre") return KeypointOrigin::kPixelCentre;
  SLAM_THROW_IF_NOT(ConfigError, name == "pixel_corner")
      << field << ": '" << name
      << "' unknown (pixel_centre: OpenCV and hloc; pixel_corner: COLMAP)";
  return KeypointOrigin::kPixelCorner;
}

H5FeatureFile::H5FeatureFile(const std::string& path, Mode mode) : path_(path) {
  const H5Guard guard;
  if (mode == Mode::kCreate) {
    file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    SLAM_THROW_IF_NOT(InputError, file_ >= 0) << path << ": cannot create the HDF5 file";
    return;
  }
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  SLAM_THROW_IF_NOT(InputError, status.type() != std::filesystem::file_type::not_found)
      << path << ": feature file not found";
  SLAM_THROW_IF_NOT(InputError, !error) << path << ": " << error.message();
  SLAM_THROW_IF_NOT(InputError, status.type() == std::filesystem::file_type::regular)
      << path << ": not a file";
  SLAM_THROW_IF_NOT(InputError, H5Fis_hdf5(path.c_str()) > 0) << path << ": not an HDF5 file";
  file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  SLAM_THROW_IF_NOT(InputError, file_ >= 0)
      << path << ": cannot be opened as HDF5 (truncated or damaged)";
}

H5FeatureFile::~H5FeatureFile() {
  if (file_ < 0) return;
  const H5Guard guard;
  H5Fclose(file_);
}

void H5FeatureFile::Close() {
  if (file_ < 0) return;
  const H5Guard guard;
  errno = 0;
  const bool flushed = H5Fflush(file_, H5F_SCOPE_GLOBAL) >= 0;
  const bool closed = H5Fclose(file_) >= 0;
  file_ = -1;
  SLAM_THROW_IF_NOT(InputError, flushed && closed)
      << path_ << ": cannot write the HDF5 file to the end: " << LastSystemError();
}

bool H5FeatureFile::HasImage(const std::string& image) const {
  const H5Guard guard;
  return LinkExists(file_, image);
}

H5ImageFeatures H5FeatureFile::Read(const std::string& image, DescriptorKind kind,
                                    KeypointOrigin origin) const {
  const H5Guard guard;
  const std::string where = path_ + ": " + image;
  SLAM_THROW_IF_NOT(InputError, LinkExists(file_, image)) << where << ": no such image group";
  const Handle group(H5Gopen2(file_, image.c_str(), H5P_DEFAULT), H5Gclose);
  SLAM_THROW_IF_NOT(InputError, group.ok()) << where << ": not a group (or damaged)";
  for (const char* name : {"keypoints", "descriptors"}) {
    SLAM_THROW_IF_NOT(InputError, H5Lexists(group.get(), name, H5P_DEFAULT) > 0)
        << where << ": no '" << name << "' dataset";
  }

  const DatasetReader keypoints(group.get(), "keypoints", where);
  SLAM_THROW_IF_NOT(InputError, keypoints.dims().size() == 2 && keypoints.dims()[1] == 2)
      << keypoints.where() << ": must be N x 2 (x, y), got " << keypoints.shape_text();
  SLAM_THROW_IF_NOT(InputError, keypoints.type_class() == H5T_FLOAT)
      << keypoints.where() << ": must be float, got " << keypoints.type_text();
  const size_t n = static_cast<size_t>(keypoints.dims()[0]);
  std::vector<float> xy(2 * n);
  keypoints.ReadAll(H5T_NATIVE_FLOAT, xy.data());
  keypoints.RequireFinite(xy.data(), xy.size());

  H5ImageFeatures out;
  out.descriptors = ReadDescriptorRows(group.get(), where, kind, n);

  std::vector<float> scores, sizes, angles;
  std::vector<int32_t> octaves;
  if (H5Lexists(group.get(), "scores", H5P_DEFAULT) > 0) {
    scores = DatasetReader(group.get(), "scores", where).ReadFloats(n, "scores");
    out.has_scores = true;
  }
  if (H5Lexists(group.get(), "keypoint_sizes", H5P_DEFAULT) > 0) {
    sizes = DatasetReader(group.get(), "keypoint_sizes", where).ReadFloats(n, "keypoint_sizes");
  }
  if (H5Lexists(group.get(), "keypoint_angles", H5P_DEFAULT) > 0) {
    angles = DatasetReader(group.get(), "keypoint_angles", where).ReadFloats(n, "keypoint_angles");
  }
  if (H5Lexists(group.get(), "keypoint_octaves", H5P_DEFAULT) > 0) {
    const DatasetReader dataset(group.get(), "keypoint_octaves", where);
    SLAM_THROW_IF_NOT(InputError, dataset.dims().size() == 1 && dataset.dims()[0] == n &&
                                      dataset.type_class() == H5T_INTEGER)
        << dataset.where() << ": must be " << n << " integers, got " << dataset.shape_text()
        << " of " << dataset.type_text();
    octaves.resize(n);
    dataset.ReadAll(H5T_NATIVE_INT32, octaves.data());
  }

  const float shift = origin == KeypointOrigin::kPixelCorner ? -0.5f : 0.0f;
  out.keypoints.resize(n);
  for (size_t i = 0; i < n; ++i) {
    cv::KeyPoint& k = out.keypoints[i];
    k.pt = cv::Point2f(xy[2 * i] + shift, xy[2 * i + 1] + shift);
    if (!scores.empty()) k.response = scores[i];
    if (!sizes.empty()) k.size = sizes[i];
    if (!angles.empty()) k.angle = angles[i];
    if (!octaves.empty()) k.octave = octaves[i];
  }
  return out;
}

void H5FeatureFile::WriteAttribute(const std::string& key, const std::string& value) {
  const H5Guard guard;
  const Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), std::max<size_t>(value.size(), 1));
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  const Handle attribute(H5Acreate2(file_, key.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                         H5Aclose);
  std::string padded = value;
  padded.resize(std::max<size_t>(value.size(), 1), '\0');
  SLAM_THROW_IF_NOT(InputError, attribute.ok() && H5Awrite(attribute.get(), type.get(), padded.data()) >= 0)
      << path_ << ": attribute '" << key << "' cannot be written";
}

std::optional<std::string> H5FeatureFile::ReadAttribute(const std::string& key) const {
  const H5Guard guard;
  if (H5Aexists(file_, key.c_str()) <= 0) return std::nullopt;
  const Handle attribute(H5Aopen(file_, key.c_str(), H5P_DEFAULT), H5Aclose);
  const Handle stored(attribute.ok() ? H5Aget_type(attribute.get()) : -1, H5Tclose);
  if (!stored.ok() || H5Tget_class(stored.get()) != H5T_STRING || H5Tis_variable_str(stored.get()) > 0) {
    return std::nullopt;
  }
  const size_t size = H5Tget_size(stored.get());
  std::string value(size, '\0');
  if (H5Aread(attribute.get(), stored.get(), value.data()) < 0) return std::nullopt;
  value.resize(value.find('\0') == std::string::npos ? size : value.find('\0'));
  return value;
}

void H5FeatureFile::Write(const std::string& image, const std::vector<cv::KeyPoint>& keypoints,
                          const cv::Mat& descriptors, DescriptorKind kind) {
  const H5Guard guard;
  const std::string where = path_ + ": " + image;
  const size_t n = keypoints.size();
  const bool binary = kind == DescriptorKind::kBinary;
  SLAM_THROW_IF_NOT(InputError, descriptors.rows == static_cast<int>(n) &&
                                    (n == 0 || descriptors.type() == (binary ? CV_8U : CV_32F)))
      << where << ": " << n << " keypoints need " << n << (binary ? " uint8" : " float32")
      << " descriptor rows, got " << descriptors.rows << " of OpenCV type " << descriptors.type();
  SLAM_THROW_IF_NOT(InputError, !image.empty() && image.front() != '/' && !LinkExists(file_, image))
      << where << ": the image group exists already (or the name is empty or absolute)";
  const Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(lcpl.get(), 1);
  const Handle group(H5Gcreate2(file_, image.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
                     H5Gclose);
  SLAM_THROW_IF_NOT(InputError, group.ok()) << where << ": the image group cannot be created";

  std::vector<float> xy(2 * n), scores(n), sizes(n), angles(n);
  std::vector<int32_t> octaves(n);
  for (size_t i = 0; i < n; ++i) {
    xy[2 * i] = keypoints[i].pt.x;
    xy[2 * i + 1] = keypoints[i].pt.y;
    scores[i] = keypoints[i].response;
    sizes[i] = keypoints[i].size;
    angles[i] = keypoints[i].angle;
    octaves[i] = keypoints[i].octave;
  }
  const hsize_t rows = n;
  WriteDataset(group.get(), "keypoints", H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, {rows, 2}, xy.data(), where);
  const cv::Mat by_column = n == 0 ? cv::Mat() : cv::Mat(descriptors.t());  // D x N, as hloc stores them
  WriteDataset(group.get(), "descriptors", binary ? H5T_STD_U8LE : H5T_IEEE_F32LE,
               binary ? H5T_NATIVE_UINT8 : H5T_NATIVE_FLOAT,
               {static_cast<hsize_t>(descriptors.cols), rows}, by_column.data, where);
  WriteDataset(group.get(), "scores", H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, {rows}, scores.data(), where);
  WriteDataset(group.get(), "keypoint_sizes", H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, {rows}, sizes.data(), where);
  WriteDataset(group.get(), "keypoint_angles", H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, {rows}, angles.data(), where);
  WriteDataset(group.get(), "keypoint_octaves", H5T_STD_I32LE, H5T_NATIVE_INT32, {rows}, octaves.data(), where);
}

}  // namespace duskmap
