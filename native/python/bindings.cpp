// Python bindings of geofair: numpy in, numpy out. Converts types only; all checks of
// content (indices, finiteness, topology) happen in the C++ library.
#include "geofair/blas.h"
#include "geofair/building_blocks.h"
#include "geofair/fairing.h"
#include "geofair/hole_filling.h"
#include "geofair/tuning.h"
#include "geofair/types.h"

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <type_traits>

namespace py = pybind11;
using namespace geofair;

namespace {

std::string shape_of(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

std::string dtype_of(const py::array& a) { return py::str(a.dtype()).cast<std::string>(); }

py::array as_array(const py::handle& obj, const char* name) {
  if (!py::isinstance<py::array>(obj))
    throw InvalidInputError(std::string(name) + " must be a numpy array, got " +
                            py::str(py::type::of(obj).attr("__name__")).cast<std::string>());
  return py::reinterpret_borrow<py::array>(obj);
}

Positions to_positions(const py::handle& obj, const char* name) {
  const py::array a = as_array(obj, name);
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw InvalidInputError(std::string(name) + " must have shape (n, 3), got " + shape_of(a));
  if (!a.dtype().is(py::dtype::of<double>()))
    throw InvalidInputError(std::string(name) + " must have dtype float64, got " + dtype_of(a) +
                            " (use numpy.asarray(x, dtype=numpy.float64))");
  const auto c = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  return Eigen::Map<const Positions>(c.data(), c.shape(0), 3);
}

// The integer array `a` (named `name` in the error) as C-ordered long long.
py::array_t<long long> integer_array(const py::array& a, const char* name) {
  if (a.dtype().kind() != 'i' && a.dtype().kind() != 'u')
    throw InvalidInputError(std::string(name) + " must have an integer dtype, got " + dtype_of(a));
  return py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(a);
}

Triangles to_triangles(const py::handle& obj) {
  const py::array a = as_array(obj, "faces");
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw InvalidInputError("faces must have shape (m, 3) (triangles), got " + shape_of(a));
  const auto c = integer_array(a, "faces");
  Triangles F(c.shape(0), 3);
  const long long* p = c.data();
  for (py::ssize_t i = 0; i < 3 * c.shape(0); ++i) {
    if (p[i] < 0 || p[i] > std::numeric_limits<int>::max())
      throw InvalidInputError("faces[" + std::to_string(i / 3) + "] has vertex index " +
                              std::to_string(p[i]) + ", out of range");
    F.data()[i] = int(p[i]);
  }
  return F;
}

std::vector<int> to_polygon_ids(const py::handle& obj, py::ssize_t m) {
  const py::array a = as_array(obj, "polygon_ids");
  if (a.ndim() != 1 || a.shape(0) != m)
    throw InvalidInputError("polygon_ids must have shape (" + std::to_string(m) +
                            ",) (one per triangle), got " + shape_of(a));
  const auto c = integer_array(a, "polygon_ids");
  std::vector<int> ids(m);
  for (py::ssize_t t = 0; t < m; ++t) {
    const long long id = c.data()[t];
    if (id < std::numeric_limits<int>::min() || id > std::numeric_limits<int>::max())
      throw InvalidInputError("polygon_ids[" + std::to_string(t) + "] = " + std::to_string(id) +
                              " is out of range");
    ids[t] = int(id);
  }
  return ids;
}

std::vector<bool> to_mask(const py::handle& obj, py::ssize_t n) {
  const py::array a = as_array(obj, "free");
  if (a.ndim() != 1 || a.shape(0) != n)
    throw InvalidInputError("free must have shape (" + std::to_string(n) + ",), got " + shape_of(a));
  if (a.dtype().kind() != 'b')
    throw InvalidInputError("free must have dtype bool, got " + dtype_of(a));
  const auto c = py::array_t<bool, py::array::c_style | py::array::forcecast>::ensure(a);
  return std::vector<bool>(c.data(), c.data() + n);
}

// A std::vector as a new 1-D numpy array (bool or int32). The bool one is returned as a
// plain array: pybind11-stubgen cannot name numpy's bool type (scripts/make_stubs.py).
py::array bool_array(const std::vector<bool>& v) {
  py::array_t<bool> a(py::ssize_t(v.size()));
  bool* p = a.mutable_data();
  for (std::size_t i = 0; i < v.size(); ++i) p[i] = v[i];
  return std::move(a);
}

py::array_t<int> int_array(const std::vector<int>& v) {
  py::array_t<int> a(py::ssize_t(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

// The Python names of the options' values, one table per enum: parse() reads them, name()
// writes them (defaults(), the signature of fair).
template <class Enum>
using Choices = std::initializer_list<std::pair<const char*, Enum>>;
const Choices<InnerFairness> kInnerFairnessNames{{"uniform", InnerFairness::Uniform},
                                                 {"conformal", InnerFairness::Conformal},
                                                 {"conformal_intrinsic", InnerFairness::ConformalIntrinsic}};
const Choices<OuterFairness> kOuterFairnessNames{{"intrinsic", OuterFairness::Intrinsic},
                                                 {"bilaplacian", OuterFairness::Bilaplacian}};
const Choices<NormalWeighting> kNormalWeightingNames{{"area", NormalWeighting::Area},
                                                     {"angle", NormalWeighting::Angle},
                                                     {"max", NormalWeighting::Max},
                                                     {"quadric", NormalWeighting::Quadric}};
const Choices<Iteration> kIterationNames{
    {"auto", Iteration::Auto}, {"newton", Iteration::Newton}, {"paper", Iteration::Paper}};
const Choices<BoundaryCondition> kBoundaryNames{{"g1", BoundaryCondition::G1},
                                                {"g0", BoundaryCondition::G0}};

template <class Enum>
Enum parse(const std::string& value, const char* name, Choices<Enum> choices) {
  std::string allowed;
  for (const auto& [key, e] : choices) {
    if (value == key) return e;
    allowed += std::string(allowed.empty() ? "" : ", ") + "'" + key + "'";
  }
  throw InvalidInputError(std::string(name) + " must be one of " + allowed + ", got '" + value + "'");
}

template <class Enum>
const char* name(Enum value, Choices<Enum> choices) {
  for (const auto& [key, e] : choices)
    if (e == value) return key;
  return "";
}

NormalWeighting parse_weighting(const std::string& s) {
  return parse(s, "normal_weighting", kNormalWeightingNames);
}

InnerFairness parse_inner_fairness(const std::string& s) {
  return parse(s, "inner_fairness", kInnerFairnessNames);
}

// fair's `remesh` argument: False/True or "off"/"always"/"if_needed".
Remesh parse_remesh(const py::object& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? Remesh::Always : Remesh::Off;
  if (py::isinstance<py::str>(value))
    return parse(value.cast<std::string>(), "remesh",
                 Choices<Remesh>{{"off", Remesh::Off}, {"always", Remesh::Always},
                                 {"if_needed", Remesh::IfNeeded}});
  throw InvalidInputError("remesh must be False, True, 'if_needed', 'off' or 'always', got " +
                          std::string(py::str(py::repr(value))));
}

// The Python value of a Remesh: False, True or "if_needed".
py::object remesh_value(Remesh remesh) {
  if (remesh == Remesh::IfNeeded) return py::str("if_needed");
  return py::bool_(remesh == Remesh::Always);
}

// fair's `tuning` argument: {"newton.patience": 30, ...} into `t`; unknown names and values
// of the wrong type raise (the ranges are checked by fair, validate_tuning).
void set_tuning(const py::object& tuning, SolverTuning& t) {
  if (!py::isinstance<py::dict>(tuning))
    throw InvalidInputError("fair: tuning must be a dict or None, got " +
                            std::string(py::str(py::type::of(tuning).attr("__name__"))));
  for (const auto& [key, value] : tuning.cast<py::dict>()) {
    const std::string name = py::str(key);
    bool found = false;
    for_each_tuning_field(t, [&](const char* field_name, auto& field, double, double, bool,
                                 bool) {
      if (found || name != field_name) return;
      found = true;
      using Field = std::decay_t<decltype(field)>;
      // Integers: anything with __index__ (Python's and numpy's ints), not bool.
      const bool integral = PyIndex_Check(value.ptr()) && !py::isinstance<py::bool_>(value);
      const auto wrong = [&] {
        return InvalidInputError("fair: tuning[\"" + name + "\"] must be " +
                                 (std::is_integral_v<Field> ? "an int" : "a number") +
                                 ", got " + std::string(py::str(py::repr(value))));
      };
      if (std::is_integral_v<Field> ? !integral : !(integral || py::isinstance<py::float_>(value)))
        throw wrong();
      try {
        field = value.cast<Field>();
      } catch (const py::cast_error&) {
        throw wrong();  // e.g. an int beyond the C++ int's range
      }
    });
    if (!found)
      throw InvalidInputError("fair: unknown tuning field \"" + name +
                              "\" (the fields: geofair.defaults()[\"tuning\"])");
  }
}

// The defaults of fair's options: FairingOptions{}, the one source (types.h).
py::dict defaults_py() {
  const FairingOptions o;
  py::dict d;
  d["inner_fairness"] = name(o.inner_fairness, kInnerFairnessNames);
  d["outer_fairness"] = name(o.outer_fairness, kOuterFairnessNames);
  d["normal_weighting"] = name(o.normal_weighting, kNormalWeightingNames);
  d["tolerance"] = o.tolerance;
  d["max_iterations"] = o.max_iterations;
  d["damping"] = o.damping;
  d["cg_iterations"] = o.cg_iterations;
  d["levels"] = o.levels;
  d["iteration"] = name(o.iteration, kIterationNames);
  d["boundary"] = name(o.boundary, kBoundaryNames);
  d["remesh"] = remesh_value(o.remesh);
  d["time_limit"] = py::none();
  d["time_limit_base"] = o.tuning.schedule.time_limit_base;
  d["time_limit_per_free_vertex"] = o.tuning.schedule.time_limit_per_free_vertex;
  d["time_limit_hard_factor"] = o.tuning.schedule.time_limit_hard_factor;
  py::dict tuning;
  for_each_tuning_field(o.tuning, [&](const char* key, const auto& value, double, double, bool,
                                      bool) { tuning[key] = value; });
  d["tuning"] = tuning;
  return d;
}

// fair's and fill_holes' docstrings with the figures of the automatic time limit, of Newton's
// method (the default tuning, tuning.h) and of fill_holes' size cap filled in.
std::string fair_doc(std::string doc) {
  const auto replace = [&doc](const std::string& key, const std::string& value) {
    for (std::size_t at; (at = doc.find(key)) != std::string::npos;) doc.replace(at, key.size(), value);
  };
  const auto number = [](double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return std::string(text);
  };
  const SolverTuning t;
  replace("{time_limit_base}", number(t.schedule.time_limit_base));
  replace("{time_limit_per_free_ms}", number(t.schedule.time_limit_per_free_vertex * 1e3));
  replace("{time_limit_hard_factor}", number(t.schedule.time_limit_hard_factor));
  replace("{newton_step}", number(t.newton.max_step));
  replace("{polished_move}", number(t.newton.polished_move));
  replace("{polishes}", number(t.newton.polishes));
  replace("{patience}", number(t.newton.patience));
  replace("{coarse_patience}", number(t.newton.coarse_patience));
  replace("{coarse_merit}", number(t.newton.coarse_merit));
  replace("{min_base_free}", number(t.schedule.newton_min_base_free));
  replace("{retry_min_free}", number(t.schedule.newton_retry_min_free));
  replace("{membrane_first}", number(t.schedule.membrane_first_irregularity));
  replace("{max_fill_vertices}", std::to_string(kMaxFillVertices));
  replace("{outer_border_percent}", number(100.0 * kOuterBorderArea));
  replace("{attempt_first}", number(t.schedule.newton_attempt_first));
  replace("{attempt_first_2}", number(2 * t.schedule.newton_attempt_first));
  replace("{attempt_first_4}", number(4 * t.schedule.newton_attempt_first));
  replace("{attempt_steps}", number(t.schedule.newton_attempt_steps));
  return doc;
}

// The fairing keywords that fair and fill_holes share, as FairingOptions.
FairingOptions fairing_options(const std::string& boundary, const std::string& inner_fairness,
                               const std::string& outer_fairness,
                               const std::string& normal_weighting, double tolerance,
                               int max_iterations, double damping, int cg_iterations,
                               int levels, const std::string& iteration,
                               const py::object& time_limit, const py::object& tuning,
                               const char* caller) {
  FairingOptions options;
  options.boundary = parse(boundary, "boundary", kBoundaryNames);
  options.inner_fairness = parse_inner_fairness(inner_fairness);
  options.outer_fairness = parse(outer_fairness, "outer_fairness", kOuterFairnessNames);
  options.normal_weighting = parse_weighting(normal_weighting);
  options.iteration = parse(iteration, "iteration", kIterationNames);
  options.tolerance = tolerance;
  options.max_iterations = max_iterations;
  options.damping = damping;
  options.cg_iterations = cg_iterations;
  options.levels = levels;
  if (!time_limit.is_none()) {
    options.time_limit = time_limit.cast<double>();
    if (!(options.time_limit >= 0.0))
      throw InvalidInputError(std::string(caller) +
                              ": time_limit must be None or a number >= 0 (seconds), got " +
                              std::string(py::str(time_limit)));
  }
  if (!tuning.is_none()) set_tuning(tuning, options.tuning);
  return options;
}

// Runs solve() without the GIL with options.progress calling `progress` (re-taking the GIL
// at most every 0.1 s); an exception in the callback (e.g. KeyboardInterrupt) stops the run
// and is re-raised.
template <class Solve>
FairingResult with_progress(FairingOptions& options, const py::object& progress, Solve solve) {
  std::optional<py::error_already_set> callback_error;
  if (!progress.is_none()) {
    auto last = std::chrono::steady_clock::now() - std::chrono::seconds(1);
    options.progress = [&, last](int k, double r) mutable {
      if (callback_error) return false;  // a later solve of the call after the callback raised
      const auto now = std::chrono::steady_clock::now();
      if (now - last < std::chrono::milliseconds(100)) return true;
      last = now;
      py::gil_scoped_acquire gil;
      try {
        const py::object ret = progress(k, r);
        return ret.is_none() || ret.cast<bool>();
      } catch (py::error_already_set& e) {
        callback_error = std::move(e);
        return false;
      }
    };
  }
  FairingResult result;
  {
    py::gil_scoped_release release;
    result = solve();
  }
  if (callback_error) throw *callback_error;
  return result;
}

FairingResult fair_py(const py::object& vertices, const py::object& faces, const py::object& free,
                      const py::object& remesh, const std::string& boundary,
                      const py::object& boundary_normals,
                      const py::object& polygon_ids,
                      const std::string& inner_fairness,
                      const std::string& outer_fairness, const std::string& normal_weighting,
                      double tolerance, int max_iterations, double damping, int cg_iterations,
                      int levels, const std::string& iteration, const py::object& progress,
                      const py::object& time_limit, const py::object& tuning) {
  const Positions V = to_positions(vertices, "vertices");
  const Triangles F = to_triangles(faces);
  const std::vector<bool> mask = to_mask(free, V.rows());
  std::optional<std::vector<int>> polygons;
  if (!polygon_ids.is_none()) polygons = to_polygon_ids(polygon_ids, F.rows());
  FairingOptions options = fairing_options(boundary, inner_fairness, outer_fairness,
                                           normal_weighting, tolerance, max_iterations, damping,
                                           cg_iterations, levels, iteration, time_limit, tuning,
                                           "fair");
  options.remesh = parse_remesh(remesh);
  std::optional<Positions> normals;  // not read with G0
  if (!boundary_normals.is_none() && options.boundary == BoundaryCondition::G1) {
    normals = to_positions(boundary_normals, "boundary_normals");
    if (normals->rows() != V.rows())
      throw InvalidInputError("boundary_normals must have the shape of vertices " +
                              std::to_string(V.rows()) + "×3");
  }
  return with_progress(options, progress, [&] {
    return fair(V, F, mask, normals ? &*normals : nullptr, options,
                polygons ? &*polygons : nullptr);
  });
}

// A list of vertex loops (sequences of integers) from Python; None: empty.
std::vector<std::vector<int>> to_loops(const py::object& loops) {
  std::vector<std::vector<int>> out;
  if (loops.is_none()) return out;
  const auto bad = [](const std::string& what) {
    return InvalidInputError("fill_holes: loops must be a list of loops, each a sequence of "
                             "vertex indices (" + what + ")");
  };
  if (py::isinstance<py::str>(loops) || !py::isinstance<py::iterable>(loops))
    throw bad("got " + std::string(py::str(py::type::of(loops).attr("__name__"))));
  const py::object index_of = py::module_::import("operator").attr("index");
  for (const py::handle loop : loops) {
    if (!py::isinstance<py::iterable>(loop) || py::isinstance<py::str>(loop))
      throw bad("loop " + std::to_string(out.size()) + " is not a sequence; a single loop "
                "goes in a list: loops=[loop]");
    std::vector<int> indices;
    for (const py::handle v : loop) {
      long long value = -1;
      try {
        value = index_of(v).cast<long long>();
      } catch (const py::error_already_set&) {  // not an integer (operator.index refuses it)
        throw bad("loop " + std::to_string(out.size()) + " holds " +
                  std::string(py::str(py::repr(v))));
      } catch (const py::cast_error&) {
        value = -1;
      }
      if (value < 0 || value > std::numeric_limits<int>::max())
        throw bad("loop " + std::to_string(out.size()) + " holds the index " +
                  std::string(py::str(py::repr(v))) + ", out of range");
      indices.push_back(int(value));
    }
    out.push_back(std::move(indices));
  }
  if (out.empty()) throw InvalidInputError("fill_holes: loops is empty (None fills every hole)");
  return out;
}

// fill_holes' and holes_to_fill's rule (HoleRule) from their keyword arguments.
HoleRule hole_rule(bool keep_outer_borders, const py::object& max_hole_edges, const char* caller) {
  HoleRule rule;
  rule.keep_outer_borders = keep_outer_borders;
  if (!max_hole_edges.is_none()) {
    long long value = 0;
    try {
      value = py::module_::import("operator").attr("index")(max_hole_edges).cast<long long>();
    } catch (const std::exception&) {
      value = 0;
    }
    if (value < 1 || value > std::numeric_limits<int>::max())
      throw InvalidInputError(std::string(caller) +
                              ": max_hole_edges must be None or a positive integer, got " +
                              std::string(py::str(py::repr(max_hole_edges))));
    rule.max_hole_edges = int(value);
  }
  return rule;
}

FairingResult fill_holes_py(const py::object& vertices, const py::object& faces,
                            const py::object& loops, const py::object& target_edge_length,
                            bool keep_outer_borders, const py::object& max_hole_edges,
                            const std::string& boundary, const std::string& inner_fairness,
                            const std::string& outer_fairness,
                            const std::string& normal_weighting, double tolerance,
                            int max_iterations, double damping, int cg_iterations, int levels,
                            const std::string& iteration, const py::object& progress,
                            const py::object& time_limit, const py::object& tuning) {
  const Positions V = to_positions(vertices, "vertices");
  const Triangles F = to_triangles(faces);
  const std::vector<std::vector<int>> holes = to_loops(loops);
  const HoleRule rule = hole_rule(keep_outer_borders, max_hole_edges, "fill_holes");
  double length = 0.0;
  if (!target_edge_length.is_none()) {
    length = target_edge_length.cast<double>();
    if (!(length > 0.0) || !std::isfinite(length))
      throw InvalidInputError(
          "fill_holes: target_edge_length must be None or a positive finite number, got " +
          std::string(py::str(target_edge_length)));
  }
  FairingOptions options = fairing_options(boundary, inner_fairness, outer_fairness,
                                           normal_weighting, tolerance, max_iterations, damping,
                                           cg_iterations, levels, iteration, time_limit, tuning,
                                           "fill_holes");
  return with_progress(options, progress,
                       [&] { return fill_holes(V, F, holes, options, length, rule); });
}

Eigen::VectorXd mean_curvature_py(const py::object& vertices, const py::object& faces,
                                  const py::object& normals, const std::string& weighting) {
  const Positions V = to_positions(vertices, "vertices");
  const Triangles F = to_triangles(faces);
  std::optional<Positions> N;
  if (!normals.is_none()) N = to_positions(normals, "normals");
  const NormalWeighting w = parse_weighting(weighting);
  py::gil_scoped_release release;
  return mean_curvature(V, F, N ? &*N : nullptr, w);
}

// A binding of f(V, F) taking (vertices, faces) arrays: converts and checks them, then runs
// f without the GIL.
template <class Function>
auto on_mesh(Function f) {
  return [f](const py::object& vertices, const py::object& faces) {
    const Positions V = to_positions(vertices, "vertices");
    const Triangles F = to_triangles(faces);
    py::gil_scoped_release release;
    return f(V, F);
  };
}

// geofair.FairingResult.
void bind_result(py::module_& m) {
  py::class_<FairingResult>(m, "FairingResult", "Result of geofair.fair.")
      .def_readonly("vertices", &FairingResult::vertices,
                    "(n', 3) float64 positions; fixed rows are bit-identical to the input. "
                    "n' = n unless .remeshed (then max(n, #fixed + #new free)).")
      .def_readonly("faces", &FairingResult::faces,
                    "(m', 3) int32 triangles of the result: the input's unless .remeshed (then "
                    "the input faces without a free vertex, unchanged and first, then the "
                    "region's new ones; fill_holes: the input's faces, then the fill's).")
      .def_property_readonly(
          "free", [](const FairingResult& r) { return bool_array(r.free); },
          "(n',) bool: the result's free vertices (the input's mask unless .remeshed; "
          "fill_holes: exactly the new vertices).")
      .def_readonly("remeshed", &FairingResult::remeshed,
                    "True when the region's triangles were replaced (fair's remesh).")
      .def_property_readonly(
          "unreferenced", [](const FairingResult& r) { return int_array(r.unreferenced); },
          "(k,) int32: rows of .vertices in no face (input free rows that the remesh did not "
          "reuse, input positions kept); empty unless .remeshed.")
      .def_property_readonly(
          "origin_face", [](const FairingResult& r) { return int_array(r.origin_face); },
          "(n',) int32: for each free vertex of a remeshed region the input face (row of the "
          "input faces) it was created on, on the input surface before fairing; -1 for the "
          "other rows and for every row unless .remeshed.")
      .def_readonly("origin_barycentric", &FairingResult::origin_barycentric,
                    "(n', 3) float64 barycentric coordinates in .origin_face (rows sum to 1); "
                    "zero rows where .origin_face is -1. With .origin_face they carry "
                    "per-corner data (UVs) over from the input.")
      .def_readonly("converged", &FairingResult::converged,
                    "True if the residual reached the tolerance.")
      .def_readonly("iterations", &FairingResult::iterations,
                    "Number of iterations M_k -> M_{k+1} performed.")
      .def_readonly("iterations_per_level", &FairingResult::iterations_per_level,
                    "Iterations on each level, coarsest first.")
      .def_readonly("vertices_per_level", &FairingResult::vertices_per_level,
                    "Region vertices (free and G1 boundary) on each level, coarsest first.")
      .def_readonly("residual", &FairingResult::residual,
                    "Normalized residual of the returned mesh (dimensionless, see fair).")
      .def_readonly("message", &FairingResult::message,
                    "How the solve ended, one sentence: \"converged (...)\" or why not (the "
                    "time limit, max_iterations, cancelled), with the residual and tolerance.")
      .def_property_readonly(
          "stop_reason",
          [](const FairingResult& r) {
            switch (r.stop_reason) {
              case StopReason::Converged: return "converged";
              case StopReason::MaxIterations: return "max_iterations";
              case StopReason::TimeLimit: return "time_limit";
              case StopReason::NoProgress: return "no_progress";
              case StopReason::Cancelled: return "cancelled";
              case StopReason::Diverged: return "diverged";
            }
            return "max_iterations";
          },
          "Why the solve ended, message's first clause as a value: \"converged\"; "
          "\"max_iterations\" (a level spent max_iterations, or Newton's method stalled with "
          "iteration=\"newton\"); \"time_limit\" (time_limit, or the automatic limit's hard "
          "cap); \"no_progress\" (the automatic limit: the residual did not halve for its "
          "span); \"cancelled\" (progress returned False); \"diverged\" "
          "(iteration=\"auto\"'s last attempt failed: the input is returned).")
      .def_property_readonly(
          "iteration",
          [](const FairingResult& r) {
            return std::string(r.iteration == Iteration::Newton ? "newton" : "paper");
          },
          "The iteration that produced the result: \"newton\" or \"paper\".")
      .def_readonly("newton_iterations", &FairingResult::newton_iterations,
                    "Newton steps performed, including an attempt that iteration=\"auto\" "
                    "abandoned for the paper's iteration.")
      .def_readonly("folds", &FairingResult::folds,
                    "Edges with a free vertex whose two triangles face apart (normals with a "
                    "negative dot product) in .vertices: triangles the result flips over. A "
                    "converged result can have them where the G1 data turn faster than the "
                    "mesh resolves, or keep them from a folded input; .message then says so.")
      .def_readonly("new_folds", &FairingResult::new_folds,
                    "Those of .folds whose two triangles did not face apart in the input.")
      .def_readonly("phase_seconds", &FairingResult::phase_seconds,
                    "Wall-clock seconds of the solve's phases, a list of (name, seconds) in "
                    "the order they ran: \"remesh\" where the region was remeshed, "
                    "\"hierarchy\", then per level l (0 = coarsest) "
                    "\"level l initial mesh\", \"level l set-up\" and, for Newton's method, "
                    "\"level l inner fairness\", \"level l Newton steps\", \"level l "
                    "polishes\", for the paper's iteration \"level l iterations\" (an "
                    "abandoned attempt's phases included). They do not overlap: their sum "
                    "stays below the call's wall time.")
      .def("__repr__", [](const FairingResult& r) {
        return "FairingResult(converged=" + std::string(r.converged ? "True" : "False") +
               ", iterations=" + std::to_string(r.iterations) +
               ", residual=" + std::to_string(r.residual) + ")";
      });
}

// Defines geofair.<python_name>: the function's own arguments `own`, then the keyword arguments of
// the solve that fair and fill_holes share (their defaults: FairingOptions'), then `doc`.
template <class Function, class... Own>
void def_solve(py::module_& m, const char* python_name, Function&& f, const char* doc,
               Own&&... own) {
  const FairingOptions d;
  m.def(python_name, std::forward<Function>(f), std::forward<Own>(own)...,
        py::arg("inner_fairness") = name(d.inner_fairness, kInnerFairnessNames),
        py::arg("outer_fairness") = name(d.outer_fairness, kOuterFairnessNames),
        py::arg("normal_weighting") = name(d.normal_weighting, kNormalWeightingNames),
        py::arg("tolerance") = d.tolerance, py::arg("max_iterations") = d.max_iterations,
        py::arg("damping") = d.damping, py::arg("cg_iterations") = d.cg_iterations,
        py::arg("levels") = d.levels,
        py::arg("iteration") = name(d.iteration, kIterationNames),
        py::arg("progress") = py::none(), py::arg("time_limit") = py::none(),
        py::arg("tuning") = py::none(), doc);
}

// geofair.defaults and geofair.fair.
void bind_fair(py::module_& m) {
  m.def("defaults", &defaults_py,
        R"doc(The defaults of geofair.fair's options, the library's one source of them.

Returns
-------
dict: "inner_fairness", "outer_fairness", "normal_weighting", "iteration" (str),
"tolerance" (float, dimensionless), "max_iterations", "cg_iterations", "levels" (int),
"damping" (float), "remesh" (False, True or "if_needed"), "time_limit" (None: automatic),
the automatic time limit of iteration="auto" (time without a halving of the residual),
"time_limit_base" (seconds) plus
"time_limit_per_free_vertex" (seconds per free vertex), its hard cap as a multiple of that,
"time_limit_hard_factor", and "tuning" (dict: the solvers' numerical choices beyond the paper, by
dotted name, e.g. "newton.patience"; their units and ranges: native/include/geofair/tuning.h).)doc");

  const FairingOptions d;
  static const std::string fair_docstring = fair_doc(R"doc(Fair the free vertices of a triangle mesh: the discrete solution of Δ_B H = 0
(Schneider & Kobbelt 2001, eqs. (4), (12), construction of section 7) with the G1 boundary
condition (fixed positions and unit normals) at the fixed vertices next to free ones, or
with boundary="g0" the G0 condition (fixed positions, H = 0).

Parameters
----------
vertices : (n, 3) float64 array, positions in mesh units.
faces : (m, 3) integer array, triangles, consistently oriented (counter-clockwise seen from
    the normal side), manifold around the free region.
free : (n,) bool array, True where a vertex may move. Each free vertex must be surrounded
    by triangles (not on the mesh border). Fixed vertices that share a triangle with a free
    vertex form the boundary.
remesh : False (default; also "off"), True (also "always") or "if_needed". False: the
    connectivity is kept (the paper's setting). True: the region's triangles (those with a
    free vertex) are first replaced by geofair.remesh_region's isotropic remesh at the mean
    length of the region's border edges (fixed vertices and the region's border edges
    kept; the G1 normals taken from the input), then faired. "if_needed": faired with the
    connectivity kept first; where that does not converge or folds triangles over that
    were not folded, remeshed and faired again: the remeshed result is returned if it
    converged without new folds, else the better of the two (converged first, then fewer
    new folds, then the smaller residual); .message says which. A remeshed result has
    other vertices and faces: n' rows (fixed rows keep index and position, the input's free
    rows are reused, extra rows appended; .unreferenced lists free rows left over), its
    .faces, .free, and .origin_face / .origin_barycentric locating each new free vertex on
    the input surface (to carry UVs over); its .folds and .new_folds count its own
    triangles (new: not folded in the remesh before fairing). polygon_ids do not apply to
    the new triangles. An explicit time_limit covers the whole call; the automatic one
    applies to each solve.
boundary : "g1" (default) or "g0". "g1": the paper's G1 condition, positions and unit
    normals (boundary_normals) prescribed at the boundary; spheres, cylinders and minimal
    surfaces that fit the data are reproduced. "g0": positions only, with H = 0 prescribed
    on the boundary; Δ_B H = 0 then gives H ≡ 0, the minimal surface spanned by the
    boundary (a plane for a planar loop, a catenoid between two coaxial circles close
    enough together; the intrinsic counterpart of Blender's Fair Positions and CGAL's fair
    with continuity 0). With "g0" boundary_normals is ignored (not read, not checked),
    nothing is estimated from the surface around the region, so the region may reach the
    mesh border, and the linear initial mesh (and outer_fairness="bilaplacian") is the
    membrane Δf = 0: Δ²f = 0 with Δf = 0 at the boundary, the linear counterpart of H = 0.
    H is signed as in geofair.mean_curvature (H = 1/r on a sphere with outward normals);
    with "g0" its sign does not matter, it vanishes on the boundary and in the result.
boundary_normals : (n, 3) float64 array or None, read with boundary="g1" only. Rows at
    G1 boundary vertices are the prescribed unit normals (other rows are ignored); one
    whose dot product with the estimate of geofair.boundary_normals is negative is
    rejected (flipped normals or faces). None: geofair.boundary_normals(vertices, faces,
    free), the tangent plane of a least-squares quadric through the fixed vertices around
    it (error O(h²); earlier releases took the one-sided area-weighted normal, O(h)).
polygon_ids : (m,) integer array or None: the polygon of the caller's mesh that each
    triangle was tessellated from (e.g. Blender's MeshLoopTriangle.polygon_index); an edge
    whose two triangles carry the same id is a diagonal of a polygon. None: every edge is
    an edge of the mesh. Read by inner_fairness="uniform" only (beyond the paper): its
    umbrella runs over the polygon mesh's edges, so the vertex distribution of a quad mesh
    does not depend on which diagonal split each quad. A free vertex left with fewer than
    three such neighbours (a G1 boundary vertex: with none) keeps its whole ring.
    The surface (Δ_B H, mean curvature, normals) is always that of the triangles.
inner_fairness : where the vertices sit on the surface (section 7.3): "uniform" (regular
    vertex distribution; along the polygons' edges with polygon_ids); "conformal" (the
    discrete harmonic map with the cotangent weights of the input mesh: discrete-conformal
    to it, keeps texture distortion low; weights that obtuse triangles make negative are
    clamped to 0, and a vertex whose remaining neighbours do not surround it, at a sharp
    cone point of the input, takes the mean value weights of its ring); or
    "conformal_intrinsic" (the discrete harmonic map with the cotangent weights of the
    intrinsic Delaunay triangulation of the input, Bobenko & Springborn 2007: never
    negative, nothing clamped, so vertices land where the harmonic map puts them also on
    meshes of obtuse triangles; identical to "conformal" on a mesh that needs no intrinsic
    flip. On rough inputs (noise as large as the features) it can stall where "conformal"
    converges; see docs/ACCURACY_AND_SPEED.md, "Negative cotangent weights").
outer_fairness : "intrinsic" (Δ_B H = 0) or "bilaplacian" (the linear Δ²f = 0 initial mesh
    of section 7.4 alone, for comparison).
normal_weighting : free-vertex normals: "quadric" (default, beyond the paper: the tangent
    plane of a least-squares quadric through the one-ring, consistent on irregular meshes),
    "area" (the paper's choice, section 6: sum of face cross products), "angle" (Thürmer &
    Wüthrich 1998) or "max" (Max 1999, exact on spheres). Measured in docs/ACCURACY_AND_SPEED.md.
tolerance : stop when the residual is at most this (dimensionless). The residual is
    L * max_i |Hbar_i - H_i| over the free vertices: how far the mean curvature H_i
    deviates from the cotangent-weighted mean Hbar_i = Σ_j w_ij H_j / Σ_j w_ij of its
    neighbours (the Jacobi-scaled residual of eq. (12), about h**2 |Δ_B H| for edge length
    h), with L the bounding-box diagonal of the region. Invariant under scaling, and it
    asks the same local smoothness of H on a coarse and a fine mesh (L**3 |Δ_B H| would
    ask (L/h)**2 times more of the fine one). Measured on disturbed sphere caps with Max's
    normals (the sphere is the exact discrete solution): 1e-4 leaves a max radial error of
    1e-6 (2000 free vertices) to 6e-6 (13000), below the discretization error of area
    normals there (1e-3 to 3e-4).
max_iterations : upper bound on the iterations spent solving each level (iterations that
    the multigrid cycles of a finer level run on a coarser one are not counted), and on
    the Newton steps.
iteration : how eq. (12) is solved; all choices solve the same discrete equations.
    "newton" (beyond the paper): Newton's method on the normal offsets of all free
    vertices at once, level by level on the progressive mesh (section 7.4's nested
    iteration; levels): the base level from the linear initial mesh, each finer level from
    the prolongation of the coarser solution, each brought to inner fairness first by
    tangential solves. Per step one inexact Newton step: GMRES on the products of the
    exact Jacobian of the defects (normals, Moreton–Séquin H and cotangent weights
    recomputed; forward differences), preconditioned by the sparse LU factorization of a
    fixed-normal Jacobian of an earlier step; steps limited to {newton_step} mean neighbour distances
    per vertex. At convergence of the finest level tangential solves restore inner
    fairness (linearized with the turn of the tangent planes, so that repeated solves
    converge quadratically; above the base level by GMRES on a two-grid preconditioner with
    the next coarser level, three-grid with the next two, without a factorization at the
    level's size), repeated while the next one would move a vertex by more than {polished_move} mean
    neighbour distances (predicted from the last move by the quadratic convergence), at
    most {polishes} times (the steps go on where one raised the residual). A level stops when the
    residual has not halved in {patience} steps (a coarse level in {coarse_patience}). Where Newton's
    method fails on the base level from its linear initial mesh, the base level runs
    {attempt_first} iterations of the paper's iteration and one Newton attempt from there; a
    coarse level that stops unconverged with a merit (the RMS of the scaled defects) of at
    most {coarse_merit} still starts the next, and a coarse level above the base stops once its
    merit is at most that and a step no longer halves it. Where a coarse level fails, the hierarchy is solved
    again with other coarse weights (uniform inner fairness: from the membrane of the
    finest weights, its hierarchy decimated on the smoothed input and then on the membrane,
    then each level's own uniform weights), then the finest level alone; the membrane's
    weights go first where at least {membrane_first} of the free vertices have a valence
    other than 6 (an irregular connectivity), its hierarchy decimated on the membrane;
    a region solved as one level (fewer than 4 × {min_base_free} free vertices) with at least
    {retry_min_free} free vertices tries two levels where the one fails.
    "paper": the local/global iteration of section 7 with multigrid cycles (levels).
    "auto" (default): "newton", and where it stops unconverged or fails, "paper" from the
    start, with Newton's method tried from the paper's iterate after {attempt_first},
    {attempt_first_2}, {attempt_first_4}, ... iterations of the finest level (at most
    {attempt_steps} steps or {patience} without halving the residual each); the
    first attempt that converges ends the solve (.message says after how many). The LU
    factors of the Newton steps take memory, growing faster than the vertex count; the
    README's speed table gives the steps per level and the peak memory
    (bench/speed.py).
damping : s in q <- q~ + s t n (section 7.2), in (0, 1].
cg_iterations : conjugate-gradient iterations of a global step (section 7.1).
levels : levels of the progressive-mesh multigrid (section 7.4, Fig. 6), 4 times as many
    free vertices per level: 1 solves the whole region as one level; 0 (default) picks
    them from the region. For "newton": as many as keep at least {min_base_free} free vertices on the
    base level (its hierarchy coarsens the G1 boundary too, see progressive_mesh); for
    "paper": one level up to 1000 free vertices and
    about log4(free vertices / 250) + 1 above, each finer level solved by nonlinear
    multigrid cycles on the coarser ones.
time_limit : seconds (float) the whole call may take, or None (default): automatic with
    iteration="auto", a limit on time without progress: Newton's attempts end by their own rule
    (see iteration), the paper's iteration once its residual has not halved for {time_limit_base} s
    plus {time_limit_per_free_ms} ms per free vertex, and the whole call in any case after {time_limit_hard_factor} times that; no limit with
    "newton" or "paper" (they run to max_iterations); float("inf") for no limit. Once spent,
    the result is returned with converged=False and a message saying so (the input
    positions if no level finished).
progress : callable(iteration, residual) -> bool or None, called at most every 0.1 s;
    returning False stops the run early (converged is then False).
tuning : dict or None (default): overrides of the solvers' numerical choices beyond the
    paper, from dotted names such as "newton.patience" to numbers; the names and defaults:
    geofair.defaults()["tuning"], units and valid ranges: native/include/geofair/tuning.h.
    An unknown name, a value of the wrong type or out of range raises ValueError.

Returns
-------
FairingResult with .vertices (n', 3) float64 (n' = n unless remeshed), .faces (m', 3)
int32, .free (n',) bool, .remeshed, .unreferenced, .origin_face and .origin_barycentric
(see remesh; the input's faces and mask, -1 and zeros when not remeshed), .converged,
.iterations (all levels),
.residual, .iterations_per_level and .vertices_per_level (lists, coarsest level first),
.iteration ("newton" or "paper"), .newton_iterations, .folds and .new_folds (edges whose
triangles the result flips over, and those not folded in the input) and .phase_seconds
(wall-clock seconds per phase, for profiling).

Raises
------
ValueError for invalid input (the message names the problem and the vertex or face; a mesh
whose squared lengths leave the normal doubles, with a bounding-box diagonal above about
1.3e154 or a mean edge length below about 1.5e-154, names its size), RuntimeError if the
computation fails or diverges. NaN or Inf is never returned. Within those sizes the result
is the same at any scale (positions are worked on in units of the mesh's own size).)doc");
  def_solve(m, "fair", &fair_py, fair_docstring.c_str(), py::arg("vertices"), py::arg("faces"),
            py::arg("free"), py::kw_only(), py::arg("remesh") = remesh_value(d.remesh),
            py::arg("boundary") = name(d.boundary, kBoundaryNames),
            py::arg("boundary_normals") = py::none(), py::arg("polygon_ids") = py::none());
}

// geofair.cotangent_laplacian, intrinsic_delaunay and intrinsic_delaunay_laplacian.
void bind_laplacians(py::module_& m) {
  m.def(
      "cotangent_laplacian",
      on_mesh([](const Positions& V, const Triangles& F) { return cotangent_laplacian(V, F); }),
      py::arg("vertices"), py::arg("faces"),
      R"doc(The cotangent Laplace–Beltrami matrix L of a triangle mesh (Schneider & Kobbelt
2001, eqs. (5)-(7)) as an (n, n) scipy.sparse CSR matrix (needs scipy).

L[i, j] = cot α_ij + cot β_ij for every edge (a single cotangent on a border edge) and
L[i, i] = -Σ_j L[i, j]: symmetric, L @ ones = 0. (L @ f)[i] = (2 A_i / 3) Δ_B f(q_i) with A_i
the area of the 1-disk, so L @ vertices = -(4 A_i / 3) H_i n_i; the matrix S of eqs. (6),
(7) is -L restricted to the free rows and columns.

Raises ValueError for invalid input.)doc");

  m.def(
      "intrinsic_delaunay",
      on_mesh([](const Positions& V, const Triangles& F) {
        IntrinsicTriangulation T = intrinsic_delaunay(V, F);
        return std::make_tuple(std::move(T.triangles), std::move(T.lengths), T.flips);
      }),
      py::arg("vertices"), py::arg("faces"),
      R"doc(Intrinsic Delaunay triangulation of a triangle mesh by edge flips (Fisher et al.
2006; Bobenko & Springborn 2007): same vertices, same surface, other edges (geodesics on
the mesh) such that the two angles opposite every interior edge sum to at most π.

Returns
-------
(triangles, lengths, flips): (m, 3) int32 vertex indices (counter-clockwise like faces; a
triangle may repeat a vertex), (m, 3) float64 edge lengths in mesh units (lengths[t, k]
from corner k to corner k+1 of triangle t), and the number of flips (0 if the mesh was
intrinsically Delaunay).

Raises ValueError for invalid input, RuntimeError if round-off made the flips cycle.)doc");

  m.def(
      "intrinsic_delaunay_laplacian",
      on_mesh([](const Positions& V, const Triangles& F) {
        return intrinsic_delaunay_laplacian(V, F);
      }),
      py::arg("vertices"), py::arg("faces"),
      R"doc(The cotangent Laplacian of the intrinsic Delaunay triangulation (Bobenko &
Springborn 2007) as an (n, n) scipy.sparse CSR matrix, with the conventions of
cotangent_laplacian: L[i, j] = Σ cot of the angles opposite the intrinsic edges between
i and j, L[i, i] = -Σ_j L[i, j]. Every off-diagonal entry is >= 0 (to round-off), unlike
the cotangent Laplacian of a mesh with obtuse triangles; equal to cotangent_laplacian
where the mesh is already intrinsically Delaunay.

Raises ValueError for invalid input.)doc");
}

// geofair.relax_inner_fairness and progressive_mesh: steps of fair() on their own.
void bind_solver_steps(py::module_& m) {
  m.def(
      "relax_inner_fairness",
      [](const py::object& vertices, const py::object& faces, const py::object& free,
         const py::object& normals, const std::string& inner_fairness,
         const std::string& tangent_planes, const py::object& polygon_ids) {
        const Positions V = to_positions(vertices, "vertices");
        const Triangles F = to_triangles(faces);
        const std::vector<bool> mask = to_mask(free, V.rows());
        std::optional<std::vector<int>> polygons;
        if (!polygon_ids.is_none()) polygons = to_polygon_ids(polygon_ids, F.rows());
        const Positions N_all = to_positions(normals, "normals");
        const InnerFairness inner = parse_inner_fairness(inner_fairness);
        const TangentPlanes planes = parse<TangentPlanes>(
            tangent_planes, "tangent_planes",
            {{"fixed", TangentPlanes::Fixed}, {"turning", TangentPlanes::Turning}});
        std::pair<Positions, double> relaxed;
        {
          py::gil_scoped_release release;
          relaxed = relax_inner_fairness(V, F, mask, N_all, inner, planes,
                                         polygons ? &*polygons : nullptr);
        }
        return py::make_tuple(relaxed.first, relaxed.second);
      },
      py::arg("vertices"), py::arg("faces"), py::arg("free"), py::arg("normals"),
      py::arg("inner_fairness") = "uniform", py::arg("tangent_planes") = "turning",
      py::arg("polygon_ids") = py::none(),
      R"doc(One global tangential solve of inner fairness, the step fair()'s Newton iteration
repeats (Schneider & Kobbelt 2001, section 7.3's condition, linearized for all free
vertices at once; beyond the paper): every free vertex moves in its tangent plane so that
the tangential part of the inner-fairness Laplacian Σ_j λ_ij q_j − q_i vanishes, the whole
move scaled so that no edge stretches or shrinks by more than half its length. The
vertices are not lifted back onto the surface.

Parameters
----------
vertices : (n, 3) float64 array; faces : (m, 3) integer array; free : (n,) bool mask, as
    for fair() (the region and its G1 boundary).
normals : (n, 3) float64 normals of the tangent planes (rows of free vertices and their
    ring neighbours are read; normalized here).
inner_fairness : "uniform" (default), "conformal" or "conformal_intrinsic", the weights
    of the mesh as given.
tangent_planes : "turning" (default): Newton's linearization, with the first-order turn of
    each tangent plane as its vertex moves along the surface (the normal part ℓ_i of the
    Laplacian vector times the normal's derivative D_i, fitted to the ring's normals, on
    the diagonal blocks); repeated solves converge quadratically. "fixed": the tangent
    planes held fixed (section 7.3's update, all vertices at once); repeated solves
    converge linearly.
polygon_ids : (m,) integer array or None, as for fair(): uniform weights over the polygon
    mesh's edges.

Returns
-------
(vertices, scale): (n, 3) float64 positions (free rows moved, mesh units) and the scale in
(0, 1] applied to the solved move.

Raises ValueError for invalid input, RuntimeError (geofair.SolverError) if the system is
singular.)doc");

  m.def(
      "progressive_mesh",
      [](const py::object& vertices, const py::object& faces, const py::object& free, int levels,
         bool coarsen_boundary) {
        const Positions V = to_positions(vertices, "vertices");
        const Triangles F = to_triangles(faces);
        const std::vector<bool> mask = to_mask(free, V.rows());
        py::gil_scoped_release release;
        return progressive_mesh_levels(V, F, mask, levels, coarsen_boundary);
      },
      py::arg("vertices"), py::arg("faces"), py::arg("free"), py::arg("levels") = 1,
      py::arg("coarsen_boundary") = false,
      R"doc(The progressive-mesh hierarchy that fair() uses for its multigrid (Schneider &
Kobbelt 2001, section 7.4): a list of (m_l, 3) int32 triangle arrays in the input's vertex
indices, coarsest level first, the last being the region (triangles with a free vertex)
itself. Levels are nested (the vertex set of each is a subset of the next).

coarsen_boundary=False: the hierarchy of the paper's iteration (iteration="paper"): G1
boundary vertices are never collapsed, free vertices keep valences 5..8 through the
collapses, and a coarse level keeps at least half as many free vertices as there are boundary
vertices. True: the hierarchy of Newton's method (iteration="newton", the default path):
boundary vertices collapse too, along the region's border into a neighbour on it (each border
loop keeps at least 12 vertices; a fixed vertex inside the region never collapses), free
vertices keep valences 4..10, those of valence 3 and 4 collapse first, and level l keeps about
(free + boundary vertices) / 4^(levels-1-l) vertices.

Measured on the input smoothed by 10 sweeps of the uniform Laplacian (fair() smooths with its
inner fairness weights).

Raises ValueError for invalid input.)doc");
}

// geofair.boundary_normals and mean_curvature.
void bind_geometry(py::module_& m) {
  m.def(
      "boundary_normals",
      [](const py::object& vertices, const py::object& faces, const py::object& free,
         const std::string& method) {
        const Positions V = to_positions(vertices, "vertices");
        const Triangles F = to_triangles(faces);
        const std::vector<bool> mask = to_mask(free, V.rows());
        const BoundaryNormalEstimate estimate = parse<BoundaryNormalEstimate>(
            method, "method",
            {{"quadric", BoundaryNormalEstimate::Quadric}, {"area", BoundaryNormalEstimate::Area}});
        py::gil_scoped_release release;
        Positions N = estimate_boundary_normals(V, F, mask, estimate);
        for (Eigen::Index v = 0; v < N.rows(); ++v)
          if (!N.row(v).allFinite())
            throw InvalidInputError("boundary_normals: the normal of G1 boundary vertex " +
                                    std::to_string(v) +
                                    " is not finite (a vertex of its surrounding triangles has "
                                    "a non-finite coordinate)");
        return N;
      },
      py::arg("vertices"), py::arg("faces"), py::arg("free"), py::kw_only(),
      py::arg("method") = "quadric",
      R"doc(The unit normals fair() prescribes at the G1 boundary when it is given no
boundary_normals: estimated from the fixed surface around the free region (beyond the
paper; Schneider & Kobbelt 2001, section 7.5, average the outside triangles' normals).

The G1 boundary is the set of fixed vertices that share a triangle with a free vertex; a
vertex's surrounding triangles are its triangles without a free vertex (the positions of
free vertices, which fairing replaces, never enter).

Parameters
----------
vertices : (n, 3) float64 array, positions in mesh units.
faces : (m, 3) integer array, consistently oriented triangles.
free : (n,) bool array, True where a vertex may move.
method : "quadric" (default): the tangent plane of a least-squares paraboloid
    z = a x + b y + c x² + d xy + e y² through the vertex, fitted to the fixed vertices
    within two rings reached through surrounding triangles, in the frame of the "area"
    normal and refitted once in the fitted normal's frame; error O(h²) for edge length h on
    a smooth surface (falls back to "area" where the fit is ill-conditioned: fewer than 6
    samples, condition number above 1e6, e.g. only two straight rows of fixed vertices, or
    a tilt of 45° or more). "area": the area-weighted normal of the surrounding
    triangles, one-sided, error O(h) (fair()'s estimate before this release). Measured in
    tests/test_boundary_normals.py.

Returns
-------
(n, 3) float64: unit normals at G1 boundary vertices, oriented like the faces (positive
dot product with the surrounding triangles' normal); zero rows at all other vertices and at
G1 boundary vertices without a surrounding triangle (where the free region reaches the
mesh border: fair() without boundary_normals raises there) or with only degenerate ones.

Raises
------
ValueError for invalid input (shapes, dtypes, indices, a non-finite vertex of a
surrounding triangle).)doc");

  m.def("mean_curvature", &mean_curvature_py, py::arg("vertices"), py::arg("faces"),
        py::arg("normals") = py::none(), py::arg("normal_weighting") = "quadric",
        R"doc(Discrete mean curvature at every vertex by Moreton & Séquin (Schneider & Kobbelt
2001, section 6, eqs. (8)-(11)), with the spiral samples of section 6.2 at vertices of
valence 3 or 4 and on the mesh border.

Parameters
----------
vertices : (n, 3) float64 array.
faces : (m, 3) integer array of consistently oriented triangles.
normals : (n, 3) float64 unit normals (tangent planes) or None to estimate them from the
    triangles with `normal_weighting` ("quadric", the default: tangent plane of a
    least-squares quadric through the one-ring; "area", the paper's choice; "angle" or
    "max").

Returns
-------
(n,) float64 mean curvature in 1/length: H = 1/r on a sphere of radius r whose faces are
oriented outward, 1/(2r) on a cylinder, 0 on a plane; 0 at vertices in no triangle.

Raises
------
ValueError for invalid input.)doc");
}

// geofair.fill_holes, geofair.holes_to_fill and geofair.boundary_loops.
void bind_holes(py::module_& m) {
  const FairingOptions d;
  static const std::string fill_holes_docstring = fair_doc(R"doc(Fill holes of a triangle mesh with intrinsically faired patches: each hole's
loop keeps its positions and takes its unit normals from the faces around it (the G1
boundary of Schneider & Kobbelt 2001, section 4; estimated as geofair.boundary_normals
does), and the patch solves Δ_B H = 0 (eq. (12)), so a hole cut into a sphere, cylinder
or catenoid is filled with that surface (beyond the paper: the triangulation and refinement).

Each hole's loop is triangulated (Liepa's dynamic programme, Liepa 2003, "Filling holes
in meshes", by the largest dihedral angle between adjacent triangles, the faces around the
loop included, then the area; loops of more than 500 vertices get a fan around their
centroid), the edges across the hole are split, the patch is remeshed isotropically at
target_edge_length (geofair.remesh_region), and all patches are faired together by
geofair.fair with the new vertices free. Where that does not converge or folds an edge and
target_edge_length is None, the holes are filled once more at half the loops' edge length
(ragged loops need a finer fill next to them) and the better result is returned; its
message says so.

Parameters
----------
vertices : (n, 3) float64 array, positions in mesh units.
faces : (m, 3) integer array, triangles, consistently oriented, manifold.
loops : None (default): the holes of geofair.holes_to_fill(vertices, faces,
    keep_outer_borders=..., max_hole_edges=...), every boundary loop but the outer borders
    of open surfaces (the result's .message names the loops left open and why); or a list
    of loops, each a sequence of vertex indices along one boundary loop (any start vertex,
    either direction), filled whatever their size.
target_edge_length : edge length of the fill in mesh units, or None (default): the mean
    length of the hole's loop edges.
keep_outer_borders : with loops=None, leave each outer border open (default True): in each
    connected part of the mesh, the boundary loop that spans the largest area (the norm of
    its vector area, ½|Σ (p_i − c) × (p_{i+1} − c)| about the centroid c of its vertices
    p_i), where that is at least {outer_border_percent} % of the area of the part's triangles. A
    sheet's border spans about the sheet's own area (a height field's: its area projected on
    the plane), a hole in a closed surface a small part of it (a sphere missing a cap of
    polar angle θ: (1 − cos θ)/2 of the rest, below {outer_border_percent} % up to θ = 66°). A part has at
    most one outer border: a hole in a sheet is filled whatever its size. False: every
    boundary loop is a hole (an open sheet is then capped into a closed surface). Not read
    when loops are given.
max_hole_edges : with loops=None, leave loops of more edges than this open (like Blender's
    Fill Holes Sides or MeshLab's Close Holes size); None (default): no limit.
boundary, inner_fairness, outer_fairness, normal_weighting, tolerance, max_iterations,
damping, cg_iterations, levels, iteration, progress, time_limit, tuning : as for
    geofair.fair (time_limit covers the filling too); boundary="g0" fills with the minimal
    surface spanned by the loop.

Returns
-------
FairingResult: .vertices (n + k, 3), the input's n rows first and bit-identical, the k new
vertices after; .faces (m + l, 3), the input's m faces first and unchanged, the new ones
after, oriented like the faces around the holes; .free (n + k,) bool, True exactly at the
new vertices; .remeshed True (.origin_face -1: a fill has no input surface); .converged,
.residual, .message, .stop_reason, .folds, .new_folds and .phase_seconds (starting with
"fill") as for fair.

Raises
------
ValueError (geofair.InvalidInputError) when loops is not a list of sequences of vertex
indices, a loop is not a boundary loop of the mesh (the offending pair of vertices is named),
a vertex is on two given loops, the mesh has no hole to fill (no boundary loop, or with
loops=None every loop is left open: the message names them and why), max_hole_edges is not
None or a positive integer, a fill would take more than {max_fill_vertices} new vertices, the mesh's
squared lengths leave the normal doubles (a bounding-box diagonal above about 1.3e154 or a
mean edge length below about 1.5e-154: the message names the size), or for the input fair
refuses (the message names the problem and the vertex or face); RuntimeError as fair.
Within those sizes the fill is the same at any scale (positions are worked on in units of
the mesh's own size).)doc");
  def_solve(m, "fill_holes", &fill_holes_py, fill_holes_docstring.c_str(), py::arg("vertices"),
            py::arg("faces"), py::arg("loops") = py::none(), py::kw_only(),
            py::arg("target_edge_length") = py::none(),
            py::arg("keep_outer_borders") = HoleRule{}.keep_outer_borders,
            py::arg("max_hole_edges") = py::none(),
            py::arg("boundary") = name(d.boundary, kBoundaryNames));
  static const std::string holes_to_fill_docstring = fair_doc(R"doc(The holes that geofair.fill_holes fills when it is given no loops: the boundary
loops of the mesh (geofair.boundary_loops) less those the rule leaves open.

Parameters
----------
vertices : (n, 3) float64 array, positions in mesh units; faces : (m, 3) integer array,
    consistently oriented, manifold.
keep_outer_borders : leave each outer border open (default True): in each connected part,
    the boundary loop that spans the largest area, where that is at least {outer_border_percent} % of the
    area of the part's triangles (see geofair.fill_holes). False: every boundary loop is a
    hole.
max_hole_edges : leave loops of more edges than this open; None (default): no limit.

Returns
-------
(holes, left_open): holes a list of (k,) int32 arrays, the loops to fill as
geofair.boundary_loops returns them (in its order); left_open a list of (loop, reason)
tuples, the other loops with one clause for a user saying why (e.g. "an outer border: it
spans 95 % of the area of its part's triangles (a hole less than 30 %)"). Both empty for
a closed mesh. The same at any scale of the mesh.

Raises
------
ValueError as geofair.boundary_loops, for max_hole_edges not None or a positive integer,
or a mesh whose squared lengths leave the normal doubles (see geofair.fill_holes).)doc");
  m.def(
      "holes_to_fill",
      [](const py::object& vertices, const py::object& faces, bool keep_outer_borders,
         const py::object& max_hole_edges) {
        const Positions V = to_positions(vertices, "vertices");
        const Triangles F = to_triangles(faces);
        const HoleRule rule = hole_rule(keep_outer_borders, max_hole_edges, "holes_to_fill");
        HoleChoice choice;
        {
          py::gil_scoped_release release;
          choice = holes_to_fill(V, F, rule);
        }
        py::list holes, left_open;
        for (const auto& loop : choice.holes) holes.append(int_array(loop));
        for (const auto& open : choice.left_open)
          left_open.append(py::make_tuple(int_array(open.loop), open.reason));
        return py::make_tuple(holes, left_open);
      },
      py::arg("vertices"), py::arg("faces"), py::kw_only(),
      py::arg("keep_outer_borders") = HoleRule{}.keep_outer_borders,
      py::arg("max_hole_edges") = py::none(),
      holes_to_fill_docstring.c_str());
  m.def(
      "boundary_loops",
      [](const py::object& vertices, const py::object& faces) {
        const Positions V = to_positions(vertices, "vertices");
        const Triangles F = to_triangles(faces);
        std::vector<std::vector<int>> loops;
        {
          py::gil_scoped_release release;
          loops = boundary_loops(V, F);
        }
        py::list out;
        for (const auto& loop : loops) out.append(int_array(loop));
        return out;
      },
      py::arg("vertices"), py::arg("faces"),
      R"doc(The boundary loops (holes) of a triangle mesh.

Parameters
----------
vertices : (n, 3) float64 array; faces : (m, 3) integer array, consistently oriented, manifold.

Returns
-------
list of (k,) int32 arrays, one per loop, its vertices in the direction of the missing face
(a followed by b: the mesh has a triangle with the edge b -> a), so a triangle (a, b, c)
added into the hole is oriented like its neighbours; empty for a closed mesh. Every border
is a loop, an open mesh's outer border too (geofair.holes_to_fill tells holes from outer
borders).

Raises
------
ValueError for invalid triangles or a vertex on two loops (holes that touch).)doc");
}

// geofair.remesh_region and its result, geofair.RemeshedRegion.
void bind_remesh(py::module_& m) {
  py::class_<RemeshedRegion>(m, "RemeshedRegion", "Result of geofair.remesh_region.")
      .def_readonly("vertices", &RemeshedRegion::vertices,
                    "(n', 3) float64 positions, mesh units; rows of fixed vertices are "
                    "bit-identical to the input, n' = max(n, #fixed + #new free).")
      .def_readonly("faces", &RemeshedRegion::faces,
                    "(m', 3) int32 triangles: the input faces without a free vertex "
                    "(unchanged, in input order), then the region's new triangles.")
      .def_property_readonly(
          "free", [](const RemeshedRegion& r) { return bool_array(r.free); },
          "(n',) bool: True exactly at the new region's free vertices.")
      .def_property_readonly(
          "unreferenced", [](const RemeshedRegion& r) { return int_array(r.unreferenced); },
          "(k,) int32: input free rows that no new vertex reuses (in no face, not free).")
      .def_property_readonly(
          "origin_face", [](const RemeshedRegion& r) { return int_array(r.origin_face); },
          "(n',) int32: for each free vertex the input face (row of the input faces) its "
          "position lies on; -1 for fixed vertices and unreferenced rows.")
      .def_readonly("origin_barycentric", &RemeshedRegion::origin_barycentric,
                    "(n', 3) float64 barycentric coordinates in origin_face (rows sum to 1; "
                    "vertices[i] = Σ_k b[i, k] * input_vertices[input_faces[f, k]] to "
                    "round-off); zeros where origin_face is -1.")
      .def("__repr__", [](const RemeshedRegion& r) {
        return "RemeshedRegion(vertices=" + std::to_string(r.vertices.rows()) +
               ", faces=" + std::to_string(r.faces.rows()) +
               ", free=" + std::to_string(std::count(r.free.begin(), r.free.end(), true)) + ")";
      });

  m.def(
      "remesh_region",
      [](const py::object& vertices, const py::object& faces, const py::object& free,
         const py::object& target_edge_length, int iterations) {
        const Positions V = to_positions(vertices, "vertices");
        const Triangles F = to_triangles(faces);
        const std::vector<bool> mask = to_mask(free, V.rows());
        RemeshOptions options;
        options.iterations = iterations;
        if (!target_edge_length.is_none()) {
          options.target_edge_length = target_edge_length.cast<double>();
          if (!(options.target_edge_length > 0.0) || !std::isfinite(options.target_edge_length))
            throw InvalidInputError(
                "remesh_region: target_edge_length must be None or a positive finite number, "
                "got " + std::string(py::str(target_edge_length)));
        }
        py::gil_scoped_release release;
        return remesh_region(V, F, mask, options);
      },
      py::arg("vertices"), py::arg("faces"), py::arg("free"), py::kw_only(),
      py::arg("target_edge_length") = py::none(), py::arg("iterations") = RemeshOptions{}.iterations,
      R"doc(Isotropic remesh of a region of a triangle mesh (Botsch & Kobbelt 2004, "A
remeshing approach to multiresolution modeling", section 4), the step fair(remesh=...)
runs before fairing: the region's triangles (those with a free vertex) are replaced, the
fixed vertices and the region's border edges are kept.

Each iteration splits edges longer than 4/3 L, collapses edges shorter than 4/5 L (a free
vertex into a neighbour; never one that would create an edge longer than 4/3 L), flips
interior edges towards valence 6 (4 on the mesh border, counting the edges outside the
region), and moves each free vertex to the area-weighted centroid of its one-ring in its
tangent plane. Every new or moved vertex is projected onto the closest point of the input
region's triangles. No step turns a triangle over, leaves it thinner (twice the area over
the longest edge squared) than 0.05 and than the triangle it replaces, or puts a vertex on
the region's border; such a step is skipped.

Parameters
----------
vertices : (n, 3) float64 array, positions in mesh units.
faces : (m, 3) integer array, triangles; those with a free vertex must form a consistently
    oriented 2-manifold.
free : (n,) bool array, True where a vertex may move (not on the mesh border).
target_edge_length : float > 0 in mesh units, or None (default): the mean length of the
    region's border edges (of all its edges where it has no border).
iterations : int >= 0, rounds of split, collapse, flip and relaxation (0: the input).

Returns
-------
RemeshedRegion with .vertices (n', 3) float64, .faces (m', 3) int32 (the faces without a
free vertex unchanged and first, then the new ones), .free (n',) bool, .unreferenced (k,)
int32, .origin_face (n',) int32 and .origin_barycentric (n', 3) float64 (where each free
vertex lies on the input surface). Rows of fixed vertices keep their index and position
bit-identically; a surviving input free vertex keeps its row, the other new free vertices
take the remaining input free rows in increasing order, then rows appended after n, so
n' = max(n, #fixed + #new free); free rows left over are listed in .unreferenced.

Raises
------
ValueError for invalid input (shapes, indices, no free vertex, a free vertex on the mesh
border, a region that is not a consistently oriented 2-manifold, invalid options).)doc");
}

// The OpenBLAS of a build that loads its BLAS at run time (geofair/blas.h): the file that
// the environment variable GEOFAIR_BLAS names (the legacy add-on sets it to the copy beside
// the module), else that of PyPI's scipy-openblas32, a dependency of the wheel.
void load_openblas() {
  if (!blas_loaded_at_run_time()) return;
  std::string path;
  if (const char* named = std::getenv("GEOFAIR_BLAS"); named && *named) {
    path = named;
  } else {
    py::object package;
    try {
      package = py::module_::import("scipy_openblas32");
    } catch (py::error_already_set& e) {
      throw py::import_error(
          "geofair needs OpenBLAS from the package scipy-openblas32 (pip install "
          "scipy-openblas32), or GEOFAIR_BLAS set to an OpenBLAS library: " + std::string(e.what()));
    }
    const std::filesystem::path dir = package.attr("get_lib_dir")().cast<std::string>();
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(dir, error)) {
      const std::string name = entry.path().filename().string();
      const std::string ext = entry.path().extension().string();
      if (name.rfind("libscipy_openblas", 0) == 0 && (ext == ".so" || ext == ".dylib" || ext == ".dll"))
        path = entry.path().string();
    }
    if (path.empty()) throw py::import_error("geofair: no OpenBLAS library in " + dir.string());
  }
  try {
    load_blas(path);
  } catch (const std::exception& e) {
    throw py::import_error(std::string("geofair: ") + e.what());
  }
}

}  // namespace

PYBIND11_MODULE(geofair, m) {
  load_openblas();
  m.doc() =
      "Intrinsic mesh fairing: discrete solutions of Δ_B H = 0 with G1 boundary conditions\n"
      "(Schneider & Kobbelt, Geometric fairing of irregular meshes for free-form surface\n"
      "design, CAGD 18, 2001).";
  m.attr("__version__") = GEOFAIR_VERSION;  // pyproject.toml's, through CMake
  py::register_exception<InvalidInputError>(m, "InvalidInputError", PyExc_ValueError);
  py::register_exception<SolverError>(m, "SolverError", PyExc_RuntimeError);

  bind_result(m);
  bind_fair(m);
  bind_laplacians(m);
  bind_solver_steps(m);
  bind_geometry(m);
  bind_remesh(m);
  bind_holes(m);
}
