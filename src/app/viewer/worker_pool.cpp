// A fixed pool of worker threads over a bounded queue.
#include "app/viewer/worker_pool.h"

namespace glint {

WorkerPool::WorkerPool(size_t workers, size_t maxQueued) : maxQueued_(maxQueued) {
  for (size_t i = 0; i < workers; ++i) threads_.emplace_back([this] { work(); });
}

WorkerPool::~WorkerPool() { shutdown(); }

void WorkerPool::enqueue(std::function<void()> job) {
  std::unique_lock lock(mutex_);
  roomMade_.wait(lock, [this] { return jobs_.size() < maxQueued_ || stopping_; });
  jobs_.push_back(std::move(job));
  jobQueued_.notify_one();
}

void WorkerPool::shutdown() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  jobQueued_.notify_all();
  roomMade_.notify_all();
  for (std::thread& thread : threads_)
    if (thread.joinable()) thread.join();
}

void WorkerPool::work() {
  for (;;) {
    std::function<void()> job;
    {
      std::unique_lock lock(mutex_);
      jobQueued_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
      if (jobs_.empty()) return;  // stopping, and every queued connection served
      job = std::move(jobs_.front());
      jobs_.pop_front();
    }
    roomMade_.notify_one();
    job();
  }
}

}  // namespace glint
