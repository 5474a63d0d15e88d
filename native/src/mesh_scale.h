// The working scale of fair and fill_holes: positions divided by a power of two so that the
// mesh's edges are about 1 long where they are far from it (the squares and fourth powers
// of lengths that normals and areas take then stay normal doubles).
#pragma once

#include "geofair/types.h"

namespace geofair {

/// Mean edge lengths within [2^-kScaleBand, 2^kScaleBand] are worked on as given.
constexpr int kScaleBand = 32;

/// The power of two s by which the caller divides V (exactly) before working on it: 1 where
/// the mean edge length of F lies within [2^-kScaleBand, 2^kScaleBand], else the power of
/// two nearest to it. 1 where F is empty, uses a vertex out of range or with a non-finite
/// coordinate, or has only zero-length edges (the caller's own checks report those).
/// \throw InvalidInputError naming `caller` and the scale where the squared bounding-box
///        diagonal of the used vertices overflows or the squared mean edge length is not a
///        normal double (at most about 1.3e154, at least about 1.5e-154).
double working_scale(const Positions& V, const Triangles& F, const char* caller);

}  // namespace geofair
