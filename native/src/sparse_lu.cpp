// The BLAS threads under UMFPACK, see sparse_lu.h.
#include "sparse_lu.h"

#include "geofair/blas.h"

#ifdef GEOFAIR_BLAS_LOADER
#include "blas_loader.h"
#elif !defined(GEOFAIR_PORTABLE) && !defined(_WIN32)
#include <dlfcn.h>
#define GEOFAIR_OPENBLAS_LOOKUP
#endif
#include "parallel.h"

namespace geofair {
namespace {

// OpenBLAS's own calls, looked up at run time: the BLAS behind Debian's libblas.so.3 is a
// choice of the machine (update-alternatives), and another BLAS has no such calls.
using SetThreads = void (*)(int);
using GetThreads = int (*)();
#ifdef GEOFAIR_BLAS_LOADER
SetThreads set_threads() { return loaded_blas_set_threads(); }
GetThreads get_threads() { return loaded_blas_get_threads(); }
#else
// OpenBLAS's call `name`: in the global scope, else in an OpenBLAS already loaded as a
// dependency of UMFPACK (RTLD_NOLOAD: never loads one).
// None in the portable build (no BLAS under Eigen's solvers) or on Windows (no dlfcn.h).
void* openblas_symbol([[maybe_unused]] const char* name) {
#ifdef GEOFAIR_OPENBLAS_LOOKUP
  if (void* f = dlsym(RTLD_DEFAULT, name)) return f;
  if (void* library = dlopen("libopenblas.so.0", RTLD_LAZY | RTLD_NOLOAD))
    return dlsym(library, name);
#endif
  return nullptr;
}
SetThreads set_threads() {
  static const auto f =
      reinterpret_cast<SetThreads>(openblas_symbol("openblas_set_num_threads"));
  return f;
}
GetThreads get_threads() {
  static const auto f =
      reinterpret_cast<GetThreads>(openblas_symbol("openblas_get_num_threads"));
  return f;
}
#endif

}  // namespace

#ifndef GEOFAIR_BLAS_LOADER
// The BLAS is linked (or, in the portable build, not used): nothing to load.
bool blas_loaded_at_run_time() { return false; }
void load_blas(const std::string&) {}
bool blas_loaded() { return true; }
#endif

BlasThreads::BlasThreads(int threads) {
  if (set_threads() && get_threads()) {
    previous_ = get_threads()();
    if (previous_ != threads) set_threads()(threads);
  }
}

BlasThreads::~BlasThreads() {
  if (previous_ > 0 && previous_ != get_threads()()) set_threads()(previous_);
}

int factorization_blas_threads(int n) { return n >= kThreadedBlasMin ? loop_threads() : 1; }

}  // namespace geofair
