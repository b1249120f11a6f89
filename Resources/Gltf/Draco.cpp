// KHR_draco_mesh_compression: a primitive's compressed mesh decoded by Draco into the accessors it stands for.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>

#include <draco/compression/decode.h>

#include "Resources/Gltf/Codecs.hpp"

namespace sr::gltf {

namespace {

// The values of one Draco attribute, point by point, as `components` values of type T each.
template <class T>
bool convertAll(const draco::PointAttribute& att, std::size_t points, int components, std::vector<unsigned char>& out) {
    out.resize(points * std::size_t(components) * sizeof(T));
    T value[16];
    for (std::size_t i = 0; i < points; ++i) {
        if (!att.ConvertValue<T>(att.mapped_index(draco::PointIndex(std::uint32_t(i))), std::int8_t(components), value)) return false;
        std::memcpy(out.data() + i * std::size_t(components) * sizeof(T), value, std::size_t(components) * sizeof(T));
    }
    return true;
}

} // namespace

Status decodeDracoPrimitive(const Document& doc, const Primitive& prim, const Json& ext, Accessors& accessors, const std::string& what) {
    const std::string name = what + " (KHR_draco_mesh_compression)";
    if (!ext.is_object()) return Status::failure(name + ": the extension must be an object");
    const auto bv = ext.find("bufferView");
    const auto attributes = ext.find("attributes");
    if (bv == ext.end() || !bv->is_number_integer() || attributes == ext.end() || !attributes->is_object())
        return Status::failure(name + ": needs a bufferView and an attributes object");
    std::size_t offset = 0, length = 0;
    auto bytes = accessors.bufferViewBytes(bv->get<int>(), offset, length);
    if (!bytes) return Status::failure(name + ": " + bytes.error());

    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(bytes.value()->data() + offset), length);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) return Status::failure(name + ": the Draco stream cannot be decoded (" + decoded.status().error_msg_string() + ")");
    const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    if (!mesh) return Status::failure(name + ": the Draco stream holds no mesh");
    const std::size_t points = mesh->num_points();

    // The attributes: each accessor of the primitive that Draco holds, in that accessor's type.
    for (auto it = attributes->begin(); it != attributes->end(); ++it) {
        const auto accessor = prim.attributes.find(it.key());
        if (accessor == prim.attributes.end()) continue; // Draco holds more than the primitive reads
        if (!it.value().is_number_integer() || it.value().get<long long>() < 0)
            return Status::failure(name + ": attribute " + it.key() + " needs a Draco attribute id");
        const draco::PointAttribute* att = mesh->GetAttributeByUniqueId(std::uint32_t(it.value().get<long long>()));
        if (!att) return Status::failure(name + ": the Draco stream has no attribute " + std::to_string(it.value().get<long long>()) + " (" + it.key() + ")");
        const int index = accessor->second;
        if (index < 0 || std::size_t(index) >= doc.accessors.size())
            return Status::failure(name + ": " + it.key() + ": accessor " + std::to_string(index) + " does not exist");
        const Accessor& a = doc.accessors[std::size_t(index)];
        const int components = componentCount(a.type);
        if (components < 1 || components > 4) return Status::failure(name + ": " + it.key() + " must be a scalar or a vector");
        if (a.count != points)
            return Status::failure(name + ": " + it.key() + ": the accessor counts " + std::to_string(a.count) + " elements, the Draco stream " +
                                   std::to_string(points) + " points");
        std::vector<unsigned char> out;
        bool ok;
        switch (a.componentType) {
        case kFloat: ok = convertAll<float>(*att, points, components, out); break;
        case kByte: ok = convertAll<std::int8_t>(*att, points, components, out); break;
        case kUnsignedByte: ok = convertAll<std::uint8_t>(*att, points, components, out); break;
        case kShort: ok = convertAll<std::int16_t>(*att, points, components, out); break;
        case kUnsignedShort: ok = convertAll<std::uint16_t>(*att, points, components, out); break;
        case kUnsignedInt: ok = convertAll<std::uint32_t>(*att, points, components, out); break;
        default: return Status::failure(name + ": " + it.key() + ": unknown component type");
        }
        if (!ok) return Status::failure(name + ": " + it.key() + ": the Draco values cannot be converted to the accessor's type");
        if (a.componentType == kFloat)
            for (std::size_t k = 0; k + 4 <= out.size(); k += 4) {
                float f;
                std::memcpy(&f, out.data() + k, 4);
                if (!std::isfinite(f)) return Status::failure(name + ": " + it.key() + ": a decoded value is not finite");
            }
        accessors.provide(index, std::move(out));
    }
    // The indices: three per face, in the indices accessor's type.
    if (prim.indices >= 0) {
        if (std::size_t(prim.indices) >= doc.accessors.size())
            return Status::failure(name + ": indices: accessor " + std::to_string(prim.indices) + " does not exist");
        const Accessor& a = doc.accessors[std::size_t(prim.indices)];
        const std::size_t faces = mesh->num_faces();
        if (a.count != faces * 3)
            return Status::failure(name + ": indices: the accessor counts " + std::to_string(a.count) + ", the Draco stream " +
                                   std::to_string(faces) + " triangles");
        const int size = componentSize(a.componentType);
        if (a.componentType != kUnsignedByte && a.componentType != kUnsignedShort && a.componentType != kUnsignedInt)
            return Status::failure(name + ": indices must be unsigned byte, short or int");
        std::vector<unsigned char> out(faces * 3 * std::size_t(size));
        const std::uint32_t limit = size == 1 ? 0xFFu : size == 2 ? 0xFFFFu : 0xFFFFFFFFu;
        for (std::size_t f = 0; f < faces; ++f) {
            const draco::Mesh::Face& face = mesh->face(draco::FaceIndex(std::uint32_t(f)));
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t v = face[k].value();
                if (v > limit) return Status::failure(name + ": an index does not fit the indices accessor's type");
                std::memcpy(out.data() + (f * 3 + std::size_t(k)) * std::size_t(size), &v, std::size_t(size)); // little-endian
            }
        }
        accessors.provide(prim.indices, std::move(out));
    }
    return success();
}

} // namespace sr::gltf
