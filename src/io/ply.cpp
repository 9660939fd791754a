// PLY tables: streaming the wanted element of a binary file (either byte order) into float
// columns, handing ASCII files to io/ply_ascii.cpp, and writing one element with per-column types.
#include "io/ply.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/input_file.h"
#include "core/printable_text.h"
#include "io/ply_ascii.h"
#include "io/ply_header.h"

namespace glint {

namespace fs = std::filesystem;

// Values are copied to and from the file with memcpy, which is only right on little-endian
// hosts (big-endian files are byte-swapped first).
static_assert(std::endian::native == std::endian::little, "PLY I/O assumes a little-endian host");

namespace {

double decodeHostValue(const uint8_t* p, PlyType type) {
  switch (type) {
    case PlyType::Int8: { int8_t v; std::memcpy(&v, p, 1); return v; }
    case PlyType::UInt8: return *p;
    case PlyType::Int16: { int16_t v; std::memcpy(&v, p, 2); return v; }
    case PlyType::UInt16: { uint16_t v; std::memcpy(&v, p, 2); return v; }
    case PlyType::Int32: { int32_t v; std::memcpy(&v, p, 4); return v; }
    case PlyType::UInt32: { uint32_t v; std::memcpy(&v, p, 4); return v; }
    case PlyType::Float32: { float v; std::memcpy(&v, p, 4); return v; }
    case PlyType::Float64: { double v; std::memcpy(&v, p, 8); return v; }
  }
  return 0.0;
}

// A value in the file's byte order: a big-endian value is reversed into host order first.
double decodeValue(const uint8_t* p, PlyType type, bool bigEndian) {
  if (!bigEndian) return decodeHostValue(p, type);
  uint8_t swapped[8];
  const size_t size = std::min<size_t>(plyTypeSize(type), sizeof(swapped));  // the bound tells GCC it fits
  for (size_t k = 0; k < size; ++k) swapped[k] = p[size - 1 - k];
  return decodeHostValue(swapped, type);
}

// Rounds and clamps to integer types so that e.g. a colour of 255.4 is stored as 255.
template <typename T>
void encodeAs(double v, uint8_t* out) {
  T value;
  if constexpr (std::is_floating_point_v<T>) {
    value = T(v);
  } else {
    value = T(std::clamp(std::round(v), double(std::numeric_limits<T>::lowest()), double(std::numeric_limits<T>::max())));
  }
  std::memcpy(out, &value, sizeof(T));
}

void encodeValue(double v, PlyType type, uint8_t* out) {
  switch (type) {
    case PlyType::Int8: return encodeAs<int8_t>(v, out);
    case PlyType::UInt8: return encodeAs<uint8_t>(v, out);
    case PlyType::Int16: return encodeAs<int16_t>(v, out);
    case PlyType::UInt16: return encodeAs<uint16_t>(v, out);
    case PlyType::Int32: return encodeAs<int32_t>(v, out);
    case PlyType::UInt32: return encodeAs<uint32_t>(v, out);
    case PlyType::Float32: return encodeAs<float>(v, out);
    case PlyType::Float64: return encodeAs<double>(v, out);
  }
}

// Buffered sequential access to the data section, tracking the absolute file position.
class DataReader {
 public:
  DataReader(std::ifstream& in, uint64_t fileSize) : in_(in), fileSize_(fileSize), position_(uint64_t(in.tellg())) {}

  uint64_t position() const { return position_; }
  uint64_t remaining() const { return fileSize_ - std::min(position_, fileSize_); }

  // Pointer to the next n bytes (valid until the next call), or nullptr if the file ends first.
  const uint8_t* take(size_t n) {
    if (end_ - begin_ < n) {
      if (n > remaining()) return nullptr;
      std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
      end_ -= begin_;
      begin_ = 0;
      if (buffer_.size() < n) buffer_.resize(std::max(n, kChunkBytes));
      size_t want = size_t(std::min<uint64_t>(buffer_.size() - end_, fileSize_ - (position_ + end_)));
      in_.read(reinterpret_cast<char*>(buffer_.data() + end_), std::streamsize(want));
      end_ += size_t(in_.gcount());
      if (end_ < n) return nullptr;
    }
    const uint8_t* p = buffer_.data() + begin_;
    begin_ += n;
    position_ += n;
    return p;
  }

  bool skip(uint64_t n) {
    if (n > remaining()) return false;
    if (n <= end_ - begin_) {
      begin_ += size_t(n);
    } else {
      in_.seekg(std::streamoff(n - (end_ - begin_)), std::ios::cur);
      begin_ = end_ = 0;
    }
    position_ += n;
    return bool(in_);
  }

 private:
  static constexpr size_t kChunkBytes = size_t(1) << 20;
  std::ifstream& in_;
  uint64_t fileSize_;
  uint64_t position_;
  std::vector<uint8_t> buffer_ = std::vector<uint8_t>(kChunkBytes);
  size_t begin_ = 0, end_ = 0;
};

// Skips one list property's items; false if the file ends first.
bool skipList(DataReader& reader, const PlyProperty& property, bool bigEndian, const std::string& path) {
  const uint8_t* p = reader.take(plyTypeSize(property.countType));
  if (!p) return false;
  double count = decodeValue(p, property.countType, bigEndian);
  if (count < 0) throw Error(path, "list property '" + printableText(property.name) + "' has a negative length");
  return reader.skip(uint64_t(count) * plyTypeSize(property.type));
}

void skipElement(DataReader& reader, const PlyElement& element, bool bigEndian, const std::string& path) {
  auto truncated = [&] {
    return Error(path, "truncated: file ends inside element '" + printableText(element.name) + "'");
  };
  if (!element.hasLists()) {
    uint64_t rowSize = element.rowSize();
    if (rowSize > 0 && element.count > reader.remaining() / rowSize) throw truncated();
    reader.skip(element.count * rowSize);
    return;
  }
  for (uint64_t row = 0; row < element.count; ++row) {
    for (const PlyProperty& property : element.properties) {
      bool ok = property.isList ? skipList(reader, property, bigEndian, path) : reader.skip(plyTypeSize(property.type));
      if (!ok) throw truncated();
    }
  }
}

}  // namespace

const char* plyTypeName(PlyType type) {
  switch (type) {
    case PlyType::Int8: return "char";
    case PlyType::UInt8: return "uchar";
    case PlyType::Int16: return "short";
    case PlyType::UInt16: return "ushort";
    case PlyType::Int32: return "int";
    case PlyType::UInt32: return "uint";
    case PlyType::Float32: return "float";
    case PlyType::Float64: return "double";
  }
  return "";
}

size_t plyTypeSize(PlyType type) {
  switch (type) {
    case PlyType::Int8: case PlyType::UInt8: return 1;
    case PlyType::Int16: case PlyType::UInt16: return 2;
    case PlyType::Int32: case PlyType::UInt32: case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 0;
}

int PlyTable::find(std::string_view name) const {
  for (size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return int(i);
  }
  return -1;
}

const std::vector<float>& PlyTable::column(std::string_view name) const {
  int i = find(name);
  if (i < 0) {
    throw Error(source.empty() ? "(PLY table)" : source,
                "element '" + element + "' has no property '" + std::string(name) + "'");
  }
  return columns[size_t(i)];
}

PlyType PlyTable::type(std::string_view name) const {
  column(name);  // throws the missing-property error
  return types[size_t(find(name))];
}

void PlyTable::add(std::string name, std::vector<float> values, PlyType type) {
  if (columns.empty()) count = values.size();
  GLINT_CHECK(values.size() == count, "PLY column '" + name + "' has the wrong length");
  GLINT_CHECK(!has(name), "duplicate PLY column '" + name + "'");
  names.push_back(std::move(name));
  types.push_back(type);
  columns.push_back(std::move(values));
}

void storePlyValue(PlyTable& table, size_t column, size_t row, double value) {
  float f = float(value);
  if (!std::isfinite(f)) {
    std::string what = std::isnan(value) ? "NaN" : std::isinf(value) ? "infinite" : "outside the float range";
    throw Error(table.source, "property '" + printableText(table.names[column]) + "' of " + table.element + " " +
                                  std::to_string(row) + " is " + what);
  }
  table.columns[column][row] = f;
}

namespace {

// The rows of the target element of a binary file; the reader stands at its first byte.
void readBinaryRows(DataReader& reader, const PlyElement& target, bool bigEndian, PlyTable& table) {
  const std::string& name = table.source;
  const std::string& elementName = table.element;
  bool fixedRows = !target.hasLists();
  uint64_t rowSize = fixedRows ? target.rowSize() : 0;
  if (fixedRows && rowSize > 0 && target.count > reader.remaining() / rowSize) {
    // count * rowSize may not fit in 64 bits (a header can declare 2^62 rows): say both.
    throw Error(name, "truncated: " + std::to_string(target.count) + " " + elementName + " rows of " +
                          std::to_string(rowSize) + " bytes declared, but only " + std::to_string(reader.remaining()) +
                          " bytes of data follow");
  }
  // Rows with lists take at least one byte each: check before allocating the columns.
  if (!fixedRows && target.count > reader.remaining()) {
    throw Error(name, "truncated: " + std::to_string(target.count) + " " + elementName + " rows declared but only " +
                          std::to_string(reader.remaining()) + " bytes of data follow");
  }
  // Where each scalar column sits in a fixed-size row.
  std::vector<size_t> offsets;
  size_t offset = 0;
  for (const PlyProperty& property : target.properties) {
    if (!property.isList) offsets.push_back(offset);
    offset += plyTypeSize(property.type);
  }
  for (auto& column : table.columns) column.resize(table.count);

  for (size_t row = 0; row < table.count && (rowSize > 0 || !fixedRows); ++row) {
    if (fixedRows) {
      const uint8_t* p = reader.take(size_t(rowSize));  // size checked above
      for (size_t c = 0; c < offsets.size(); ++c)
        storePlyValue(table, c, row, decodeValue(p + offsets[c], table.types[c], bigEndian));
      continue;
    }
    size_t c = 0;
    for (const PlyProperty& property : target.properties) {
      bool ok = true;
      if (property.isList) {
        ok = skipList(reader, property, bigEndian, name);
      } else if (const uint8_t* p = reader.take(plyTypeSize(property.type))) {
        storePlyValue(table, c++, row, decodeValue(p, property.type, bigEndian));
      } else {
        ok = false;
      }
      if (!ok) throw Error(name, "truncated: file ends inside " + elementName + " " + std::to_string(row));
    }
  }
}

}  // namespace

PlyTable readPly(const fs::path& path, const std::string& elementName) {
  std::string name = path.string();
  const uint64_t fileSize = checkInputFile(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(quotedPath(path), "cannot open for reading");
  PlyHeader header = parsePlyHeader(in, name);
  const std::vector<PlyElement>& elements = header.elements;

  auto target = std::find_if(elements.begin(), elements.end(), [&](const PlyElement& e) { return e.name == elementName; });
  if (target == elements.end()) throw Error(name, "PLY file has no element '" + elementName + "'");

  // A header without a final newline leaves the stream at end of file with no position.
  if (in.tellg() < 0) {
    in.clear();
    in.seekg(0, std::ios::end);
  }

  // One column per scalar property, in the file's order; the readers size and fill them.
  PlyTable table;
  table.element = elementName;
  table.source = name;
  table.count = size_t(target->count);
  table.comments = header.comments;
  for (const PlyProperty& property : target->properties) {
    if (property.isList) continue;
    table.names.push_back(property.name);
    table.types.push_back(property.type);
    table.columns.emplace_back();
  }

  if (header.format == PlyFormat::Ascii) {
    uint64_t dataBytes = fileSize - std::min<uint64_t>(fileSize, uint64_t(in.tellg()));
    readAsciiPlyData(in, dataBytes, header, size_t(target - elements.begin()), table);
    return table;
  }
  const bool bigEndian = header.format == PlyFormat::BinaryBigEndian;
  DataReader reader(in, fileSize);
  for (auto it = elements.begin(); it != target; ++it) skipElement(reader, *it, bigEndian, name);
  readBinaryRows(reader, *target, bigEndian, table);
  return table;
}

void writePly(const fs::path& path, const PlyTable& table, const PlyWriteOptions& options) {
  std::string name = path.string();
  GLINT_CHECK(table.names.size() == table.columns.size() && table.types.size() == table.columns.size(),
              "PLY table columns, names and types disagree");
  for (size_t c = 0; c < table.columns.size(); ++c) {
    const std::string& property = table.names[c];
    GLINT_CHECK(!property.empty() && property.find_first_of(" \t\r\n") == std::string::npos, "bad PLY name '" + property + "'");
    GLINT_CHECK(table.columns[c].size() == table.count, "PLY column '" + property + "' has the wrong length");
    for (size_t row = 0; row < table.count; ++row) {
      if (!std::isfinite(table.columns[c][row])) {
        throw Error(name, "cannot write property '" + property + "' of " + table.element + " " + std::to_string(row) +
                              ": value is " + (std::isnan(table.columns[c][row]) ? "NaN" : "infinite"));
      }
    }
  }

  std::ostringstream header;
  header << "ply\nformat binary_little_endian 1.0\n";
  for (const std::string& comment : options.comments) {
    GLINT_CHECK(comment.find('\n') == std::string::npos, "PLY comment with a line break");
    header << "comment " << comment << "\n";
  }
  header << "element " << table.element << " " << table.count << "\n";
  size_t rowSize = 0;
  for (size_t c = 0; c < table.columns.size(); ++c) {
    header << "property " << plyTypeName(table.types[c]) << " " << table.names[c] << "\n";
    rowSize += plyTypeSize(table.types[c]);
  }
  header << "end_header\n";

  writeAtomically(path, [&](const std::string& temp) {
    std::ofstream out(temp, std::ios::binary);
    if (!out) throw Error(name, "cannot open for writing");
    std::string text = header.str();
    out.write(text.data(), std::streamsize(text.size()));
    // Encode a block of rows at a time to keep memory flat for large tables.
    size_t rowsPerBlock = std::max<size_t>(1, (size_t(1) << 20) / std::max<size_t>(rowSize, 1));
    std::vector<uint8_t> block(rowsPerBlock * rowSize);
    for (size_t first = 0; first < table.count; first += rowsPerBlock) {
      size_t rows = std::min(rowsPerBlock, table.count - first);
      uint8_t* p = block.data();
      for (size_t row = first; row < first + rows; ++row) {
        for (size_t c = 0; c < table.columns.size(); ++c) {
          encodeValue(table.columns[c][row], table.types[c], p);
          p += plyTypeSize(table.types[c]);
        }
      }
      out.write(reinterpret_cast<const char*>(block.data()), std::streamsize(rows * rowSize));
    }
    out.close();
    if (!out) throw Error(name, "write failed (disk full?)");
  });
}

}  // namespace glint
