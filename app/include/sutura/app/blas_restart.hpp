#pragma once
// The restart that gives OpenBLAS better kernels: a process-level step, so it lives with the
// executables (sutura, the benchmark programs), not in the engine, which only says which
// kernels would be better (engine/blas_kernels.hpp explains why).
#include <unistd.h>

#include <cstdlib>

#include "sutura/engine/blas_kernels.hpp"

namespace sutura::app {

/// If engine::better_blas_coretype() names kernels, sets OPENBLAS_CORETYPE and re-executes the
/// running program (/proc/self/exe) with the same arguments, so OpenBLAS loads with those
/// kernels; does not return then. Returns normally (the program continues with the kernels it
/// has) when no change is needed or the restart fails. Call it first thing in main(), before
/// any thread starts or any file is opened. `argv` is main's argv.
inline void restart_with_better_blas_kernels(char** argv) {
  const char* coretype = engine::better_blas_coretype();
  if (coretype == nullptr || argv == nullptr || argv[0] == nullptr) return;
  // The restarted program finds the variable set, so it cannot restart again.
  if (setenv("OPENBLAS_CORETYPE", coretype, 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Only reached when the restart failed: carry on with the generic kernels, and leave the
  // environment as it was for any child process.
  unsetenv("OPENBLAS_CORETYPE");
}

}  // namespace sutura::app
