// The input layout the libFuzzer targets share, so that one seed corpus serves them all
// (little-endian bytes, all wrapped into range): n_vertices (1 byte, 3..66), n_triangles
// (1 byte, 1..128), an option byte (each target reads its own options from it), then per
// vertex 3 coordinates (int8 each, scaled by 1/16) and a flag (the low bit of a byte), then
// per triangle 3 vertex indices. Bytes past the end read as 0.
#pragma once

#include "geofair/types.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace fuzz {

struct Reader {
  const std::uint8_t* data;
  std::size_t size, pos = 0;
  std::uint8_t next() { return pos < size ? data[pos++] : 0; }
};

struct Input {
  geofair::Positions V;
  geofair::Triangles F;
  std::vector<bool> flagged;  // per vertex: free (fair, remesh) or cut out (fill)
  std::uint8_t options = 0;
};

// Reads the mesh part of the layout; `in` is left at the first byte after it.
inline Input read_input(Reader& in) {
  Input input;
  const int nv = 3 + in.next() % 64;
  const int nf = 1 + in.next() % 128;
  input.options = in.next();
  input.V.resize(nv, 3);
  input.flagged.resize(nv);
  for (int v = 0; v < nv; ++v) {
    for (int c = 0; c < 3; ++c) input.V(v, c) = static_cast<std::int8_t>(in.next()) / 16.0;
    input.flagged[v] = in.next() & 1;
  }
  input.F.resize(nf, 3);
  for (int f = 0; f < nf; ++f)
    for (int c = 0; c < 3; ++c) input.F(f, c) = in.next() % nv;
  return input;
}

}  // namespace fuzz
