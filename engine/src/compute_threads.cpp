#include "sutura/engine/compute_threads.hpp"

#include <omp.h>

#include "sim/blas_threads.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine {

ComputeThreads compute_threads() {
  return {omp_get_max_threads(), detail::blas_thread_count()};
}

void set_compute_threads(int n) {
  if (n < 1) throw InvalidArgument("the number of threads must be at least 1");
  omp_set_num_threads(n);
  detail::set_blas_thread_count(n);
}

}  // namespace sutura::engine
