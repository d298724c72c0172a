#include "serial_openmp.hpp"

#include <omp.h>

namespace sutura::engine::detail {

SerialOpenMp::SerialOpenMp() : saved_levels_(omp_get_max_active_levels()) {
  omp_set_max_active_levels(0);
}

SerialOpenMp::~SerialOpenMp() { omp_set_max_active_levels(saved_levels_); }

}  // namespace sutura::engine::detail
