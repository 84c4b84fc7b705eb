#include "writers/write_pool.h"

namespace sdg {

WritePool::WritePool(size_t threads, size_t maxQueued) : maxQueued_(std::max<size_t>(1, maxQueued)) {
  for (size_t i = 0; i < std::max<size_t>(1, threads); ++i) threads_.emplace_back([this] { work(); });
}

WritePool::~WritePool() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  hasWork_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void WritePool::submit(std::function<void()> job) {
  std::unique_lock lock(mutex_);
  hasRoom_.wait(lock, [&] { return queue_.size() < maxQueued_ || error_; });
  if (error_) std::rethrow_exception(error_);
  queue_.push_back(std::move(job));
  hasWork_.notify_one();
}

void WritePool::finish() {
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [&] { return (queue_.empty() && running_ == 0) || error_; });
  if (error_) std::rethrow_exception(error_);
}

void WritePool::work() {
  while (true) {
    std::function<void()> job;
    {
      std::unique_lock lock(mutex_);
      hasWork_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;
      job = std::move(queue_.front());
      queue_.pop_front();
      ++running_;
    }
    hasRoom_.notify_one();
    try {
      job();
    } catch (...) {
      std::lock_guard lock(mutex_);
      if (!error_) error_ = std::current_exception();
      queue_.clear();  // stop: later frames would only repeat the failure
    }
    {
      std::lock_guard lock(mutex_);
      --running_;
    }
    idle_.notify_all();
    hasRoom_.notify_all();
  }
}

}  // namespace sdg
