// proto3 binary encoding and decoding driven by protobufjs's reflection
// (the Types that protobuf.parse builds from protocol/tessera.proto), with
// its Reader and Writer for the primitive encodings.
//
// Why not protobufjs's own encode/decode: it generates them with
// Function(source) at run time, which the server's Content-Security-Policy
// (script-src 'self' 'wasm-unsafe-eval', docs/PROTOCOL.md 1.2) rightly
// forbids. Walking the reflected fields needs no eval.
//
// Decoded messages are plain objects holding every field of their type
// (proto3 defaults for the unset ones: 0, a zero Long for 64-bit fields,
// '', an empty Uint8Array, [], false, null for messages), and for each oneof
// the name of its set member under the oneof's name (message.body ===
// 'snapshot'), or null. Members of a oneof that are not set, and unset
// proto3 `optional` fields, are left undefined.
import protobuf from 'protobufjs';
import Long from 'long';

const { basic, packed, long: longTypes } = protobuf.types;
const LENGTH_DELIMITED = 2;

function isLongType(type) {
  return longTypes[type] !== undefined;
}

function defaultOf(field) {
  if (field.repeated) return [];
  if (field.resolvedType instanceof protobuf.Enum) return 0;
  if (field.resolvedType) return null;
  switch (field.type) {
    case 'string': return '';
    case 'bytes': return new Uint8Array(0);
    case 'bool': return false;
    default: return isLongType(field.type) ? Long.fromInt(0, field.type.startsWith('u') || field.type === 'fixed64') : 0;
  }
}

// A 64-bit value as protobufjs's writer takes it (a Long or a number).
function toWritableLong(value, type) {
  if (typeof value === 'bigint') {
    const unsigned = type === 'uint64' || type === 'fixed64';
    return Long.fromString((unsigned ? BigInt.asUintN(64, value) : BigInt.asIntN(64, value)).toString(), unsigned);
  }
  return value;
}

function isDefault(field, value) {
  if (value === undefined || value === null) return true;
  if (field.partOf) return false; // a oneof member or optional: set means sent
  if (field.repeated) return value.length === 0;
  if (field.resolvedType && !(field.resolvedType instanceof protobuf.Enum)) return false;
  if (typeof value === 'bigint') return value === 0n;
  if (Long.isLong(value)) return value.isZero();
  if (typeof value === 'string') return value === '';
  if (value instanceof Uint8Array) return value.length === 0;
  return value === 0 || value === false ? !Object.is(value, -0) : false;
}

function writeScalar(writer, type, value) {
  writer[type](isLongType(type) ? toWritableLong(value, type) : value);
}

// Writes `object` (plain fields by schema name) as `type` into `writer`.
function encodeInto(type, object, writer) {
  for (const name of Object.keys(object)) {
    if (!type.fields[name] && !type.oneofs?.[name]) throw new Error(`${type.fullName} has no field ${name}`);
  }
  for (const field of type.fieldsArray.slice().sort((a, b) => a.id - b.id)) {
    const value = object[field.name];
    if (isDefault(field, value)) continue;
    const message = field.resolvedType && !(field.resolvedType instanceof protobuf.Enum) ? field.resolvedType : null;
    const scalar = field.resolvedType instanceof protobuf.Enum ? 'int32' : field.type;
    if (field.repeated) {
      if (message) {
        for (const v of value) encodeInto(message, v, writer.uint32((field.id << 3) | LENGTH_DELIMITED).fork()).ldelim();
      } else if (packed[scalar] !== undefined) {
        writer.uint32((field.id << 3) | LENGTH_DELIMITED).fork();
        for (const v of value) writeScalar(writer, scalar, v);
        writer.ldelim();
      } else {
        for (const v of value) writeScalar(writer.uint32((field.id << 3) | basic[scalar]), scalar, v);
      }
    } else if (message) {
      encodeInto(message, value, writer.uint32((field.id << 3) | LENGTH_DELIMITED).fork()).ldelim();
    } else {
      writeScalar(writer.uint32((field.id << 3) | basic[scalar]), scalar, value);
    }
  }
  return writer;
}

export function encodeMessage(type, object) {
  return encodeInto(type, object, protobuf.Writer.create()).finish();
}

function readScalar(reader, type) {
  return reader[type]();
}

function decodeFrom(type, reader, end) {
  const out = {};
  for (const field of type.fieldsArray) if (!field.partOf) out[field.name] = defaultOf(field);
  for (const oneof of type.oneofsArray) if (!oneof.name.startsWith('_')) out[oneof.name] = null;
  while (reader.pos < end) {
    const tag = reader.uint32();
    const id = tag >>> 3, wireType = tag & 7;
    const field = type.fieldsById[id];
    if (!field) {
      reader.skipType(wireType); // unknown fields are kept by nobody here: ignored (10)
      continue;
    }
    const message = field.resolvedType && !(field.resolvedType instanceof protobuf.Enum) ? field.resolvedType : null;
    const scalar = field.resolvedType instanceof protobuf.Enum ? 'int32' : field.type;
    let value;
    if (message) {
      const length = reader.uint32();
      value = decodeFrom(message, reader, reader.pos + length);
    } else if (field.repeated && wireType === LENGTH_DELIMITED && packed[scalar] !== undefined) {
      const length = reader.uint32();
      const stop = reader.pos + length;
      while (reader.pos < stop) out[field.name].push(readScalar(reader, scalar));
      continue;
    } else {
      if (wireType !== basic[scalar]) throw new Error(`${type.fullName}.${field.name}: wire type ${wireType}, expected ${basic[scalar]}`);
      value = readScalar(reader, scalar);
    }
    if (field.repeated) {
      out[field.name].push(value);
    } else {
      out[field.name] = value;
      if (field.partOf && !field.partOf.name.startsWith('_')) out[field.partOf.name] = field.name;
    }
  }
  if (reader.pos !== end) throw new Error(`${type.fullName}: a field runs past the end of its message`);
  return out;
}

export function decodeMessage(type, bytes) {
  const reader = protobuf.Reader.create(bytes);
  return decodeFrom(type, reader, bytes.length);
}
