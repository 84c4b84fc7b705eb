#pragma once
// A bounded pool of background threads that encodes and writes frames while
// the next one renders. submit() blocks when `maxQueued` jobs wait, so memory
// stays bounded. The first error stops the pool and is rethrown by the next
// submit() or by finish(). What a job writes does not depend on the pool size.
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace sdg {

class WritePool {
 public:
  WritePool(size_t threads, size_t maxQueued);
  ~WritePool();
  WritePool(const WritePool&) = delete;
  WritePool& operator=(const WritePool&) = delete;

  void submit(std::function<void()> job);
  // Waits for every job; rethrows the first error.
  void finish();

 private:
  void work();
  std::mutex mutex_;
  std::condition_variable hasWork_, hasRoom_, idle_;
  std::deque<std::function<void()>> queue_;
  std::vector<std::thread> threads_;
  size_t maxQueued_;
  size_t running_ = 0;
  bool stopping_ = false;
  std::exception_ptr error_;
};

}  // namespace sdg
