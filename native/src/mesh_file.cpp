// Mesh files through OpenMesh's IO (geofair/mesh_file.h).
#include "geofair/mesh_file.h"

#include "geofair/errors.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace geofair {

namespace {

// Double positions; RGBA colours as bytes; 2D texture coordinates.
struct FileTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  using Color = OpenMesh::Vec4uc;
  using TexCoord2D = OpenMesh::Vec2d;
};
using FileMesh = OpenMesh::PolyMesh_ArrayKernelT<FileTraits>;

std::string extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of("/\\");
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

void check_extension(const std::string& path, const char* caller) {
  const std::string ext = extension(path);
  if (ext != "obj" && ext != "ply" && ext != "off" && ext != "stl")
    throw InvalidInputError(std::string(caller) + ": " + path +
                            ": unknown mesh format (expected .obj, .ply, .off or .stl)");
}

// OpenMesh's readers, writers and its omerr/omlog streams are process-wide: one IO at a time
// (read_mesh and write_mesh run without the GIL).
std::mutex& io_mutex() {
  static std::mutex mutex;
  return mutex;
}

// OpenMesh's warnings (omerr) during a read, e.g. its "complex edge" for a non-manifold face;
// its log (omlog, "write file") is silenced meanwhile. Holds io_mutex while it lives.
class CaptureOmerr {
 public:
  CaptureOmerr() : lock_(io_mutex()) {
    omerr().connect(text_);
    omlog().connect(log_);
    omlog().disable();
  }
  ~CaptureOmerr() {
    omerr().disconnect(text_);
    omlog().disconnect(log_);
    omlog().enable();
  }
  std::string text() {
    omerr().flush();
    return text_.str();
  }

 private:
  std::lock_guard<std::mutex> lock_;
  std::ostringstream text_, log_;
};

// A name beside ``path`` for the write in progress: a counter and the clock keep threads and
// processes writing beside the same destination apart.
std::string temporary_name(const std::string& path, const std::string& ext) {
  static std::atomic<unsigned long> counter{0};
  const auto slash = path.find_last_of("/\\");
  const std::string dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
  const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const auto now = std::chrono::steady_clock::now().time_since_epoch().count();
  return dir + "." + name + ".geofair-partial-" + std::to_string(now) + "-" +
         std::to_string(counter++) + "." + ext;
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

MeshFile read_mesh_file(const std::string& path) {
  check_extension(path, "read_mesh");
  FileMesh mesh;
  mesh.request_vertex_colors();
  mesh.request_vertex_texcoords2D();
  OpenMesh::IO::Options options;
  options += OpenMesh::IO::Options::VertexColor;
  options += OpenMesh::IO::Options::ColorAlpha;
  options += OpenMesh::IO::Options::VertexTexCoord;
  std::string warnings;
  {
    CaptureOmerr capture;
    if (!OpenMesh::IO::read_mesh(mesh, path, options))
      throw InvalidInputError("read_mesh: " + path + ": cannot be read (missing, or not a valid " +
                              extension(path) + " file)");
    warnings = capture.text();
  }
  const int skipped = count(warnings, "complex edge") + count(warnings, "complex vertex") +
                      count(warnings, "patch re-linking failed");
  if (skipped > 0)
    throw InvalidInputError("read_mesh: " + path + ": not a manifold mesh, " +
                            std::to_string(skipped) +
                            " faces would share an edge or vertex with others in a way a "
                            "surface cannot (non-manifold); repair it first");
  MeshFile out;
  out.vertices.resize(Eigen::Index(mesh.n_vertices()), 3);
  for (const auto vh : mesh.vertices()) {
    const auto& p = mesh.point(vh);
    out.vertices.row(vh.idx()) << p[0], p[1], p[2];
    if (!out.vertices.row(vh.idx()).allFinite())
      throw InvalidInputError("read_mesh: " + path + ": vertex " + std::to_string(vh.idx()) +
                              " has a non-finite coordinate");
  }
  std::vector<std::array<int, 3>> triangles;
  for (const auto fh : mesh.faces()) {
    std::vector<int> corners;
    for (const auto vh : fh.vertices()) corners.push_back(vh.idx());
    for (size_t k = 1; k + 1 < corners.size(); ++k) {
      triangles.push_back({corners[0], corners[k], corners[k + 1]});
      out.polygon.push_back(fh.idx());
    }
  }
  if (triangles.empty())
    throw InvalidInputError("read_mesh: " + path + ": the file has no face");
  out.faces.resize(Eigen::Index(triangles.size()), 3);
  for (size_t t = 0; t < triangles.size(); ++t)
    out.faces.row(Eigen::Index(t)) << triangles[t][0], triangles[t][1], triangles[t][2];
  // What each format can carry (the STL reader leaves the options as they were asked).
  const std::string ext = extension(path);
  if ((ext == "ply" || ext == "off") && options.check(OpenMesh::IO::Options::VertexColor)) {
    out.colors.resize(out.vertices.rows(), 4);
    const bool alpha = options.check(OpenMesh::IO::Options::ColorAlpha);
    for (const auto vh : mesh.vertices()) {
      const auto& c = mesh.color(vh);
      out.colors.row(vh.idx()) << c[0], c[1], c[2], alpha ? c[3] : std::uint8_t(255);
    }
  }
  if ((ext == "obj" || ext == "ply") && options.check(OpenMesh::IO::Options::VertexTexCoord)) {
    out.texcoords.resize(out.vertices.rows(), 2);
    for (const auto vh : mesh.vertices()) {
      const auto& t = mesh.texcoord2D(vh);
      out.texcoords.row(vh.idx()) << t[0], t[1];
    }
  }
  return out;
}

void write_mesh_file(const std::string& path, const MeshFile& in) {
  check_extension(path, "write_mesh");
  const Eigen::Index n = in.vertices.rows();
  if (!in.vertices.allFinite())
    throw InvalidInputError("write_mesh: " + path + ": a vertex has a non-finite coordinate");
  if (in.faces.size() > 0 && (in.faces.minCoeff() < 0 || in.faces.maxCoeff() >= n))
    throw InvalidInputError("write_mesh: " + path + ": a face indexes no vertex");
  const bool colors = in.colors.rows() == n && n > 0;
  const bool texcoords = in.texcoords.rows() == n && n > 0;
  FileMesh mesh;
  if (colors) mesh.request_vertex_colors();
  if (texcoords) mesh.request_vertex_texcoords2D();
  std::vector<FileMesh::VertexHandle> handles;
  handles.reserve(size_t(n));
  for (Eigen::Index v = 0; v < n; ++v) {
    const auto vh = mesh.add_vertex(
        FileMesh::Point(in.vertices(v, 0), in.vertices(v, 1), in.vertices(v, 2)));
    if (colors)
      mesh.set_color(vh, FileMesh::Color(in.colors(v, 0), in.colors(v, 1), in.colors(v, 2),
                                         in.colors(v, 3)));
    if (texcoords) mesh.set_texcoord2D(vh, FileMesh::TexCoord2D(in.texcoords(v, 0), in.texcoords(v, 1)));
    handles.push_back(vh);
  }
  {
    CaptureOmerr capture;
    for (Eigen::Index f = 0; f < in.faces.rows(); ++f) {
      const auto fh = mesh.add_face(handles[size_t(in.faces(f, 0))], handles[size_t(in.faces(f, 1))],
                                    handles[size_t(in.faces(f, 2))]);
      if (!fh.is_valid())
        throw InvalidInputError("write_mesh: " + path + ": face " + std::to_string(f) +
                                " cannot be added (non-manifold or degenerate)");
    }
  }
  OpenMesh::IO::Options options;
  const std::string ext = extension(path);
  if (ext == "ply" || ext == "stl") options += OpenMesh::IO::Options::Binary;
  // What each format carries: colours in PLY and OFF, texture coordinates in OBJ and PLY.
  if (colors && (ext == "ply" || ext == "off")) options += OpenMesh::IO::Options::VertexColor;
  if (colors && ext == "ply") options += OpenMesh::IO::Options::ColorAlpha;
  if (texcoords && (ext == "obj" || ext == "ply")) options += OpenMesh::IO::Options::VertexTexCoord;
  // Written under a temporary name beside the destination, then renamed over it (replacing an
  // existing file on Windows too: std::filesystem::rename, not std::rename).
  const std::string temporary = temporary_name(path, ext);
  bool written = false;
  {
    CaptureOmerr capture;
    written = OpenMesh::IO::write_mesh(mesh, temporary, options, 17);
  }
  std::error_code error;
  if (written) std::filesystem::rename(temporary, path, error);
  if (!written || error) {
    std::filesystem::remove(temporary, error);
    throw std::runtime_error("write_mesh: " + path + ": cannot be written");
  }
}

}  // namespace geofair
