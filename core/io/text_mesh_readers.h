// Readers of OBJ, ASCII OFF, PLY (ASCII and binary) and STL (ASCII and
// binary), straight into a PolygonSoup. Internal to core/io; mesh_import.cc
// chooses the reader.
//
// Why not OpenMesh's readers (used earlier): they parse coordinates as
// 32-bit float, so a mesh far from its origin lost its shape (a fan of radius
// 0.05 around (1000, 1000, 1000) moved by 3e-5, its limit normals 3.6e-4 rad);
// and they are lenient in ways that would hide bad input (dropping vertices
// they cannot parse and renumbering the rest, dropping faces, reading garbage
// counts from a truncated file). These readers keep every coordinate as the
// file gives it (decimal text correctly rounded to double, binary PLY values
// widened from their declared type) and check the whole file strictly, with
// line numbers, while reading it.
//
// Validation of the result (index range, degenerate faces, manifoldness) is
// buildBaseMesh()'s; a reader checks only what it alone can say with a line.
#pragma once

#include <string>
#include <string_view>

#include "core/mesh/polygon_soup.h"
#include "core/util/status.h"

namespace tessera::io_detail {

struct TextReadOptions {
  // Refuse, at its line, a face index that names no vertex (in OBJ, no
  // vertex read so far; in PLY, none of those the header declares). The triangle import leaves indices to
  // buildBaseMesh, which names the whole face; the polygon import
  // (importPolygonSoup) uses the soup as the file states it.
  bool checkIndices = false;
  // USD: the Mesh prim to read, by its path ("/World/Cube") or its name
  // ("Cube"); empty: the layer's only Mesh.
  std::string usdPrim;
};

// OBJ: `v x y z [w | r g b]` and `f` with v, v/vt, v//vn or v/vt/vn references
// (1-based, negative relative to the vertices so far). Other statements
// (vt, vn, o, g, s, usemtl, mtllib, l, p, ...) carry no geometry Tessera uses.
Status readObj(std::string_view text, const std::string& src, PolygonSoup& soup,
               const TextReadOptions& options = {});

// ASCII OFF and its C/N/ST prefixes, with '#' comments; a face's optional
// colour is checked to be numbers and ignored.
Status readOff(std::string_view text, const std::string& src, PolygonSoup& soup,
               const TextReadOptions& options = {});

// PLY 1.0 (ascii, binary_little_endian, binary_big_endian): element vertex
// with x, y, z of any numeric type, element face with a list property
// vertex_indices (or vertex_index); other elements and properties are skipped.
// With checkIndices, a face index is checked against the declared vertex count.
Status readPly(std::string_view text, const std::string& src, PolygonSoup& soup,
               const TextReadOptions& options = {});

// STL: binary when the size is exactly 84 + 50 * (the declared facet count),
// else ASCII (starting with 'solid'). STL stores float: ASCII coordinates are
// rounded to float as a binary STL would hold them. STL has no indices:
// corners with equal positions become one vertex, numbered by first
// appearance; a facet whose corners coincide is an error naming it.
Status readStl(std::string_view text, const std::string& src, PolygonSoup& soup);

// USDA: one Mesh prim of a text USD layer (usda_parser.h: the subset read
// and what is refused), its points, faces, creases, corners, subdivision
// scheme, boundary rule and crease method (docs/FORMATS.md "USD"). Every
// face index is checked against the points.
Status readUsda(std::string_view text, const std::string& src, PolygonSoup& soup,
                const TextReadOptions& options = {});

}  // namespace tessera::io_detail
