#include "sutura/ui/op_thread.hpp"

#include <stdexcept>
#include <utility>

namespace sutura::ui {

OpThread::OpThread() : thread_([this] { loop(); }) {}

OpThread::~OpThread() {
  {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return !busy_; });
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void OpThread::loop() {
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return stop_ || job_; });
    if (stop_) return;
    std::function<void()> job = std::move(job_);
    job_ = nullptr;
    lock.unlock();
    std::exception_ptr error;
    try {
      job();
    } catch (...) {
      error = std::current_exception();  // a broken promise: wait() rethrows it
    }
    lock.lock();
    error_ = error;
    busy_ = false;
    changed_.notify_all();
  }
}

void OpThread::post(std::function<void()> job) {
  {
    std::lock_guard lock(mutex_);
    if (busy_) throw std::logic_error("OpThread::post while a job runs");
    job_ = std::move(job);
    busy_ = true;
  }
  changed_.notify_all();
}

void OpThread::wait() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return !busy_; });
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

void OpThread::run(const std::function<void()>& job) {
  std::exception_ptr error;
  post([&] {
    try {
      job();
    } catch (...) {
      error = std::current_exception();
    }
  });
  wait();
  if (error) std::rethrow_exception(error);
}

bool OpThread::idle() const {
  std::lock_guard lock(mutex_);
  return !busy_;
}

}  // namespace sutura::ui
