// TensorBoard event records, encoded by hand: the protobuf wire format of the few Event
// fields TensorBoard reads for scalars, in TFRecord framing.
#include "io/tensorboard_events.h"

#include <unistd.h>

#include <array>
#include <chrono>
#include <cstring>

#include "core/error.h"

namespace glint {

namespace {

// The reflected CRC-32C table (polynomial 0x82f63b78).
const std::array<uint32_t, 256>& crcTable() {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t i = 0; i < 256; ++i) {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? (c >> 1) ^ 0x82f63b78u : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  return table;
}

void appendLittleEndian(std::string* out, uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out->push_back(char((value >> (8 * i)) & 0xffu));
}

// Protocol buffer wire format: varints, and fields as (number << 3 | wire type).
void appendVarint(std::string* out, uint64_t value) {
  while (value >= 0x80) {
    out->push_back(char((value & 0x7fu) | 0x80u));
    value >>= 7;
  }
  out->push_back(char(value));
}

void appendKey(std::string* out, int field, int wireType) { appendVarint(out, uint64_t(field) << 3 | uint64_t(wireType)); }

void appendBytesField(std::string* out, int field, std::string_view bytes) {
  appendKey(out, field, 2);
  appendVarint(out, bytes.size());
  out->append(bytes);
}

void appendDoubleField(std::string* out, int field, double value) {
  appendKey(out, field, 1);
  uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  appendLittleEndian(out, bits, 8);
}

double wallTimeNow() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace

uint32_t crc32c(std::string_view bytes) {
  uint32_t crc = 0xffffffffu;
  for (unsigned char b : bytes) crc = crcTable()[(crc ^ b) & 0xffu] ^ (crc >> 8);
  return crc ^ 0xffffffffu;
}

uint32_t maskedCrc32c(std::string_view bytes) {
  const uint32_t crc = crc32c(bytes);
  return ((crc >> 15) | (crc << 17)) + 0xa282ead8u;
}

std::string tfRecord(std::string_view data) {
  std::string length;
  appendLittleEndian(&length, data.size(), 8);
  std::string record = length;
  appendLittleEndian(&record, maskedCrc32c(length), 4);
  record.append(data);
  appendLittleEndian(&record, maskedCrc32c(data), 4);
  return record;
}

// tensorflow.Event: wall_time = 1 (double), step = 2 (int64), file_version = 3 (string),
// summary = 5 (Summary). Summary: value = 1 (repeated Value). Value: tag = 1 (string),
// simple_value = 2 (float).
std::string fileVersionEvent(double wallTime) {
  std::string event;
  appendDoubleField(&event, 1, wallTime);
  appendBytesField(&event, 3, "brain.Event:2");
  return event;
}

std::string scalarEvent(double wallTime, int64_t step, std::string_view tag, float value) {
  std::string summaryValue;
  appendBytesField(&summaryValue, 1, tag);
  appendKey(&summaryValue, 2, 5);
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  appendLittleEndian(&summaryValue, bits, 4);
  std::string summary;
  appendBytesField(&summary, 1, summaryValue);
  std::string event;
  appendDoubleField(&event, 1, wallTime);
  appendKey(&event, 2, 0);
  appendVarint(&event, uint64_t(step));
  appendBytesField(&event, 5, summary);
  return event;
}

TensorBoardWriter::TensorBoardWriter(const std::filesystem::path& folder) {
  std::filesystem::create_directories(folder);
  char host[256] = "host";
  gethostname(host, sizeof(host) - 1);
  const double now = wallTimeNow();
  file_ = folder / ("events.out.tfevents." + std::to_string(int64_t(now)) + "." + host + ".glint");
  out_.open(file_, std::ios::binary | std::ios::app);
  if (!out_) throw Error(file_.string(), "cannot be written");
  out_ << tfRecord(fileVersionEvent(now));
  out_.flush();
}

void TensorBoardWriter::scalar(std::string_view tag, int64_t step, float value) {
  out_ << tfRecord(scalarEvent(wallTimeNow(), step, tag, value));
}

void TensorBoardWriter::flush() { out_.flush(); }

}  // namespace glint
