#pragma once
// Hands back objects that own big buffers (a frame's passes are ~9 MB at
// 512 x 512) so a steady run reuses them instead of allocating, zero-filling
// and page-faulting that memory for every frame. Thread-safe: the render
// thread takes, the write pool's workers give back.
#include <mutex>
#include <utility>
#include <vector>

namespace sdg {

template <typename T>
class Recycler {
 public:
  // A previously given object (contents as they were left), or a new one.
  T take() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (spare_.empty()) return T{};
    T t = std::move(spare_.back());
    spare_.pop_back();
    return t;
  }
  void give(T&& t) {
    std::lock_guard<std::mutex> lock(mutex_);
    spare_.push_back(std::move(t));
  }

 private:
  std::mutex mutex_;
  std::vector<T> spare_;
};

}  // namespace sdg
