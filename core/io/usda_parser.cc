// The usda subset of usda_parser.h: a recursive descent over the grammar of
// Pixar's text format (pxr/usd/sdf/textFileFormat.yy), keeping only what a
// Mesh prim's control mesh needs and skipping other values whole.
#include "core/io/usda_parser.h"

#include <array>
#include <cmath>

#include "core/io/text_scan.h"

namespace tessera::io_detail {
namespace {

using Kind = UsdaToken::Kind;

constexpr int kMaxPrimDepth = 256;

bool isPunct(const UsdaToken& t, char c) {
  return t.kind == Kind::kPunct && t.text[0] == c;
}
bool isWord(const UsdaToken& t, std::string_view word) {
  return t.kind == Kind::kIdentifier && t.text == word;
}

std::string describe(const UsdaToken& t) {
  switch (t.kind) {
    case Kind::kEnd:
      return "the end of the file";
    case Kind::kString:
      return "a string";
    case Kind::kAssetPath:
      return "an asset path";
    case Kind::kPathRef:
      return "a path <" + clip(t.text, 40) + ">";
    default:
      return "'" + clip(t.text, 40) + "'";
  }
}

// Metadata and statements that compose other layers or pick among values:
// reading this layer alone would not give the mesh USD composes.
const char* refusedComposition(std::string_view key) {
  if (key == "references") return "references";
  if (key == "payload") return "payloads";
  if (key == "inherits") return "inherits";
  if (key == "specializes") return "specializes";
  if (key == "variants" || key == "variantSets" || key == "variantSet") return "variants and variant sets";
  if (key == "subLayers") return "sublayers";
  if (key == "relocates") return "relocates";
  return nullptr;
}

class Parser {
 public:
  Parser(std::string_view text, std::string source, int line, size_t offset)
      : lexer_(text, std::move(source), line, offset) {}

  Expected<std::vector<UsdaMeshPrim>> layer() {
    TESSERA_ASSIGN_OR_RETURN(UsdaToken t, lexer_.peek());
    if (isPunct(t, '(')) {
      TESSERA_RETURN_IF_ERROR(lexer_.next().status());
      TESSERA_RETURN_IF_ERROR(metadata("layer"));
    }
    while (true) {
      TESSERA_ASSIGN_OR_RETURN(t, lexer_.next());
      if (t.kind == Kind::kEnd) break;
      TESSERA_RETURN_IF_ERROR(prim(t, ""));
    }
    return std::move(meshes_);
  }

 private:
  Status unexpected(const UsdaToken& t, const std::string& wanted) {
    return parseError(lexer_.at(t) + "expected " + wanted + ", found " + describe(t));
  }
  Status refuse(const UsdaToken& t, const char* what) {
    return unsupported(lexer_.at(t) + "'" + std::string(t.text) + "': " + what +
                       " are not supported (Tessera reads one layer's own meshes; docs/FORMATS.md \"USD\")");
  }
  Status expect(char c) {
    TESSERA_ASSIGN_OR_RETURN(UsdaToken t, lexer_.next());
    return isPunct(t, c) ? Status::ok() : unexpected(t, "'" + std::string(1, c) + "'");
  }

  // A value of any kind, skipped: an atom, or a bracketed group whose
  // brackets must balance.
  Status skipValue() {
    TESSERA_ASSIGN_OR_RETURN(UsdaToken t, lexer_.next());
    if (t.kind == Kind::kEnd) return unexpected(t, "a value");
    if (!isPunct(t, '(') && !isPunct(t, '[') && !isPunct(t, '{')) {
      if (t.kind == Kind::kPunct) return unexpected(t, "a value");
      return Status::ok();
    }
    std::vector<char> open{t.text[0]};
    while (!open.empty()) {
      TESSERA_ASSIGN_OR_RETURN(t, lexer_.next());
      if (t.kind == Kind::kEnd) return unexpected(t, "a closing bracket");
      if (t.kind != Kind::kPunct) continue;
      const char c = t.text[0];
      if (c == '(' || c == '[' || c == '{') {
        open.push_back(c);
      } else if (c == ')' || c == ']' || c == '}') {
        const char want = open.back() == '(' ? ')' : open.back() == '[' ? ']' : '}';
        if (c != want) return unexpected(t, "'" + std::string(1, want) + "'");
        open.pop_back();
      }
    }
    return Status::ok();
  }

  // `( ... )` after its '(': a doc string, or `[listop] key = value`, each
  // optionally ended by ';'. Composition keys are refused by name.
  Status metadata(const std::string& owner) {
    while (true) {
      TESSERA_ASSIGN_OR_RETURN(UsdaToken t, lexer_.next());
      if (isPunct(t, ')')) return Status::ok();
      if (isPunct(t, ';') || t.kind == Kind::kString) continue;
      if (t.kind != Kind::kIdentifier) return unexpected(t, "metadata of " + owner + " or ')'");
      if (t.text == "prepend" || t.text == "append" || t.text == "add" || t.text == "delete" ||
          t.text == "reorder") {
        TESSERA_ASSIGN_OR_RETURN(t, lexer_.next());
        if (t.kind != Kind::kIdentifier) return unexpected(t, "a metadata name");
      }
      if (const char* what = refusedComposition(t.text)) return refuse(t, what);
      TESSERA_RETURN_IF_ERROR(expect('='));
      TESSERA_RETURN_IF_ERROR(skipValue());
    }
  }

  // `def [Type] "name" [( metadata )] { ... }`, its specifier already read.
  Status prim(const UsdaToken& specifier, const std::string& parent, int depth = 0) {
    // Each level of nesting is a frame of this recursion: bounded, so that a
    // hostile file cannot exhaust the stack.
    if (depth >= kMaxPrimDepth)
      return unsupported(lexer_.at(specifier) + "prims nested deeper than " + std::to_string(kMaxPrimDepth));
    if (isWord(specifier, "over") || isWord(specifier, "class"))
      return unsupported(lexer_.at(specifier) + "'" + std::string(specifier.text) +
                         "' prims are not supported: they compose over other prims (only 'def' is read; "
                         "docs/FORMATS.md \"USD\")");
    if (const char* what = refusedComposition(specifier.text)) return refuse(specifier, what);
    if (!isWord(specifier, "def")) return unexpected(specifier, "a prim ('def')");
    TESSERA_ASSIGN_OR_RETURN(UsdaToken t, lexer_.next());
    std::string type;
    if (t.kind == Kind::kIdentifier) {
      type = std::string(t.text);
      TESSERA_ASSIGN_OR_RETURN(t, lexer_.next());
    }
    if (t.kind != Kind::kString || t.text.empty()) return unexpected(t, "the prim's name in quotes");
    const std::string path = parent + "/" + std::string(t.text);
    TESSERA_ASSIGN_OR_RETURN(t, lexer_.next());
    if (isPunct(t, '(')) {
      TESSERA_RETURN_IF_ERROR(metadata("prim " + path));
      TESSERA_ASSIGN_OR_RETURN(t, lexer_.next());
    }
    if (!isPunct(t, '{')) return unexpected(t, "'{' opening prim " + path);
    UsdaMeshPrim* mesh = nullptr;
    size_t meshIndex = 0;
    if (type == "Mesh") {
      meshIndex = meshes_.size();
      meshes_.push_back(UsdaMeshPrim{});
      meshes_.back().path = path;
      meshes_.back().line = specifier.line;
    }
    while (true) {
      TESSERA_ASSIGN_OR_RETURN(t, lexer_.next());
      if (isPunct(t, '}')) return Status::ok();
      if (isPunct(t, ';')) continue;
      if (isWord(t, "def") || isWord(t, "over") || isWord(t, "class")) {
        TESSERA_RETURN_IF_ERROR(prim(t, path, depth + 1));
        continue;
      }
      // Child prims may have grown meshes_: look the mesh up again.
      mesh = type == "Mesh" ? &meshes_[meshIndex] : nullptr;
      TESSERA_RETURN_IF_ERROR(property(t, path, mesh));
    }
  }

  // `[custom] [uniform|varying] type[[]] name[.field] [= value] [( metadata )]`
  // or `[custom] rel name [= targets]`, its first token read.
  Status property(UsdaToken t, const std::string& prim, UsdaMeshPrim* mesh) {
    if (const char* what = refusedComposition(t.text)) return refuse(t, what);
    if (isWord(t, "reorder")) {  // `reorder nameChildren = [...]`: order only
      TESSERA_ASSIGN_OR_RETURN(t, lexer_.next());
      TESSERA_RETURN_IF_ERROR(expect('='));
      return skipValue();
    }
    while (isWord(t, "custom") || isWord(t, "uniform") || isWord(t, "varying") || isWord(t, "config")) {
      TESSERA_ASSIGN_OR_RETURN(t, lexer_.next());
    }
    if (t.kind != Kind::kIdentifier) return unexpected(t, "a property of prim " + prim);
    const bool relationship = t.text == "rel";
    std::string type(t.text);
    TESSERA_ASSIGN_OR_RETURN(UsdaToken name, lexer_.next());
    if (!relationship && isPunct(name, '[')) {
      TESSERA_RETURN_IF_ERROR(expect(']'));
      type += "[]";
      TESSERA_ASSIGN_OR_RETURN(name, lexer_.next());
    }
    if (name.kind != Kind::kIdentifier) return unexpected(name, "the name of a property of prim " + prim);
    const std::string attribute = "attribute '" + std::string(name.text) + "'";
    TESSERA_ASSIGN_OR_RETURN(t, lexer_.peek());
    if (isPunct(t, '.')) {
      TESSERA_RETURN_IF_ERROR(lexer_.next().status());
      TESSERA_ASSIGN_OR_RETURN(UsdaToken field, lexer_.next());
      if (isWord(field, "timeSamples") || isWord(field, "spline"))
        return unsupported(lexer_.at(field) + attribute + ": ." + std::string(field.text) +
                           " is not supported (Tessera reads default values only; docs/FORMATS.md \"USD\")");
      if (isWord(field, "connect"))
        return unsupported(lexer_.at(field) + attribute + ": .connect is not supported");
      return unexpected(field, "timeSamples, spline or connect");
    }
    if (isPunct(t, '=')) {
      TESSERA_RETURN_IF_ERROR(lexer_.next().status());
      TESSERA_RETURN_IF_ERROR(value(type, name, relationship ? nullptr : mesh));
      TESSERA_ASSIGN_OR_RETURN(t, lexer_.peek());
    }
    if (isPunct(t, '(')) {
      TESSERA_RETURN_IF_ERROR(lexer_.next().status());
      return metadata(attribute);
    }
    return Status::ok();
  }

  template <typename T>
  Status begin(UsdaAttribute<T>& attribute, const UsdaToken& name, const std::string& type,
               std::initializer_list<std::string_view> types) {
    bool known = false;
    std::string list;
    for (std::string_view ok : types) {
      known = known || type == ok;
      list += (list.empty() ? "" : " or ") + std::string(ok);
    }
    const std::string what = "attribute '" + std::string(name.text) + "'";
    if (!known) return parseError(lexer_.at(name) + what + ": type " + list + " expected, found " + type);
    if (attribute.authored) return parseError(lexer_.at(name) + what + ": authored twice");
    attribute.authored = true;
    attribute.where = name;
    return Status::ok();
  }

  // A number token as int or double; errors name the attribute and element.
  Status number(const UsdaToken& t, const std::string& what, size_t index, int& out) {
    if (t.kind != Kind::kNumber || !parseInt(t.text, out))
      return parseError(lexer_.at(t) + what + "[" + std::to_string(index) + "]: expected an integer, found " +
                        describe(t));
    return Status::ok();
  }
  Status number(const UsdaToken& t, const std::string& what, size_t index, double& out) {
    if (t.kind == Kind::kNumber && parseNumber(t.text, out)) return Status::ok();
    if (t.kind == Kind::kIdentifier && (t.text == "inf" || t.text == "nan")) {
      out = t.text == "inf" ? HUGE_VAL : NAN;
      return Status::ok();
    }
    return parseError(lexer_.at(t) + what + "[" + std::to_string(index) + "]: expected a number, found " +
                      describe(t));
  }
  Status number(const UsdaToken& t, const std::string& what, size_t index, Vec3& out) {
    // A tuple: its '(' is `t`.
    if (!isPunct(t, '('))
      return parseError(lexer_.at(t) + what + "[" + std::to_string(index) +
                        "]: expected a point (x, y, z), found " + describe(t));
    double xyz[3];
    for (int k = 0; k < 3; ++k) {
      if (k > 0) TESSERA_RETURN_IF_ERROR(expect(','));
      TESSERA_ASSIGN_OR_RETURN(UsdaToken c, lexer_.next());
      TESSERA_RETURN_IF_ERROR(number(c, what, index, xyz[k]));
      if (!std::isfinite(xyz[k]) || std::abs(xyz[k]) > kMaxCoordinate)
        return invalidMesh(lexer_.at(c) + what + "[" + std::to_string(index) + "]: coordinate " +
                           clip(c.text, 40) + " is not finite or outside float range");
    }
    TESSERA_RETURN_IF_ERROR(expect(')'));
    out = Vec3(xyz[0], xyz[1], xyz[2]);
    return Status::ok();
  }

  template <typename T>
  Status array(const UsdaToken& name, std::vector<T>& out) {
    const std::string what = "attribute '" + std::string(name.text) + "'";
    TESSERA_ASSIGN_OR_RETURN(UsdaToken t, lexer_.next());
    if (!isPunct(t, '[')) return parseError(lexer_.at(t) + what + ": expected '[', found " + describe(t));
    TESSERA_ASSIGN_OR_RETURN(t, lexer_.next());
    while (!isPunct(t, ']')) {
      T element{};
      TESSERA_RETURN_IF_ERROR(number(t, what, out.size(), element));
      out.push_back(element);
      TESSERA_ASSIGN_OR_RETURN(t, lexer_.next());
      if (isPunct(t, ',')) {
        TESSERA_ASSIGN_OR_RETURN(t, lexer_.next());
      } else if (!isPunct(t, ']')) {
        return parseError(lexer_.at(t) + what + ": expected ',' or ']', found " + describe(t));
      }
    }
    return Status::ok();
  }

  Status token(const UsdaToken& name, std::string& out) {
    TESSERA_ASSIGN_OR_RETURN(UsdaToken t, lexer_.next());
    if (t.kind != Kind::kString)
      return parseError(lexer_.at(t) + "attribute '" + std::string(name.text) +
                        "': expected a token in quotes, found " + describe(t));
    out = std::string(t.text);
    return Status::ok();
  }

  // The value after '='; a Mesh's attributes that define its control mesh
  // are read by their schema type, anything else is skipped.
  Status value(const std::string& type, const UsdaToken& name, UsdaMeshPrim* mesh) {
    if (mesh == nullptr) return skipValue();
    TESSERA_ASSIGN_OR_RETURN(UsdaToken next, lexer_.peek());
    if (isWord(next, "None"))
      return parseError(lexer_.at(next) + "attribute '" + std::string(name.text) +
                        "': None (blocked) is not supported");
    const std::string_view n = name.text;
    auto ints = [&](UsdaAttribute<std::vector<int>>& a) -> Status {
      TESSERA_RETURN_IF_ERROR(begin(a, name, type, {"int[]"}));
      return array(name, a.value);
    };
    auto floats = [&](UsdaAttribute<std::vector<double>>& a) -> Status {
      TESSERA_RETURN_IF_ERROR(begin(a, name, type, {"float[]", "double[]"}));
      return array(name, a.value);
    };
    auto tokenOf = [&](UsdaAttribute<std::string>& a) -> Status {
      TESSERA_RETURN_IF_ERROR(begin(a, name, type, {"token"}));
      return token(name, a.value);
    };
    if (n == "points") {
      TESSERA_RETURN_IF_ERROR(begin(mesh->points, name, type, {"point3f[]", "point3d[]"}));
      return array(name, mesh->points.value);
    }
    if (n == "faceVertexCounts") return ints(mesh->faceVertexCounts);
    if (n == "faceVertexIndices") return ints(mesh->faceVertexIndices);
    if (n == "creaseIndices") return ints(mesh->creaseIndices);
    if (n == "creaseLengths") return ints(mesh->creaseLengths);
    if (n == "cornerIndices") return ints(mesh->cornerIndices);
    if (n == "holeIndices") return ints(mesh->holeIndices);
    if (n == "creaseSharpnesses") return floats(mesh->creaseSharpnesses);
    if (n == "cornerSharpnesses") return floats(mesh->cornerSharpnesses);
    if (n == "subdivisionScheme") return tokenOf(mesh->subdivisionScheme);
    if (n == "interpolateBoundary") return tokenOf(mesh->interpolateBoundary);
    if (n == "orientation") return tokenOf(mesh->orientation);
    if (n == "triangleSubdivisionRule") return tokenOf(mesh->triangleSubdivisionRule);
    if (n == "tessera:creaseMethod") return tokenOf(mesh->creaseMethod);
    return skipValue();
  }

 private:
  UsdaLexer lexer_;
  std::vector<UsdaMeshPrim> meshes_;
};

}  // namespace

Expected<std::vector<UsdaMeshPrim>> parseUsdaMeshes(std::string_view text, const std::string& source) {
  if (text.substr(0, 8) == "PXR-USDC")
    return unsupported(source +
                       ": a binary USD file (usdc, 'PXR-USDC'): Tessera reads the text format (usda); "
                       "convert it with `usdcat -o mesh.usda`");
  if (text.find('\0') != std::string_view::npos) return parseError(source + ": binary data, not a usda file");
  const size_t lineEnd = std::min(text.find('\n'), text.size());
  std::string_view header = text.substr(0, lineEnd);
  while (!header.empty() && isBlank(header.back())) header.remove_suffix(1);
  if (header != "#usda 1.0")
    return parseError(source + ":1: header: expected '#usda 1.0', found '" + clip(header, 40) + "'");
  Parser parser(text, source, 1, lineEnd);
  return parser.layer();
}

}  // namespace tessera::io_detail
