// The Fortran BLAS/LAPACK routines SuiteSparse calls, forwarded to a BLAS loaded at run
// time (blas_loader.h). Every argument of these routines is a pointer (SuiteSparse declares
// them without Fortran's hidden string lengths), so each forwarder passes its pointers on.
#include "blas_loader.h"

#include "geofair/blas.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <stdexcept>

#ifdef _WIN32
#include <windows.h>
#else
#include <dlfcn.h>
#endif

namespace geofair {
namespace {

using P = void*;
// The routines by their number of (pointer) arguments.
using F5 = void (*)(P, P, P, P, P);
using F8 = void (*)(P, P, P, P, P, P, P, P);
using F9 = void (*)(P, P, P, P, P, P, P, P, P);
using F10 = void (*)(P, P, P, P, P, P, P, P, P, P);
using F11 = void (*)(P, P, P, P, P, P, P, P, P, P, P);
using F13 = void (*)(P, P, P, P, P, P, P, P, P, P, P, P, P);

// X(name, function type): every routine the static SuiteSparse (CHOLMOD, UMFPACK) refers
// to, in all four of their arithmetics.
#define GEOFAIR_BLAS_ROUTINES(X)                                                          \
  X(dgemm_, F13) X(sgemm_, F13) X(zgemm_, F13) X(cgemm_, F13)                            \
  X(dgemv_, F11) X(sgemv_, F11) X(zgemv_, F11) X(cgemv_, F11)                            \
  X(dtrsm_, F11) X(strsm_, F11) X(ztrsm_, F11) X(ctrsm_, F11)                            \
  X(dsyrk_, F10) X(ssyrk_, F10) X(zherk_, F10) X(cherk_, F10)                            \
  X(dtrsv_, F8) X(strsv_, F8) X(ztrsv_, F8) X(ctrsv_, F8)                                \
  X(dger_, F9) X(zgeru_, F9)                                                             \
  X(dpotrf_, F5) X(spotrf_, F5) X(zpotrf_, F5) X(cpotrf_, F5)

struct Routines {
#define GEOFAIR_FIELD(name, type) type name = nullptr;
  GEOFAIR_BLAS_ROUTINES(GEOFAIR_FIELD)
#undef GEOFAIR_FIELD
  BlasSetThreads set_threads = nullptr;
  BlasGetThreads get_threads = nullptr;
};

Routines routines;
std::atomic<bool> loaded{false};
std::mutex load_mutex;

[[noreturn]] void not_loaded(const char* name) {
  std::fprintf(stderr, "geofair: BLAS routine %s called before the BLAS was loaded\n", name);
  std::abort();
}

void* open_library(const std::string& path) {
#ifdef _WIN32
  const int n = MultiByteToWideChar(CP_UTF8, 0, path.c_str(), -1, nullptr, 0);
  std::wstring wide(n > 0 ? n - 1 : 0, L'\0');
  if (n > 0) MultiByteToWideChar(CP_UTF8, 0, path.c_str(), -1, wide.data(), n);
  return reinterpret_cast<void*>(
      LoadLibraryExW(wide.c_str(), nullptr, LOAD_LIBRARY_SEARCH_DLL_LOAD_DIR |
                                                 LOAD_LIBRARY_SEARCH_DEFAULT_DIRS));
#else
  return dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
#endif
}

std::string open_error() {
#ifdef _WIN32
  return "Windows error " + std::to_string(GetLastError());
#else
  const char* e = dlerror();
  return e ? e : "unknown error";
#endif
}

void* symbol(void* library, const std::string& name) {
#ifdef _WIN32
  return reinterpret_cast<void*>(GetProcAddress(reinterpret_cast<HMODULE>(library), name.c_str()));
#else
  return dlsym(library, name.c_str());
#endif
}

}  // namespace

bool blas_loaded_at_run_time() { return true; }

void load_blas(const std::string& path) {
  const std::lock_guard<std::mutex> lock(load_mutex);
  if (loaded) return;
  void* library = open_library(path);
  if (!library) throw std::runtime_error("cannot load the BLAS " + path + ": " + open_error());
  // scipy-openblas32's prefix, or a plain OpenBLAS's names.
  std::string prefix = "scipy_";
  if (!symbol(library, prefix + "dgemm_")) prefix.clear();
  Routines found;
  const auto resolve = [&](const std::string& name) {
    void* f = symbol(library, prefix + name);
    if (!f) throw std::runtime_error("the BLAS " + path + " has no routine " + prefix + name);
    return f;
  };
#define GEOFAIR_RESOLVE(name, type) found.name = reinterpret_cast<type>(resolve(#name));
  GEOFAIR_BLAS_ROUTINES(GEOFAIR_RESOLVE)
#undef GEOFAIR_RESOLVE
  // Only OpenBLAS has these.
  found.set_threads =
      reinterpret_cast<BlasSetThreads>(symbol(library, prefix + "openblas_set_num_threads"));
  found.get_threads =
      reinterpret_cast<BlasGetThreads>(symbol(library, prefix + "openblas_get_num_threads"));
  routines = found;  // the library stays loaded for the life of the process
  loaded = true;
}

bool blas_loaded() { return loaded; }
BlasSetThreads loaded_blas_set_threads() { return loaded ? routines.set_threads : nullptr; }
BlasGetThreads loaded_blas_get_threads() { return loaded ? routines.get_threads : nullptr; }

}  // namespace geofair

// The forwarders, by SuiteSparse's Fortran names (hidden: the module exports none of them).
#if defined(__GNUC__) && !defined(_WIN32)
#define GEOFAIR_HIDDEN __attribute__((visibility("hidden")))
#else
#define GEOFAIR_HIDDEN
#endif
#define GEOFAIR_ARGS5 P a, P b, P c, P d, P e
#define GEOFAIR_PASS5 a, b, c, d, e
#define GEOFAIR_ARGS8 GEOFAIR_ARGS5, P f, P g, P h
#define GEOFAIR_PASS8 GEOFAIR_PASS5, f, g, h
#define GEOFAIR_ARGS9 GEOFAIR_ARGS8, P i
#define GEOFAIR_PASS9 GEOFAIR_PASS8, i
#define GEOFAIR_ARGS10 GEOFAIR_ARGS9, P j
#define GEOFAIR_PASS10 GEOFAIR_PASS9, j
#define GEOFAIR_ARGS11 GEOFAIR_ARGS10, P k
#define GEOFAIR_PASS11 GEOFAIR_PASS10, k
#define GEOFAIR_ARGS13 GEOFAIR_ARGS11, P l, P m
#define GEOFAIR_PASS13 GEOFAIR_PASS11, l, m
#define GEOFAIR_FORWARD(name, type)                                       \
  extern "C" GEOFAIR_HIDDEN void name(GEOFAIR_ARGS_##type) {              \
    using geofair::routines;                                              \
    if (!routines.name) geofair::not_loaded(#name);                       \
    routines.name(GEOFAIR_PASS_##type);                                   \
  }
using P = void*;
#define GEOFAIR_ARGS_F5 GEOFAIR_ARGS5
#define GEOFAIR_PASS_F5 GEOFAIR_PASS5
#define GEOFAIR_ARGS_F8 GEOFAIR_ARGS8
#define GEOFAIR_PASS_F8 GEOFAIR_PASS8
#define GEOFAIR_ARGS_F9 GEOFAIR_ARGS9
#define GEOFAIR_PASS_F9 GEOFAIR_PASS9
#define GEOFAIR_ARGS_F10 GEOFAIR_ARGS10
#define GEOFAIR_PASS_F10 GEOFAIR_PASS10
#define GEOFAIR_ARGS_F11 GEOFAIR_ARGS11
#define GEOFAIR_PASS_F11 GEOFAIR_PASS11
#define GEOFAIR_ARGS_F13 GEOFAIR_ARGS13
#define GEOFAIR_PASS_F13 GEOFAIR_PASS13
GEOFAIR_BLAS_ROUTINES(GEOFAIR_FORWARD)
