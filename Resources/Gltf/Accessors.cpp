// gltf::Accessors: views into buffers, checked so that no element is read outside them; sparse and bufferView-less accessors built once.
#include "Resources/Gltf/Accessors.hpp"

#include <algorithm>
#include <cstring>

#include "Resources/Gltf/Codecs.hpp"

namespace sr::gltf {

float readFloat(const View& v, std::size_t i, int c) {
    const unsigned char* p = v.base + i * v.stride;
    switch (v.componentType) {
    case kFloat: {
        float f;
        std::memcpy(&f, p + 4 * c, 4);
        return f;
    }
    case kUnsignedByte: return v.normalized ? float(p[c]) / 255.0f : float(p[c]);
    case kUnsignedShort: {
        std::uint16_t s;
        std::memcpy(&s, p + 2 * c, 2);
        return v.normalized ? float(s) / 65535.0f : float(s);
    }
    case kByte: {
        const float f = float(std::int8_t(p[c]));
        return v.normalized ? std::max(f / 127.0f, -1.0f) : f;
    }
    case kShort: {
        std::int16_t s;
        std::memcpy(&s, p + 2 * c, 2);
        return v.normalized ? std::max(float(s) / 32767.0f, -1.0f) : float(s);
    }
    case kUnsignedInt: {
        std::uint32_t u;
        std::memcpy(&u, p + 4 * c, 4);
        return float(u);
    }
    default: return 0.0f;
    }
}

std::uint32_t readIndex(const View& v, std::size_t i) {
    const unsigned char* p = v.base + i * v.stride;
    switch (v.componentType) {
    case kUnsignedByte: return p[0];
    case kUnsignedShort: {
        std::uint16_t s;
        std::memcpy(&s, p, 2);
        return s;
    }
    default: {
        std::uint32_t u;
        std::memcpy(&u, p, 4);
        return u;
    }
    }
}

std::uint32_t readIndexComponent(const View& v, std::size_t i, int c) {
    const unsigned char* p = v.base + i * v.stride;
    if (v.componentType == kUnsignedByte) return p[c];
    std::uint16_t s;
    std::memcpy(&s, p + 2 * c, 2);
    return s;
}

void Accessors::provide(int index, std::vector<unsigned char> bytes) { provided_[index] = std::move(bytes); }

Result<const std::vector<unsigned char>*> Accessors::bufferViewBytes(int index, std::size_t& offset, std::size_t& length) {
    using R = Result<const std::vector<unsigned char>*>;
    if (index < 0 || std::size_t(index) >= doc_.bufferViews.size())
        return R::failure("buffer view " + std::to_string(index) + " does not exist");
    const BufferView& bv = doc_.bufferViews[std::size_t(index)];
    const std::string name = "buffer view " + std::to_string(index);
    // A compressed view: its elements are what the decoder gives (once per file).
    for (const char* ext : {"EXT_meshopt_compression", "KHR_meshopt_compression"}) {
        const auto e = bv.extensions.find(ext);
        if (e == bv.extensions.end()) continue;
        auto& slot = decodedViews_[index];
        if (!slot) {
            auto decoded = decodeMeshoptView(doc_, *e, name + " (" + ext + ")");
            if (!decoded) return R::failure(decoded.error());
            slot = std::make_shared<std::vector<unsigned char>>(std::move(decoded).value());
        }
        offset = 0;
        length = slot->size();
        return R(slot.get());
    }
    if (bv.buffer < 0 || std::size_t(bv.buffer) >= doc_.buffers.size())
        return R::failure(name + ": buffer " + std::to_string(bv.buffer) + " does not exist");
    const Buffer& buffer = doc_.buffers[std::size_t(bv.buffer)];
    if (buffer.data.empty() && bv.byteLength > 0) return R::failure(name + " reads " + buffer.source);
    // Sizes are checked in a way that cannot overflow: every term is bounded first.
    if (bv.byteOffset > buffer.data.size() || bv.byteLength > buffer.data.size() - bv.byteOffset)
        return R::failure(name + " lies outside its buffer (" + std::to_string(buffer.data.size()) + " bytes)");
    offset = bv.byteOffset;
    length = bv.byteLength;
    return R(&buffer.data);
}

Result<View> Accessors::view(int index, const std::string& what) {
    using RV = Result<View>;
    if (index < 0 || std::size_t(index) >= doc_.accessors.size())
        return RV::failure(what + ": accessor " + std::to_string(index) + " does not exist");
    const Accessor& a = doc_.accessors[std::size_t(index)];
    const std::string name = what + " (accessor " + std::to_string(index) + ")";
    View v;
    v.componentType = a.componentType;
    v.components = componentCount(a.type);
    v.normalized = a.normalized;
    v.count = a.count;
    const int csize = componentSize(a.componentType);
    if (csize == 0 || v.components == 0) return RV::failure(name + ": unknown component or element type");
    const std::size_t element = std::size_t(csize) * std::size_t(v.components);
    if (a.count > (std::size_t(1) << 32) / element) return RV::failure(name + ": " + std::to_string(a.count) + " elements is too many");
    if (const auto p = provided_.find(index); p != provided_.end()) { // decoded by Draco
        if (p->second.size() != element * a.count)
            return RV::failure(name + ": the decoded attribute has " + std::to_string(p->second.size() / element) + " elements, the accessor " +
                               std::to_string(a.count));
        v.base = p->second.data();
        v.stride = element;
        return RV(v);
    }
    if (v.count == 0) return RV(v);
    if (a.bufferView >= 0) {
        std::size_t offset = 0, span = 0;
        auto bytes = bufferViewBytes(a.bufferView, offset, span);
        if (!bytes) return RV::failure(name + ": " + bytes.error());
        const BufferView& bv = doc_.bufferViews[std::size_t(a.bufferView)];
        v.stride = bv.byteStride ? bv.byteStride : element;
        if (v.stride < element || v.stride > 252)
            return RV::failure(name + ": byte stride " + std::to_string(v.stride) + " is invalid for " + std::to_string(element) +
                               "-byte elements");
        if (a.byteOffset > span || v.count > (span - a.byteOffset) / v.stride + 1 ||
            (v.count - 1) * v.stride + element > span - a.byteOffset)
            return RV::failure(name + ": " + std::to_string(v.count) + " elements do not fit in buffer view " +
                               std::to_string(a.bufferView) + " (" + std::to_string(span) + " bytes)");
        v.base = bytes.value()->data() + offset + a.byteOffset;
        if (a.sparse.count == 0) return RV(v);
    }
    // Sparse, or no buffer view: the elements (zeros without a view) copied tightly packed,
    // then the sparse values written over those at the sparse indices.
    auto found = owned_.find(index);
    if (found == owned_.end()) {
        std::vector<unsigned char> bytes(element * a.count, 0);
        if (v.base)
            for (std::size_t i = 0; i < a.count; ++i) std::memcpy(bytes.data() + i * element, v.base + i * v.stride, element);
        if (a.sparse.count > 0) {
            const Accessor::Sparse& s = a.sparse;
            if (s.count > a.count)
                return RV::failure(name + ": sparse.count " + std::to_string(s.count) + " is more than the accessor's count");
            const int isize = componentSize(s.indicesComponentType);
            if (s.indicesComponentType != kUnsignedByte && s.indicesComponentType != kUnsignedShort && s.indicesComponentType != kUnsignedInt)
                return RV::failure(name + ": sparse.indices must be unsigned byte, short or int");
            std::size_t io = 0, il = 0, vo = 0, vl = 0;
            auto ib = bufferViewBytes(s.indicesBufferView, io, il);
            if (!ib) return RV::failure(name + " sparse.indices: " + ib.error());
            if (s.indicesByteOffset > il || s.count > (il - s.indicesByteOffset) / std::size_t(isize))
                return RV::failure(name + ": sparse.indices do not fit in buffer view " + std::to_string(s.indicesBufferView));
            auto vb = bufferViewBytes(s.valuesBufferView, vo, vl);
            if (!vb) return RV::failure(name + " sparse.values: " + vb.error());
            if (s.valuesByteOffset > vl || s.count > (vl - s.valuesByteOffset) / element)
                return RV::failure(name + ": sparse.values do not fit in buffer view " + std::to_string(s.valuesBufferView));
            View iv;
            iv.base = ib.value()->data() + io + s.indicesByteOffset;
            iv.stride = std::size_t(isize);
            iv.componentType = s.indicesComponentType;
            const unsigned char* values = vb.value()->data() + vo + s.valuesByteOffset;
            std::uint32_t previous = 0;
            for (std::size_t k = 0; k < s.count; ++k) {
                const std::uint32_t target = readIndex(iv, k);
                if (target >= a.count)
                    return RV::failure(name + ": sparse index " + std::to_string(target) + " is out of range (" + std::to_string(a.count) +
                                       " elements)");
                if (k > 0 && target <= previous) return RV::failure(name + ": sparse indices are not strictly increasing");
                previous = target;
                std::memcpy(bytes.data() + std::size_t(target) * element, values + k * element, element);
            }
        }
        found = owned_.emplace(index, std::move(bytes)).first;
    }
    v.base = found->second.data();
    v.stride = element;
    return RV(v);
}

} // namespace sr::gltf
