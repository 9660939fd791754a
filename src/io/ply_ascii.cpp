// ASCII PLY data: each value a decimal token, rows and elements one after another.
#include "io/ply_ascii.h"

#include <charconv>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include "core/error.h"
#include "core/printable_text.h"

namespace glint {

namespace {

// The range of an integer PLY type.
std::pair<int64_t, int64_t> integerRange(PlyType type) {
  switch (type) {
    case PlyType::Int8: return {INT8_MIN, INT8_MAX};
    case PlyType::UInt8: return {0, UINT8_MAX};
    case PlyType::Int16: return {INT16_MIN, INT16_MAX};
    case PlyType::UInt16: return {0, UINT16_MAX};
    case PlyType::Int32: return {INT32_MIN, INT32_MAX};
    case PlyType::UInt32: return {0, UINT32_MAX};
    default: return {0, 0};
  }
}

// The token as a value of type: false if it is not a number, or, for an integer type, not a
// whole number in the type's range. "nan" and "inf" parse, for storePlyValue to refuse by name.
bool parseAsciiValue(const std::string& token, PlyType type, double* value) {
  const char* begin = token.data();
  const char* end = begin + token.size();
  if (begin != end && *begin == '+') ++begin;  // from_chars takes no plus sign
  if (type == PlyType::Float32 || type == PlyType::Float64) {
    auto [stop, ec] = std::from_chars(begin, end, *value);
    return ec == std::errc() && stop == end;
  }
  int64_t integer = 0;
  auto [stop, ec] = std::from_chars(begin, end, integer);
  auto [lowest, highest] = integerRange(type);
  if (ec != std::errc() || stop != end || integer < lowest || integer > highest) return false;
  *value = double(integer);
  return true;
}

// Tokens of the data section, one row (one line, as the PLY format lays them out) at a time,
// so that a row with more values than its header declares is refused instead of shifting
// every value after it into the next row. The row being read names errors.
class AsciiValues {
 public:
  AsciiValues(std::istream& in, const std::string& path) : in_(in), path_(path) {}

  // Starts the next row: the next line that holds anything but blanks.
  void beginRow(const std::string& where) {
    std::string line;
    do {
      if (!std::getline(in_, line)) throw Error(path_, "truncated: file ends before " + where);
    } while (line.find_first_not_of(" \t\r") == std::string::npos);
    row_.clear();
    row_.str(line);
    values_ = 0;
  }

  // Ends a row: nothing may be left on its line.
  void endRow(const std::string& where) {
    size_t extra = 0;
    while (row_ >> token_) ++extra;
    if (extra > 0)
      throw Error(path_, where + " has " + std::to_string(values_ + extra) + " values on its line, but the header " +
                             "declares " + std::to_string(values_) + " (a property missing from the header?)");
  }

  // The next value of a property of the given type; throws Error for a malformed token or
  // the end of the row ("where" says which element and row).
  double next(PlyType type, const std::string& property, const std::string& where) {
    if (!(row_ >> token_))
      throw Error(path_, where + " ends after " + std::to_string(values_) + " values, before property '" +
                             printableText(property) + "'");
    ++values_;
    double value = 0.0;
    if (!parseAsciiValue(token_, type, &value)) {
      throw Error(path_, "property '" + printableText(property) + "' of " + where + " is '" + printableText(token_) +
                             "', not a " + plyTypeName(type) + " value");
    }
    return value;
  }

  // Reads a list's length and skips its items.
  void skipList(const PlyProperty& property, const std::string& where) {
    double count = next(property.countType, property.name, where);
    if (count < 0) throw Error(path_, "list property '" + printableText(property.name) + "' has a negative length");
    for (double i = 0; i < count; ++i) {
      if (!(row_ >> token_)) throw Error(path_, where + " ends inside list property '" + printableText(property.name) + "'");
      ++values_;
    }
  }

 private:
  std::istream& in_;
  const std::string& path_;
  std::istringstream row_;
  std::string token_;
  size_t values_ = 0;  // values read from the current row
};

}  // namespace

void readAsciiPlyData(std::istream& in, uint64_t dataBytes, const PlyHeader& header, size_t target, PlyTable& table) {
  AsciiValues values(in, table.source);
  for (size_t e = 0; e < target; ++e) {
    const PlyElement& element = header.elements[e];
    const std::string where = "element '" + printableText(element.name) + "'";
    // Rows without properties hold no tokens: a huge count of them is no work.
    for (uint64_t row = 0; row < element.count && !element.properties.empty(); ++row) {
      const std::string rowName = where + " row " + std::to_string(row);
      values.beginRow(rowName);
      for (const PlyProperty& property : element.properties) {
        if (property.isList) values.skipList(property, rowName);
        else values.next(property.type, property.name, rowName);
      }
      values.endRow(rowName);
    }
  }

  // Every property of a row is at least one byte: check before allocating the columns.
  const PlyElement& element = header.elements[target];
  const uint64_t tokensPerRow = element.properties.size();
  if (tokensPerRow > 0 && element.count > dataBytes / tokensPerRow) {
    throw Error(table.source, "truncated: " + std::to_string(element.count) + " " + table.element +
                                  " rows declared but only " + std::to_string(dataBytes) + " bytes of data follow");
  }
  for (auto& column : table.columns) column.resize(table.count);
  for (size_t row = 0; row < table.count && tokensPerRow > 0; ++row) {
    const std::string where = table.element + " " + std::to_string(row);
    values.beginRow(where);
    size_t c = 0;
    for (const PlyProperty& property : element.properties) {
      if (property.isList) values.skipList(property, where);
      else storePlyValue(table, c++, row, values.next(property.type, property.name, where));
    }
    values.endRow(where);
  }
}

}  // namespace glint
