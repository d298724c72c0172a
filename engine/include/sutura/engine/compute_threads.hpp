#pragma once
// How many threads the engine computes with: OpenMP for the per-element loops and the sparse
// assembly, OpenBLAS for CHOLMOD's dense blocks.
//
// Why a setting: by default both use every core, which is fastest on an otherwise idle machine.
// Where other processes keep the cores busy, threads that wait for each other at every parallel
// region (and OpenBLAS threads spinning between calls) lose whole scheduler time slices:
// measured on the 2-core machine with two busy-looping processes beside it, the default
// patch aortoplasty took 19.2 s with 2 threads and 2.6 s with 1 (2.0 and 2.3 s on the idle
// machine; docs/performance.md). Results are deterministic for a given count, but the BLAS
// summation order, and so the last bits of positions, depend on it; reports record it.

namespace sutura::engine {

struct ComputeThreads {
  int openmp = 1;  ///< OpenMP threads of parallel regions started from the calling thread
  int blas = 1;    ///< OpenBLAS threads (1 when another BLAS is loaded: not controlled)
};

/// The current counts.
ComputeThreads compute_threads();

/// Sets both counts to n >= 1 (throws InvalidArgument otherwise). Call it before any
/// computation, from the thread that will start the parallel regions (OpenMP's count is a
/// per-thread setting inherited by threads started afterwards).
void set_compute_threads(int n);

}  // namespace sutura::engine
