// Solving a small symmetric system (N ≤ 6) by LDLᵀ with diagonal pivoting, written out for
// its size: the operations and their order are those of Eigen 3.4's Eigen::LDLT (lower
// triangle; ldlt_inplace::unblocked, then LDLT::solve) where Eigen sums packets of two doubles
// and fuses no multiply-add (x86-64's SSE2, our builds), so the solution is bit-identical to
// Eigen's there (native/tests/test_mean_curvature.cpp compares them), without the general
// code's dynamic-size blocks, which cost more than the arithmetic at this size.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <limits>
#include <utility>

namespace geofair {
namespace small_ldlt_detail {

// Σ a[k] b[k] over k in [begin, begin + length), summed as Eigen's unrolled reduction of a
// product whose terms are not contiguous in memory: by halves.
template <int Begin, int Length, typename A, typename B>
inline double sum_by_halves(const A& a, const B& b) {
  if constexpr (Length == 1) {
    return a(Begin) * b(Begin);
  } else {
    constexpr int half = Length / 2;
    return sum_by_halves<Begin, half>(a, b) + sum_by_halves<Begin + half, Length - half>(a, b);
  }
}

// The same sum where the terms are contiguous (Eigen's reduction by packets of two doubles,
// SSE2): the pairs' lanes summed first, then the lanes, then an odd last term.
template <int Begin, int Length, typename A, typename B>
inline double sum_by_packets(const A& a, const B& b) {
  if constexpr (Length < 2) {
    return sum_by_halves<Begin, Length>(a, b);
  } else {
    double lane0 = a(Begin) * b(Begin), lane1 = a(Begin + 1) * b(Begin + 1);
    for (int k = Begin + 2; k + 1 < Begin + Length; k += 2) {
      lane0 = lane0 + a(k) * b(k);
      lane1 = lane1 + a(k + 1) * b(k + 1);
    }
    const double packets = lane0 + lane1;
    if constexpr (Length % 2 == 0) return packets;
    else return packets + a(Begin + Length - 1) * b(Begin + Length - 1);
  }
}

// The unit lower solve, row by row from the top (rows of a column-major L are strided).
template <int N, int I = 1>
inline void lower_solve(const Eigen::Matrix<double, N, N>& m, Eigen::Matrix<double, N, 1>& x) {
  if constexpr (I < N) {
    x(I) -= sum_by_halves<0, I>([&](int j) { return m(I, j); }, [&](int j) { return x(j); });
    lower_solve<N, I + 1>(m, x);
  }
}

// The unit upper solve with Lᵀ, row by row from the bottom (rows of Lᵀ are contiguous).
template <int N, int Step = 1>
inline void upper_solve(const Eigen::Matrix<double, N, N>& m, Eigen::Matrix<double, N, 1>& x) {
  if constexpr (Step < N) {
    constexpr int d = N - Step - 1;
    x(d) -= sum_by_packets<d + 1, Step>([&](int j) { return m(j, d); }, [&](int j) { return x(j); });
    upper_solve<N, Step + 1>(m, x);
  }
}

// Step K of the factorization (ldlt_inplace::unblocked's loop body); false where Eigen stops.
template <int N, int K>
inline bool factor_step(Eigen::Matrix<double, N, N>& m, int (&transposition)[N]) {
  int biggest = K;  // the first of the largest diagonal entries from K on
  double largest = std::abs(m(K, K));
  for (int i = K + 1; i < N; ++i)
    if (std::abs(m(i, i)) > largest) largest = std::abs(m(i, i)), biggest = i;
  transposition[K] = biggest;
  if (biggest != K) {  // the symmetric swap, in the lower triangle
    for (int j = 0; j < K; ++j) std::swap(m(K, j), m(biggest, j));
    for (int i = biggest + 1; i < N; ++i) std::swap(m(i, K), m(i, biggest));
    std::swap(m(K, K), m(biggest, biggest));
    for (int i = K + 1; i < biggest; ++i) {
      const double t = m(i, K);
      m(i, K) = m(biggest, i);
      m(biggest, i) = t;
    }
  }
  if constexpr (K > 0) {
    double temp[K];
    for (int j = 0; j < K; ++j) temp[j] = m(j, j) * m(K, j);
    double s = m(K, 0) * temp[0];
    for (int j = 1; j < K; ++j) s = s + m(K, j) * temp[j];
    m(K, K) -= s;
    for (int i = K + 1; i < N; ++i) {
      // From 0 as Eigen's packet path (its scalar path starts at the first term: a zero's sign).
      double c = 0.0;
      for (int j = 0; j < K; ++j) c = m(i, j) * temp[j] + c;
      m(i, K) -= c;
    }
  }
  const double pivot = m(K, K);
  const bool valid = std::abs(pivot) > 0.0;
  if (K == 0 && !valid) {  // a zero diagonal: Eigen stops with no transpositions
    for (int j = 0; j < N; ++j) transposition[j] = j;
    return false;
  }
  if (valid)
    for (int i = K + 1; i < N; ++i) m(i, K) /= pivot;
  return true;
}

template <int N, int K = 0>
inline void factor(Eigen::Matrix<double, N, N>& m, int (&transposition)[N]) {
  if constexpr (K < N) {
    if (factor_step<N, K>(m, transposition)) factor<N, K + 1>(m, transposition);
  }
}

}  // namespace small_ldlt_detail

// The solution x of A x = b for a symmetric N×N matrix A (its lower triangle is read), as
// Eigen::LDLT<Matrix<double, N, N>>(A).solve(b) gives it, zero pivots included (their rows
// of x are zero).
template <int N>
Eigen::Matrix<double, N, 1> solve_small_ldlt(Eigen::Matrix<double, N, N> m,
                                             const Eigen::Matrix<double, N, 1>& b) {
  static_assert(N >= 1 && N <= 6, "Eigen sums three or more packets of Lᵀ's rows by halves");
  int transposition[N];
  small_ldlt_detail::factor<N>(m, transposition);
  Eigen::Matrix<double, N, 1> x = b;
  for (int k = 0; k < N; ++k)
    if (transposition[k] != k) std::swap(x(k), x(transposition[k]));
  small_ldlt_detail::lower_solve<N>(m, x);
  for (int i = 0; i < N; ++i) {
    if (std::abs(m(i, i)) > std::numeric_limits<double>::min()) x(i) /= m(i, i);
    else x(i) = 0.0;
  }
  small_ldlt_detail::upper_solve<N>(m, x);
  for (int k = N - 1; k >= 0; --k)
    if (transposition[k] != k) std::swap(x(k), x(transposition[k]));
  return x;
}

}  // namespace geofair
