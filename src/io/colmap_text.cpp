// Line-by-line parsing and writing of COLMAP's text model files.
#include "io/colmap_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <string_view>
#include <unordered_set>

#include "core/error.h"
#include "core/printable_text.h"
#include "io/colmap_records.h"

namespace glint {

namespace {

// The lines of a file with their 1-based numbers; '\r' of Windows line ends is dropped.
class LineReader {
 public:
  explicit LineReader(const std::string& text) : text_(text) {}

  // The next line, or false at the end of the text.
  bool next(std::string_view* line) {
    if (pos_ >= text_.size()) return false;
    size_t end = text_.find('\n', pos_);
    if (end == std::string::npos) end = text_.size();
    std::string_view view(text_.data() + pos_, end - pos_);
    if (!view.empty() && view.back() == '\r') view.remove_suffix(1);
    pos_ = end + 1;
    ++number_;
    *line = view;
    return true;
  }
  // The next line that is neither blank nor a '#' comment.
  bool nextData(std::string_view* line) {
    while (next(line)) {
      std::string_view trimmed = trim(*line);
      if (!trimmed.empty() && trimmed.front() != '#') {
        *line = trimmed;
        return true;
      }
    }
    return false;
  }
  int number() const { return number_; }

  static std::string_view trim(std::string_view s) {
    size_t first = s.find_first_not_of(" \t");
    if (first == std::string_view::npos) return {};
    size_t last = s.find_last_not_of(" \t");
    return s.substr(first, last - first + 1);
  }

 private:
  const std::string& text_;
  size_t pos_ = 0;
  int number_ = 0;
};

// Whitespace-separated fields of one line, converted with messages that name the line.
class Fields {
 public:
  Fields(std::string_view line, const std::string& fileName, int lineNumber)
      : line_(line), fileName_(fileName), lineNumber_(lineNumber) {}

  [[noreturn]] void fail(const std::string& problem) const {
    throw Error(fileName_, "line " + std::to_string(lineNumber_) + ": " + problem);
  }
  bool atEnd() {
    skipSpace();
    return pos_ >= line_.size();
  }
  std::string_view word(const char* what) {
    skipSpace();
    if (pos_ >= line_.size()) fail(std::string(what) + " is missing");
    size_t end = line_.find_first_of(" \t", pos_);
    if (end == std::string_view::npos) end = line_.size();
    std::string_view w = line_.substr(pos_, end - pos_);
    pos_ = end;
    return w;
  }
  // Everything left on the line, trimmed (image names may hold spaces).
  std::string_view rest(const char* what) {
    std::string_view r = LineReader::trim(line_.substr(std::min(pos_, line_.size())));
    if (r.empty()) fail(std::string(what) + " is missing");
    pos_ = line_.size();
    return r;
  }
  template <typename T>
  T integer(const char* what) {
    std::string_view w = word(what);
    T value{};
    auto [end, error] = std::from_chars(w.data(), w.data() + w.size(), value);
    if (error != std::errc() || end != w.data() + w.size())
      fail(std::string(what) + " \"" + printableText(w) + "\" is not an integer in range");
    return value;
  }
  double number(const char* what) {
    std::string_view w = word(what);
    double value = 0;
    auto [end, error] = std::from_chars(w.data(), w.data() + w.size(), value);
    if (error != std::errc() || end != w.data() + w.size())
      fail(std::string(what) + " \"" + printableText(w) + "\" is not a number");
    // from_chars reads "nan" and "inf"; no model holds them.
    if (!std::isfinite(value)) fail(std::string(what) + " is not a finite number");
    return value;
  }

 private:
  void skipSpace() {
    while (pos_ < line_.size() && (line_[pos_] == ' ' || line_[pos_] == '\t')) ++pos_;
  }
  std::string_view line_;
  const std::string& fileName_;
  int lineNumber_;
  size_t pos_ = 0;
};

// Shortest text that reads back as exactly the same double.
std::string exact(double value) {
  char buffer[32];
  auto [end, error] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, end);
}

// Appends fields separated by single spaces (a space before each but a line's first).
void appendFields(std::string& out, std::initializer_list<std::string> fields) {
  for (const std::string& field : fields) {
    if (!out.empty() && out.back() != '\n') out += ' ';
    out += field;
  }
}

}  // namespace

std::vector<int> colmapTextRecordLines(const std::string& text) {
  std::vector<int> numbers;
  LineReader lines(text);
  std::string_view line;
  while (lines.nextData(&line)) numbers.push_back(lines.number());
  return numbers;
}

std::vector<ColmapCamera> parseColmapCamerasText(const std::string& text, const std::string& fileName) {
  std::vector<ColmapCamera> cameras;
  std::unordered_set<uint32_t> ids;
  LineReader lines(text);
  std::string_view line;
  while (lines.nextData(&line)) {
    Fields fields(line, fileName, lines.number());
    ColmapCamera camera;
    camera.id = fields.integer<uint32_t>("CAMERA_ID");
    camera.model = std::string(fields.word("MODEL"));
    const std::string_view width = fields.word("WIDTH"), height = fields.word("HEIGHT");
    // Checked as text, so that the message quotes the size as written.
    const std::string sizeProblem = colmapImageSizeProblem(width, height);
    if (!sizeProblem.empty()) fields.fail("camera " + std::to_string(camera.id) + ": " + sizeProblem);
    camera.width = std::stoi(std::string(width)), camera.height = std::stoi(std::string(height));
    while (!fields.atEnd()) {
      if (camera.params.size() >= 64) fields.fail("more than 64 camera parameters");
      camera.params.push_back(fields.number("camera parameter"));
    }
    std::string problem = colmapCameraProblem(camera);
    if (!problem.empty()) fields.fail("camera " + std::to_string(camera.id) + ": " + problem);
    if (!ids.insert(camera.id).second) fields.fail("camera id " + std::to_string(camera.id) + " is used twice");
    cameras.push_back(std::move(camera));
  }
  return cameras;
}

std::vector<ColmapImage> parseColmapImagesText(const std::string& text, const std::string& fileName) {
  std::vector<ColmapImage> images;
  std::unordered_set<uint32_t> ids;
  std::unordered_set<std::string> names;
  LineReader lines(text);
  std::string_view line;
  while (lines.nextData(&line)) {
    Fields fields(line, fileName, lines.number());
    ColmapImage image;
    image.id = fields.integer<uint32_t>("IMAGE_ID");
    image.qvec.w = fields.number("QW");
    image.qvec.x = fields.number("QX");
    image.qvec.y = fields.number("QY");
    image.qvec.z = fields.number("QZ");
    image.tvec.x = fields.number("TX");
    image.tvec.y = fields.number("TY");
    image.tvec.z = fields.number("TZ");
    image.cameraId = fields.integer<uint32_t>("CAMERA_ID");
    image.name = std::string(fields.rest("NAME"));
    std::string problem = colmapImageProblem(image);
    std::string which = "image " + std::to_string(image.id) + ": ";
    if (!problem.empty()) fields.fail(which + problem);
    if (!ids.insert(image.id).second) fields.fail("image id " + std::to_string(image.id) + " is used twice");
    if (!names.insert(image.name).second)
      fields.fail(which + "the name \"" + printableText(image.name) + "\" is used by an earlier image too");

    // POINTS2D[] as (X, Y, POINT3D_ID): the very next line, even when blank.
    std::string_view points;
    if (lines.next(&points)) {
      Fields point(points, fileName, lines.number());
      while (!point.atEnd()) {
        const std::string count = std::to_string(image.points2D.size());
        ColmapPoint2D p;
        p.xy.x = point.number("2D point X");
        if (point.atEnd()) point.fail(which + "2D point " + count + " has no Y");
        p.xy.y = point.number("2D point Y");
        if (point.atEnd()) point.fail(which + "2D point " + count + " has no POINT3D_ID");
        // -1 marks a point without a 3D point; ids are otherwise unsigned 64-bit.
        std::string_view id = point.word("POINT3D_ID");
        if (id != "-1") {
          uint64_t value = 0;
          auto [end, error] = std::from_chars(id.data(), id.data() + id.size(), value);
          if (error != std::errc() || end != id.data() + id.size())
            point.fail(which + "POINT3D_ID \"" + printableText(id) + "\" is neither -1 nor an unsigned integer");
          p.point3DId = value;
        }
        image.points2D.push_back(p);
      }
    }
    images.push_back(std::move(image));
  }
  return images;
}

std::vector<ColmapPoint> parseColmapPointsText(const std::string& text, const std::string& fileName) {
  std::vector<ColmapPoint> points;
  std::unordered_set<uint64_t> ids;
  LineReader lines(text);
  std::string_view line;
  while (lines.nextData(&line)) {
    Fields fields(line, fileName, lines.number());
    ColmapPoint point;
    point.id = fields.integer<uint64_t>("POINT3D_ID");
    point.xyz.x = fields.number("X");
    point.xyz.y = fields.number("Y");
    point.xyz.z = fields.number("Z");
    point.rgb[0] = fields.integer<uint8_t>("R");
    point.rgb[1] = fields.integer<uint8_t>("G");
    point.rgb[2] = fields.integer<uint8_t>("B");
    point.error = fields.number("ERROR");
    // TRACK[] as (IMAGE_ID, POINT2D_IDX).
    while (!fields.atEnd()) {
      ColmapTrackElement element;
      element.imageId = fields.integer<uint32_t>("track IMAGE_ID");
      if (fields.atEnd()) fields.fail("point " + std::to_string(point.id) + ": the track ends inside a pair");
      element.point2DIndex = fields.integer<uint32_t>("track POINT2D_IDX");
      point.track.push_back(element);
    }
    std::string problem = colmapPointProblem(point);
    if (!problem.empty()) fields.fail("point " + std::to_string(point.id) + ": " + problem);
    if (!ids.insert(point.id).second) fields.fail("point id " + std::to_string(point.id) + " is used twice");
    points.push_back(point);
  }
  return points;
}

// The formatters append piece by piece: GCC 12 warns falsely (-Wrestrict) on
// " " + std::to_string(...) chains.
std::string formatColmapCamerasText(const std::vector<ColmapCamera>& cameras) {
  std::string out =
      "# Camera list with one line of data per camera:\n"
      "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
      "# Number of cameras: ";
  out += std::to_string(cameras.size());
  out += '\n';
  for (const ColmapCamera& camera : cameras) {
    appendFields(out, {std::to_string(camera.id), camera.model, std::to_string(camera.width),
                       std::to_string(camera.height)});
    for (double p : camera.params) appendFields(out, {exact(p)});
    out += '\n';
  }
  return out;
}

std::string formatColmapImagesText(const std::vector<ColmapImage>& images) {
  std::string out =
      "# Image list with two lines of data per image:\n"
      "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
      "#   POINTS2D[] as (X, Y, POINT3D_ID)\n"
      "# Number of images: ";
  out += std::to_string(images.size());
  out += '\n';
  for (const ColmapImage& image : images) {
    const Quatd& q = image.qvec;
    const Vec3d& t = image.tvec;
    appendFields(out, {std::to_string(image.id), exact(q.w), exact(q.x), exact(q.y), exact(q.z), exact(t.x),
                       exact(t.y), exact(t.z), std::to_string(image.cameraId), image.name});
    out += '\n';
    for (const ColmapPoint2D& p : image.points2D)
      appendFields(out, {exact(p.xy.x), exact(p.xy.y),
                         p.point3DId == kColmapNoPoint3D ? std::string("-1") : std::to_string(p.point3DId)});
    out += '\n';
  }
  return out;
}

std::string formatColmapPointsText(const std::vector<ColmapPoint>& points) {
  std::string out =
      "# 3D point list with one line of data per point:\n"
      "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n"
      "# Number of points: ";
  out += std::to_string(points.size());
  out += '\n';
  for (const ColmapPoint& point : points) {
    appendFields(out, {std::to_string(point.id), exact(point.xyz.x), exact(point.xyz.y), exact(point.xyz.z),
                       std::to_string(int(point.rgb[0])), std::to_string(int(point.rgb[1])),
                       std::to_string(int(point.rgb[2])), exact(point.error)});
    for (const ColmapTrackElement& e : point.track)
      appendFields(out, {std::to_string(e.imageId), std::to_string(e.point2DIndex)});
    out += '\n';
  }
  return out;
}

}  // namespace glint
