// OpenBLAS's thread count calls of the BLAS loaded by load_blas (geofair/blas.h).
#pragma once

namespace geofair {

using BlasSetThreads = void (*)(int);
using BlasGetThreads = int (*)();
/// The loaded library's openblas_set_num_threads / openblas_get_num_threads, or null.
BlasSetThreads loaded_blas_set_threads();
BlasGetThreads loaded_blas_get_threads();

}  // namespace geofair
