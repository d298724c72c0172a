#pragma once
// BLAS thread count control (private to engine/src/sim).
//
// Why: CHOLMOD's supernodal triangular solves are sequences of small dense BLAS-2 calls (one per
// supernode). OpenBLAS hands each to its thread pool; between OpenMP element loops on a 2-core
// machine the hand-over and the spinning threads cost more than they save: 50 implicit steps at
// 5k elements took 3.7 s with two BLAS threads and 1.9 s with one (docs/performance.md). The
// factorisation, BLAS-3 on large supernodes, does profit from threads, so only the solve phase
// is made single-threaded.
//
// OpenBLAS is looked up at run time (dlsym), so the engine links against any BLAS; with another
// BLAS this is a no-op.

namespace sutura::engine::detail {

/// OpenBLAS's thread count (1 when another BLAS is loaded).
int blas_thread_count();
/// Sets OpenBLAS's thread count (no-op with another BLAS).
void set_blas_thread_count(int n);

/// Runs BLAS on one thread while alive, then restores the previous count.
class SingleThreadedBlas {
 public:
  SingleThreadedBlas();
  ~SingleThreadedBlas();
  SingleThreadedBlas(const SingleThreadedBlas&) = delete;
  SingleThreadedBlas& operator=(const SingleThreadedBlas&) = delete;

 private:
  int previous_ = 0;  ///< 0: nothing to restore
};

}  // namespace sutura::engine::detail
