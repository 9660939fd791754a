// Checks that user-facing failures throw glint::Error naming the file (and the problem).
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <initializer_list>
#include <string>

#include "core/error.h"

namespace glint::test {

// Expects fn to throw glint::Error whose message names path's file and contains every detail.
inline void expectErrorNaming(const std::function<void()>& fn, const std::filesystem::path& path,
                              std::initializer_list<std::string> details = {}) {
  try {
    fn();
    ADD_FAILURE() << "no error for " << path;
  } catch (const Error& e) {
    std::string message = e.what();
    EXPECT_NE(message.find(path.filename().string()), std::string::npos) << message;
    for (const std::string& detail : details) EXPECT_NE(message.find(detail), std::string::npos) << message;
  }
}

inline void expectErrorNaming(const std::function<void()>& fn, const std::filesystem::path& path,
                              const std::string& detail) {
  expectErrorNaming(fn, path, {detail});
}

}  // namespace glint::test
