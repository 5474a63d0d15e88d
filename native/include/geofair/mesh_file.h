// Reading and writing mesh files (OBJ, PLY, OFF, STL) through OpenMesh's IO, for the command
// line (beyond the paper).
#pragma once

#include "geofair/types.h"

#include <cstdint>
#include <string>
#include <vector>

namespace geofair {

/// A mesh as read from or written to a file.
struct MeshFile {
  Positions vertices;  ///< #V×3 float64 positions, file units
  Triangles faces;     ///< #F×3 triangles; polygons are split into fans
  std::vector<int> polygon;  ///< #F: the file's face (0-based) each triangle comes from
  /// #V×4 RGBA vertex colours in [0, 255] where the file has them (PLY, OFF), else 0 rows.
  Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 4, Eigen::RowMajor> colors;
  /// #V×2 vertex texture coordinates where the file has them (OBJ's vt), else 0 rows.
  Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> texcoords;
};

/// Reads an OBJ, PLY, OFF or STL file (by its extension) with OpenMesh's readers: positions
/// in double precision, polygons split into fans, vertex colours and texture coordinates
/// where the file has them. STL's repeated corners are merged into shared vertices.
/// \throw InvalidInputError naming the file and the problem: unreadable or of an unknown
///        extension, faces OpenMesh's reader skipped as non-manifold (it builds a halfedge
///        mesh), no triangle, or a non-finite coordinate.
MeshFile read_mesh_file(const std::string& path);

/// Writes `mesh` (vertices, faces; colours and texcoords where they have #V rows) to an OBJ,
/// PLY (binary), OFF or STL (binary) file by its extension. The file is written beside its
/// destination under a temporary name and renamed over it at the end, so an error never
/// leaves a partial file.
/// \throw InvalidInputError for an unknown extension, faces that index no vertex, a
///        non-finite coordinate, or triangles OpenMesh cannot add (non-manifold);
///        std::runtime_error if the file cannot be written (the message names it).
void write_mesh_file(const std::string& path, const MeshFile& mesh);

}  // namespace geofair
