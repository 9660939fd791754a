// The header of a PLY file (its format, comments, and elements with their properties) and
// the value check, shared by the binary and ASCII readers of io/ply.cpp and io/ply_ascii.cpp.
#pragma once

#include <cstdint>
#include <istream>
#include <string>
#include <vector>

#include "io/ply.h"

namespace glint {

enum class PlyFormat { BinaryLittleEndian, BinaryBigEndian, Ascii };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // of the value, or of the list items
  bool isList = false;
  PlyType countType = PlyType::UInt8;  // lists only
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;

  bool hasLists() const;
  size_t rowSize() const;  // bytes of a binary row; fixed-size rows (no lists) only
};

struct PlyHeader {
  PlyFormat format = PlyFormat::BinaryLittleEndian;
  std::vector<std::string> comments;  // the text after "comment ", in order
  std::vector<PlyElement> elements;
};

// Parses the header up to and including "end_header"; leaves `in` at the first data byte.
// Throws Error naming path for a missing magic line or format line, an unknown keyword or
// type, a malformed element line or a duplicate property (quoting the header line).
PlyHeader parsePlyHeader(std::istream& in, const std::string& path);

// Stores a value read from the file in table.columns[column][row], the check every reader
// applies: throws Error naming table.source, the property and the row for a value that is
// NaN, infinite or outside the float range.
void storePlyValue(PlyTable& table, size_t column, size_t row, double value);

}  // namespace glint
