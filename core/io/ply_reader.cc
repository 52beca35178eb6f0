// PLY reader (see text_mesh_readers.h). The header is parsed strictly and
// the body walked element by element (ASCII: one element per line; binary:
// byte sizes, list counts included, checked against the end of the file
// before anything is read), so a truncated or mistyped body is an error
// naming the element, never a read past the end or an unbounded allocation.
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include "core/io/text_mesh_readers.h"
#include "core/io/text_scan.h"

namespace tessera::io_detail {
namespace {

enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64, kNone };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kNone;       // a scalar's type, or a list's items
  PlyType countType = PlyType::kNone;  // a list's count; kNone for scalars
  bool isList() const { return countType != PlyType::kNone; }
};

struct PlyElement {
  std::string name;
  size_t count = 0;
  std::vector<PlyProperty> properties;
};

// What the reader keeps from the vertex and face elements.
struct PlyRoles {
  int x = -1, y = -1, z = -1;  // property indices in the vertex element
  int faceList = -1;           // property index in the face element
};

PlyType plyType(std::string_view name) {
  static const std::pair<const char*, PlyType> kTypes[] = {
      {"char", PlyType::kInt8},      {"int8", PlyType::kInt8},       {"uchar", PlyType::kUint8},
      {"uint8", PlyType::kUint8},    {"short", PlyType::kInt16},     {"int16", PlyType::kInt16},
      {"ushort", PlyType::kUint16},  {"uint16", PlyType::kUint16},   {"int", PlyType::kInt32},
      {"int32", PlyType::kInt32},    {"uint", PlyType::kUint32},     {"uint32", PlyType::kUint32},
      {"float", PlyType::kFloat32},  {"float32", PlyType::kFloat32}, {"double", PlyType::kFloat64},
      {"float64", PlyType::kFloat64}};
  for (const auto& [n, t] : kTypes) {
    if (name == n) return t;
  }
  return PlyType::kNone;
}

int sizeOf(PlyType type) {
  switch (type) {
    case PlyType::kInt8:
    case PlyType::kUint8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUint16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
    case PlyType::kNone:
      return 0;
  }
  return 0;
}

bool isInteger(PlyType type) {
  return type != PlyType::kFloat32 && type != PlyType::kFloat64;
}

// One binary value, exactly (every PLY type fits a double without rounding).
double readBinary(const unsigned char* p, PlyType type, bool bigEndian) {
  unsigned char bytes[8];
  const int size = sizeOf(type);
  for (int k = 0; k < size; ++k) bytes[k] = p[bigEndian ? size - 1 - k : k];
  switch (type) {
    case PlyType::kInt8: {
      int8_t v;
      std::memcpy(&v, bytes, 1);
      return v;
    }
    case PlyType::kUint8:
      return bytes[0];
    case PlyType::kInt16: {
      int16_t v;
      std::memcpy(&v, bytes, 2);
      return v;
    }
    case PlyType::kUint16: {
      uint16_t v;
      std::memcpy(&v, bytes, 2);
      return v;
    }
    case PlyType::kInt32: {
      int32_t v;
      std::memcpy(&v, bytes, 4);
      return v;
    }
    case PlyType::kUint32: {
      uint32_t v;
      std::memcpy(&v, bytes, 4);
      return v;
    }
    case PlyType::kFloat32: {
      float v;
      std::memcpy(&v, bytes, 4);
      return v;
    }
    case PlyType::kFloat64: {
      double v;
      std::memcpy(&v, bytes, 8);
      return v;
    }
    case PlyType::kNone:
      return 0;
  }
  return 0;
}

struct PlyHeader {
  std::string format;
  std::vector<PlyElement> elements;
  size_t bodyStart = 0;
};

Status parseHeader(std::string_view text, const std::string& src, PlyHeader& header) {
  if (text.substr(0, 4) != "ply\n" && text.substr(0, 5) != "ply\r\n")
    return parseError(src + ": header: missing 'ply' magic");
  // The header ends at a line that is exactly "end_header".
  const size_t end = text.find("\nend_header");
  if (end == std::string_view::npos) return parseError(src + ": header: truncated, no 'end_header'");
  size_t bodyStart = text.find('\n', end + 1);
  if (bodyStart == std::string_view::npos) return parseError(src + ": header: truncated after 'end_header'");
  const std::string_view endLine = text.substr(end + 1, bodyStart - end - 1);
  if (endLine != "end_header" && endLine != "end_header\r") {
    return parseError(src + ": header: bad 'end_header' line '" + clip(endLine, 30) + "'");
  }
  header.bodyStart = bodyStart + 1;
  LineCursor cursor(text.substr(0, end));
  std::string_view line;
  std::vector<std::string_view> tokens;
  while (cursor.next(line)) {
    splitLine(line, tokens);
    const std::string where = at(src, cursor.lineNumber()) + "header: ";
    if (tokens.empty() || cursor.lineNumber() == 1 || tokens[0] == "comment" || tokens[0] == "obj_info")
      continue;
    if (tokens[0] == "format") {
      if (tokens.size() != 3 || tokens[2] != "1.0" ||
          (tokens[1] != "ascii" && tokens[1] != "binary_little_endian" && tokens[1] != "binary_big_endian")) {
        return parseError(where + "bad format line '" + clip(line, 60) + "'");
      }
      header.format = tokens[1];
    } else if (tokens[0] == "element") {
      int n = -1;
      if (tokens.size() != 3 || !parseInt(tokens[2], n) || n < 0)
        return parseError(where + "bad element line");
      header.elements.push_back({std::string(tokens[1]), static_cast<size_t>(n), {}});
    } else if (tokens[0] == "property" && !header.elements.empty()) {
      PlyProperty property;
      if (tokens.size() == 5 && tokens[1] == "list") {
        property.countType = plyType(tokens[2]);
        property.type = plyType(tokens[3]);
        if (property.countType == PlyType::kNone || !isInteger(property.countType) ||
            sizeOf(property.countType) > 4 || property.type == PlyType::kNone) {
          return parseError(where + "bad list property types '" + clip(tokens[2]) + " " + clip(tokens[3]) +
                            "'");
        }
        property.name = tokens[4];
      } else if (tokens.size() == 3) {
        property.type = plyType(tokens[1]);
        if (property.type == PlyType::kNone)
          return parseError(where + "unknown property type '" + clip(tokens[1]) + "'");
        property.name = tokens[2];
      } else {
        return parseError(where + "bad property line");
      }
      header.elements.back().properties.push_back(property);
    } else {
      return parseError(where + "unexpected '" + clip(tokens[0]) + "'");
    }
  }
  if (header.format.empty()) return parseError(src + ": header: no 'format' line");
  return Status::ok();
}

// Finds x, y, z and the face list; errors name what is missing.
Status findRoles(const PlyHeader& header, const std::string& src, PlyRoles& roles) {
  bool haveVertex = false, haveFace = false;
  for (const PlyElement& element : header.elements) {
    // Roles are property indices within "the" vertex or face element: a
    // second one would have its values read under the first one's roles (a
    // float of a second 'face' taken as an index; found by fuzz_import_ply).
    if ((element.name == "vertex" && haveVertex) || (element.name == "face" && haveFace)) {
      return parseError(src + ": header: element '" + element.name + "' is declared twice");
    }
    for (int p = 0; p < static_cast<int>(element.properties.size()); ++p) {
      const PlyProperty& property = element.properties[p];
      if (element.name == "vertex" && !property.isList()) {
        if (property.name == "x") roles.x = p;
        if (property.name == "y") roles.y = p;
        if (property.name == "z") roles.z = p;
      }
      if (element.name == "face" && property.isList() &&
          (property.name == "vertex_indices" || property.name == "vertex_index")) {
        if (!isInteger(property.type)) {
          return parseError(src + ": header: face property '" + property.name + "' has non-integer items");
        }
        roles.faceList = p;
      }
    }
    haveVertex |= element.name == "vertex";
    haveFace |= element.name == "face";
  }
  if (!haveVertex || !haveFace)
    return parseError(src + ": header: needs 'element vertex' and 'element face'");
  if (roles.x < 0 || roles.y < 0 || roles.z < 0) {
    return parseError(src + ": header: element vertex needs properties x, y and z");
  }
  if (roles.faceList < 0) {
    return parseError(src +
                      ": header: element face needs a list property 'vertex_indices' (or 'vertex_index')");
  }
  return Status::ok();
}

// Receives every value of the body in order; keeps the vertex coordinates
// and face indices.
class SoupBuilder {
 public:
  // `vertices`: the declared vertex count every face index is checked
  // against (TextReadOptions::checkIndices), or none.
  SoupBuilder(const PlyRoles& roles, const std::string& src, PolygonSoup& soup,
              std::optional<size_t> vertices)
      : roles_(roles), src_(src), soup_(soup), vertices_(vertices) {}

  void beginElement(const PlyElement& element, size_t index) {
    element_ = &element;
    index_ = index;
    face_.clear();
  }
  // The next value of property `p` (each item of a list in turn).
  Status value(int p, double v) {
    if (element_->name == "vertex") {
      if (p == roles_.x) xyz_[0] = v;
      if (p == roles_.y) xyz_[1] = v;
      if (p == roles_.z) xyz_[2] = v;
    } else if (element_->name == "face" && p == roles_.faceList) {
      // The header admits integer lists only; kept as a guard, since a NaN
      // would pass the range test below and its cast is undefined.
      if (!std::isfinite(v) || v != std::floor(v)) {
        return invalidMesh(src_ + ": face " + std::to_string(index_) + ": vertex index " + std::to_string(v) +
                           " is not an integer");
      }
      if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max()) {
        return invalidMesh(src_ + ": face " + std::to_string(index_) + ": vertex index " + std::to_string(v) +
                           " is out of range");
      }
      if (vertices_ && (v < 0 || v >= static_cast<double>(*vertices_))) {
        return invalidMesh(src_ + ": face " + std::to_string(index_) + ": vertex index " +
                           std::to_string(static_cast<int>(v)) + " names no vertex (" +
                           std::to_string(*vertices_) + " vertices)");
      }
      face_.push_back(static_cast<int>(v));
    }
    return Status::ok();
  }
  Status endElement() {
    if (element_->name == "vertex") {
      const std::string name = src_ + ": vertex " + std::to_string(index_);
      for (double c : xyz_) {
        if (!std::isfinite(c))
          return invalidMesh(name + ": coordinate is " + (std::isnan(c) ? "NaN" : "infinite"));
        if (std::abs(c) > kMaxCoordinate)
          return invalidMesh(name + ": coordinate is outside float range (|x| <= 3.4e38)");
      }
      soup_.points.emplace_back(xyz_[0], xyz_[1], xyz_[2]);
    } else if (element_->name == "face") {
      soup_.addFace(face_);
    }
    return Status::ok();
  }

 private:
  const PlyRoles& roles_;
  const std::string& src_;
  PolygonSoup& soup_;
  std::optional<size_t> vertices_;
  const PlyElement* element_ = nullptr;
  size_t index_ = 0;
  double xyz_[3] = {0, 0, 0};
  std::vector<int> face_;
};

Status readAsciiBody(std::string_view body, const PlyHeader& header, const std::string& src,
                     SoupBuilder& out) {
  LineCursor cursor(body);
  std::string_view line;
  std::vector<std::string_view> tokens;
  for (const PlyElement& element : header.elements) {
    for (size_t i = 0; i < element.count; ++i) {
      const std::string name = element.name + " " + std::to_string(i);
      tokens.clear();
      while (tokens.empty() && cursor.next(line)) splitLine(line, tokens);
      if (tokens.empty()) return parseError(src + ": truncated: " + name + " is missing");
      out.beginElement(element, i);
      size_t at = 0;
      for (int p = 0; p < static_cast<int>(element.properties.size()); ++p) {
        const PlyProperty& property = element.properties[p];
        int n = 1;
        if (property.isList() && (at >= tokens.size() || !parseInt(tokens[at++], n) || n < 0)) {
          return parseError(src + ": " + name + ": bad list length");
        }
        for (int k = 0; k < n; ++k, ++at) {
          double value;
          if (at >= tokens.size()) return parseError(src + ": " + name + ": too few values");
          if (!parseNumber(tokens[at], value) || (isInteger(property.type) && value != std::floor(value))) {
            return parseError(src + ": " + name + ": bad value '" + clip(tokens[at]) + "'");
          }
          TESSERA_RETURN_IF_ERROR(out.value(p, value));
        }
      }
      if (at != tokens.size())
        return parseError(src + ": " + name + ": unexpected '" + clip(tokens[at]) + "'");
      TESSERA_RETURN_IF_ERROR(out.endElement());
    }
  }
  return Status::ok();
}

Status readBinaryBody(std::string_view text, const PlyHeader& header, const std::string& src,
                      SoupBuilder& out) {
  const bool bigEndian = header.format == "binary_big_endian";
  const auto* data = reinterpret_cast<const unsigned char*>(text.data());
  size_t at = header.bodyStart;
  for (const PlyElement& element : header.elements) {
    // Instances without properties take no bytes, so the end of the input
    // would never stop their loop: 282 bytes declaring 555,555,555 of them
    // cost minutes of CPU (fuzz_import_ply). They carry nothing to read,
    // and the vertex and face elements always have properties (findRoles).
    if (element.properties.empty()) continue;
    for (size_t i = 0; i < element.count; ++i) {
      const auto truncated = [&] {
        return parseError(src + ": truncated: " + element.name + " " + std::to_string(i) +
                          " runs past the end of the file");
      };
      out.beginElement(element, i);
      for (int p = 0; p < static_cast<int>(element.properties.size()); ++p) {
        const PlyProperty& property = element.properties[p];
        uint64_t n = 1;
        if (property.isList()) {
          const size_t countSize = static_cast<size_t>(sizeOf(property.countType));
          if (at + countSize > text.size()) return truncated();
          const double count = readBinary(data + at, property.countType, bigEndian);
          if (count < 0)
            return parseError(src + ": " + element.name + " " + std::to_string(i) + ": bad list length");
          n = static_cast<uint64_t>(count);
          at += countSize;
        }
        const uint64_t size = static_cast<uint64_t>(sizeOf(property.type));
        if (at > text.size() || n * size > text.size() - at) return truncated();
        for (uint64_t k = 0; k < n; ++k, at += size) {
          TESSERA_RETURN_IF_ERROR(out.value(p, readBinary(data + at, property.type, bigEndian)));
        }
      }
      TESSERA_RETURN_IF_ERROR(out.endElement());
    }
  }
  return Status::ok();
}

}  // namespace

Status readPly(std::string_view text, const std::string& src, PolygonSoup& soup,
               const TextReadOptions& options) {
  PlyHeader header;
  TESSERA_RETURN_IF_ERROR(parseHeader(text, src, header));
  PlyRoles roles;
  TESSERA_RETURN_IF_ERROR(findRoles(header, src, roles));
  // The header declares every element's count, so a face may be checked
  // before the vertices it names are read.
  std::optional<size_t> vertices;
  if (options.checkIndices) {
    vertices = 0;
    for (const PlyElement& e : header.elements)
      if (e.name == "vertex") vertices = e.count;
  }
  SoupBuilder out(roles, src, soup, vertices);
  if (header.format == "ascii") return readAsciiBody(text.substr(header.bodyStart), header, src, out);
  return readBinaryBody(text, header, src, out);
}

}  // namespace tessera::io_detail
