// Writes the generated part of the seed corpora (corpus/<target>/gen_*):
// real encodings made by the code under test from the creased cube, so the
// fuzzer starts from valid frames, regions, documents and journals rather
// than from bytes it would need millions of runs to discover. The mesh, tag
// and script seeds are copies of tests/data and deploy/samples files.
//
//   build/fuzz/tests/fuzz/fuzz_make_corpus tests/fuzz/corpus
//
// The output is deterministic, so re-running it changes nothing unless an
// encoder changed (then the corpus should follow, and be committed).
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/document/document_file.h"
#include "core/morph/keyed_document_file.h"
#include "core/tessellation/document_grid.h"
#include "core/tessellation/region_codec.h"
#include "core/tessellation/tessellation.h"
#include "fuzz_support.h"
#include "protocol/framing.h"
#include "protocol/tessera.pb.h"
#include "server/document/journal_entry.h"

namespace tessera::fuzz {
namespace {

std::filesystem::path root;

void write(const std::string& target, const std::string& name, const std::string& bytes) {
  const auto dir = root / target;
  std::filesystem::create_directories(dir);
  std::ofstream out(dir / ("gen_" + name), std::ios::binary | std::ios::trunc);
  out << bytes;
  if (!out) fail("cannot write " + (dir / name).string());
}

template <typename T>
T value(Expected<T> e, const char* what) {
  if (!e.isOk()) fail(std::string(what) + ": " + e.status().toString());
  return std::move(*e);
}

void ok(const Status& s, const char* what) {
  if (!s.isOk()) fail(std::string(what) + ": " + s.toString());
}

// The cube with one edit of each kind, the last sharpness undone, then an
// interpolating vertex (edit kind 4).
Document editedCube() {
  Document doc = cubeDocument(3);
  const VertexId corner(1, 3), fine[] = {VertexId(2, 5), VertexId(2, 6)};
  value(doc.moveToLimit(std::span(&corner, 1), Vec3(1.1, -0.1, -0.1)), "move");
  value(doc.moveBy(fine, Vec3(0, 0, 0.04)), "offset");
  value(doc.setEdgeSharpness(EdgeId(1, 4), 2.5f), "crease");
  EditId last = value(doc.setVertexSharpness(VertexId(2, 1), 3.0f), "corner");
  ok(doc.undo(last), "undo");
  value(doc.setInterpolation(VertexId(1, 8), true, 2.5), "interpolate");
  return doc;
}

// Key 1 of the morph seeds: the cube's points moved (same triangles).
std::vector<Vec3> secondKeyPoints(const Document& doc) {
  std::vector<Vec3> points = doc.basePoints();
  for (Vec3& p : points) p = Vec3(1.25 * p[0], p[1] + 0.1 * p[0], 0.8 * p[2]);
  return points;
}

void documents() {
  write("document_file", "cube.tsd", serializeDocument(cubeDocument(3)));
  write("document_file", "edited.tsd", serializeDocument(editedCube()));
  // A morph document (two keys, keyed_document_file.h), as snapshots hold it.
  KeyedDocument morph(editedCube());
  ok(morph.addKey(secondKeyPoints(morph.key0()),
                  {std::string("\x89PNG\r\n\x1a\n", 8), std::string("\x89PNG\r\n\x1a\n", 8)}),
     "add key");
  const VertexId moved[] = {VertexId(1, 3)};
  value((*morph.editKey(1))->moveBy(moved, Vec3(0.05, 0, 0)), "key 1 offset");
  write("document_file", "morph.tsd", serializeKeyedDocument(morph));
}

std::string prefixed(const std::vector<std::string>& entries) {
  std::string out;
  for (const std::string& e : entries) {
    if (e.size() > 255) fail("a journal entry longer than one length byte");
    out += static_cast<char>(e.size());
    out += e;
  }
  return out;
}

void journals() {
  const Document doc = editedCube();
  std::vector<std::string> entries;
  for (const Edit& edit : doc.edits()) {
    Edit made = edit;
    made.active = true;  // journaled as made; the undo follows as its own entry
    entries.push_back(server::encodeJournalEntry({server::JournalEntry::Kind::kEdit, made, {}}));
  }
  const EditId last = doc.edits().back().id;
  entries.push_back(server::encodeJournalEntry({server::JournalEntry::Kind::kUndo, {}, last}));
  entries.push_back(server::encodeJournalEntry({server::JournalEntry::Kind::kRedo, {}, last}));
  write("journal_entry", "history", prefixed(entries));
  // A second morph key, then an edit and its undo on it.
  {
    server::JournalEntry add, onKey1, undo;
    add.kind = server::JournalEntry::Kind::kAddKey;
    add.keyPoints = secondKeyPoints(cubeDocument(3));
    onKey1.kind = server::JournalEntry::Kind::kEdit;
    onKey1.edit = doc.edits().front();
    onKey1.edit.active = true;
    onKey1.key = 1;
    undo.kind = server::JournalEntry::Kind::kUndo;
    undo.target = onKey1.edit.id;
    undo.key = 1;
    write("journal_entry", "morph",
          prefixed({server::encodeJournalEntry(add), server::encodeJournalEntry(onKey1),
                    server::encodeJournalEntry(undo)}));
  }
  for (size_t i = 0; i < 5; ++i)
    write("journal_entry", "edit" + std::to_string(i + 1), prefixed({entries[i]}));
}

// The edited cube's first two regions in each id coding, in `codec`'s
// payload, for `target`'s seeds.
void regions(const std::string& target, RegionCodec codec) {
  Document doc = editedCube();
  const QuantizationGrid grid = value(documentGrid(doc), "grid");
  const LodProfile profile{.baseLevel = 1, .maxLevel = 3, .angleThresholdDegrees = 15};
  Tessellation t = value(Tessellation::build(doc, profile), "tessellation");
  int n = 0;
  for (const auto& [id, mesh] : t.regions()) {
    if (n++ == 2) break;
    RegionHeader header{id, 6, 5, profile, grid, true};
    header.codec = codec;
    write(target, "ids_" + std::to_string(n), value(encodeRegion(header, mesh), "encode"));
    // A group of base faces has no one root face, so no lattice frame
    // (Tessellation::regionsAreGroups); the lattice seeds written before
    // groups existed stay in the corpus.
    if (!t.regionsAreGroups()) {
      header.frame = value(regionFrame(doc.hierarchy(), doc.counts(), FaceId::fromPacked(id)), "frame");
      write(target, "lattice_" + std::to_string(n), value(encodeRegion(header, mesh), "encode"));
      header.frame.reset();
    }
    header.idsInline = false;
    write(target, "layout_" + std::to_string(n), value(encodeRegion(header, mesh), "encode"));
    header.idsInline = true;
    header.profile.vertexIds = false;
    write(target, "noids_" + std::to_string(n), value(encodeRegion(header, mesh, 0), "encode"));
  }
}

std::string frame(const google::protobuf::MessageLite& m) {
  return value(encodeFrame(m, 1u << 20), "frame");
}

// Client messages for document 1, with client_seq `seq` (its low bit picks
// the session in the document host target), subscribing up to `maxLevel`.
std::vector<wire::ClientMessage> session(uint64_t seq, int maxLevel) {
  std::vector<wire::ClientMessage> out;
  auto add = [&]() -> wire::ClientMessage& {
    out.emplace_back().set_client_seq(seq);
    seq += 2;
    return out.back();
  };
  auto* sub = add().mutable_subscribe();
  sub->set_document_id(1);
  sub->mutable_profile()->set_base_level(1);
  sub->mutable_profile()->set_max_level(maxLevel);
  sub->mutable_profile()->set_angle_threshold_degrees(15);
  sub->set_with_commands(true);
  auto* move = add().mutable_move_vertex();
  move->set_document_id(1);
  move->add_vertex_ids(VertexId(1, 3).packed());
  move->mutable_target()->set_x(1.1);
  move->mutable_target()->set_y(-0.1);
  move->mutable_target()->set_z(-0.1);
  move->set_mode(wire::MOVE_MODE_DIRECT_MANIPULATION);
  auto* offset = add().mutable_move_vertex();
  offset->set_document_id(1);
  offset->add_vertex_ids(VertexId(2, 5).packed());
  offset->add_vertex_ids(VertexId(2, 6).packed());
  offset->mutable_target()->set_z(0.04);
  offset->set_mode(wire::MOVE_MODE_OFFSET);
  auto* crease = add().mutable_set_edge_sharpness();
  crease->set_document_id(1);
  crease->set_edge_id(EdgeId(1, 4).packed());
  crease->set_sharpness(2.5f);
  auto* byEnds = add().mutable_set_edge_sharpness();
  byEnds->set_document_id(1);
  byEnds->set_edge_id(~uint64_t{0});
  byEnds->add_end_vertex_ids(VertexId(0, 0).packed());
  byEnds->add_end_vertex_ids(VertexId(0, 1).packed());
  byEnds->set_sharpness(10.0f);
  auto* corner = add().mutable_set_vertex_type();
  corner->set_document_id(1);
  corner->set_vertex_id(VertexId(2, 1).packed());
  corner->set_type(wire::VERTEX_TYPE_CORNER);
  if (maxLevel < 3) {  // the host's documents: an interpolating vertex (the frame seeds stay as they were)
    auto* tag = add().mutable_set_interpolation();
    tag->set_document_id(1);
    tag->set_vertex_id(VertexId(1, 8).packed());
    tag->set_interpolating(true);
    tag->set_tension(2.0);
    // A morph document: key 1, a subscription at t = 0.5, an edit of key 1
    // and the coarse stream (docs/PROTOCOL.md §14).
    const Document cube = cubeDocument(maxLevel);
    std::string obj;
    for (const Vec3& p : secondKeyPoints(cube)) {
      obj += "v " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + "\n";
    }
    for (const auto& t : cube.baseTopology().triangles) {
      obj += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " +
             std::to_string(t[2] + 1) + "\n";
    }
    auto* key = add().mutable_add_morph_key();
    key->set_document_id(1);
    key->set_mesh(obj);
    key->set_mesh_format(wire::MESH_FORMAT_OBJ);
    auto* at = add().mutable_subscribe();
    at->set_document_id(1);
    at->mutable_profile()->set_base_level(1);
    at->mutable_profile()->set_max_level(2);
    at->mutable_profile()->set_angle_threshold_degrees(20);
    at->mutable_profile()->set_morph_t(0.5);
    auto* onKey = add().mutable_move_vertex();
    onKey->set_document_id(1);
    onKey->add_vertex_ids(VertexId(1, 3).packed());
    onKey->mutable_target()->set_z(0.05);
    onKey->set_mode(wire::MOVE_MODE_OFFSET);
    onKey->set_key(1);
    auto* control = add().mutable_get_morph_control();
    control->set_document_id(1);
    control->set_t(0.25);
    control->set_with_topology(true);
  }
  for (uint32_t level : {0u, 2u, 9u}) {
    auto* cage = add().mutable_get_cage();
    cage->set_document_id(1);
    cage->set_level(level);
  }
  auto* undo = add().mutable_undo();
  undo->set_document_id(1);
  undo->set_edit_id(2);
  auto* redo = add().mutable_redo();
  redo->set_document_id(1);
  redo->set_edit_id(2);
  auto* select = add().mutable_select();
  select->set_document_id(1);
  select->mutable_selection()->add_vertex_ids(VertexId(1, 3).packed());
  select->mutable_selection()->add_edge_ids(EdgeId(1, 4).packed());
  auto* exported = add().mutable_export_document();
  exported->set_document_id(1);
  exported->set_level(1);
  exported->set_limit(true);
  add().mutable_unsubscribe()->set_document_id(1);
  return out;
}

void hostSessions() {
  std::string editor(1, '\0'), both(1, '\2'), failing(1, '\1');
  for (const auto& m : session(0, kFuzzDocumentLevel)) editor += frame(m), failing += frame(m);
  const auto a = session(0, kFuzzDocumentLevel), b = session(1, kFuzzDocumentLevel);
  for (size_t i = 0; i < a.size(); ++i) both += frame(a[i]) + frame(b[i]);
  write("document_host", "editor", editor);
  write("document_host", "two_sessions", both);
  write("document_host", "store_fails", failing);
}

void frames() {
  wire::ClientMessage hello;
  hello.set_client_seq(1);
  hello.mutable_hello()->set_protocol_version(1);
  hello.mutable_hello()->set_client_name("fuzz");
  hello.mutable_hello()->set_token("0123456789abcdef");
  std::string client = frame(hello);
  for (const auto& m : session(2, 3)) client += frame(m);
  // Byte 0: chunk size and envelope type; byte 1: maxFrameBytes 16 << 12 = 64 KiB.
  write("frame_decoder", "client_stream", std::string("\x07\x0c", 2) + client);
  write("frame_decoder", "client_bytewise", std::string("\x00\x0c", 2) + client);
  write("frame_decoder", "client_too_large", std::string("\x03\x01", 2) + client);

  std::string server;
  wire::ServerMessage ack;
  ack.mutable_ack()->set_client_seq(4);
  ack.mutable_ack()->set_document_id(1);
  ack.mutable_ack()->set_version(2);
  ack.mutable_ack()->set_edit_id(1);
  server += frame(ack);
  wire::ServerMessage reject;
  reject.mutable_reject()->set_client_seq(5);
  reject.mutable_reject()->set_reason(wire::REJECT_REASON_NOT_FOUND);
  reject.mutable_reject()->set_message("vertex v9:1 does not exist");
  server += frame(reject);
  wire::ServerMessage snapshot;
  snapshot.mutable_snapshot()->set_document_id(1);
  snapshot.mutable_snapshot()->set_version(2);
  auto* region = snapshot.mutable_snapshot()->add_regions();
  region->set_region_id(FaceId(0, 1).packed());
  region->set_draco("TSRG region bytes");
  server += frame(snapshot);
  write("frame_decoder", "server_stream", std::string("\x25\x0c", 2) + server);
}

// Regions of a Catmull-Clark document (the cube as six quads, a level-1
// vertex moved): one per base quad at max level 4, their ids on the quad's
// lattice (flag 8, region_lattice.h), in `codec`'s payload.
void quadRegions(const std::string& target, RegionCodec codec) {
  PolyTopology quads;
  quads.numVertices = 8;
  for (const auto& face : {std::array{0, 3, 2, 1}, std::array{4, 5, 6, 7}, std::array{0, 1, 5, 4},
                           std::array{1, 2, 6, 5}, std::array{2, 3, 7, 6}, std::array{3, 0, 4, 7}})
    quads.addFace(face);
  const std::vector<Vec3> points = creasedCube().positions();
  Document doc = value(
      Document::create(std::move(quads), points, {.maxLevel = 4, .scheme = DocumentScheme::kCatmullClark}),
      "catmull-clark cube");
  const VertexId moved(1, 9);
  value(doc.moveBy(std::span(&moved, 1), Vec3(0.05, 0.1, -0.02)), "offset");
  const QuantizationGrid grid = value(documentGrid(doc), "grid");
  const LodProfile profile{.baseLevel = 1, .maxLevel = 4, .angleThresholdDegrees = 15};
  Tessellation t = value(Tessellation::build(doc, profile), "tessellation");
  int n = 0;
  for (const auto& [id, mesh] : t.regions()) {
    if (n++ == 2) break;
    RegionHeader header{id, 2, 2, profile, grid, true};
    header.codec = codec;
    header.frame = value(regionFrame(doc.hierarchy(), doc.counts(), FaceId::fromPacked(id)), "quad frame");
    write(target, "quad_lattice_" + std::to_string(n), value(encodeRegion(header, mesh), "encode"));
  }
}

// Meshopt regions of shapes a document's regions do not have: a bow tie
// (two triangles on one vertex) beside a lone triangle, with 8-byte ids and
// without, and one triangle at the grid's corners on the coarsest grid the
// decoder takes (1 position bit, 2 normal bits).
void meshoptShapes() {
  RegionMesh bowTie;
  bowTie.positions = {{0, 0, 0},  {1, 0, 0}, {0, 1, 0}, {-1, 0, 0},
                      {0, -1, 0}, {2, 2, 0}, {3, 2, 0}, {2, 3, 0}};
  bowTie.normals.assign(bowTie.positions.size(), Vec3(0, 0, 1));
  for (size_t i = 0; i < bowTie.positions.size(); ++i) bowTie.vertexIds.push_back(VertexId(2, i).packed());
  bowTie.triangles = {{0, 1, 2}, {0, 3, 4}, {5, 6, 7}};
  const QuantizationGrid grid = value(gridFor(Vec3(-1, -1, 0), Vec3(3, 3, 0)), "bow tie grid");
  const LodProfile profile{.baseLevel = 1, .maxLevel = 2, .angleThresholdDegrees = 15};
  RegionHeader header{FaceId(0, 0).packed(), 3, 3, profile, grid, true};
  header.codec = RegionCodec::kMeshopt;
  write("region_meshopt", "bow_tie_ids", value(encodeRegion(header, bowTie), "encode"));
  header.profile.vertexIds = false;
  write("region_meshopt", "bow_tie_noids", value(encodeRegion(header, bowTie), "encode"));

  RegionMesh corner;
  corner.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 1}};
  corner.normals = {Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, 0, -1)};
  corner.vertexIds = {VertexId(0, 0).packed(), VertexId(0, 1).packed(), VertexId(0, 2).packed()};
  corner.triangles = {{0, 1, 2}};
  QuantizationGrid coarse;
  coarse.origin = Vec3(0, 0, 0);
  coarse.range = 1;
  coarse.positionBits = 1;
  coarse.normalBits = 2;
  RegionHeader one{FaceId(0, 1).packed(), 1, 1, profile, coarse, true};
  one.codec = RegionCodec::kMeshopt;
  write("region_meshopt", "one_triangle_coarse", value(encodeRegion(one, corner), "encode"));
}

// Cameras around the creased cube (view_selection): a far and a near one,
// an orthographic one, and refused ones (NaN, zero viewport, tolerance 0).
void views() {
  auto make = [](double ex, double ey, double ez, double tolerance, bool ortho) {
    wire::View v;
    v.mutable_eye()->set_x(ex), v.mutable_eye()->set_y(ey), v.mutable_eye()->set_z(ez);
    v.mutable_forward()->set_x(0.5 - ex), v.mutable_forward()->set_y(0.5 - ey),
        v.mutable_forward()->set_z(0.5 - ez);
    v.mutable_up()->set_y(1);
    v.set_orthographic(ortho);
    v.set_fov_y_radians(0.8);
    v.set_ortho_height(2);
    v.set_near_distance(0.001);
    v.set_width(390);
    v.set_height(844);
    v.set_tolerance_pixels(tolerance);
    return v.SerializeAsString();
  };
  auto prefixed = [](const std::vector<std::string>& views) {
    std::string out;
    for (const std::string& v : views) out += static_cast<char>(v.size()) + v;
    return out;
  };
  write("view_selection", "far_and_near",
        prefixed({make(0.5, 0.5, 4, 1, false), make(1.2, 1.1, 1.3, 1, false)}));
  write("view_selection", "orthographic", prefixed({make(3, 2, 1, 2, true)}));
  wire::View nan;
  nan.ParseFromString(make(0.5, 0.5, 4, 1, false));
  nan.mutable_eye()->set_x(std::nan(""));
  wire::View zero;
  zero.ParseFromString(make(0.5, 0.5, 4, 1, false));
  zero.set_width(0);
  write("view_selection", "refused",
        prefixed({nan.SerializeAsString(), zero.SerializeAsString(), make(0.5, 0.5, 4, 0, false)}));
}

}  // namespace
}  // namespace tessera::fuzz

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s CORPUS_DIR\n", argv[0]);
    return 2;
  }
  tessera::fuzz::root = argv[1];
  tessera::fuzz::documents();
  tessera::fuzz::journals();
  tessera::fuzz::regions("region_decoder", tessera::RegionCodec::kDraco);
  tessera::fuzz::quadRegions("region_decoder", tessera::RegionCodec::kDraco);
  tessera::fuzz::regions("region_meshopt", tessera::RegionCodec::kMeshopt);
  tessera::fuzz::quadRegions("region_meshopt", tessera::RegionCodec::kMeshopt);
  tessera::fuzz::meshoptShapes();
  tessera::fuzz::hostSessions();
  tessera::fuzz::frames();
  tessera::fuzz::views();
  return 0;
}
