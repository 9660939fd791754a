// Generic PLY tables: one element's scalar properties as named float columns.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace glint {

// PLY scalar property types (http://paulbourke.net/dataformats/ply/). Reading records each
// column's type in the file; writing stores each column in its type.
enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

const char* plyTypeName(PlyType type);  // "char", "uchar", ..., "float", "double"
size_t plyTypeSize(PlyType type);       // bytes per value

// One element of a PLY file (usually "vertex") as a structure of arrays. Every column has
// count values. Integer values are stored as floats holding the integer (a uchar 200 is 200.0f).
struct PlyTable {
  std::string element = "vertex";
  size_t count = 0;
  std::vector<std::string> names;
  std::vector<PlyType> types;
  std::vector<std::vector<float>> columns;
  std::string source;  // the file it was read from, for error messages (empty if built in memory)
  std::vector<std::string> comments;  // the header's "comment" lines (text after the keyword), when read

  // Index of the named column, or -1.
  int find(std::string_view name) const;
  bool has(std::string_view name) const { return find(name) >= 0; }
  // The named column; throws Error naming the source file and the missing property.
  const std::vector<float>& column(std::string_view name) const;
  PlyType type(std::string_view name) const;  // same lookup and error as column()

  // Appends a column (its size must equal count, or sets count for the first column).
  void add(std::string name, std::vector<float> values, PlyType type = PlyType::Float32);
};

// Reads the element elementName of a PLY file: binary little-endian, binary big-endian or
// ASCII (values as a whitespace-separated stream). Other elements (before or after) and list
// properties are skipped. Throws Error naming the file for an unknown format or type, a
// missing element, truncated data, a malformed ASCII value, or NaN/infinite values.
PlyTable readPly(const std::filesystem::path& path, const std::string& elementName = "vertex");

struct PlyWriteOptions {
  std::vector<std::string> comments;  // written as "comment ..." header lines
};

// Writes table atomically as binary little-endian PLY with one element (table.comments are
// not written: options.comments are). Float columns are
// written as is; integer columns are rounded and clamped to their type's range. Throws Error
// naming the file if a value is NaN or infinite (readPly would reject the file).
void writePly(const std::filesystem::path& path, const PlyTable& table, const PlyWriteOptions& options = {});

}  // namespace glint
