// rt2/io/gltf_compression.cpp — meshopt buffer views and Draco primitives decoded into the
// tinygltf model (rt2/io/gltf_compression.h). The glTF extensions' specifications:
// EXT_meshopt_compression (modes ATTRIBUTES, TRIANGLES, INDICES; filters OCTAHEDRAL,
// QUATERNION, EXPONENTIAL) and KHR_draco_mesh_compression (attributes by Draco unique id,
// dequantized by the decoder). Every range is checked before it is read, every size before
// it is allocated, and the decoders' own failures become messages.
#include "rt2/io/gltf_compression.h"

#include <draco/compression/decode.h>
#include <meshoptimizer.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "rt2/io/text.h"

namespace rt2::io {
namespace {

class Decoder {
 public:
  Decoder(const std::string& path, const GltfDocument& doc, tinygltf::Model& model)
      : path_(path), doc_(doc), model_(model) {}

  void run() {
    for (const MeshoptView& m : doc_.meshopt) meshopt(m);
    for (std::size_t v = 0; v < model_.bufferViews.size(); ++v)
      if (is_fallback(model_.bufferViews[v].buffer) &&
          !model_.bufferViews[v].extensions.count("EXT_meshopt_compression") &&
          !decoded_views_.count(int(v)))
        fail("bufferView " + std::to_string(v) + " reads buffer " +
             std::to_string(model_.bufferViews[v].buffer) +
             ", a meshopt fallback buffer that holds no data");
    for (const DracoPrimitive& d : doc_.draco) draco(d);
  }

 private:
  [[noreturn]] void fail(const std::string& msg) const { error_at(path_, 0, 0, msg); }

  bool is_fallback(int buffer) const {
    return std::find(doc_.fallback_buffers.begin(), doc_.fallback_buffers.end(), buffer) !=
           doc_.fallback_buffers.end();
  }

  // Bytes [offset, offset + length) of buffer `b`, checked.
  std::string_view buffer_bytes(int b, std::size_t offset, std::size_t length,
                                const std::string& at) const {
    if (b < 0 || std::size_t(b) >= model_.buffers.size())
      fail(at + ": buffer " + std::to_string(b) + " does not exist (" +
           std::to_string(model_.buffers.size()) + " buffers)");
    if (is_fallback(b))
      fail(at + ": reads buffer " + std::to_string(b) + ", a fallback buffer with no data");
    const std::vector<unsigned char>& data = model_.buffers[std::size_t(b)].data;
    if (offset > data.size() || length > data.size() - offset)
      fail(at + ": bytes " + std::to_string(offset) + " + " + std::to_string(length) +
           " lie beyond buffer " + std::to_string(b) + " of " + std::to_string(data.size()) +
           " bytes");
    return {reinterpret_cast<const char*>(data.data()) + offset, length};
  }

  // A new buffer holding `bytes`, and a view of all of it; returns the view.
  int add_view(std::vector<unsigned char> bytes, std::size_t stride) {
    tinygltf::Buffer buffer;
    buffer.data = std::move(bytes);
    tinygltf::BufferView view;
    view.buffer = int(model_.buffers.size());
    view.byteOffset = 0;
    view.byteLength = buffer.data.size();
    view.byteStride = stride;
    model_.buffers.push_back(std::move(buffer));
    model_.bufferViews.push_back(view);
    return int(model_.bufferViews.size() - 1);
  }

  // `bytes` more decoded bytes, within kMaxDecodedBytes in all.
  void spend(std::size_t bytes, const std::string& at) {
    if (bytes > kMaxDecodedBytes - decoded_)
      fail(at + ": decodes to more than " + std::to_string(kMaxDecodedBytes >> 20) +
           " MiB of data in all");
    decoded_ += bytes;
  }

  void meshopt(const MeshoptView& m) {
    const int index = m.view;
    const std::string at = "bufferView " + std::to_string(index) + " (EXT_meshopt_compression)";
    if (std::size_t(index) >= model_.bufferViews.size()) fail(at + " does not exist");
    const std::size_t stride = m.stride, count = m.count;
    const std::string& mode = m.mode;
    const std::string& filter = m.filter;
    if (mode == "ATTRIBUTES" ? stride % 4 != 0 || stride > 256 : stride != 2 && stride != 4)
      fail(at + ": byteStride " + std::to_string(stride) + " does not suit mode " + mode);
    if (mode == "TRIANGLES" && count % 3 != 0)
      fail(at + ": count " + std::to_string(count) + " is not a multiple of 3 for TRIANGLES");
    if (filter != "NONE" && mode != "ATTRIBUTES")
      fail(at + ": filter " + filter + " needs mode ATTRIBUTES");
    if ((filter == "OCTAHEDRAL" && stride != 4 && stride != 8) ||
        (filter == "QUATERNION" && stride != 8))
      fail(at + ": byteStride " + std::to_string(stride) + " does not suit filter " + filter);
    if (count > kMaxDecodedBytes / stride)
      fail(at + ": count " + std::to_string(count) + " is too large");
    spend(count * stride, at);
    const std::string_view src = buffer_bytes(m.buffer, m.offset, m.length, at);
    const auto* in = reinterpret_cast<const unsigned char*>(src.data());
    std::vector<unsigned char> out(count * stride);
    int status = 0;
    if (mode == "ATTRIBUTES")
      status = meshopt_decodeVertexBuffer(out.data(), count, stride, in, src.size());
    else if (mode == "TRIANGLES")
      status = meshopt_decodeIndexBuffer(out.data(), count, stride, in, src.size());
    else
      status = meshopt_decodeIndexSequence(out.data(), count, stride, in, src.size());
    if (status != 0)
      fail(at + ": the compressed data is malformed (meshoptimizer: " + std::to_string(status) +
           ")");
    if (filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out.data(), count, stride);
    if (filter == "QUATERNION") meshopt_decodeFilterQuat(out.data(), count, stride);
    if (filter == "EXPONENTIAL") meshopt_decodeFilterExp(out.data(), count, stride);
    // The view keeps its own byteStride (the accessors' layout); its bytes are the decoded ones.
    const std::size_t own_stride = model_.bufferViews[std::size_t(index)].byteStride;
    const int decoded = add_view(std::move(out), own_stride);
    model_.bufferViews[std::size_t(index)] = model_.bufferViews[std::size_t(decoded)];
    decoded_views_.insert(index);
  }

  void draco(const DracoPrimitive& d) {
    tinygltf::Primitive& prim =
        model_.meshes[std::size_t(d.mesh)].primitives[std::size_t(d.primitive)];
    const std::string at = "mesh " + std::to_string(d.mesh) + " primitive " +
                           std::to_string(d.primitive) + " (KHR_draco_mesh_compression)";
    const int view_index = d.view;
    if (view_index < 0 || std::size_t(view_index) >= model_.bufferViews.size())
      fail(at + ": bufferView " + std::to_string(view_index) + " does not exist");
    const tinygltf::BufferView& view = model_.bufferViews[std::size_t(view_index)];
    const std::string_view bytes = buffer_bytes(view.buffer, view.byteOffset, view.byteLength, at);
    if (prim.mode >= 0 && prim.mode != TINYGLTF_MODE_TRIANGLES)
      fail(at + ": mode " + std::to_string(prim.mode) + "; Draco primitives are triangles");
    draco::DecoderBuffer buffer;
    buffer.Init(bytes.data(), bytes.size());
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok())
      fail(at + ": the compressed data is malformed (Draco: " +
           one_line(decoded.status().error_msg_string()) + ")");
    const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    const std::size_t points = mesh->num_points(), faces = mesh->num_faces();

    for (const auto& [name, id] : d.attributes) {
      const auto a = prim.attributes.find(name);
      if (a == prim.attributes.end()) continue;  // compressed but not used by the primitive
      const std::string a_at = at + " " + one_line(name);
      if (a->second < 0 || std::size_t(a->second) >= model_.accessors.size())
        fail(a_at + ": accessor " + std::to_string(a->second) + " does not exist");
      tinygltf::Accessor& acc = model_.accessors[std::size_t(a->second)];
      const draco::PointAttribute* att = mesh->GetAttributeByUniqueId(id);
      if (!att) fail(a_at + ": Draco attribute " + std::to_string(id) + " does not exist");
      const int components = tinygltf::GetNumComponentsInType(std::uint32_t(acc.type));
      if (components < 1 || components > 4)
        fail(a_at + ": accessor " + std::to_string(a->second) + " is not a vector");
      if (acc.count != points)
        fail(a_at + ": accessor " + std::to_string(a->second) + " declares " +
             std::to_string(acc.count) + " elements, the Draco data holds " +
             std::to_string(points));
      spend(points * std::size_t(components) * 4, a_at);
      std::vector<unsigned char> out(points * std::size_t(components) * 4);
      auto* values = reinterpret_cast<float*>(out.data());
      for (std::size_t i = 0; i < points; ++i)
        if (!att->ConvertValue<float>(att->mapped_index(draco::PointIndex(std::uint32_t(i))),
                                      std::int8_t(components),
                                      values + i * std::size_t(components)))
          fail(a_at + ": Draco cannot convert point " + std::to_string(i));
      acc.bufferView = add_view(std::move(out), 0);
      acc.byteOffset = 0;
      acc.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
      acc.normalized = false;
    }

    if (d.indices >= 0 && std::size_t(d.indices) < model_.accessors.size() &&
        model_.accessors[std::size_t(d.indices)].count != faces * 3)
      fail(at + ": accessor " + std::to_string(d.indices) + " declares " +
           std::to_string(model_.accessors[std::size_t(d.indices)].count) +
           " indices, the Draco data holds " + std::to_string(faces * 3));
    spend(faces * 12, at);
    std::vector<unsigned char> out(faces * 12);
    auto* idx = reinterpret_cast<std::uint32_t*>(out.data());
    for (std::size_t f = 0; f < faces; ++f)
      for (int k = 0; k < 3; ++k)
        idx[3 * f + std::size_t(k)] = mesh->face(draco::FaceIndex(std::uint32_t(f)))[k].value();
    tinygltf::Accessor indices;
    indices.bufferView = add_view(std::move(out), 0);
    indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    indices.type = TINYGLTF_TYPE_SCALAR;
    indices.count = faces * 3;
    model_.accessors.push_back(indices);
    prim.indices = int(model_.accessors.size() - 1);
  }

  const std::string& path_;
  const GltfDocument& doc_;
  tinygltf::Model& model_;
  std::size_t decoded_ = 0;
  std::set<int> decoded_views_;
};

}  // namespace

void decode_compressed(const std::string& path, const GltfDocument& doc, tinygltf::Model& model) {
  Decoder(path, doc, model).run();
}

}  // namespace rt2::io
