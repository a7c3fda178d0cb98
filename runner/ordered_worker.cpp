// The ordered background worker (see ordered_worker.h).
#include "trackbed/runner/ordered_worker.h"

#include <chrono>

namespace trackbed::runner {

OrderedWorker::OrderedWorker() : thread_([this] { Loop(); }) {}

OrderedWorker::~OrderedWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  work_ready_.notify_one();
  thread_.join();
}

void OrderedWorker::Submit(std::function<void()> task) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    tasks_.push_back(std::move(task));
    ++submitted_;
  }
  work_ready_.notify_one();
}

void OrderedWorker::Deliver(std::function<void()> delivery) {
  std::lock_guard<std::mutex> lock(mutex_);
  deliveries_.push_back(std::move(delivery));
}

void OrderedWorker::RunDeliveries() {
  std::deque<std::function<void()>> ready;
  std::exception_ptr error;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ready.swap(deliveries_);
    error = error_;
  }
  for (auto& d : ready) d();
  if (error) std::rethrow_exception(error);
}

void OrderedWorker::WaitUntilPendingAtMost(std::int64_t max_pending) {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    task_done_.wait(lock, [&] { return submitted_ - finished_ <= max_pending; });
  }
  RunDeliveries();
}

double OrderedWorker::busy_s() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return busy_s_;
}

void OrderedWorker::Loop() {
  for (;;) {
    std::function<void()> task;
    bool skip;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      work_ready_.wait(lock, [&] { return stopping_ || !tasks_.empty(); });
      if (tasks_.empty()) return;  // stopping, nothing left
      task = std::move(tasks_.front());
      tasks_.pop_front();
      skip = static_cast<bool>(error_);
    }
    const auto start = std::chrono::steady_clock::now();
    std::exception_ptr error;
    if (!skip) {
      try {
        task();
      } catch (...) {
        error = std::current_exception();
      }
    }
    const double spent =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (error && !error_) error_ = error;
      busy_s_ += spent;
      ++finished_;
    }
    task_done_.notify_all();
  }
}

}  // namespace trackbed::runner
