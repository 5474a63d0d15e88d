// LiveFairing's remeshes (remesh IfNeeded): the live mesh replaced by a remesh of the last
// frame's surface where a frame folds or its triangles degenerate (live.h, live_state.h).
#include "live_state.h"

#include "fairing_internal.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace geofair {

using namespace live_detail;

// The smallest angle of triangles T (rows into X), radians.
double live_detail::smallest_angle(const Positions& X, const Triangles& T) {
  double smallest = M_PI;
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int c = 0; c < 3; ++c) {
      const Eigen::RowVector3d a = X.row(T(t, (c + 1) % 3)) - X.row(T(t, c));
      const Eigen::RowVector3d b = X.row(T(t, (c + 2) % 3)) - X.row(T(t, c));
      smallest = std::min(smallest, std::atan2(a.cross(b).norm(), a.dot(b)));
    }
  return smallest;
}

FairingResult LiveState::remesh_frame(const Positions& V,
                                      const Positions* boundary_normals) const {
  // fair()'s remesh (at the length of the region's border edges, which also resolves the
  // strip that a handle dragged towards the border squeezes) of the last converged frame,
  // whose free vertices fit its fixed ones (with the frame's, those the handle has moved
  // over would fan over it), then its fair with the frame's fixed positions.
  const Positions U = remesh_source(V);
  FairingResult result =
      fair_remeshed_from(U, last.vertices, F, free, boundary_normals, timed_options());
  // Rows in no face: the remesh's spare rows and those of earlier remeshes (never free).
  result.unreferenced.insert(result.unreferenced.end(), unreferenced.begin(), unreferenced.end());
  std::sort(result.unreferenced.begin(), result.unreferenced.end());
  return result;
}

void LiveState::swap_mesh(LiveMesh& other) noexcept {
  std::swap(F, other.F);
  std::swap(free, other.free);
  std::swap(polygon_ids, other.polygon_ids);
  std::swap(V0, other.V0);
  std::swap(region, other.region);
  std::swap(finest, other.finest);
  std::swap(construction, other.construction);
  std::swap(predictor, other.predictor);
  std::swap(used_fixed, other.used_fixed);
  std::swap(unreferenced, other.unreferenced);
  std::swap(X, other.X);
  std::swap(pending, other.pending);  // a folded warm frame of the old mesh is taken from it
  std::swap(drag_steps, other.drag_steps);
  std::swap(trigger.mesh_angle, other.mesh_angle);
}

std::optional<FairingResult> LiveState::warm_remesh(const Positions& V,
                                                    const Positions* boundary_normals,
                                                    const std::string& reason,
                                                    Phases& phases,
                                                    RemeshFailure& failure) {
  Laps laps;
  const Positions U = remesh_source(V);
  RemeshedRegion mesh;
  try {
    mesh = remesh_followed(U / scale, last.vertices / scale, F, free, boundary_normals,
                           options.boundary);
  } catch (const std::exception& error) {
    failure.remesh_threw = true;
    failure.why = std::string("remeshing failed: ") + error.what();
    return std::nullopt;
  }
  phases.emplace_back("remesh", laps.lap());
  // The new mesh's rows in the caller's units: V's fixed rows, the remesh's free ones, and
  // rows in no face their last positions (as the cold remesh's result).
  Positions V_new = mesh.vertices * scale;
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (!mesh.free[std::size_t(v)]) V_new.row(v) = V.row(v);
  for (int v : mesh.unreferenced)
    if (v < last.vertices.rows()) V_new.row(v) = last.vertices.row(v);
  std::optional<Positions> normals;
  if (boundary_normals) normals = live_rows(*boundary_normals, Positions::Zero(V_new.rows(), 3));
  const Positions* normals_new = normals ? &*normals : nullptr;
  LiveMesh old;
  swap_mesh(old);
  std::optional<FairingResult> result;
  try {  // anything that throws on the new mesh brings the old one back
    prepare(mesh.faces, mesh.free, std::nullopt, V_new, normals_new);
    unreferenced = mesh.unreferenced;  // with those of earlier remeshes (never free)
    unreferenced.insert(unreferenced.end(), old.unreferenced.begin(), old.unreferenced.end());
    std::sort(unreferenced.begin(), unreferenced.end());
    X = gather(V0, region.global);
    phases.emplace_back("remesh's preparation", laps.lap());
    std::string warm_why;
    result = warm_frame(V_new, frame_input(V_new), normals_new, phases, warm_why);
    if (!result) failure.why = "the warm solve on the remesh did not converge: " + warm_why;
  } catch (const std::exception& error) {
    result.reset();
    failure.why = std::string("the warm solve on the remesh failed: ") + error.what();
  }
  if (result && result->folds > input_folds)
    failure.why = "the warm solve on the remesh converged with " +
                  std::to_string(result->folds) + " folded edges, the input " +
                  std::to_string(input_folds);
  if (!result || result->folds > input_folds) {
    swap_mesh(old);
    return std::nullopt;
  }
  result->remeshed = true;
  result->origin_face = std::move(mesh.origin_face);
  result->origin_barycentric = std::move(mesh.origin_barycentric);
  result->message += "; remeshed from the last frame, solved warm on the new mesh (" + reason +
                     ")";
  return result;
}

std::optional<FairingResult> LiveState::remesh_first(const Positions& V,
                                                     const Positions* boundary_normals,
                                                     Phases& phases,
                                                     std::optional<RemeshFailure>& failed) {
  if (!trigger.next) return std::nullopt;
  if (out_of_time()) {
    frame_note = "; the remesh first (" + trigger.reason + ") waits for a frame with time";
    return std::nullopt;
  }
  trigger.next = false;
  RemeshFailure failure;
  if (auto result = warm_remesh(V, boundary_normals, trigger.reason, phases, failure)) {
    take_warm_remesh(*result, phases);
    return result;
  }
  failed = failure;
  if (out_of_time() && !failure.remesh_threw && !trigger.deferred) {  // cut short: once more
    trigger.next = true;
    trigger.deferred = true;
    frame_note = "; the remesh first (" + trigger.reason +
                 ") ran out of the frame's time and waits for the next frame";
    return std::nullopt;
  }
  trigger.degenerate_tried = frames;  // not again for kRemeshRetry frames
  frame_note = "; remeshing first (" + trigger.reason + "): " + failure.why;
  return std::nullopt;
}

void LiveState::take_warm_remesh(FairingResult& result, Phases& phases) {
  trigger.folds_tried = -kRemeshRetry;
  trigger.deferred = false;
  take_warm(result, phases);
  V0 = result.vertices / scale;
  trigger.mesh_angle = smallest_angle(X, region.triangles);
  drag_steps.clear();  // a remesh is no drag response
  ++remeshes;
}

void RemeshTrigger::check_angle(double angle) {
  if (!(angle < kDegenerateAngle * mesh_angle)) return;
  char text[160];
  std::snprintf(text, sizeof text,
                "the last frame's triangles degenerated: smallest angle %.1f°, %.1f° where the "
                "live mesh was last solved anew",
                angle * 180.0 / M_PI, mesh_angle * 180.0 / M_PI);
  reason = text;
  next = true;
  deferred = false;
}

void LiveState::check_degenerate() {
  if (options.remesh != Remesh::IfNeeded || !trigger.watching(frames)) return;
  trigger.check_angle(smallest_angle(X, region.triangles));
}

void LiveState::switch_mesh(const FairingResult& result,
                            const Positions* boundary_normals) {
  std::optional<Positions> normals;  // the new rows (free) are not read
  if (boundary_normals)
    normals = live_rows(*boundary_normals, Positions::Zero(result.vertices.rows(), 3));
  std::vector<int> rows_in_no_face = result.unreferenced;
  // The remesh's triangles come from no polygon.
  prepare(result.faces, result.free, std::nullopt, result.vertices, normals ? &*normals : nullptr);
  unreferenced = std::move(rows_in_no_face);
}

std::optional<FairingResult> LiveState::try_remesh(const Positions& V,
                                                   const Positions* boundary_normals,
                                                   bool folded,
                                                   std::string& why) const {
  try {
    FairingResult result = remesh_frame(V, boundary_normals);
    result.message += "; remeshed from the last frame (the warm start " +
                      std::string(folded ? "folded: " : "did not converge: ") + why + ")";
    return result;
  } catch (const std::exception& error) {
    why += std::string("; remeshing failed: ") + error.what();
    return std::nullopt;
  }
}

}  // namespace geofair
