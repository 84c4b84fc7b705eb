#pragma once
// An immutable array of numbers shared by every copy of the Value that
// holds it: a Stage is copied per iteration, and a mesh's points must not
// be copied with it. The content hash is computed once, when the array is
// made, so the renderer's and the colliders' caches key geometry by content
// without reading it again each frame.
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>
#include <vector>

namespace sdg {

template <typename T>
class SharedArray {
 public:
  SharedArray() : data_(std::make_shared<const std::vector<T>>()), hash_(hashOf(*data_)) {}
  explicit SharedArray(std::vector<T> items)
      : data_(std::make_shared<const std::vector<T>>(std::move(items))), hash_(hashOf(*data_)) {}

  std::span<const T> items() const { return *data_; }
  size_t size() const { return data_->size(); }
  const T& operator[](size_t i) const { return (*data_)[i]; }
  // FNV-1a of the bytes: equal arrays have equal hashes.
  uint64_t hash() const { return hash_; }

  // Exact (bitwise) comparison, as every Value compares.
  bool operator==(const SharedArray& o) const {
    if (data_ == o.data_) return true;
    return hash_ == o.hash_ && data_->size() == o.data_->size() &&
           std::memcmp(data_->data(), o.data_->data(), data_->size() * sizeof(T)) == 0;
  }

 private:
  static uint64_t hashOf(const std::vector<T>& v) {
    uint64_t h = 1469598103934665603ull;
    const auto* bytes = reinterpret_cast<const unsigned char*>(v.data());
    for (size_t i = 0; i < v.size() * sizeof(T); ++i) h = (h ^ bytes[i]) * 1099511628211ull;
    return h;
  }
  std::shared_ptr<const std::vector<T>> data_;
  uint64_t hash_;
};

using FloatArray = SharedArray<float>;
using IntArray = SharedArray<int32_t>;

}  // namespace sdg
