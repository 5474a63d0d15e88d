// The BLAS of the shipped builds (docs/PACKAGING.md): SuiteSparse is linked statically
// without a BLAS, the library defines the Fortran BLAS and LAPACK routines SuiteSparse calls
// and forwards each to a shared OpenBLAS loaded at run time (PyPI's scipy-openblas32, whose
// routines carry the prefix "scipy_"), so the module finds OpenBLAS wherever Python
// installed it. In builds that link a BLAS these calls do nothing.
#pragma once

#include <string>

namespace geofair {

/// Whether this build forwards the BLAS to a library given to load_blas.
bool blas_loaded_at_run_time();

/// Loads the shared library at `path` and resolves the BLAS and LAPACK routines SuiteSparse
/// calls, under their Fortran names with the prefix "scipy_" (scipy-openblas32) or none
/// (a plain OpenBLAS), and OpenBLAS's thread count calls where it has them. Once a library
/// is loaded, later calls do nothing. Throws std::runtime_error naming the library and
/// what is missing.
void load_blas(const std::string& path);

/// Whether the routines are available: a BLAS was loaded, or is linked.
bool blas_loaded();

}  // namespace geofair
