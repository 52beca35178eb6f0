#include "core/document/document_file.h"

#include "core/document/edit_codec.h"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/util/byte_io.h"
#include "core/util/crc32.h"

namespace tessera {

namespace {

// PNG-style magic: the CR LF pair reveals text-mode mangling of the file.
constexpr char kMagic[8] = {'T', 'S', 'R', 'D', 'O', 'C', '\r', '\n'};
constexpr size_t kHeaderSize = 8 + 4 + 4 + 8;  // magic, version, reserved, payload size
constexpr size_t kTrailerSize = 4;             // CRC-32 of the payload

// The oldest version that holds the document: Loop documents stay readable
// by builds that know no other scheme.
uint32_t versionFor(const Document& doc) {
  return doc.scheme() == DocumentScheme::kLoop ? 2 : 3;
}

void writeFaces(const BaseTopology& base, ByteWriter& w) {
  w.put<uint32_t>(static_cast<uint32_t>(base.triangles.size()));
  for (const auto& t : base.triangles) {
    for (int k = 0; k < 3; ++k) w.put<uint32_t>(static_cast<uint32_t>(t[k]));
  }
}

void writeFaces(const PolyTopology& base, ByteWriter& w) {
  w.put<uint32_t>(static_cast<uint32_t>(base.numFaces()));
  for (int f = 0; f < base.numFaces(); ++f) {
    w.put<uint32_t>(static_cast<uint32_t>(base.faceOffsets[f + 1] - base.faceOffsets[f]));
    for (int i = base.faceOffsets[f]; i < base.faceOffsets[f + 1]; ++i)
      w.put<uint32_t>(static_cast<uint32_t>(base.indices[i]));
  }
}

template <class Topology>
void writeTags(const Topology& base, ByteWriter& w) {
  w.put<uint32_t>(static_cast<uint32_t>(base.creases.size()));
  for (const auto& c : base.creases) {
    w.put<uint32_t>(static_cast<uint32_t>(c.v0));
    w.put<uint32_t>(static_cast<uint32_t>(c.v1));
    w.put<float>(c.sharpness);
  }
  uint32_t corners = 0;
  for (float s : base.vertexSharpness) corners += s > 0.0f ? 1 : 0;
  w.put<uint32_t>(corners);
  for (size_t v = 0; v < base.vertexSharpness.size(); ++v) {
    if (base.vertexSharpness[v] <= 0.0f) continue;
    w.put<uint32_t>(static_cast<uint32_t>(v));
    w.put<float>(base.vertexSharpness[v]);
  }
}

void writePayload(const Document& doc, ByteWriter& w) {
  const auto& options = doc.options();
  w.put<uint8_t>(options.loop.creaseMethod == CreaseMethod::kUniform ? 0 : 1);
  w.put<uint8_t>(options.loop.boundary == BoundaryInterpolation::kEdgeOnly ? 0 : 1);
  w.put<uint8_t>(static_cast<uint8_t>(options.maxLevel));
  w.put<uint8_t>(static_cast<uint8_t>(options.scheme));

  w.put<uint32_t>(static_cast<uint32_t>(doc.basePoints().size()));
  for (const Vec3& p : doc.basePoints()) {
    for (int k = 0; k < 3; ++k) w.put<double>(p[k]);
  }
  std::visit(
      [&](const auto& base) {
        writeFaces(base, w);
        writeTags(base, w);
      },
      doc.base());

  w.put<uint64_t>(doc.nextEditId());
  w.put<uint32_t>(static_cast<uint32_t>(doc.edits().size()));
  for (const Edit& edit : doc.edits()) writeEdit(edit, w);
}

// Version 3 names each face's corner count; earlier versions hold triangles.
Status readFaces(ByteReader& r, uint32_t version, size_t numPoints, PolyTopology& faces) {
  uint32_t count = 0;
  TESSERA_RETURN_IF_ERROR(r.getCount(count, version >= 3 ? 16 : 12, "face count"));
  for (uint32_t f = 0; f < count; ++f) {
    uint32_t size = 3;
    if (version >= 3) {
      TESSERA_RETURN_IF_ERROR(r.get(size, "a face"));
      if (size < 3 || size > r.remaining() / 4) {
        return parseError(r.source() + ": face " + std::to_string(f) + " has " + std::to_string(size) +
                          " corners");
      }
    }
    for (uint32_t k = 0; k < size; ++k) {
      uint32_t v = 0;
      TESSERA_RETURN_IF_ERROR(r.get(v, "a face"));
      if (v >= numPoints) return parseError(r.source() + ": a face names vertex " + std::to_string(v));
      faces.indices.push_back(static_cast<int>(v));
    }
    faces.faceOffsets.push_back(static_cast<int>(faces.indices.size()));
  }
  return Status::ok();
}

Expected<Document> readPayload(ByteReader& r, uint32_t version) {
  uint8_t crease = 0, boundary = 0, maxLevel = 0, scheme = 0;
  TESSERA_RETURN_IF_ERROR(r.get(crease, "options"));
  TESSERA_RETURN_IF_ERROR(r.get(boundary, "options"));
  TESSERA_RETURN_IF_ERROR(r.get(maxLevel, "options"));
  TESSERA_RETURN_IF_ERROR(r.get(scheme, "options"));
  // Before version 3 this byte was reserved: every such document is Loop.
  if (crease > 1 || boundary > 1 || scheme > (version >= 3 ? 1 : 0))
    return parseError(r.source() + ": bad options");
  DocumentOptions options;
  options.loop.creaseMethod = crease == 0 ? CreaseMethod::kUniform : CreaseMethod::kChaikin;
  options.loop.boundary =
      boundary == 0 ? BoundaryInterpolation::kEdgeOnly : BoundaryInterpolation::kEdgeAndCorner;
  options.maxLevel = maxLevel;
  options.scheme = static_cast<DocumentScheme>(scheme);

  PolyTopology base;
  uint32_t count = 0;
  TESSERA_RETURN_IF_ERROR(r.getCount(count, 24, "vertex count"));
  std::vector<Vec3> points(count);
  for (auto& p : points) {
    for (int k = 0; k < 3; ++k) TESSERA_RETURN_IF_ERROR(r.get(p[k], "a vertex"));
  }
  base.numVertices = static_cast<int>(count);
  TESSERA_RETURN_IF_ERROR(readFaces(r, version, points.size(), base));
  TESSERA_RETURN_IF_ERROR(r.getCount(count, 12, "crease count"));
  for (uint32_t i = 0; i < count; ++i) {
    uint32_t v0 = 0, v1 = 0;
    float s = 0;
    TESSERA_RETURN_IF_ERROR(r.get(v0, "a crease"));
    TESSERA_RETURN_IF_ERROR(r.get(v1, "a crease"));
    TESSERA_RETURN_IF_ERROR(r.get(s, "a crease"));
    if (v0 >= points.size() || v1 >= points.size() || !(s >= 0.0f)) {
      return parseError(r.source() + ": crease " + std::to_string(i) + " is invalid");
    }
    base.creases.push_back({static_cast<int>(v0), static_cast<int>(v1), s});
  }
  TESSERA_RETURN_IF_ERROR(r.getCount(count, 8, "corner count"));
  base.vertexSharpness.assign(points.size(), 0.0f);
  for (uint32_t i = 0; i < count; ++i) {
    uint32_t v = 0;
    float s = 0;
    TESSERA_RETURN_IF_ERROR(r.get(v, "a corner"));
    TESSERA_RETURN_IF_ERROR(r.get(s, "a corner"));
    if (v >= points.size() || !(s >= 0.0f))
      return parseError(r.source() + ": corner " + std::to_string(i) + " is invalid");
    base.vertexSharpness[v] = s;
  }

  uint64_t nextEditId = 0;
  TESSERA_RETURN_IF_ERROR(r.get(nextEditId, "the next edit id"));
  TESSERA_RETURN_IF_ERROR(r.getCount(count, 8 + 1 + 1 + 12, "edit count"));
  std::vector<Edit> edits;
  for (uint32_t i = 0; i < count; ++i) {
    TESSERA_ASSIGN_OR_RETURN(Edit edit, readEdit(r));
    edits.push_back(std::move(edit));
  }
  if (r.remaining() != 0)
    return parseError(r.source() + ": " + std::to_string(r.remaining()) +
                      " unexpected bytes after the edits");
  // A Loop document's faces are checked to be triangles on the way.
  auto doc = Document::restore(std::move(base), std::move(points), options, std::move(edits), nextEditId);
  if (!doc.isOk()) return doc.status().withContext(r.source());
  return doc;
}

}  // namespace

std::string serializeDocument(const Document& document) {
  ByteWriter payload;
  writePayload(document, payload);
  ByteWriter out;
  out.putBytes(std::string(kMagic, sizeof(kMagic)));
  out.put<uint32_t>(versionFor(document));
  out.put<uint32_t>(0);
  out.put<uint64_t>(payload.bytes().size());
  out.putBytes(payload.bytes());
  out.put<uint32_t>(crc32Of(payload.bytes()));
  return std::move(out.bytes());
}

Expected<Document> deserializeDocument(const std::string& bytes, const std::string& source) {
  if (bytes.size() < sizeof(kMagic) || bytes.compare(0, sizeof(kMagic), kMagic, sizeof(kMagic)) != 0) {
    return parseError(source + ": not a Tessera document (bad magic)");
  }
  ByteReader header(bytes.data() + sizeof(kMagic), bytes.size() - sizeof(kMagic), source);
  uint32_t version = 0, reserved = 0;
  uint64_t payloadSize = 0;
  TESSERA_RETURN_IF_ERROR(header.get(version, "the format version"));
  TESSERA_RETURN_IF_ERROR(header.get(reserved, "the header"));
  TESSERA_RETURN_IF_ERROR(header.get(payloadSize, "the payload size"));
  if (version == 0 || version > kDocumentFormatVersion) {
    return unsupported(source + ": document format version " + std::to_string(version) +
                       " is not supported (this build reads 1.." + std::to_string(kDocumentFormatVersion) +
                       ")");
  }
  const size_t held =
      bytes.size() >= kHeaderSize + kTrailerSize ? bytes.size() - kHeaderSize - kTrailerSize : 0;
  if (bytes.size() < kHeaderSize + kTrailerSize || payloadSize != held) {
    return parseError(source + ": truncated or padded: the header announces " + std::to_string(payloadSize) +
                      " payload bytes, the file holds " + std::to_string(held));
  }
  uint32_t stored = 0;
  std::memcpy(&stored, bytes.data() + kHeaderSize + payloadSize, sizeof(stored));
  if (stored != crc32Of(std::string_view(bytes.data() + kHeaderSize, payloadSize))) {
    return parseError(source + ": corrupted (payload checksum mismatch)");
  }
  ByteReader payload(bytes.data() + kHeaderSize, payloadSize, source);
  return readPayload(payload, version);
}

Status saveDocument(const Document& document, const std::string& path) {
  const std::string bytes = serializeDocument(document);
  // Write beside the target and rename, so a crash never leaves half a file.
  const std::string temp = path + ".tmp";
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) return ioError(path + ": cannot open for writing");
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) return ioError(path + ": write failed");
  }
  if (std::rename(temp.c_str(), path.c_str()) != 0) return ioError(path + ": cannot replace the file");
  return Status::ok();
}

Expected<Document> loadDocument(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return notFound(path + ": cannot open the document");
  std::ostringstream data;
  data << in.rdbuf();
  return deserializeDocument(data.str(), path);
}

}  // namespace tessera
