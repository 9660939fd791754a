// Bounds-checked reading and writing of COLMAP's binary model files.
#include "io/colmap_binary.h"

#include <bit>
#include <cstring>
#include <unordered_set>

#include "core/error.h"
#include "core/printable_text.h"
#include "io/colmap_camera_models.h"
#include "io/colmap_records.h"

namespace glint {

// COLMAP writes little-endian; values are copied byte for byte, which needs the same order.
static_assert(std::endian::native == std::endian::little, "the COLMAP binary reader assumes a little-endian machine");

namespace {

// Smallest possible record of each file: the count check uses it to refuse a count that
// the remaining bytes cannot hold before any vector is sized from it.
constexpr size_t kMinCameraRecord = 4 + 4 + 8 + 8 + 3 * 8;         // id, model, width, height, >= 3 params
constexpr size_t kMinImageRecord = 4 + 7 * 8 + 4 + 2 + 8;          // id, pose, camera, 1-letter name + NUL, count
constexpr size_t kMinPointRecord = 8 + 3 * 8 + 3 + 8 + 8;          // id, xyz, rgb, error, track length
constexpr size_t kPoint2DBytes = 8 + 8 + 8;                        // x, y, point3D id
constexpr size_t kTrackElementBytes = 4 + 4;                       // image id, point2D index

// A cursor over a file's bytes whose every read is checked against the end.
class ByteReader {
 public:
  ByteReader(const std::string& bytes, const std::string& fileName) : bytes_(bytes), fileName_(fileName) {}

  // Starts record `index` (0-based) at the current offset, for messages.
  void beginRecord(uint64_t index) {
    record_ = index;
    recordStart_ = pos_;
    inRecord_ = true;
  }
  [[noreturn]] void fail(const std::string& problem) const {
    std::string where = inRecord_ ? "record " + std::to_string(record_) + " at byte " + std::to_string(recordStart_) + ": "
                                  : "";
    throw Error(fileName_, where + problem);
  }
  size_t remaining() const { return bytes_.size() - pos_; }
  size_t offset() const { return pos_; }

  template <typename T>
  T read(const char* what) {
    need(sizeof(T), what);
    T value;
    std::memcpy(&value, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }
  // Refuses count records of size bytes that the bytes left cannot hold, before anything is
  // allocated for them. count comes from the file: compared by division so that count * size
  // cannot overflow.
  void checkFits(uint64_t count, size_t size, const char* what) {
    if (count > remaining() / size)
      fail(std::to_string(count) + " " + what + " of " + std::to_string(size) + " bytes each do not fit in the " +
           std::to_string(remaining()) + " bytes left (truncated or corrupt file)");
  }
  // A NUL-terminated string.
  std::string readString(const char* what) {
    const char* start = bytes_.data() + pos_;
    const void* nul = std::memchr(start, '\0', remaining());
    if (!nul) fail(std::string(what) + " has no terminating NUL byte (truncated file)");
    size_t length = size_t(static_cast<const char*>(nul) - start);
    pos_ += length + 1;
    return std::string(start, length);
  }
  // The record count at the start of a file, checked against the bytes that follow it.
  uint64_t readCount(size_t minRecordBytes, const char* what) {
    uint64_t count = read<uint64_t>("the record count");
    if (count > remaining() / minRecordBytes)
      fail("the header counts " + std::to_string(count) + " " + what + ", but the " + std::to_string(remaining()) +
           " bytes after it hold at most " + std::to_string(remaining() / minRecordBytes) +
           " (truncated or corrupt file)");
    return count;
  }
  void expectEnd() {
    inRecord_ = false;
    if (remaining() != 0)
      fail(std::to_string(remaining()) + " unexpected bytes after the last record at byte " + std::to_string(pos_));
  }

 private:
  void need(size_t size, const char* what) {
    if (remaining() < size)
      fail(std::string(what) + " needs " + std::to_string(size) + " bytes at byte " + std::to_string(pos_) + ", but " +
           std::to_string(remaining()) + " are left (truncated file)");
  }
  const std::string& bytes_;
  const std::string& fileName_;
  size_t pos_ = 0;
  uint64_t record_ = 0;
  size_t recordStart_ = 0;
  bool inRecord_ = false;
};

// Appends the bytes of a value (little-endian, as on this machine).
template <typename T>
void put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

}  // namespace

std::vector<ColmapCamera> parseColmapCamerasBinary(const std::string& bytes, const std::string& fileName) {
  ByteReader in(bytes, fileName);
  uint64_t count = in.readCount(kMinCameraRecord, "cameras");
  std::vector<ColmapCamera> cameras;
  cameras.reserve(size_t(count));
  std::unordered_set<uint32_t> ids;
  for (uint64_t i = 0; i < count; ++i) {
    in.beginRecord(i);
    ColmapCamera camera;
    camera.id = in.read<uint32_t>("CAMERA_ID");
    int32_t modelId = in.read<int32_t>("the model id");
    uint64_t width = in.read<uint64_t>("WIDTH"), height = in.read<uint64_t>("HEIGHT");
    const ColmapCameraModel* model = findColmapCameraModel(modelId);
    if (!model) in.fail("camera " + std::to_string(camera.id) + ": unknown camera model id " + std::to_string(modelId));
    camera.model = model->name;
    const std::string sizeProblem = colmapImageSizeProblem(std::to_string(width), std::to_string(height));
    if (!sizeProblem.empty()) in.fail("camera " + std::to_string(camera.id) + ": " + sizeProblem);
    camera.width = int(width), camera.height = int(height);
    camera.params.resize(size_t(model->numParams));
    for (double& p : camera.params) p = in.read<double>("a camera parameter");
    std::string problem = colmapCameraProblem(camera);
    if (!problem.empty()) in.fail("camera " + std::to_string(camera.id) + ": " + problem);
    if (!ids.insert(camera.id).second) in.fail("camera id " + std::to_string(camera.id) + " is used twice");
    cameras.push_back(std::move(camera));
  }
  in.expectEnd();
  return cameras;
}

std::vector<ColmapImage> parseColmapImagesBinary(const std::string& bytes, const std::string& fileName) {
  ByteReader in(bytes, fileName);
  uint64_t count = in.readCount(kMinImageRecord, "images");
  std::vector<ColmapImage> images;
  images.reserve(size_t(count));
  std::unordered_set<uint32_t> ids;
  std::unordered_set<std::string> names;
  for (uint64_t i = 0; i < count; ++i) {
    in.beginRecord(i);
    ColmapImage image;
    image.id = in.read<uint32_t>("IMAGE_ID");
    image.qvec.w = in.read<double>("QW");
    image.qvec.x = in.read<double>("QX");
    image.qvec.y = in.read<double>("QY");
    image.qvec.z = in.read<double>("QZ");
    image.tvec.x = in.read<double>("TX");
    image.tvec.y = in.read<double>("TY");
    image.tvec.z = in.read<double>("TZ");
    image.cameraId = in.read<uint32_t>("CAMERA_ID");
    image.name = in.readString("NAME");
    std::string which = "image " + std::to_string(image.id) + ": ";
    std::string problem = colmapImageProblem(image);
    if (!problem.empty()) in.fail(which + problem);
    if (!ids.insert(image.id).second) in.fail("image id " + std::to_string(image.id) + " is used twice");
    if (!names.insert(image.name).second)
      in.fail(which + "the name \"" + printableText(image.name) + "\" is used by an earlier image too");
    // POINTS2D[] as (X, Y, POINT3D_ID), -1 for a keypoint without a 3D point.
    uint64_t points2D = in.read<uint64_t>("the number of 2D points");
    in.checkFits(points2D, kPoint2DBytes, "2D points");
    image.points2D.resize(size_t(points2D));
    for (ColmapPoint2D& p : image.points2D) {
      p.xy.x = in.read<double>("2D point X");
      p.xy.y = in.read<double>("2D point Y");
      p.point3DId = in.read<uint64_t>("POINT3D_ID");
    }
    images.push_back(std::move(image));
  }
  in.expectEnd();
  return images;
}

std::vector<ColmapPoint> parseColmapPointsBinary(const std::string& bytes, const std::string& fileName) {
  ByteReader in(bytes, fileName);
  uint64_t count = in.readCount(kMinPointRecord, "points");
  std::vector<ColmapPoint> points;
  points.reserve(size_t(count));
  std::unordered_set<uint64_t> ids;
  for (uint64_t i = 0; i < count; ++i) {
    in.beginRecord(i);
    ColmapPoint point;
    point.id = in.read<uint64_t>("POINT3D_ID");
    point.xyz.x = in.read<double>("X");
    point.xyz.y = in.read<double>("Y");
    point.xyz.z = in.read<double>("Z");
    for (uint8_t& c : point.rgb) c = in.read<uint8_t>("a colour channel");
    point.error = in.read<double>("ERROR");
    std::string problem = colmapPointProblem(point);
    if (!problem.empty()) in.fail("point " + std::to_string(point.id) + ": " + problem);
    if (!ids.insert(point.id).second) in.fail("point id " + std::to_string(point.id) + " is used twice");
    // TRACK[] as (IMAGE_ID, POINT2D_IDX).
    uint64_t trackLength = in.read<uint64_t>("the track length");
    in.checkFits(trackLength, kTrackElementBytes, "track elements");
    point.track.resize(size_t(trackLength));
    for (ColmapTrackElement& e : point.track) {
      e.imageId = in.read<uint32_t>("track IMAGE_ID");
      e.point2DIndex = in.read<uint32_t>("track POINT2D_IDX");
    }
    points.push_back(point);
  }
  in.expectEnd();
  return points;
}

std::string formatColmapCamerasBinary(const std::vector<ColmapCamera>& cameras) {
  std::string out;
  put<uint64_t>(out, cameras.size());
  for (const ColmapCamera& camera : cameras) {
    const ColmapCameraModel* model = findColmapCameraModel(camera.model);
    GLINT_CHECK(model && int(camera.params.size()) == model->numParams, "camera with an unknown model or parameters");
    put<uint32_t>(out, camera.id);
    put<int32_t>(out, model->id);
    put<uint64_t>(out, uint64_t(camera.width));
    put<uint64_t>(out, uint64_t(camera.height));
    for (double p : camera.params) put<double>(out, p);
  }
  return out;
}

std::string formatColmapImagesBinary(const std::vector<ColmapImage>& images) {
  std::string out;
  put<uint64_t>(out, images.size());
  for (const ColmapImage& image : images) {
    put<uint32_t>(out, image.id);
    for (double v : {image.qvec.w, image.qvec.x, image.qvec.y, image.qvec.z, image.tvec.x, image.tvec.y, image.tvec.z})
      put<double>(out, v);
    put<uint32_t>(out, image.cameraId);
    out.append(image.name.c_str(), image.name.size() + 1);  // with its NUL
    put<uint64_t>(out, image.points2D.size());
    for (const ColmapPoint2D& p : image.points2D) {
      put<double>(out, p.xy.x);
      put<double>(out, p.xy.y);
      put<uint64_t>(out, p.point3DId);
    }
  }
  return out;
}

std::string formatColmapPointsBinary(const std::vector<ColmapPoint>& points) {
  std::string out;
  put<uint64_t>(out, points.size());
  for (const ColmapPoint& point : points) {
    put<uint64_t>(out, point.id);
    for (double v : {point.xyz.x, point.xyz.y, point.xyz.z}) put<double>(out, v);
    for (uint8_t c : point.rgb) put<uint8_t>(out, c);
    put<double>(out, point.error);
    put<uint64_t>(out, point.track.size());
    for (const ColmapTrackElement& e : point.track) {
      put<uint32_t>(out, e.imageId);
      put<uint32_t>(out, e.point2DIndex);
    }
  }
  return out;
}

}  // namespace glint
