// Wire compatibility: every published field number, type and enum value of
// protocol/tessera.proto is pinned here, so a renumbering or a type change
// cannot slip through. Adding a field means adding its line here and its
// row in docs/PROTOCOL.md, in the same change.
#include <gtest/gtest.h>

#include <google/protobuf/descriptor.h>

#include <set>
#include <sstream>

#include "protocol/framing.h"
#include "protocol/handshake.h"
#include "protocol/sample_messages.h"
#include "protocol/tessera.pb.h"

namespace tessera {
namespace {

using google::protobuf::Descriptor;
using google::protobuf::EnumDescriptor;
using google::protobuf::FieldDescriptor;

std::string fieldType(const FieldDescriptor& field) {
  if (field.message_type()) return field.message_type()->name();
  if (field.enum_type()) return field.enum_type()->name();
  return field.type_name();
}

// One line per field and per enum value, in declaration order.
std::string describeSchema() {
  const auto* file = wire::ClientMessage::descriptor()->file();
  std::ostringstream out;
  for (int m = 0; m < file->message_type_count(); ++m) {
    const Descriptor& message = *file->message_type(m);
    for (int f = 0; f < message.field_count(); ++f) {
      const FieldDescriptor& field = *message.field(f);
      out << message.name() << "." << field.name() << " = " << field.number() << " "
          << (field.is_repeated() ? "repeated " : "") << fieldType(field);
      if (field.real_containing_oneof()) out << " oneof " << field.real_containing_oneof()->name();
      out << "\n";
    }
  }
  for (int e = 0; e < file->enum_type_count(); ++e) {
    const EnumDescriptor& type = *file->enum_type(e);
    for (int v = 0; v < type.value_count(); ++v) {
      out << type.name() << "." << type.value(v)->name() << " = " << type.value(v)->number() << "\n";
    }
  }
  return out.str();
}

constexpr const char* kPublishedSchema = R"(Vec3.x = 1 double
Vec3.y = 2 double
Vec3.z = 3 double
LodProfile.base_level = 1 uint32
LodProfile.max_level = 2 uint32
LodProfile.angle_threshold_degrees = 3 double
LodProfile.triangle_budget = 4 uint64
LodProfile.fidelity = 5 uint32
LodProfile.omit_vertex_ids = 6 bool
LodProfile.morph_t = 7 double
Selection.vertex_ids = 1 repeated uint64
Selection.edge_ids = 2 repeated uint64
Selection.face_ids = 3 repeated uint64
ClientMessage.client_seq = 1 uint64
ClientMessage.hello = 2 Hello oneof command
ClientMessage.list_documents = 3 ListDocuments oneof command
ClientMessage.create_document = 4 CreateDocument oneof command
ClientMessage.open_document = 5 OpenDocument oneof command
ClientMessage.close_document = 6 CloseDocument oneof command
ClientMessage.delete_document = 7 DeleteDocument oneof command
ClientMessage.subscribe = 8 Subscribe oneof command
ClientMessage.unsubscribe = 9 Unsubscribe oneof command
ClientMessage.move_vertex = 10 MoveVertex oneof command
ClientMessage.set_edge_sharpness = 11 SetEdgeSharpness oneof command
ClientMessage.set_vertex_type = 12 SetVertexType oneof command
ClientMessage.undo = 13 Undo oneof command
ClientMessage.redo = 14 Redo oneof command
ClientMessage.export_document = 15 ExportDocument oneof command
ClientMessage.ping = 16 Ping oneof command
ClientMessage.stats = 17 Stats oneof command
ClientMessage.select = 18 Select oneof command
ClientMessage.grant_token = 19 GrantToken oneof command
ClientMessage.edit_batch = 20 EditBatch oneof command
ClientMessage.set_interpolation = 21 SetInterpolation oneof command
ClientMessage.add_morph_key = 22 AddMorphKey oneof command
ClientMessage.get_morph_control = 23 GetMorphControl oneof command
ClientMessage.set_view = 24 SetView oneof command
ClientMessage.get_cage = 25 GetCage oneof command
Hello.protocol_version = 1 uint32
Hello.client_name = 2 string
Hello.token = 3 string
CreateDocument.name = 1 string
CreateDocument.mesh = 2 bytes
CreateDocument.mesh_format = 3 MeshFormat
CreateDocument.tags = 4 string
CreateDocument.max_level = 5 uint32
CreateDocument.triangulate = 6 bool
CreateDocument.crease_method = 7 CreaseMethod
CreateDocument.boundary = 8 BoundaryInterpolation
CreateDocument.file_name = 9 string
CreateDocument.tags_file_name = 10 string
CreateDocument.drop_unused = 11 bool
CreateDocument.crease_by_angle = 12 bool
CreateDocument.crease_angle = 13 double
CreateDocument.scheme = 14 SubdivisionScheme
OpenDocument.document_id = 1 uint64
OpenDocument.token = 2 string
CloseDocument.document_id = 1 uint64
DeleteDocument.document_id = 1 uint64
Subscribe.document_id = 1 uint64
Subscribe.profile = 2 LodProfile
Subscribe.with_commands = 3 bool
Subscribe.view = 4 View
Subscribe.codec = 5 RegionCodec
View.eye = 1 Vec3
View.forward = 2 Vec3
View.up = 3 Vec3
View.orthographic = 4 bool
View.fov_y_radians = 5 double
View.ortho_height = 6 double
View.near_distance = 7 double
View.width = 8 uint32
View.height = 9 uint32
View.tolerance_pixels = 10 double
SetView.document_id = 1 uint64
SetView.view = 2 View
Unsubscribe.document_id = 1 uint64
MoveVertex.document_id = 1 uint64
MoveVertex.vertex_ids = 2 repeated uint64
MoveVertex.target = 3 Vec3
MoveVertex.mode = 4 MoveMode
MoveVertex.key = 5 uint32
SetEdgeSharpness.document_id = 1 uint64
SetEdgeSharpness.edge_id = 2 uint64
SetEdgeSharpness.sharpness = 3 float
SetEdgeSharpness.end_vertex_ids = 4 repeated uint64
SetEdgeSharpness.key = 5 uint32
SetVertexType.document_id = 1 uint64
SetVertexType.vertex_id = 2 uint64
SetVertexType.type = 3 VertexType oneof value
SetVertexType.sharpness = 4 float oneof value
SetVertexType.key = 5 uint32
SetInterpolation.document_id = 1 uint64
SetInterpolation.vertex_id = 2 uint64
SetInterpolation.interpolating = 3 bool
SetInterpolation.tension = 4 double
SetInterpolation.tangent = 5 Vec3
SetInterpolation.key = 6 uint32
Undo.document_id = 1 uint64
Undo.edit_id = 2 uint64
Undo.key = 3 uint32
Redo.document_id = 1 uint64
Redo.edit_id = 2 uint64
Redo.key = 3 uint32
AddMorphKey.document_id = 1 uint64
AddMorphKey.mesh = 2 bytes
AddMorphKey.mesh_format = 3 MeshFormat
AddMorphKey.file_name = 4 string
AddMorphKey.image_from = 5 bytes
AddMorphKey.image_to = 6 bytes
GetMorphControl.document_id = 1 uint64
GetMorphControl.t = 2 double
GetMorphControl.with_topology = 3 bool
EditCommand.move_vertex = 1 MoveVertex oneof command
EditCommand.set_edge_sharpness = 2 SetEdgeSharpness oneof command
EditCommand.set_vertex_type = 3 SetVertexType oneof command
EditCommand.undo = 4 Undo oneof command
EditCommand.redo = 5 Redo oneof command
EditCommand.set_interpolation = 6 SetInterpolation oneof command
EditBatch.document_id = 1 uint64
EditBatch.commands = 2 repeated EditCommand
ExportDocument.document_id = 1 uint64
ExportDocument.level = 2 uint32
ExportDocument.limit = 3 bool
ExportDocument.draco = 4 bool
GetCage.document_id = 1 uint64
GetCage.level = 2 uint32
Select.document_id = 1 uint64
Select.selection = 2 Selection
GrantToken.document_id = 1 uint64
GrantToken.role = 2 Role
GrantToken.token = 3 string
ServerMessage.hello_ack = 1 HelloAck oneof body
ServerMessage.ack = 2 Ack oneof body
ServerMessage.reject = 3 Reject oneof body
ServerMessage.snapshot = 4 Snapshot oneof body
ServerMessage.delta = 5 Delta oneof body
ServerMessage.presence = 6 Presence oneof body
ServerMessage.error = 7 Error oneof body
ServerMessage.document_list = 8 DocumentList oneof body
ServerMessage.export_result = 9 ExportResult oneof body
ServerMessage.pong = 10 Pong oneof body
ServerMessage.stats_reply = 11 StatsReply oneof body
ServerMessage.applied_command = 12 AppliedCommand oneof body
ServerMessage.morph_control = 13 MorphControl oneof body
ServerMessage.cage = 14 Cage oneof body
HelloAck.client_seq = 1 uint64
HelloAck.protocol_version = 2 uint32
HelloAck.server_version = 3 string
HelloAck.session_id = 4 uint64
HelloAck.role = 5 Role
HelloAck.max_frame_bytes = 6 uint32
Ack.client_seq = 1 uint64
Ack.document_id = 2 uint64
Ack.version = 3 uint64
Ack.edit_id = 4 uint64
Ack.edit_ids = 5 repeated uint64
Ack.dropped_vertices = 6 uint32
Ack.creased_edges = 7 uint32
Ack.scheme = 8 SubdivisionScheme
Reject.client_seq = 1 uint64
Reject.reason = 2 RejectReason
Reject.message = 3 string
Reject.batch_index = 4 uint32
Region.region_id = 1 uint64
Region.draco = 2 bytes
Snapshot.document_id = 1 uint64
Snapshot.version = 2 uint64
Snapshot.profile = 3 LodProfile
Snapshot.regions = 4 repeated Region
Snapshot.remaining_parts = 5 uint32
Snapshot.resync = 6 bool
Snapshot.surface_hash = 7 uint64
Delta.document_id = 1 uint64
Delta.from_version = 2 uint64
Delta.to_version = 3 uint64
Delta.regions = 4 repeated Region
Delta.removed_region_ids = 5 repeated uint64
Delta.author_session_id = 6 uint64
Delta.edit_id = 7 uint64
Delta.surface_hash = 8 uint64
Delta.view_complete = 9 bool
Delta.view_seq = 10 uint64
Participant.session_id = 1 uint64
Participant.name = 2 string
Participant.role = 3 Role
Participant.selection = 4 Selection
Presence.document_id = 1 uint64
Presence.participants = 2 repeated Participant
Presence.full = 3 bool
Presence.left_session_ids = 4 repeated uint64
Error.code = 1 ErrorCode
Error.message = 2 string
Error.fatal = 3 bool
DocumentInfo.document_id = 1 uint64
DocumentInfo.name = 2 string
DocumentInfo.version = 3 uint64
DocumentInfo.max_level = 4 uint32
DocumentList.client_seq = 1 uint64
DocumentList.documents = 2 repeated DocumentInfo
ExportResult.client_seq = 1 uint64
ExportResult.document_id = 2 uint64
ExportResult.version = 3 uint64
ExportResult.glb = 4 bytes
MorphControl.client_seq = 1 uint64
MorphControl.document_id = 2 uint64
MorphControl.version = 3 uint64
MorphControl.t = 4 double
MorphControl.points = 5 repeated float
MorphControl.triangles = 6 repeated uint32
MorphControl.crease_vertices = 7 repeated uint32
MorphControl.crease_sharpness = 8 repeated float
MorphControl.vertex_sharpness = 9 repeated float
MorphControl.crease_method = 10 CreaseMethod
MorphControl.boundary = 11 BoundaryInterpolation
MorphControl.max_level = 12 uint32
MorphControl.image_from = 13 bytes
MorphControl.image_to = 14 bytes
Cage.client_seq = 1 uint64
Cage.document_id = 2 uint64
Cage.version = 3 uint64
Cage.level = 4 uint32
Cage.face_sizes = 5 repeated uint32
Cage.vertices = 6 repeated uint64
Pong.client_seq = 1 uint64
Pong.server_time_unix_ms = 2 uint64
Stat.name = 1 string
Stat.value = 2 double
StatsReply.client_seq = 1 uint64
StatsReply.stats = 2 repeated Stat
AppliedCommand.document_id = 1 uint64
AppliedCommand.version = 2 uint64
AppliedCommand.edit_id = 3 uint64
AppliedCommand.author_session_id = 4 uint64
AppliedCommand.author_name = 5 string
AppliedCommand.server_time_unix_ms = 6 uint64
AppliedCommand.move_vertex = 7 MoveVertex oneof command
AppliedCommand.set_edge_sharpness = 8 SetEdgeSharpness oneof command
AppliedCommand.set_vertex_type = 9 SetVertexType oneof command
AppliedCommand.undo = 10 Undo oneof command
AppliedCommand.redo = 11 Redo oneof command
AppliedCommand.edit_batch = 12 EditBatch oneof command
AppliedCommand.set_interpolation = 14 SetInterpolation oneof command
AppliedCommand.add_morph_key = 15 AddMorphKey oneof command
AppliedCommand.edit_ids = 13 repeated uint64
Role.ROLE_UNSPECIFIED = 0
Role.ROLE_VIEWER = 1
Role.ROLE_EDITOR = 2
Role.ROLE_ADMIN = 3
MeshFormat.MESH_FORMAT_UNSPECIFIED = 0
MeshFormat.MESH_FORMAT_OBJ = 1
MeshFormat.MESH_FORMAT_OFF = 2
MeshFormat.MESH_FORMAT_PLY = 3
MeshFormat.MESH_FORMAT_STL = 4
MeshFormat.MESH_FORMAT_GLB = 5
MeshFormat.MESH_FORMAT_USDA = 6
CreaseMethod.CREASE_METHOD_UNSPECIFIED = 0
CreaseMethod.CREASE_METHOD_UNIFORM = 1
CreaseMethod.CREASE_METHOD_CHAIKIN = 2
BoundaryInterpolation.BOUNDARY_INTERPOLATION_UNSPECIFIED = 0
BoundaryInterpolation.BOUNDARY_INTERPOLATION_EDGE_ONLY = 1
BoundaryInterpolation.BOUNDARY_INTERPOLATION_EDGE_AND_CORNER = 2
SubdivisionScheme.SUBDIVISION_SCHEME_UNSPECIFIED = 0
SubdivisionScheme.SUBDIVISION_SCHEME_LOOP = 1
SubdivisionScheme.SUBDIVISION_SCHEME_CATMULL_CLARK = 2
RegionCodec.REGION_CODEC_UNSPECIFIED = 0
RegionCodec.REGION_CODEC_DRACO = 1
RegionCodec.REGION_CODEC_MESHOPT = 2
MoveMode.MOVE_MODE_UNSPECIFIED = 0
MoveMode.MOVE_MODE_DIRECT_MANIPULATION = 1
MoveMode.MOVE_MODE_OFFSET = 2
VertexType.VERTEX_TYPE_UNSPECIFIED = 0
VertexType.VERTEX_TYPE_SMOOTH = 1
VertexType.VERTEX_TYPE_CUSP = 2
VertexType.VERTEX_TYPE_CORNER = 3
RejectReason.REJECT_REASON_UNSPECIFIED = 0
RejectReason.REJECT_REASON_INVALID_ARGUMENT = 1
RejectReason.REJECT_REASON_NOT_FOUND = 2
RejectReason.REJECT_REASON_NOT_AUTHENTICATED = 3
RejectReason.REJECT_REASON_PERMISSION_DENIED = 4
RejectReason.REJECT_REASON_NOT_OPEN = 5
RejectReason.REJECT_REASON_INVALID_MESH = 6
RejectReason.REJECT_REASON_LIMIT_EXCEEDED = 7
RejectReason.REJECT_REASON_RATE_LIMITED = 8
RejectReason.REJECT_REASON_INVALID_STATE = 9
RejectReason.REJECT_REASON_UNKNOWN_COMMAND = 10
RejectReason.REJECT_REASON_INTERNAL = 11
ErrorCode.ERROR_CODE_UNSPECIFIED = 0
ErrorCode.ERROR_CODE_VERSION_MISMATCH = 1
ErrorCode.ERROR_CODE_BAD_HANDSHAKE = 2
ErrorCode.ERROR_CODE_AUTH_FAILED = 3
ErrorCode.ERROR_CODE_FRAME_TOO_LARGE = 4
ErrorCode.ERROR_CODE_MALFORMED_FRAME = 5
ErrorCode.ERROR_CODE_TIMEOUT = 6
ErrorCode.ERROR_CODE_TOO_MANY_CONNECTIONS = 7
ErrorCode.ERROR_CODE_SHUTTING_DOWN = 8
ErrorCode.ERROR_CODE_INTERNAL = 9
)";

TEST(ProtocolWireSchema, FieldNumbersAndTypesArePinned) {
  EXPECT_EQ(describeSchema(), kPublishedSchema) << "the schema changed; the full description now is:\n"
                                                << describeSchema();
}

TEST(ProtocolWireSchema, PackageAndEnvelopes) {
  EXPECT_EQ(wire::ClientMessage::descriptor()->full_name(), "tessera.wire.ClientMessage");
  EXPECT_EQ(wire::ServerMessage::descriptor()->full_name(), "tessera.wire.ServerMessage");
  EXPECT_EQ(kProtocolVersion, 1u);
  EXPECT_EQ(kDefaultMaxFrameBytes, 16u * 1024 * 1024);
}

// The samples the round-trip and fuzz tests use must cover every command and
// every reply, so a new message cannot skip them.
template <typename Envelope>
void expectEveryCaseSampled(const std::vector<Envelope>& samples) {
  const auto* oneof = Envelope::descriptor()->oneof_decl(0);
  std::set<int> sampled;
  for (const Envelope& sample : samples) {
    const auto* reflection = sample.GetReflection();
    const auto* field = reflection->GetOneofFieldDescriptor(sample, oneof);
    ASSERT_NE(field, nullptr) << sample.DebugString();
    sampled.insert(field->number());
  }
  for (int i = 0; i < oneof->field_count(); ++i) {
    EXPECT_TRUE(sampled.count(oneof->field(i)->number())) << "no sample of " << oneof->field(i)->name();
  }
}

TEST(ProtocolWireSchema, SamplesCoverEveryMessage) {
  expectEveryCaseSampled(testing::sampleClientMessages());
  expectEveryCaseSampled(testing::sampleServerMessages());
}

// The exact bytes of a small Hello, as docs/PROTOCOL.md shows them to
// implementers in other languages.
TEST(ProtocolWireSchema, GoldenHelloFrame) {
  auto frame = encodeFrame(makeHello({.clientSeq = 1, .clientName = "cli"}));
  ASSERT_TRUE(frame.isOk());
  const std::string expected(
      "\x00\x00\x00\x0b\x08\x01\x12\x07\x08\x01\x12\x03"
      "cli",
      15);
  EXPECT_EQ(*frame, expected);
}

}  // namespace
}  // namespace tessera
