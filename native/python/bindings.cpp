// Python bindings of geofair: numpy in, numpy out. Converts types only; all checks of
// content (indices, finiteness, topology) happen in the C++ library.
#include "geofair/blas.h"
#include "geofair/building_blocks.h"
#include "geofair/fairing.h"
#include "geofair/hole_filling.h"
#include "geofair/mesh_file.h"
#include "geofair/live.h"
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
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

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

// The (m, 3) faces of `caller`'s mesh of n vertices; an index outside [0, n) is reported as
// the library reports it ("fair: triangle 7 has vertex index -1, out of range [0, 162)").
Triangles to_triangles(const py::handle& obj, const char* caller, Eigen::Index n) {
  const py::array a = as_array(obj, "faces");
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw InvalidInputError("faces must have shape (m, 3) (triangles), got " + shape_of(a));
  const auto c = integer_array(a, "faces");
  Triangles F(c.shape(0), 3);
  const long long* p = c.data();
  for (py::ssize_t i = 0; i < 3 * c.shape(0); ++i) {
    if (p[i] < 0 || p[i] >= n)
      throw InvalidInputError(std::string(caller) + ": triangle " + std::to_string(i / 3) +
                              " has vertex index " + std::to_string(p[i]) + ", out of range [0, " +
                              std::to_string(n) + ")");
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

// Whether pybind11 converts `value` to the C++ parameter type T, as a call does (convert mode).
template <class T>
bool converts(py::handle value) {
  py::detail::make_caster<T> caster;
  return caster.load(value, true);
}

// T in the words of a wrong-type message; nullptr for py::object (anything converts).
template <class T>
const char* type_words() {
  using U = std::decay_t<T>;
  if constexpr (std::is_same_v<U, double>) return "a number";
  if constexpr (std::is_same_v<U, int>) return "an int";
  if constexpr (std::is_same_v<U, bool>) return "a bool";
  if constexpr (std::is_same_v<U, std::string>) return "a str";
  return nullptr;
}

// The C++ parameter types of a function pointer or lambda, as converters.
struct Converter {
  bool (*converts)(py::handle);
  const char* words;
};
template <class F>
struct ParameterTypes : ParameterTypes<decltype(&F::operator())> {};
template <class R, class... A>
struct ParameterTypes<R (*)(A...)> {
  static std::vector<Converter> get() { return {Converter{&converts<A>, type_words<A>()}...}; }
};
template <class R, class C, class... A>
struct ParameterTypes<R (C::*)(A...) const> : ParameterTypes<R (*)(A...)> {};
template <class R, class C, class... A>
struct ParameterTypes<R (C::*)(A...)> : ParameterTypes<R (*)(A...)> {};

// A module function's parameters as its py::arg extras declare them: the source of its text
// signature (CPython's __text_signature__, so inspect.signature works) and of the checks that
// give a wrong call a short TypeError naming the argument (pybind11's own lists the signature
// and the repr of every argument, input arrays included).
class Signature {
 public:
  explicit Signature(std::string function) : function_(std::move(function)) {}

  void add(const py::arg_v& a) {
    parameters_.push_back({a.name, std::string(py::repr(a.value)), keyword_only_, {}});
  }
  void add(const py::arg& a) { parameters_.push_back({a.name, std::nullopt, keyword_only_, {}}); }
  void add(const py::kw_only&) { keyword_only_ = true; }
  void add(const char* doc) { doc_ = doc; }

  const std::string& doc() const { return doc_; }

  void set_types(const std::vector<Converter>& types) {
    if (types.size() != parameters_.size())
      throw std::logic_error(function_ + ": py::arg count differs from the C++ parameters");
    for (std::size_t i = 0; i < types.size(); ++i) parameters_[i].type = types[i];
  }

  // "(vertices, faces, free, *, remesh=False, ...)": Python literals as defaults.
  std::string text() const {
    std::string t = "(";
    bool star = false;
    for (const auto& p : parameters_) {
      if (t.size() > 1) t += ", ";
      if (p.keyword_only && !star) {
        t += "*, ";
        star = true;
      }
      t += p.name + (p.default_value ? "=" + *p.default_value : "");
    }
    return t + ")";
  }

  // Checks a call's arguments as CPython does for a Python function (count, names, missing,
  // repeated; an unknown keyword with the nearest valid name), and their types as pybind11
  // converts them; then calls `inner`.
  py::object call(const py::object& inner, const py::args& args, const py::kwargs& kwargs) const {
    std::size_t positional = 0;
    while (positional < parameters_.size() && !parameters_[positional].keyword_only) ++positional;
    if (args.size() > positional)
      throw py::type_error(function_ + "() takes " + std::to_string(positional) +
                           " positional argument" + (positional == 1 ? "" : "s") + " but " +
                           std::to_string(args.size()) + " were given" +
                           (positional < parameters_.size() ? " (the others are keyword-only)" : ""));
    std::vector<bool> given(parameters_.size(), false);
    for (std::size_t i = 0; i < args.size(); ++i) {
      given[i] = true;
      check_type(parameters_[i], args[i]);
    }
    for (const auto& [key, value] : kwargs) {
      const std::string name = py::str(key);
      const auto at = std::find_if(parameters_.begin(), parameters_.end(),
                                   [&](const Parameter& p) { return p.name == name; });
      if (at == parameters_.end()) throw unknown_keyword(name);
      const std::size_t i = std::size_t(at - parameters_.begin());
      if (given[i])
        throw py::type_error(function_ + "() got multiple values for argument '" + name + "'");
      given[i] = true;
      check_type(*at, value);
    }
    for (std::size_t i = 0; i < parameters_.size(); ++i)
      if (!given[i] && !parameters_[i].default_value)
        throw py::type_error(function_ + "() missing required argument '" + parameters_[i].name +
                             "'");
    try {
      return inner(*args, **kwargs);
    } catch (py::error_already_set& e) {
      // A conversion the checks above did not foresee: pybind11's message without its lists.
      if (e.matches(PyExc_TypeError) &&
          std::string(e.what()).find("incompatible function arguments") != std::string::npos)
        throw py::type_error(function_ + "(): incompatible function arguments; help(geofair." +
                             function_ + ") gives the signature");
      throw;
    }
  }

 private:
  struct Parameter {
    std::string name;
    std::optional<std::string> default_value;  // a Python literal; none: required
    bool keyword_only;
    Converter type;
  };

  void check_type(const Parameter& p, py::handle value) const {
    if (!p.type.words || p.type.converts(value)) return;
    std::string got = "None";
    if (!value.is_none()) {
      got = py::str(py::type::of(value).attr("__name__"));
      const std::string repr = py::repr(value);
      if (repr.size() <= 40) got += " " + repr;  // not an array's
    }
    throw py::type_error(function_ + "(): " + p.name + " must be " + p.type.words + ", got " + got);
  }

  py::type_error unknown_keyword(const std::string& name) const {
    py::list names;
    std::string all;
    for (const auto& p : parameters_) {
      names.append(p.name);
      all += (all.empty() ? "" : ", ") + p.name;
    }
    const py::list close =
        py::module_::import("difflib").attr("get_close_matches")(name, names, 1);
    const std::string hint = close.empty()
                                 ? " (its arguments: " + all + ")"
                                 : "; did you mean '" + py::str(close[0]).cast<std::string>() + "'?";
    return py::type_error(function_ + "() got an unexpected keyword argument '" + name + "'" + hint);
  }

  std::string function_;
  std::vector<Parameter> parameters_;
  bool keyword_only_ = false;
  std::string doc_;
};

// Defines geofair.<name>(...) = f as m.def(name, f, extra...) would, `extra` being py::arg,
// py::arg_v, py::kw_only and the docstring: pybind11 converts the arguments as it would, after
// the checks of Signature, and CPython reads the signature from the docstring's first line.
// f as pybind11 converts its arguments (`inner`), the Signature that checks a call first, and
// the docstring whose first line CPython reads as the text signature; `name` is the function's
// name in messages, `signature_name` the one of the text signature ("__init__" for a class's).
struct CheckedFunction {
  std::shared_ptr<Signature> signature;
  py::object inner;
  std::string docstring;

  py::object operator()(const py::args& args, const py::kwargs& kwargs) const {
    return signature->call(inner, args, kwargs);
  }
};

template <class Function, class... Extra>
CheckedFunction checked_function(const char* name, const char* signature_name, Function&& f,
                                 const Extra&... extra) {
  auto signature = std::make_shared<Signature>(name);
  (signature->add(extra), ...);
  signature->set_types(ParameterTypes<std::decay_t<Function>>::get());
  const py::object inner = py::cpp_function(std::forward<Function>(f), py::name(name), extra...);
  std::string docstring = signature_name + signature->text() + "\n--\n\n" + signature->doc();
  return {std::move(signature), inner, std::move(docstring)};
}

template <class Function, class... Extra>
void def_checked(py::module_& m, const char* name, Function&& f, const Extra&... extra) {
  const CheckedFunction checked =
      checked_function(name, name, std::forward<Function>(f), extra...);
  py::options options;
  options.disable_function_signatures();
  m.def(
      name,
      [checked](const py::args& args, const py::kwargs& kwargs) { return checked(args, kwargs); },
      checked.docstring.c_str());
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

// LiveFairing's `remesh` argument: False or "off"/"if_needed" (a frame keeps its vertex rows
// unless it must remesh; "always" would replace them every frame).
Remesh parse_live_remesh(const py::object& value) {
  if (py::isinstance<py::bool_>(value) && !value.cast<bool>()) return Remesh::Off;
  if (py::isinstance<py::str>(value)) {
    const std::string s = value.cast<std::string>();
    if (s == "off") return Remesh::Off;
    if (s == "if_needed") return Remesh::IfNeeded;
  }
  throw InvalidInputError("remesh must be False, 'off' or 'if_needed', got " +
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
  for (const auto& item : tuning.cast<py::dict>()) {
    const std::string name = py::str(item.first);
    const py::handle value = item.second;  // (a lambda may not capture a structured binding in C++17)
    bool found = false;
    for_each_tuning_field(t, [&](const char* field_name, auto& field, double, double, bool,
                                 bool, const char*) {
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

// The defaults of fair's keyword arguments, in its signature's order: FairingOptions{}, the
// one source (types.h); "tuning" spelled out (None in the signature means these).
py::dict defaults_py() {
  const FairingOptions o;
  py::dict d;
  d["remesh"] = remesh_value(o.remesh);
  d["boundary"] = name(o.boundary, kBoundaryNames);
  d["boundary_normals"] = py::none();
  d["polygon_ids"] = py::none();
  d["inner_fairness"] = name(o.inner_fairness, kInnerFairnessNames);
  d["outer_fairness"] = name(o.outer_fairness, kOuterFairnessNames);
  d["normal_weighting"] = name(o.normal_weighting, kNormalWeightingNames);
  d["tolerance"] = o.tolerance;
  d["max_iterations"] = o.max_iterations;
  d["damping"] = o.damping;
  d["cg_iterations"] = o.cg_iterations;
  d["levels"] = o.levels;
  d["iteration"] = name(o.iteration, kIterationNames);
  d["progress"] = py::none();
  d["time_limit"] = py::none();
  py::dict tuning;
  for_each_tuning_field(o.tuning, [&](const char* key, const auto& value, double, double, bool,
                                      bool, const char*) { tuning[key] = value; });
  d["tuning"] = tuning;
  return d;
}

// fair's and fill_holes' docstrings with the figures of the automatic time limit (the default
// tuning, tuning.h), of fair's numerical defaults and of fill_holes' size cap filled in.
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
  const FairingOptions o;
  replace("{tolerance}", number(o.tolerance));
  replace("{max_iterations}", std::to_string(o.max_iterations));
  replace("{damping}", number(o.damping));
  replace("{cg_iterations}", std::to_string(o.cg_iterations));
  replace("{max_fill_vertices}", std::to_string(kMaxFillVertices));
  replace("{fill_max_iterations}", std::to_string(t.schedule.fill_max_iterations));
  replace("{outer_border_percent}", number(100.0 * kOuterBorderArea));
  return doc;
}

// A time_limit keyword as FairingOptions::time_limit: None and 0 the automatic limit (or
// none) as a negative number, so that the add-on's Time Limit property, which cannot hold
// None, means the same with 0; else seconds > 0.
// `none_means`: what None and 0 stand for, in the message for another value.
double time_limit_seconds(const py::object& time_limit, const char* caller,
                          const char* none_means = "automatic") {
  if (time_limit.is_none()) return -1.0;
  const auto bad = [&] {
    return InvalidInputError(std::string(caller) + ": time_limit must be None or 0 (" +
                             none_means + ") or a number of seconds > 0, got " +
                             std::string(py::str(py::repr(time_limit))));
  };
  double seconds = 0.0;
  try {
    seconds = time_limit.cast<double>();
  } catch (const py::cast_error&) {
    throw bad();
  }
  if (!(seconds >= 0.0)) throw bad();  // negative or NaN
  return seconds > 0.0 ? seconds : -1.0;
}

// A target_edge_length keyword: None as 0 (automatic), else a positive finite length.
double edge_length_keyword(const py::object& length, const char* caller) {
  if (length.is_none()) return 0.0;
  const auto bad = [&] {
    return InvalidInputError(std::string(caller) +
                             ": target_edge_length must be None or a positive finite number, got " +
                             std::string(py::str(py::repr(length))));
  };
  double value = 0.0;
  try {
    value = length.cast<double>();
  } catch (const py::cast_error&) {
    throw bad();
  }
  if (!(value > 0.0) || !std::isfinite(value)) throw bad();
  return value;
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
  options.time_limit = time_limit_seconds(time_limit, caller);
  if (!tuning.is_none()) set_tuning(tuning, options.tuning);
  return options;
}

// Runs solve() without the GIL with options.progress calling `progress` (re-taking the GIL
// at most every 0.1 s); an exception in the callback (e.g. KeyboardInterrupt) stops the run
// and is re-raised.
template <class Solve>
auto with_progress(FairingOptions& options, const py::object& progress, Solve solve) {
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
  decltype(solve()) result;  // FairingResult, or fill_holes' FillResult
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
  const Triangles F = to_triangles(faces, "fair", V.rows());
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

FillResult fill_holes_py(const py::object& vertices, const py::object& faces,
                         const py::object& loops, const py::object& target_edge_length,
                         bool keep_outer_borders, const py::object& max_hole_edges,
                         const std::string& rim, const std::string& boundary, const std::string& inner_fairness,
                            const std::string& outer_fairness,
                            const std::string& normal_weighting, double tolerance,
                            int max_iterations, double damping, int cg_iterations, int levels,
                            const std::string& iteration, const py::object& progress,
                            const py::object& time_limit, const py::object& tuning) {
  const Positions V = to_positions(vertices, "vertices");
  const Triangles F = to_triangles(faces, "fill_holes", V.rows());
  const std::vector<std::vector<int>> holes = to_loops(loops);
  const HoleRule rule = hole_rule(keep_outer_borders, max_hole_edges, "fill_holes");
  const double length = edge_length_keyword(target_edge_length, "fill_holes");
  FairingOptions options = fairing_options(boundary, inner_fairness, outer_fairness,
                                           normal_weighting, tolerance, max_iterations, damping,
                                           cg_iterations, levels, iteration, time_limit, tuning,
                                           "fill_holes");
  if (rim != "keep" && rim != "trim")
    throw InvalidInputError("rim must be 'keep' or 'trim', got " +
                            std::string(py::str(py::repr(py::str(rim)))));
  const Rim rim_mode = rim == "trim" ? Rim::Trim : Rim::Keep;
  return with_progress(options, progress,
                       [&] { return fill_holes(V, F, holes, options, length, rule, rim_mode); });
}

Eigen::VectorXd mean_curvature_py(const py::object& vertices, const py::object& faces,
                                  const py::object& normals, const std::string& weighting) {
  const Positions V = to_positions(vertices, "vertices");
  const Triangles F = to_triangles(faces, "mean_curvature", V.rows());
  std::optional<Positions> N;
  if (!normals.is_none()) N = to_positions(normals, "normals");
  const NormalWeighting w = parse_weighting(weighting);
  py::gil_scoped_release release;
  return mean_curvature(V, F, N ? &*N : nullptr, w);
}

// A binding of f(V, F) taking (vertices, faces) arrays: converts and checks them, then runs
// f without the GIL.
template <class Function>
auto on_mesh(const char* name, Function f) {
  return [name, f](const py::object& vertices, const py::object& faces) {
    const Positions V = to_positions(vertices, "vertices");
    const Triangles F = to_triangles(faces, name, V.rows());
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
  def_checked(m, python_name, std::forward<Function>(f), std::forward<Own>(own)...,
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
  def_checked(m, "defaults", &defaults_py,
        R"doc(The defaults of geofair.fair's keyword arguments, the library's one source of them:
geofair.fair(vertices, faces, free, **geofair.defaults()) is fair's default call.

Returns
-------
dict, a new one per call, in the order of fair's signature: "remesh" (False),
"boundary", "inner_fairness", "outer_fairness", "normal_weighting", "iteration" (str),
"boundary_normals", "polygon_ids", "progress", "time_limit" (None; None or 0 is the
automatic time limit), "tolerance" (float, dimensionless), "max_iterations",
"cg_iterations", "levels" (int), "damping" (float), and "tuning": a dict of the solvers'
numerical choices beyond the paper by dotted name, e.g. "newton.patience" or
"schedule.time_limit_base" (seconds; the automatic time limit's figures), which fair's
tuning=None means (units and ranges: native/include/geofair/tuning.h).)doc");

  const FairingOptions d;
  static const std::string fair_docstring = fair_doc(R"doc(Fair the free vertices of a triangle mesh: the discrete solution of Δ_B H = 0
(Schneider & Kobbelt 2001, eqs. (4) and (12), solved as in section 7) with the G1 boundary
condition (fixed positions and unit normals) at the fixed vertices next to free ones, or with
boundary="g0" the G0 condition (fixed positions, H = 0). Every option in detail:
docs/REFERENCE.md, "The options of geofair.fair".

Parameters
----------
vertices : (n, 3) float64 array, positions in mesh units.
faces : (m, 3) integer array, triangles counter-clockwise seen from the normal side, a
    consistently oriented manifold around the free region.
free : (n,) bool array, True where a vertex may move (not on the mesh border). The fixed
    vertices that share a triangle with a free one form the boundary.
remesh : False (default; also "off"): the triangles are kept. True (also "always"): the
    region's triangles are first replaced by geofair.remesh_region's isotropic remesh.
    "if_needed": remeshed and faired again only where the kept triangles do not converge
    or fold over.
boundary : "g1" (default): positions and unit normals prescribed (section 4). "g0":
    positions only and H = 0: the minimal surface spanned by the boundary.
boundary_normals : (n, 3) float64 unit normals, read at the G1 boundary vertices, oriented
    like the faces; None (default): geofair.boundary_normals(vertices, faces, free).
polygon_ids : (m,) integer array, the polygon each triangle was cut from: "uniform" inner
    fairness runs over the polygons' edges; None (default): over the triangles' edges.
inner_fairness : where the vertices sit on the surface (section 7.3): "uniform" (default,
    a regular distribution), "conformal" (the input's cotangent weights: low UV distortion)
    or "conformal_intrinsic" (those of the input's intrinsic Delaunay triangulation).
outer_fairness : "intrinsic" (default, Δ_B H = 0) or "bilaplacian" (the linear Δ²f = 0
    initial mesh of section 7.4 alone).
normal_weighting : the free vertices' normals (section 6): "quadric" (default, the tangent
    plane of a least-squares quadric), "area" (the paper's), "angle" or "max".
tolerance : stop once the residual is at most this (default {tolerance}, dimensionless): the
    residual is L max_i |Hbar_i - H_i| over the free vertices, Hbar_i the cotangent-weighted
    mean of the neighbours' H (eq. (12) scaled), L the region's bounding-box diagonal.
max_iterations : iterations at most on each level, and Newton steps (default {max_iterations}).
damping : s in q <- q~ + s t n (section 7.2), in (0, 1] (default {damping}).
cg_iterations : conjugate-gradient iterations of a global step (section 7.1, default {cg_iterations}).
levels : levels of the progressive-mesh multigrid (section 7.4): 0 (default) picks them from
    the region, 1 solves the region as one level.
iteration : how eq. (12) is solved, the same equations each: "auto" (default: "newton",
    then "paper" where it stops unconverged), "newton" (Newton's method on all free vertices
    at once, beyond the paper) or "paper" (section 7's iteration with multigrid cycles).
progress : callable(iteration, residual) -> bool, or None; called at most every 0.1 s,
    returning False stops the solve (stop_reason "cancelled").
time_limit : None or 0 (default): automatic. With iteration="auto" the solve stops once the
    residual has not halved for {time_limit_base} s plus {time_limit_per_free_ms} ms per free vertex, and after
    {time_limit_hard_factor} times that in any case; "newton" and "paper" run to max_iterations. A number > 0:
    the seconds the whole call may take (float("inf"): no limit).
tuning : dict or None: numerical choices beyond the paper by dotted name, e.g.
    "newton.patience": 40; the names and defaults: geofair.defaults()["tuning"].

Returns
-------
FairingResult, whose fields are
    vertices : (n', 3) float64, fixed rows bit-identical to the input; n' = n unless remeshed.
    faces : (m', 3) int32 and free : (n',) bool, the input's unless remeshed.
    remeshed : bool; unreferenced : (k,) int32, rows in no face; origin_face : (n',) int32
        and origin_barycentric : (n', 3) float64, where each new free vertex lay on the
        input (-1 and zeros for the other rows, and unless remeshed).
    converged : bool, residual <= tolerance; residual : float, dimensionless.
    message : str, how the solve ended: one sentence with the residual and the tolerance.
    stop_reason : str, "converged", "max_iterations", "time_limit", "no_progress" (the
        automatic limit), "cancelled" (progress returned False) or "diverged" (the input is
        returned).
    iterations : int, all levels; iterations_per_level, vertices_per_level : lists, coarsest
        level first; iteration : "newton" or "paper"; newton_iterations : int.
    folds : int, edges with a free vertex whose two triangles face apart; new_folds : int,
        those not folded in the input.
    phase_seconds : list of (phase, seconds), wall-clock time per phase.

Raises
------
geofair.InvalidInputError (a ValueError): invalid input or option value; the message names
    the problem and the vertex, face or option (a mesh whose squared lengths leave the
    normal doubles, with a bounding-box diagonal above about 1.3e154 or a mean edge length
    below about 1.5e-154, names its size). Within those sizes the result is the same at any
    scale (positions are worked on in units of the mesh's own size).
geofair.SolverError (a RuntimeError): the computation failed or diverged. NaN or Inf is
    never returned.
TypeError: an unknown keyword argument, or an argument of the wrong type.)doc");
  def_solve(m, "fair", &fair_py, fair_docstring.c_str(), py::arg("vertices"), py::arg("faces"),
            py::arg("free"), py::kw_only(), py::arg("remesh") = remesh_value(d.remesh),
            py::arg("boundary") = name(d.boundary, kBoundaryNames),
            py::arg("boundary_normals") = py::none(), py::arg("polygon_ids") = py::none());
}

// geofair.cotangent_laplacian, intrinsic_delaunay and intrinsic_delaunay_laplacian.
void bind_laplacians(py::module_& m) {
  def_checked(m, 
      "cotangent_laplacian",
      on_mesh("cotangent_laplacian",
              [](const Positions& V, const Triangles& F) { return cotangent_laplacian(V, F); }),
      py::arg("vertices"), py::arg("faces"),
      R"doc(The cotangent Laplace–Beltrami matrix L of a triangle mesh (Schneider & Kobbelt
2001, eqs. (5)-(7)) as an (n, n) scipy.sparse CSR matrix (needs scipy).

L[i, j] = cot α_ij + cot β_ij for every edge (a single cotangent on a border edge) and
L[i, i] = -Σ_j L[i, j]: symmetric, L @ ones = 0. (L @ f)[i] = (2 A_i / 3) Δ_B f(q_i) with A_i
the area of the 1-disk, so L @ vertices = -(4 A_i / 3) H_i n_i; the matrix S of eqs. (6),
(7) is -L restricted to the free rows and columns.

Raises geofair.InvalidInputError (a ValueError) for invalid input.)doc");

  def_checked(m, 
      "intrinsic_delaunay",
      on_mesh("intrinsic_delaunay", [](const Positions& V, const Triangles& F) {
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

Raises geofair.InvalidInputError (a ValueError) for invalid input, geofair.SolverError (a
RuntimeError) if round-off made the flips cycle.)doc");

  def_checked(m, 
      "intrinsic_delaunay_laplacian",
      on_mesh("intrinsic_delaunay_laplacian", [](const Positions& V, const Triangles& F) {
        return intrinsic_delaunay_laplacian(V, F);
      }),
      py::arg("vertices"), py::arg("faces"),
      R"doc(The cotangent Laplacian of the intrinsic Delaunay triangulation (Bobenko &
Springborn 2007) as an (n, n) scipy.sparse CSR matrix, with the conventions of
cotangent_laplacian: L[i, j] = Σ cot of the angles opposite the intrinsic edges between
i and j, L[i, i] = -Σ_j L[i, j]. Every off-diagonal entry is >= 0 (to round-off), unlike
the cotangent Laplacian of a mesh with obtuse triangles; equal to cotangent_laplacian
where the mesh is already intrinsically Delaunay.

Raises geofair.InvalidInputError (a ValueError) for invalid input.)doc");
}

// geofair.relax_inner_fairness and progressive_mesh: steps of fair() on their own.
void bind_solver_steps(py::module_& m) {
  def_checked(m, 
      "relax_inner_fairness",
      [](const py::object& vertices, const py::object& faces, const py::object& free,
         const py::object& normals, const std::string& inner_fairness,
         const std::string& tangent_planes, const py::object& polygon_ids) {
        const Positions V = to_positions(vertices, "vertices");
        const Triangles F = to_triangles(faces, "relax_inner_fairness", V.rows());
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

Raises geofair.InvalidInputError (a ValueError) for invalid input, geofair.SolverError (a
RuntimeError) if the system is
singular.)doc");

  def_checked(m, 
      "progressive_mesh",
      [](const py::object& vertices, const py::object& faces, const py::object& free, int levels,
         bool coarsen_boundary) {
        const Positions V = to_positions(vertices, "vertices");
        const Triangles F = to_triangles(faces, "progressive_mesh", V.rows());
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

Raises geofair.InvalidInputError (a ValueError) for invalid input.)doc");
}

// geofair.boundary_normals and mean_curvature.
void bind_geometry(py::module_& m) {
  def_checked(m, 
      "boundary_normals",
      [](const py::object& vertices, const py::object& faces, const py::object& free,
         const std::string& method) {
        const Positions V = to_positions(vertices, "vertices");
        const Triangles F = to_triangles(faces, "boundary_normals", V.rows());
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
geofair.InvalidInputError (a ValueError) for invalid input (shapes, dtypes, indices, a
non-finite vertex of a
surrounding triangle).)doc");

  def_checked(m, "mean_curvature", &mean_curvature_py, py::arg("vertices"), py::arg("faces"),
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
geofair.InvalidInputError (a ValueError) for invalid input.)doc");
}

// geofair.HoleFill and geofair.FillResult (fill_holes' per-hole records).
void bind_fill_result(py::module_& m) {
  py::class_<HoleFill>(m, "HoleFill", "What geofair.fill_holes did with one hole.")
      .def_property_readonly(
          "loop", [](const HoleFill& h) { return int_array(h.loop); },
          "(k,) int32: the hole's loop, input vertex indices in the direction of the missing "
          "face (as geofair.boundary_loops orders them).")
      .def_property_readonly(
          "method", [](const HoleFill& h) { return std::string(fill_method_name(h.method)); },
          "The fill kept: \"intrinsic\" (G1, Δ_B H = 0 at the loop's edge length), "
          "\"intrinsic_finer\" (at half of it), \"intrinsic_trimmed\" (after rim=\"trim\" "
          "removed faces at the rim), \"g0\" (positions only at the loop: H = 0), "
          "\"linear\" (the linear Δ²f = 0 fill of the same patch), or \"none\": left open "
          "(.reason says why). With boundary=\"g0\" the first fill is \"g0\", and "
          "\"intrinsic_finer\" and \"intrinsic_trimmed\" are G0 fills too.")
      .def_property_readonly("filled", [](const HoleFill& h) { return h.method != FillMethod::None; },
                             "True unless the hole was left open.")
      .def_readonly("converged", &HoleFill::converged, "The kept fill's solve converged.")
      .def_readonly("folds", &HoleFill::folds,
                    "Folded edges of the kept fill: edges of its triangles, among them and with "
                    "the input's triangles at the loop, whose two triangles' normals have a "
                    "non-positive dot product.")
      .def_readonly("residual", &HoleFill::residual,
                    "The kept fill's normalized residual (dimensionless, see geofair.fair).")
      .def_readonly("new_vertices", &HoleFill::new_vertices, "Vertices the fill added.")
      .def_readonly("new_faces", &HoleFill::new_faces, "Triangles the fill added.")
      .def_property_readonly(
          "removed_faces", [](const HoleFill& h) { return int_array(h.removed_faces); },
          "(r,) int32: input face indices (rows of the input faces) removed at this hole's "
          "rim, sorted; empty unless rim=\"trim\" trimmed it.")
      .def_property_readonly(
          "attempts",
          [](const HoleFill& h) {
            py::list out;
            for (const FillAttempt& a : h.attempts) {
              py::dict d;
              d["method"] = fill_method_name(a.method);
              d["converged"] = a.converged;
              d["folds"] = a.folds;
              d["seconds"] = a.seconds;
              d["message"] = a.message;
              out.append(d);
            }
            return out;
          },
          "Every fill tried, in order: a list of dicts with \"method\", \"converged\", "
          "\"folds\", \"seconds\" (wall-clock) and \"message\" (the solve's, or why it "
          "was not made).")
      .def_readonly("reason", &HoleFill::reason,
                    "Left open: why, one clause for a user; filled: \"\".")
      .def("__repr__", [](const HoleFill& h) {
        return "HoleFill(loop of " + std::to_string(h.loop.size()) + " vertices, method=\"" +
               fill_method_name(h.method) + "\", converged=" +
               (h.converged ? "True" : "False") + ", folds=" + std::to_string(h.folds) +
               ", removed_faces=" + std::to_string(h.removed_faces.size()) + ")";
      });
  py::class_<FillResult, FairingResult>(
      m, "FillResult",
      "Result of geofair.fill_holes: geofair.FairingResult's fields for the filled mesh, and "
      "a record per hole.")
      .def_readonly("holes", &FillResult::holes,
                    "list of geofair.HoleFill: the holes in the order of the loops (given, or "
                    "geofair.holes_to_fill's), then the loops the rule left open (method "
                    "\"none\", with the reason).")
      .def_property_readonly(
          "removed_faces", [](const FillResult& r) { return int_array(r.removed_faces); },
          "(r,) int32: the input face indices removed at the rims (rim=\"trim\"), sorted; "
          "the result's faces are the other input faces in their order, then the fills'.")
      .def("__repr__", [](const FillResult& r) {
        size_t filled = 0;
        for (const HoleFill& h : r.holes) filled += h.method != FillMethod::None;
        return "FillResult(holes filled=" + std::to_string(filled) + " of " +
               std::to_string(r.holes.size()) + ", converged=" + (r.converged ? "True" : "False") +
               ", folds=" + std::to_string(r.folds) + ")";
      });
}

// geofair.read_mesh and geofair.write_mesh (OpenMesh's IO; the command line's files).
void bind_mesh_files(py::module_& m) {
  def_checked(
      m, "read_mesh",
      [](const std::string& path) {
        MeshFile mesh;
        {
          py::gil_scoped_release release;
          mesh = read_mesh_file(path);
        }
        py::dict out;
        out["vertices"] = mesh.vertices;
        out["faces"] = mesh.faces;
        out["polygon"] = int_array(mesh.polygon);
        out["colors"] = mesh.colors.rows() ? py::object(py::cast(mesh.colors)) : py::none();
        out["texcoords"] = mesh.texcoords.rows() ? py::object(py::cast(mesh.texcoords)) : py::none();
        return out;
      },
      py::arg("path"),
      R"doc(Read an OBJ, PLY, OFF or STL file (by its extension) with OpenMesh's readers.

Parameters
----------
path : str, the file.

Returns
-------
dict: "vertices" (n, 3) float64 positions in file units (OpenMesh's readers keep single
precision: about 1e-7 relative); "faces" (m, 3) int32 triangles
(polygons split into fans, oriented as in the file); "polygon" (m,) int32 the file's face of
each triangle; "colors" (n, 4) uint8 RGBA vertex colours (PLY, OFF) or None; "texcoords"
(n, 2) float64 vertex texture coordinates (OBJ's vt) or None. STL's repeated corners are
merged into shared vertices.

Raises
------
geofair.InvalidInputError (a ValueError) naming the file and the problem: an unknown
extension, an unreadable file, faces OpenMesh's reader skips as non-manifold, no face, or a
non-finite coordinate.)doc");
  def_checked(
      m, "write_mesh",
      [](const std::string& path, const py::object& vertices, const py::object& faces,
         const py::object& colors, const py::object& texcoords) {
        MeshFile mesh;
        mesh.vertices = to_positions(vertices, "vertices");
        mesh.faces = to_triangles(faces, "write_mesh", mesh.vertices.rows());
        const auto n = mesh.vertices.rows();
        if (!colors.is_none()) {
          const auto c = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(colors);
          if (!c || c.ndim() != 2 || c.shape(0) != n || c.shape(1) != 4)
            throw InvalidInputError("write_mesh: colors must be None or an (n, 4) uint8 array, n = " +
                                    std::to_string(n));
          mesh.colors.resize(n, 4);
          std::copy(c.data(), c.data() + 4 * n, mesh.colors.data());
        }
        if (!texcoords.is_none()) {
          const auto t = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(texcoords);
          if (!t || t.ndim() != 2 || t.shape(0) != n || t.shape(1) != 2)
            throw InvalidInputError("write_mesh: texcoords must be None or an (n, 2) float array, n = " +
                                    std::to_string(n));
          mesh.texcoords.resize(n, 2);
          std::copy(t.data(), t.data() + 2 * n, mesh.texcoords.data());
        }
        try {
          py::gil_scoped_release release;
          write_mesh_file(path, mesh);
        } catch (const InvalidInputError&) {
          throw;
        } catch (const std::runtime_error& error) {  // the file system's: an OSError
          PyErr_SetString(PyExc_OSError, error.what());
          throw py::error_already_set();
        }
      },
      py::arg("path"), py::arg("vertices"), py::arg("faces"), py::kw_only(),
      py::arg("colors") = py::none(), py::arg("texcoords") = py::none(),
      R"doc(Write a triangle mesh to an OBJ, PLY (binary), OFF or STL (binary) file (by its
extension) with OpenMesh's writers, positions in single precision (about 1e-7 relative).
The file is written under a temporary name beside the destination and renamed over it at the
end: an error never leaves a partial file.

Parameters
----------
path : str, the file.
vertices : (n, 3) float64 positions; faces : (m, 3) integer triangles.
colors : None or (n, 4) uint8 RGBA vertex colours (written to PLY and OFF).
texcoords : None or (n, 2) float64 vertex texture coordinates (written to OBJ and PLY; per
    vertex, so a UV seam is not kept).

Raises
------
geofair.InvalidInputError (a ValueError) for an unknown extension, faces that index no
vertex, a non-finite coordinate, or triangles that do not form a manifold mesh; OSError if
the file cannot be written.)doc");
}

// geofair.fill_holes, geofair.holes_to_fill and geofair.boundary_loops.
void bind_holes(py::module_& m) {
  bind_fill_result(m);
  bind_mesh_files(m);
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
target_edge_length (geofair.remesh_region), and faired by geofair.fair with the new
vertices free, each hole on its own (its patch and the faces within three rings of its loop).

Every hole gets a fill: per hole the fills below are tried in order and the first that
converges without a folded edge is kept, else the one with the fewest folded edges
(converged first among equals): "intrinsic" (the fill above), "intrinsic_trimmed"
(rim="trim" only, where the rim has something to trim: the rim's teeth, triangles with two
loop edges, and the triangles at loop vertices whose faces span less than 90° removed, up to
three rounds, while the hole stays one simple loop; MeshFix's remove-and-fill, Attene
2010; then, where the fill still folds, the input triangles that fold against it, up to
three rounds; at most as many faces as the loop has vertices), "intrinsic_finer" (at half
the loop's edge length, on the input's rim and then on the trimmed one, where
target_edge_length is None and the first fill has at most 5000 new vertices: ragged loops
need a finer fill next to them), "g0" (positions only at the loop: the minimal surface) and "linear" (the linear
Δ²f = 0 fill of the same patch, the method of CGAL's triangulate_refine_and_fair_hole; the
last two on the last trimmed rim where it was trimmed). .holes says which fill each hole got.
A hole is left open only where no fill can be made (over {max_fill_vertices} new vertices).

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
rim : "keep" (default): every input face is kept; "trim": where the fill of a loop as it is
    folds or does not converge, input faces at its rim may be removed first (see above; named
    in .removed_faces and each hole's .removed_faces).
boundary, inner_fairness, outer_fairness, normal_weighting, tolerance, max_iterations,
damping, cg_iterations, levels, iteration, progress, time_limit, tuning : as for
    geofair.fair (time_limit covers the filling too), except that each fill's fair takes
    max_iterations (iterations per level) at most tuning "schedule.fill_max_iterations"
    ({fill_max_iterations}), so that a fill that does not converge gives way to the next (its
    attempt then reports "did not converge within max_iterations"); boundary="g0" fills
    with the minimal surface spanned by the loop.

Returns
-------
FillResult (a FairingResult): .vertices (n + k, 3), the input's n rows first and
bit-identical, the k new vertices after (with rim="trim", input rows whose every face was
removed stay, listed in .unreferenced); .faces, the input's m faces first and unchanged
(with rim="trim" less .removed_faces, the others in their order), then each hole's fill,
oriented like the faces around the holes; .free (n + k,) bool, True exactly at the new
vertices; .remeshed True (.origin_face -1: a fill has no input surface); .converged (every
fill converged), .residual (the largest), .folds and .new_folds (the fills' folded edges,
HoleFill.folds, summed), .message (one clause per method), .stop_reason and .phase_seconds
(starting with "fill", the holes' phases summed); .holes, a list of geofair.HoleFill (loop,
method, converged, folds, removed_faces, attempts, reason), the holes in the order of the
loops, then the loops the rule left open; .removed_faces (r,) int32, sorted.

Raises
------
geofair.InvalidInputError (a ValueError) when loops is not a list of sequences of vertex
indices, a loop is not a boundary loop of the mesh (the offending pair of vertices is named),
a vertex is on two given loops, rim is not "keep" or "trim", the mesh has no hole to fill (no boundary loop, or with
loops=None every loop is left open: the message names them and why), max_hole_edges is not
None or a positive integer, no hole can be filled under {max_fill_vertices} new vertices, the mesh's
squared lengths leave the normal doubles (a bounding-box diagonal above about 1.3e154 or a
mean edge length below about 1.5e-154: the message names the size), or for the input fair
refuses (the message names the problem and the vertex or face); geofair.SolverError (a
RuntimeError) as fair. Within those sizes the fill is the same at any scale (positions are
worked on in units of the mesh's own size).)doc");
  def_solve(m, "fill_holes", &fill_holes_py, fill_holes_docstring.c_str(), py::arg("vertices"),
            py::arg("faces"), py::arg("loops") = py::none(), py::kw_only(),
            py::arg("target_edge_length") = py::none(),
            py::arg("keep_outer_borders") = HoleRule{}.keep_outer_borders,
            py::arg("max_hole_edges") = py::none(), py::arg("rim") = "keep",
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
spans 95 % of the area of its part's triangles (a hole less than 30 %)"; a piece of border
that passes more than once through a vertex, where holes touch: "not a simple loop: ...",
its vertices sorted). Both empty for
a closed mesh. The same at any scale of the mesh.

Raises
------
geofair.InvalidInputError (a ValueError) as geofair.boundary_loops, for max_hole_edges not
None or a positive integer, or a mesh whose squared lengths leave the normal doubles (see
geofair.fill_holes).)doc");
  def_checked(m,
      "holes_to_fill",
      [](const py::object& vertices, const py::object& faces, bool keep_outer_borders,
         const py::object& max_hole_edges) {
        const Positions V = to_positions(vertices, "vertices");
        const Triangles F = to_triangles(faces, "holes_to_fill", V.rows());
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
  def_checked(m,
      "boundary_loops",
      [](const py::object& vertices, const py::object& faces) {
        const Positions V = to_positions(vertices, "vertices");
        const Triangles F = to_triangles(faces, "boundary_loops", V.rows());
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
geofair.InvalidInputError (a ValueError) for invalid triangles or a vertex on two loops (holes that touch).)doc");
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
      .def_readonly("target_edge_length", &RemeshedRegion::target_edge_length,
                    "float: the target edge length L the remesh used (the given one, or the "
                    "mean length of the region's border edges, of all its edges where it has "
                    "no border), mesh units.")
      .def("__repr__", [](const RemeshedRegion& r) {
        return "RemeshedRegion(vertices=" + std::to_string(r.vertices.rows()) +
               ", faces=" + std::to_string(r.faces.rows()) +
               ", free=" + std::to_string(std::count(r.free.begin(), r.free.end(), true)) + ")";
      });

  def_checked(m, 
      "remesh_region",
      [](const py::object& vertices, const py::object& faces, const py::object& free,
         const py::object& target_edge_length, int iterations) {
        const Positions V = to_positions(vertices, "vertices");
        const Triangles F = to_triangles(faces, "remesh_region", V.rows());
        const std::vector<bool> mask = to_mask(free, V.rows());
        RemeshOptions options;
        options.iterations = iterations;
        options.target_edge_length = edge_length_keyword(target_edge_length, "remesh_region");
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
geofair.InvalidInputError (a ValueError) for invalid input (shapes, indices, no free vertex, a free vertex on the mesh
border, a region that is not a consistently oriented 2-manifold, invalid options).)doc");
}

// geofair.LiveFairing: a region prepared once, faired again per frame.
void bind_live(py::module_& m) {
  static const std::string class_docstring = fair_doc(R"doc(A fairing region prepared once and faired again for new positions of its
fixed vertices: live intrinsic modelling, a handle dragged through the surface (beyond the
paper; Schneider & Kobbelt 2001, section 8, asks for it).

    live = geofair.LiveFairing(vertices, faces, free, **fair_options)
    result = live.update(new_vertices)  # a FairingResult, as geofair.fair's

The constructor fairs the region cold (geofair.fair; live.result) and keeps what does not
depend on the fixed vertices' positions: the region, its one-rings, the symbolic analysis
of the Newton preconditioner, the inner fairness pattern. Each update starts from the last
converged frame with the new fixed positions (a warm start): a tangential relaxation
towards inner fairness and Newton's method on the region (eq. (12)), preconditioned by the
last frame's factorizations where GMRES still converges on them, and fair's polish near the end. A
frame whose warm start does not converge in max_warm_steps Newton steps runs the cold path,
geofair.fair's whole schedule, and its .message says so.

Fixed vertices inside the region (a handle: fixed vertices with free neighbours, surrounded
by the region) are boundary conditions like the outer ones, as in geofair.fair: their
positions and, with boundary="g1", their tangent planes, estimated from their own
triangles (those without a free vertex) as geofair.boundary_normals does, again from the
new positions at every update: a rigid handle turns its tangent planes with it. A handle
needs such triangles (two rings of fixed vertices give the estimate its samples), or
boundary_normals at each update.

A frame's input is its positions of the fixed vertices with the free vertices' positions
given to the constructor: update(v) returns the surface of geofair.fair of that input
within the tolerance wherever fair converges (the conformal inner fairness weights and the
bounding box of the residual's length read the free rows, as fair does).

Parameters
----------
vertices : (n, 3) float64 array, positions in mesh units.
faces : (m, 3) integer array, consistently oriented triangles.
free : (n,) bool array, True where a vertex may move.
details : False (default): the region is the fair surface itself. True: detail
    preservation (Kobbelt et al. 1998, Botsch & Kobbelt 2004): the region is split into its
    own faired base (Δ_B H = 0 with the input's boundary and handle) and the details, the
    input's offsets from the base in the base's local frames (normal and a tangent from a
    neighbour edge); every update adds them back onto the new base (its residual and folds
    are the base's), and live.result at the start is the input itself.
max_warm_steps : int >= 1 (default 8), Newton steps each warm start of a frame may take
    (from the secant predictor, then where that does not converge from the harmonic one)
    before the frame runs the cold path; a frame's .iterations counts both starts' steps.
remesh : False (default; also "off"): the region keeps the input's triangles in every frame.
    "if_needed": connectivity that follows the drag. A frame whose warm start does not
    converge, or converges with more folded edges than the input had, is remeshed, and so
    is the frame after one whose smallest triangle angle fell below 1/3 of that of the last
    frame solved anew (the constructor's or a remesh's; squeezed triangles fold a few frames
    later):
    geofair.remesh_region's remesh of the last converged frame's surface, its new free
    vertices moved with the fixed ones to the frame (their harmonic extension), and solved
    warm from there (Newton's method on the new mesh; taken where it converges with no more
    folds than the input had); where that fails, faired cold with the frame's fixed positions
    (where that folds or does not converge, remeshed once more at 4/5 of the edge length).
    It is taken where it converged (with fewer folds than
    the warm start's, where that converged); a remesh that leaves folds is tried again three
    frames later at the earliest. The result's .remeshed, .faces, .free, .unreferenced and
    .origin_face (into the last frame's faces) say so, and later frames start warm on the
    new mesh, whose result is their input's reference (the conformal weights' too). The
    fixed vertices keep their rows; new free vertices take free rows the remesh leaves over,
    then appended rows (n' >= n rows); rows left in no face keep their last positions. The
    constructor fairs the input's own triangles. Not with details=True (its details are
    coded per vertex of the input).
boundary, boundary_normals, polygon_ids, inner_fairness, outer_fairness, normal_weighting,
tolerance, max_iterations, damping, cg_iterations, levels, iteration, time_limit, tuning :
    as for geofair.fair; boundary_normals are those of the constructor's vertices (an
    update estimates them unless given its own); iteration, levels and time_limit apply to
    the cold solves (the warm start is Newton's method on the region alone).

Attributes
----------
result : the last converged frame's FairingResult (the constructor's cold fair until then).
frames, cold_frames, remeshes : updates finished so far, those that ran the cold path, and
    those that replaced the region's triangles (remesh="if_needed").

Raises
------
geofair.InvalidInputError (a ValueError) and geofair.SolverError (a RuntimeError) as
geofair.fair; InvalidInputError for max_warm_steps < 1, remesh=True ("always"), or
remesh="if_needed" with details=True; SolverError with details=True where
the input's base (its cold fair) did not converge.)doc");
  py::class_<LiveFairing, std::shared_ptr<LiveFairing>> cls(m, "LiveFairing",
                                                            class_docstring.c_str());
  const FairingOptions d;
  const LiveOptions live_defaults;
  const CheckedFunction make = checked_function(
      "LiveFairing", "__init__",
      [](const py::object& vertices, const py::object& faces, const py::object& free,
         bool details, int max_warm_steps, const py::object& remesh,
         const std::string& boundary, const py::object& boundary_normals,
         const py::object& polygon_ids,
         const std::string& inner_fairness, const std::string& outer_fairness,
         const std::string& normal_weighting, double tolerance, int max_iterations,
         double damping, int cg_iterations, int levels, const std::string& iteration,
         const py::object& time_limit, const py::object& tuning) {
        const Positions V = to_positions(vertices, "vertices");
        const Triangles F = to_triangles(faces, "LiveFairing", V.rows());
        const std::vector<bool> mask = to_mask(free, V.rows());
        std::optional<std::vector<int>> polygons;
        if (!polygon_ids.is_none()) polygons = to_polygon_ids(polygon_ids, F.rows());
        FairingOptions options = fairing_options(
            boundary, inner_fairness, outer_fairness, normal_weighting, tolerance,
            max_iterations, damping, cg_iterations, levels, iteration, time_limit, tuning,
            "LiveFairing");
        options.remesh = parse_live_remesh(remesh);
        std::optional<Positions> normals;
        if (!boundary_normals.is_none() && options.boundary == BoundaryCondition::G1) {
          normals = to_positions(boundary_normals, "boundary_normals");
          if (normals->rows() != V.rows())
            throw InvalidInputError("boundary_normals must have the shape of vertices " +
                                    std::to_string(V.rows()) + "×3");
        }
        LiveOptions live;
        live.details = details;
        live.max_warm_steps = max_warm_steps;
        py::gil_scoped_release release;
        return std::make_shared<LiveFairing>(V, F, mask, normals ? &*normals : nullptr, options,
                                             live, polygons ? &*polygons : nullptr);
      },
      py::arg("vertices"), py::arg("faces"), py::arg("free"), py::kw_only(),
      py::arg("details") = live_defaults.details,
      py::arg("max_warm_steps") = live_defaults.max_warm_steps,
      py::arg("remesh") = remesh_value(d.remesh),
      py::arg("boundary") = name(d.boundary, kBoundaryNames),
      py::arg("boundary_normals") = py::none(), py::arg("polygon_ids") = py::none(),
      py::arg("inner_fairness") = name(d.inner_fairness, kInnerFairnessNames),
      py::arg("outer_fairness") = name(d.outer_fairness, kOuterFairnessNames),
      py::arg("normal_weighting") = name(d.normal_weighting, kNormalWeightingNames),
      py::arg("tolerance") = d.tolerance, py::arg("max_iterations") = d.max_iterations,
      py::arg("damping") = d.damping, py::arg("cg_iterations") = d.cg_iterations,
      py::arg("levels") = d.levels, py::arg("iteration") = name(d.iteration, kIterationNames),
      py::arg("time_limit") = py::none(), py::arg("tuning") = py::none(), "");
  const CheckedFunction update = checked_function(
      "LiveFairing.update", "update",
      [](LiveFairing& self, const py::object& vertices, const py::object& boundary_normals,
         const py::object& time_limit) {
        const Positions V = to_positions(vertices, "vertices");
        std::optional<Positions> normals;
        if (!boundary_normals.is_none()) normals = to_positions(boundary_normals, "boundary_normals");
        const double limit = time_limit_seconds(time_limit, "LiveFairing.update", "no limit");
        py::gil_scoped_release release;
        return self.update(V, normals ? &*normals : nullptr, limit);
      },
      py::arg("self"), py::arg("vertices"), py::arg("boundary_normals") = py::none(),
      py::arg("time_limit") = py::none(),
      R"doc(Fair the region for new positions of its fixed vertices, starting from the last
converged frame (see LiveFairing).

Parameters
----------
vertices : (n, 3) float64 array, mesh units, n as at construction or, after a remesh, the
    live mesh's n' rows (.result.vertices): the rows of fixed vertices are the frame's
    positions (the handle's and the surroundings'); the rows of free vertices are not read
    (any values, NaN too).
boundary_normals : (n, 3) float64 unit normals read at the G1 boundary vertices (the
    handle's included), or None (default): estimated from vertices as geofair.fair does.
time_limit : seconds the frame may take (float > 0; an interactive drag's bound), or None,
    0 or inf (default None): no bound beyond the constructor's time_limit on the cold path.
    The warm start stops before a Newton step once it is spent; a remesh and the cold path
    stop at it too (.stop_reason "time_limit"; the constructor's time_limit, automatic or
    not, still applies to them); where nothing is left for them, the frame is returned
    unconverged without them (.stop_reason "time_limit"), its free rows the last converged
    frame's, its .residual and .folds evaluated there.

Returns
-------
FairingResult as geofair.fair's for the frame's input: .vertices (n', 3) (the live mesh's
rows; n' = n unless remesh="if_needed" replaced the triangles) with the fixed rows
bit-identical to vertices; .message says how the frame was solved ("warm start from the
last frame (k Newton steps)", "remeshed from the last frame (...)", or "cold path (fair):
the warm start did not converge (...)"). A frame that did not converge even on the cold path is returned unconverged, with the
reason in .message, and leaves .result and the next warm start at the last converged frame.

Raises
------
geofair.InvalidInputError (a ValueError) if vertices has another number of rows than at
construction (or than the live mesh after a remesh), a fixed vertex of a triangle has a non-finite coordinate (the vertex is
named), for boundary_normals as geofair.fair, or for a negative or NaN time_limit;
geofair.SolverError (a RuntimeError) where the cold path raises. Either leaves the state as
it was.)doc");
  // The properties and __repr__ first, with the signatures pybind11 writes; then the
  // checked functions, whose docstrings carry their own (self first, as a Python method's).
  // A copy: a reference into the object would change under the caller with the next update.
  // The getters wait for an update running in another thread: without the GIL meanwhile.
  const auto released = [](auto getter) {
    return py::cpp_function(getter, py::call_guard<py::gil_scoped_release>());
  };
  cls.def_property_readonly(
      "result", released([](const LiveFairing& live) { return live.result(); }),
      "A copy of the last converged frame's FairingResult (the constructor's cold fair until "
      "then, converged or not).");
  cls.def_property_readonly("frames",
                            released([](const LiveFairing& live) { return live.frames(); }),
                            "Updates finished so far (returned, converged or not).");
  cls.def_property_readonly("cold_frames",
                            released([](const LiveFairing& live) { return live.cold_frames(); }),
                            "Finished updates that ran the cold path (geofair.fair).");
  cls.def_property_readonly("remeshes",
                            released([](const LiveFairing& live) { return live.remeshes(); }),
                            "Finished updates that replaced the region's triangles "
                            "(remesh=\"if_needed\").");
  cls.def("__repr__", [](const LiveFairing& live) {
    int frames = 0, cold = 0, remeshes = 0;
    {
      py::gil_scoped_release release;
      frames = live.frames();
      cold = live.cold_frames();
      remeshes = live.remeshes();
    }
    return "LiveFairing(frames=" + std::to_string(frames) + ", cold_frames=" +
           std::to_string(cold) + ", remeshes=" + std::to_string(remeshes) + ")";
  });
  static const std::string init_docstring = "__init__(self, " + make.docstring.substr(9);
  const std::string& update_docstring = update.docstring;
  py::options options;
  options.disable_function_signatures();
  cls.def(py::init([make](const py::args& args, const py::kwargs& kwargs) {
            return make(args, kwargs).cast<std::shared_ptr<LiveFairing>>();
          }),
          init_docstring.c_str());
  cls.def(
      "update",
      [update](const py::args& args, const py::kwargs& kwargs) { return update(args, kwargs); },
      update_docstring.c_str());
}

// OPENBLAS_NUM_THREADS=1 in os.environ while alive, the earlier value (or none) restored
// after. OpenBLAS starts its worker threads as it is loaded, and they wait for work by
// spinning (about 0.1 s of a core): a fair() called right after the import lost that core.
// fair() runs its BLAS on one thread (BlasThreads).
class OneBlasThreadWhileLoading {
 public:
  OneBlasThreadWhileLoading() : environ_(py::module_::import("os").attr("environ")) {
    if (environ_.contains(kName)) earlier_ = environ_[kName];
    environ_[kName] = "1";
  }
  ~OneBlasThreadWhileLoading() {
    try {
      if (earlier_)
        environ_[kName] = *earlier_;
      else
        environ_.attr("pop")(kName, py::none());
    } catch (...) {  // never from a destructor
    }
  }
  OneBlasThreadWhileLoading(const OneBlasThreadWhileLoading&) = delete;
  OneBlasThreadWhileLoading& operator=(const OneBlasThreadWhileLoading&) = delete;

 private:
  static constexpr const char* kName = "OPENBLAS_NUM_THREADS";
  py::object environ_;
  std::optional<py::object> earlier_;
};

// The OpenBLAS of a build that loads its BLAS at run time (geofair/blas.h): the file that
// the environment variable GEOFAIR_BLAS names (the legacy add-on sets it to the copy beside
// the module), else that of PyPI's scipy-openblas32, a dependency of the wheel (whose import
// loads it), with one thread (OneBlasThreadWhileLoading).
void load_openblas() {
  if (!blas_loaded_at_run_time()) return;
  const OneBlasThreadWhileLoading one_thread;
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
  bind_live(m);
}
