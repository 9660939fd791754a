// TensorBoard event files: scalars written in the documented record format (TFRecord
// framing of tensorflow.Event protocol buffers), so `tensorboard --logdir RUN` shows a
// training run as users of the 3DGS codes are used to watching theirs.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace glint {

// CRC-32C (Castagnoli), the checksum of TFRecord framing.
uint32_t crc32c(std::string_view bytes);
// TFRecord's masked CRC: rotated right by 15 bits, plus 0xa282ead8.
uint32_t maskedCrc32c(std::string_view bytes);

// One record: length (uint64, little-endian), its masked CRC, the data, the data's masked CRC.
std::string tfRecord(std::string_view data);

// A tensorflow.Event holding file_version "brain.Event:2" (the first record of every file).
std::string fileVersionEvent(double wallTime);
// A tensorflow.Event holding one scalar summary value (simple_value) under `tag`.
std::string scalarEvent(double wallTime, int64_t step, std::string_view tag, float value);

// Appends scalar events to a new file RUN_FOLDER/events.out.tfevents.<seconds>.<host>.glint.
class TensorBoardWriter {
 public:
  explicit TensorBoardWriter(const std::filesystem::path& folder);
  void scalar(std::string_view tag, int64_t step, float value);
  // Makes what was written visible to a running TensorBoard.
  void flush();
  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path file_;
  std::ofstream out_;
};

}  // namespace glint
