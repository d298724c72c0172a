#pragma once
// One long-lived thread on which the session controller runs every op, one job at a time.
// Why one thread for all of them, rather than a new thread per long op: an op run on a fresh
// thread allocates every buffer of its solve from that thread's new, empty malloc arena (new
// memory, faulted in page by page), and was measurably slower than a headless replay
// (docs/performance.md, GUI).
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace sutura::ui {

class OpThread {
 public:
  OpThread();
  ~OpThread();  ///< waits for the job in hand, then ends the thread
  OpThread(const OpThread&) = delete;
  OpThread& operator=(const OpThread&) = delete;

  /// Starts `job` on the thread and returns at once. Only when idle() (std::logic_error
  /// otherwise). A job should not throw; one that does is caught, and wait() rethrows it.
  void post(std::function<void()> job);
  /// Waits until the job posted last has returned (at once when idle()); rethrows what it threw.
  void wait();
  /// Runs `job` on the thread and waits for it; an exception it throws is rethrown here.
  void run(const std::function<void()>& job);
  /// The job posted last has returned (or none was posted).
  [[nodiscard]] bool idle() const;

 private:
  void loop();

  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::function<void()> job_;  ///< the job to run; empty when none is waiting
  std::exception_ptr error_;   ///< what the last job threw, until wait() rethrows it
  bool busy_ = false;          ///< a job was posted and has not returned yet
  bool stop_ = false;
  std::thread thread_;         ///< last: starts once the members above exist
};

}  // namespace sutura::ui
