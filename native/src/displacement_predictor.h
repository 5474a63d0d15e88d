// The harmonic extension of fixed vertices' moves into the free ones (LiveFairing's warm
// start, and the remesh of a frame in fair_remeshed_from).
#pragma once

#include "region.h"

#include <Eigen/SparseCholesky>

#include <vector>

namespace geofair {

/// The harmonic extension (uniform weights, Δu = 0 at the free vertices) of the fixed
/// vertices' moves into the free ones, so that the vertices next to a moving handle move
/// with it instead of being squashed against it (a start within Newton's reach where the
/// last frame alone folds its triangles). `region` must outlive the predictor.
class DisplacementPredictor {
 public:
  explicit DisplacementPredictor(const FairingRegion& region) : region_(region) {
    const OneRings& rings = region.rings;
    const int nf = region.n_free;
    std::vector<Eigen::Triplet<double>> entries;
    for (int i = 0; i < nf; ++i) {
      entries.emplace_back(i, i, double(rings.valence(i)));
      for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k)
        if (rings.ring[k] < nf) entries.emplace_back(i, rings.ring[k], -1.0);
    }
    Eigen::SparseMatrix<double> L(nf, nf);
    L.setFromTriplets(entries.begin(), entries.end());
    ldlt_.compute(L);
  }

  /// Adds to the free rows of Y the extension of `moves` (#V_B×3, the fixed rows' moves);
  /// false (Y unchanged) where the factorization or the solve failed.
  bool predict(const Positions& moves, Positions& Y) const {
    if (ldlt_.info() != Eigen::Success) return false;
    const OneRings& rings = region_.rings;
    const int nf = region_.n_free;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(nf, 3);
    for (int i = 0; i < nf; ++i)
      for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k)
        if (rings.ring[k] >= nf) rhs.row(i) += moves.row(rings.ring[k] - nf);
    const Eigen::MatrixXd u = ldlt_.solve(rhs);
    if (ldlt_.info() != Eigen::Success || !u.allFinite()) return false;
    Y.topRows(nf) += u;
    return true;
  }

 private:
  const FairingRegion& region_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
};

}  // namespace geofair
