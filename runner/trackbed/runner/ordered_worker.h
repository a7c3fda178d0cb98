// One background thread that runs tasks strictly in submission order, so the
// robot software can run on the second core while the main thread simulates
// and renders ahead — with the same inputs in the same order, hence the same
// results to the bit. Tasks hand results back as deliveries that the owner's
// thread runs, again in order (observers and file writers stay single-threaded).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace trackbed::runner {

class OrderedWorker {
 public:
  OrderedWorker();
  /// Waits for the queued tasks; undelivered results are dropped.
  ~OrderedWorker();
  OrderedWorker(const OrderedWorker&) = delete;
  OrderedWorker& operator=(const OrderedWorker&) = delete;

  /// Queues `task` after every task submitted before it.
  void Submit(std::function<void()> task);
  /// From inside a task: queues `delivery` for the owner's thread (RunDeliveries).
  void Deliver(std::function<void()> delivery);
  /// Owner's thread: runs the deliveries that are ready, in order. Rethrows the first
  /// exception a task threw (later tasks are skipped once one has thrown).
  void RunDeliveries();
  /// Owner's thread: blocks until at most `max_pending` submitted tasks are unfinished,
  /// then runs the ready deliveries.
  void WaitUntilPendingAtMost(std::int64_t max_pending);
  /// Owner's thread: waits for every task and runs every delivery.
  void Drain() { WaitUntilPendingAtMost(0); }
  /// Wall-clock seconds the worker spent inside tasks.
  double busy_s() const;

 private:
  void Loop();

  mutable std::mutex mutex_;
  std::condition_variable work_ready_, task_done_;
  std::deque<std::function<void()>> tasks_, deliveries_;
  std::int64_t submitted_ = 0, finished_ = 0;
  std::exception_ptr error_;
  bool stopping_ = false;
  double busy_s_ = 0.0;
  std::thread thread_;  // last: starts after the members it uses exist
};

}  // namespace trackbed::runner
