#include "client/python/element_ids.h"

#include "client/python/bindings.h"
#include "client/python/errors.h"

namespace tessera::python {

namespace {

template <typename Id>
Id idOf(const py::handle& value, Expected<Id> (*parse)(const std::string&), const char* kind) {
  if (py::isinstance<py::str>(value)) return valueOf(parse(value.cast<std::string>()));
  // NumPy's integer scalars are not ints but convert through __index__.
  if (py::isinstance<py::int_>(value) || py::hasattr(value, "__index__"))
    return Id::fromPacked(py::reinterpret_borrow<py::object>(value).cast<uint64_t>());
  throw py::type_error(std::string("a ") + kind + " id is an int (packed) or a str like '" +
                       (kind[0] == 'v' ? "v2:40" : "e1:5") + "', not " +
                       py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
}

}  // namespace

VertexId vertexIdOf(const py::handle& value) {
  return idOf<VertexId>(value, parseVertexId, "vertex");
}

EdgeId edgeIdOf(const py::handle& value) {
  return idOf<EdgeId>(value, parseEdgeId, "edge");
}

std::vector<VertexId> vertexIdsOf(const py::handle& value) {
  if (py::isinstance<py::str>(value) || py::isinstance<py::int_>(value) ||
      (py::hasattr(value, "__index__") && !py::hasattr(value, "__len__")))
    return {vertexIdOf(value)};
  std::vector<VertexId> ids;
  for (const py::handle& item : py::iter(value)) ids.push_back(vertexIdOf(item));
  return ids;
}

void bindElementIds(py::module_& m) {
  m.def(
      "vertex_id",
      [](const py::object& value) -> uint64_t {
        if (py::isinstance<py::str>(value)) return vertexIdOf(value).packed();
        throw py::type_error("vertex_id(text) takes a str like 'v2:40', or use vertex_id(level, index)");
      },
      py::arg("text"),
      "The packed 64-bit id of a vertex given as text, e.g. vertex_id('v2:40').\n\n"
      "Packed ids are what regions' vertex_ids arrays hold and what every command\n"
      "accepts (docs/PROTOCOL.md section 3.1): the level in the top 6 bits, the\n"
      "index in the low 58. Raises tessera.Error for text that is not an id.");
  m.def(
      "vertex_id", [](int level, uint64_t index) { return VertexId(level, index).packed(); },
      py::arg("level"), py::arg("index"), "The packed id of vertex `index` of subdivision level `level`.");
  m.def(
      "edge_id", [](const std::string& text) { return edgeIdOf(py::str(text)).packed(); }, py::arg("text"),
      "The packed 64-bit id of an edge given as text, e.g. edge_id('e1:5').");
  m.def(
      "edge_id", [](int level, uint64_t index) { return EdgeId(level, index).packed(); }, py::arg("level"),
      py::arg("index"), "The packed id of edge `index` of subdivision level `level`.");
  m.def(
      "format_vertex_id", [](uint64_t packed) { return VertexId::fromPacked(packed).toString(); },
      py::arg("packed"),
      "The text form of a packed vertex id: format_vertex_id(vertex_id(2, 40)) == 'v2:40'.");
  m.def(
      "id_level", [](uint64_t packed) { return VertexId::fromPacked(packed).level(); }, py::arg("packed"),
      "The subdivision level of a packed id (vertex, edge or face alike).");
  m.def(
      "id_index", [](uint64_t packed) { return VertexId::fromPacked(packed).index(); }, py::arg("packed"),
      "The index within its level of a packed id (vertex, edge or face alike).");
}

}  // namespace tessera::python
