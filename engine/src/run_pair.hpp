#pragma once
// Two independent pieces of work at once when the compute threads allow (engine-internal).
#include <exception>
#include <system_error>
#include <thread>

#include "sutura/engine/compute_threads.hpp"

namespace sutura::engine::detail {

/// Runs `first` and `second`, which must not write anything the other reads: `second` on a
/// thread of its own when compute_threads().openmp > 1 and a thread can be had, otherwise one
/// after the other on this thread. Returns when both are done; an exception of either is
/// rethrown (`first`'s before `second`'s). Results cannot depend on the thread count.
template <class First, class Second>
void run_pair(const First& first, const Second& second) {
  std::thread other;
  std::exception_ptr failure;
  if (compute_threads().openmp > 1) {
    try {
      other = std::thread([&] {
        try {
          second();
        } catch (...) {
          failure = std::current_exception();
        }
      });
    } catch (const std::system_error&) {
      // No thread to be had: both on this one.
    }
  }
  if (!other.joinable()) {
    first();
    second();
    return;
  }
  try {
    first();
  } catch (...) {
    other.join();
    throw;
  }
  other.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace sutura::engine::detail
