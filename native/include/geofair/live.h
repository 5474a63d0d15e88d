// Live intrinsic modelling: one region faired again and again as its fixed vertices move
// (Schneider & Kobbelt 2001, section 8; a handle dragged through the surface).
#pragma once

#include "geofair/fairing.h"
#include "geofair/types.h"

#include <memory>
#include <vector>

namespace geofair {

struct LiveState;  // the prepared region and the warm start between frames (native/src)

/// A fairing region prepared once and faired again for new positions of its fixed vertices
/// (beyond the paper; its section 8 asks for interactive modelling with interior
/// constraints): the connectivity, the region and its one-rings, the symbolic analysis of
/// the Newton preconditioner and the inner fairness pattern are kept, and each frame starts
/// from the last frame's solution (a warm start), its free vertices moved with the fixed
/// ones by the harmonic extension of their moves (uniform weights, factorized once): one
/// tangential relaxation towards inner fairness and Newton's method on the finest level
/// (Construction::run_newton), both preconditioned by the factorizations of the last frame
/// where GMRES still converges on them, then the polishes of fair. A frame whose warm start
/// does not converge in LiveOptions::max_warm_steps Newton steps (or fails) is remeshed
/// where options.remesh is IfNeeded (see the constructor) and otherwise, or where that did
/// not converge, runs the cold path, fair() with the whole schedule (bounded by
/// options.time_limit, as fair, and by update()'s time_limit); FairingResult::message says
/// which. Design and measurements: docs/LIVE.md.
///
/// Fixed vertices inside the region (a handle) are boundary conditions like the outer ones
/// (fair does the same): their positions and, with G1, the tangent planes estimated from
/// their own triangles (the triangles without a free vertex, estimate_boundary_normals of
/// building_blocks.h), re-estimated from the new positions every frame, so a rigid handle
/// turns its tangent planes with it. A handle needs triangles of its own (at least two
/// rings of fixed vertices at its centre give the quadric fit its samples), or
/// boundary_normals.
///
/// update() and result() may be called from several threads: they take turns.
///
/// Each frame's input is the frame's positions of the fixed vertices with the free
/// vertices' positions of the construction's V (which the conformal inner fairness weights
/// and the bounding box of the residual's length read, as fair does): update() returns the
/// same surface as fair() of that input, within the tolerance, wherever fair() converges.
class LiveFairing {
 public:
  /// Prepares the region of (V, F, free) and fairs it cold (fair(); result(), with
  /// live.details the input V itself, its details coded over that fair base).
  /// \param V, F, free, boundary_normals, options, polygon_ids  as for fair (fairing.h);
  ///        options.remesh Off or IfNeeded (connectivity that follows the drag: a frame whose
  ///        warm start does not converge, or converges with more folded edges than the
  ///        input, is remeshed, and so is the frame after one whose smallest triangle angle
  ///        fell below 1/3 of that of the last frame solved anew (constructor or remesh):
  ///        remesh_region of the last converged frame's surface with the
  ///        frame's fixed positions, and solved warm from there (Newton's method on the new
  ///        mesh, taken where it converges with no more folds than the input), else faired
  ///        cold (at a second edge length of 4/5 where the first fails); taken where it
  ///        converged, with fewer folds than a converged warm start; a remesh that leaves
  ///        folds is tried again three frames later at the earliest; later frames start
  ///        warm on that mesh (its result their input's reference), whose rows are
  ///        remesh_region's layout:
  ///        fixed rows kept, #V' >= #V, rows in no face keep their last positions; the
  ///        constructor fairs the input's own triangles);
  ///        options.progress is not called; options.deadline bounds the constructor's own
  ///        fair alone (update's time_limit bounds a frame).
  /// \throw InvalidInputError as fair, or for options.remesh Always, IfNeeded with
  ///        live.details (details are coded per input vertex) or live.max_warm_steps out of
  ///        range; SolverError as fair, or with live.details where the base did not converge.
  LiveFairing(const Positions& V, const Triangles& F, const std::vector<bool>& free,
              const Positions* boundary_normals, const FairingOptions& options,
              const LiveOptions& live = {}, const std::vector<int>* polygon_ids = nullptr);
  ~LiveFairing();
  LiveFairing(LiveFairing&&) noexcept;
  LiveFairing& operator=(LiveFairing&&) noexcept;

  /// Fairs the region for new positions of the fixed vertices.
  /// \param V  #V×3 positions, mesh units (#V the construction's or, after a remesh, the
  ///           live mesh's #V'): the rows of fixed vertices are the frame's data, those of
  ///           free vertices are not read
  /// \param boundary_normals  #V×3 unit normals read at the G1 boundary vertices (handle
  ///           included), or nullptr: estimated from V as fair does
  /// \return the frame's FairingResult as fair's (the live mesh's #V' rows, faces and free;
  ///         remeshed where this frame replaced the triangles, origin_face then into the
  ///         last frame's faces; rows of fixed vertices bit-identical to V; with details
  ///         the base's fair surface plus the details, the residual and folds the base's);
  ///         a frame that did not converge (the cold path failed too) is returned
  ///         unconverged, with the reason in message (and what the frame tried before,
  ///         such as a remesh that failed), and leaves result() and the next warm start at
  ///         the last converged frame
  /// \throw InvalidInputError if V has another number of rows (than the construction's
  ///        or the live mesh's), a
  ///        fixed vertex of a triangle has a non-finite coordinate, or for the normals (as
  ///        fair), or for a NaN time_limit; SolverError where the cold path raises (as
  ///        fair). Either leaves the state unchanged.
  /// \param time_limit  seconds the frame may take (an interactive drag's bound), or < 0 or
  ///           infinite: none beyond options.time_limit on the cold path. The warm start
  ///           stops before a Newton step once it is spent; a remesh and the cold path stop
  ///           at it too (their own options.time_limit, automatic or not, still applies);
  ///           where nothing is left for them, the frame is returned unconverged
  ///           (StopReason::TimeLimit) without them, its free rows the last converged
  ///           frame's, its residual and folds evaluated there.
  FairingResult update(const Positions& V, const Positions* boundary_normals = nullptr,
                       double time_limit = -1.0);

  /// A copy of the last converged frame (the construction's cold fair until then, converged
  /// or not).
  FairingResult result() const;

  /// Frames since the construction: all of them, those that ran the cold path, and those
  /// that replaced the region's triangles (remesh = IfNeeded).
  int frames() const;
  int cold_frames() const;
  int remeshes() const;

 private:
  std::unique_ptr<LiveState> state_;
};

}  // namespace geofair
