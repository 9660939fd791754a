// Fuzz harness for training configuration files (train/train_config.cpp, --config).
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.h"
#include "train/train_config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return glint::fuzz::parseAsFile(data, size, "config", ".json", [](const auto& path) {
    glint::TrainConfig config = glint::readTrainConfig(path);
    glint::toJson(config);  // what is accepted must also write back (RUN/config.json)
  });
}
