// An array in GPU memory that frees itself, grows on demand and copies to and from the host;
// running out of GPU memory is one clear error saying how much was asked and what is free.
#pragma once

#include <cuda_runtime.h>

#include <cstddef>
#include <cstdio>
#include <span>
#include <string>
#include <utility>

#include "cuda/cuda_check.h"

namespace glint::cuda {

// "123.4 MiB"
inline std::string mebibytes(size_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / (1024.0 * 1024.0));
  return text;
}

template <typename T>
class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
  DeviceBuffer(DeviceBuffer&& b) noexcept { swap(b); }
  DeviceBuffer& operator=(DeviceBuffer&& b) noexcept {
    swap(b);
    return *this;
  }
  ~DeviceBuffer() {
    if (data_) cudaFree(data_);
  }

  T* data() { return data_; }
  const T* data() const { return data_; }
  size_t size() const { return size_; }
  size_t bytes() const { return capacity_ * sizeof(T); }

  // Holds at least n elements (contents are not kept when it grows); `what` names the
  // array in the error when the GPU has no room.
  void resize(size_t n, const char* what) {
    if (n > capacity_) {
      if (data_) cudaFree(data_);
      data_ = nullptr;
      capacity_ = 0;
      size_t want = n + n / 8;  // room to grow a little without reallocating
      if (cudaMalloc(reinterpret_cast<void**>(&data_), want * sizeof(T)) != cudaSuccess) {
        cudaGetLastError();  // clear the (not sticky) allocation error
        size_t free = 0, total = 0;
        cudaMemGetInfo(&free, &total);
        throw Error(std::string("the GPU has no room for ") + what + ": it needs " + mebibytes(want * sizeof(T)) +
                    ", and " + mebibytes(free) + " of the GPU's " + mebibytes(total) +
                    " are free (run on the CPU with --device cpu, or free GPU memory)");
      }
      capacity_ = want;
    }
    size_ = n;
  }

  void upload(std::span<const T> host, const char* what) {
    resize(host.size(), what);
    if (!host.empty()) check(cudaMemcpy(data_, host.data(), host.size_bytes(), cudaMemcpyHostToDevice), what);
  }
  void download(std::span<T> host, const char* what) const {
    if (!host.empty()) check(cudaMemcpy(host.data(), data_, host.size_bytes(), cudaMemcpyDeviceToHost), what);
  }

 private:
  void swap(DeviceBuffer& b) {
    std::swap(data_, b.data_);
    std::swap(size_, b.size_);
    std::swap(capacity_, b.capacity_);
  }

  T* data_ = nullptr;
  size_t size_ = 0;
  size_t capacity_ = 0;
};

}  // namespace glint::cuda
