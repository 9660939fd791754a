// The data section of an ASCII PLY file: values as a whitespace-separated stream of numbers.
#pragma once

#include <cstdint>
#include <istream>

#include "io/ply.h"
#include "io/ply_header.h"

namespace glint {

// Reads the rows of header.elements[target] into table, whose names, types and count are set
// and whose columns are empty: skips the elements before it and the list properties (count,
// then items), and leaves what follows unread. `in` stands at the first data byte, and
// dataBytes follow it. Throws Error naming table.source for a value that is not a number of
// its property's type (integers must be whole and in range), NaN or infinite values, a
// negative list length, or a file that ends early.
void readAsciiPlyData(std::istream& in, uint64_t dataBytes, const PlyHeader& header, size_t target, PlyTable& table);

}  // namespace glint
