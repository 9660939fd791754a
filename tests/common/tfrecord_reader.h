// Reads TensorBoard event files for the tests, written from the documented formats (TFRecord
// framing, the tensorflow.Event and Summary protocol buffers), not from Glint's writer.
#pragma once

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "io/tensorboard_events.h"

namespace glint::test {

struct ScalarEvent {
  int64_t step = 0;
  std::string tag;
  float value = 0;
};

struct EventFile {
  bool framingValid = true;  // every length and data CRC as TFRecord's masked CRC-32C says
  std::string fileVersion;   // of the first event
  std::vector<ScalarEvent> scalars;
};

// Protocol buffer reading: varints, and each field's number, wire type and payload.
class ProtoReader {
 public:
  explicit ProtoReader(const std::string& bytes) : bytes_(bytes) {}
  bool done() const { return at_ >= bytes_.size(); }
  uint64_t varint() {
    uint64_t value = 0;
    for (int shift = 0; at_ < bytes_.size(); shift += 7) {
      const uint8_t b = uint8_t(bytes_[at_++]);
      value |= uint64_t(b & 0x7fu) << shift;
      if (!(b & 0x80u)) break;
    }
    return value;
  }
  // The next field: its number and wire type; the payload in *bytes (wire types 1, 2, 5) or
  // *number (0).
  void field(int* fieldNumber, int* wireType, std::string* bytes, uint64_t* number) {
    const uint64_t key = varint();
    *fieldNumber = int(key >> 3), *wireType = int(key & 7u);
    if (*wireType == 0) {
      *number = varint();
    } else {
      const size_t size = *wireType == 1 ? 8 : *wireType == 5 ? 4 : size_t(varint());
      *bytes = bytes_.substr(at_, size);
      at_ += size;
    }
  }

 private:
  std::string bytes_;
  size_t at_ = 0;
};

inline uint64_t littleEndian(const std::string& bytes, size_t at, int count) {
  uint64_t v = 0;
  for (int i = 0; i < count; ++i) v |= uint64_t(uint8_t(bytes[at + size_t(i)])) << (8 * i);
  return v;
}

inline EventFile readEventFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EventFile file;
  for (size_t at = 0; at + 12 <= data.size();) {
    const uint64_t length = littleEndian(data, at, 8);
    file.framingValid &= uint32_t(littleEndian(data, at + 8, 4)) == maskedCrc32c(data.substr(at, 8));
    const std::string event = data.substr(at + 12, size_t(length));
    file.framingValid &= uint32_t(littleEndian(data, at + 12 + length, 4)) == maskedCrc32c(event);
    at += 16 + length;
    ProtoReader reader(event);
    int64_t step = 0;
    std::vector<ScalarEvent> values;
    while (!reader.done()) {
      int number, wire;
      std::string bytes;
      uint64_t integer = 0;
      reader.field(&number, &wire, &bytes, &integer);
      if (number == 2 && wire == 0) step = int64_t(integer);
      if (number == 3 && wire == 2) file.fileVersion = bytes;
      if (number != 5 || wire != 2) continue;
      ProtoReader summary(bytes);
      while (!summary.done()) {
        std::string valueBytes;
        summary.field(&number, &wire, &valueBytes, &integer);
        ProtoReader value(valueBytes);
        ScalarEvent scalar;
        while (!value.done()) {
          std::string payload;
          value.field(&number, &wire, &payload, &integer);
          if (number == 1) scalar.tag = payload;
          if (number == 2 && wire == 5) std::memcpy(&scalar.value, payload.data(), 4);
        }
        values.push_back(scalar);
      }
    }
    for (ScalarEvent& v : values) v.step = step, file.scalars.push_back(v);
  }
  return file;
}

}  // namespace glint::test
