// The viewer server's workers: a fixed number of threads over a bounded queue of accepted
// connections. cpp-httplib serves a connection on one worker for its whole keep-alive life,
// so its default pool (8 workers, unbounded queue) let 16 long-polling or slow clients hold
// every worker while the other connections queued without an answer.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include <httplib.h>

namespace glint {

class WorkerPool : public httplib::TaskQueue {
 public:
  WorkerPool(size_t workers, size_t maxQueued);
  ~WorkerPool() override;

  // Queues the job. While maxQueued jobs wait, it blocks the caller (the accepting thread),
  // so further connections wait in the kernel's listen backlog and cost the server nothing.
  void enqueue(std::function<void()> job) override;
  // Runs the queued jobs, then joins the workers.
  void shutdown() override;

 private:
  void work();

  size_t maxQueued_;
  std::mutex mutex_;
  std::condition_variable jobQueued_, roomMade_;
  std::deque<std::function<void()>> jobs_;
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace glint
