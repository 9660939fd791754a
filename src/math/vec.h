// Small fixed-size vectors (2 and 3 components) in float or double, with the usual operators.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/cpu_gpu.h"

namespace glint {

template <typename T>
struct Vec2 {
  T x = 0, y = 0;
  constexpr Vec2() = default;
  constexpr Vec2(T x_, T y_) : x(x_), y(y_) {}
  constexpr T operator[](int i) const { return i == 0 ? x : y; }
  constexpr T& operator[](int i) { return i == 0 ? x : y; }
  constexpr Vec2 operator+(Vec2 b) const { return {x + b.x, y + b.y}; }
  constexpr Vec2 operator-(Vec2 b) const { return {x - b.x, y - b.y}; }
  constexpr Vec2 operator*(T s) const { return {x * s, y * s}; }
};

template <typename T>
struct Vec3 {
  T x = 0, y = 0, z = 0;

  constexpr Vec3() = default;
  constexpr Vec3(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
  constexpr explicit Vec3(T s) : x(s), y(s), z(s) {}
  template <typename U>
  constexpr explicit Vec3(const Vec3<U>& v) : x(T(v.x)), y(T(v.y)), z(T(v.z)) {}

  constexpr T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr T& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3 operator+(const Vec3& b) const { return {x + b.x, y + b.y, z + b.z}; }
  constexpr Vec3 operator-(const Vec3& b) const { return {x - b.x, y - b.y, z - b.z}; }
  constexpr Vec3 operator*(const Vec3& b) const { return {x * b.x, y * b.y, z * b.z}; }
  constexpr Vec3 operator/(const Vec3& b) const { return {x / b.x, y / b.y, z / b.z}; }
  constexpr Vec3 operator*(T s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3 operator/(T s) const { return {x / s, y / s, z / s}; }
  constexpr Vec3& operator+=(const Vec3& b) { x += b.x; y += b.y; z += b.z; return *this; }
  constexpr Vec3& operator-=(const Vec3& b) { x -= b.x; y -= b.y; z -= b.z; return *this; }
  constexpr Vec3& operator*=(const Vec3& b) { x *= b.x; y *= b.y; z *= b.z; return *this; }
  constexpr Vec3& operator*=(T s) { x *= s; y *= s; z *= s; return *this; }
  constexpr Vec3& operator/=(T s) { x /= s; y /= s; z /= s; return *this; }
  constexpr bool operator==(const Vec3& b) const { return x == b.x && y == b.y && z == b.z; }
};

template <typename T>
constexpr Vec3<T> operator*(T s, const Vec3<T>& v) { return v * s; }

template <typename T>
constexpr T dot(const Vec3<T>& a, const Vec3<T>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

template <typename T>
constexpr Vec3<T> cross(const Vec3<T>& a, const Vec3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

template <typename T>
GLINT_CPU_GPU inline T length(const Vec3<T>& v) { return std::sqrt(dot(v, v)); }

template <typename T>
GLINT_CPU_GPU inline Vec3<T> normalize(const Vec3<T>& v) {
  T len = length(v);
  return len > T(0) ? v / len : Vec3<T>();
}

template <typename T>
constexpr Vec3<T> min(const Vec3<T>& a, const Vec3<T>& b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}

template <typename T>
constexpr Vec3<T> max(const Vec3<T>& a, const Vec3<T>& b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}

template <typename T>
constexpr T maxComponent(const Vec3<T>& v) { return std::max(v.x, std::max(v.y, v.z)); }

template <typename T>
constexpr T luminance(const Vec3<T>& c) { return T(0.2126) * c.x + T(0.7152) * c.y + T(0.0722) * c.z; }

template <typename T>
GLINT_CPU_GPU inline bool isFinite(const Vec3<T>& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

template <typename T>
constexpr Vec3<T> lerp(const Vec3<T>& a, const Vec3<T>& b, T t) { return a * (T(1) - t) + b * t; }

// Reflects v about the normal n (both pointing away from the surface).
template <typename T>
constexpr Vec3<T> reflect(const Vec3<T>& v, const Vec3<T>& n) { return n * (T(2) * dot(v, n)) - v; }

using Vec2f = Vec2<float>;
using Vec2d = Vec2<double>;
using Vec3f = Vec3<float>;
using Vec3d = Vec3<double>;
using Vec2i = Vec2<int>;

// Linear RGB colour; same operations as a vector.
using Rgb = Vec3f;

}  // namespace glint
