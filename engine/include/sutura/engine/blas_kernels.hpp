#pragma once
// OpenBLAS kernel selection for CPUs newer than the installed OpenBLAS.
//
// Why: OpenBLAS picks its compute kernels once, when the library is loaded, from the CPU model
// number. Debian 12's OpenBLAS 0.3.21 does not know CPUs released after it (measured on an
// Intel Xeon of family 6, model 207, i.e. Emerald Rapids) and falls back to its generic
// "Prescott" SSE3 kernels although the CPU has AVX2 and AVX-512. The supernodal Cholesky
// factorisation is BLAS-3, so that fallback made one Newton iteration at 20k elements 780 ms
// instead of 490 ms with the SkylakeX kernels (docs/performance.md). The kernels can only be
// chosen through the environment variable OPENBLAS_CORETYPE before the library loads, hence a
// restart of the program, which is the executable's business (app/blas_restart.hpp): the engine
// only says which kernels would be better.
//
// With another BLAS, or an OpenBLAS that recognised the CPU, or OPENBLAS_CORETYPE already set by
// the user, nothing happens. Results remain deterministic for a given machine: only the BLAS
// summation order differs between kernels.

#include <string>

namespace sutura::engine {

/// The OPENBLAS_CORETYPE value that would give this CPU faster kernels than the ones OpenBLAS
/// chose ("SkylakeX" with AVX-512 F/DQ/BW/VL/CD, "Haswell" with AVX2 and FMA), or nullptr
/// when no change is needed (OpenBLAS not loaded, its choice is not the generic fallback, the
/// variable is already set, or the CPU has neither instruction set). Cost: a few CPUID reads.
const char* better_blas_coretype();

/// "OpenBLAS <kernels>" (e.g. "OpenBLAS SkylakeX") when OpenBLAS is the loaded BLAS, else
/// "unknown". Reported with results: position hashes depend on the BLAS kernels.
std::string blas_kernels_in_use();

}  // namespace sutura::engine
