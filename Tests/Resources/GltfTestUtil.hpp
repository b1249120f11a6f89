// Builds small glTF 2.0 assets in memory for the loader tests: one binary buffer, accessors over it, JSON around them; as .gltf (data URI or external .bin) or .glb.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace sr::gltftest {

inline std::string base64(const std::vector<unsigned char>& bytes) {
    static const char* const kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const unsigned v = unsigned(bytes[i]) << 16 | unsigned(bytes[i + 1]) << 8 | bytes[i + 2];
        for (int k = 3; k >= 0; --k) out += kAlphabet[(v >> (6 * k)) & 63u];
    }
    if (i + 1 == bytes.size()) {
        const unsigned v = unsigned(bytes[i]) << 16;
        out += kAlphabet[(v >> 18) & 63u];
        out += kAlphabet[(v >> 12) & 63u];
        out += "==";
    } else if (i + 2 == bytes.size()) {
        const unsigned v = unsigned(bytes[i]) << 16 | unsigned(bytes[i + 1]) << 8;
        out += kAlphabet[(v >> 18) & 63u];
        out += kAlphabet[(v >> 12) & 63u];
        out += kAlphabet[(v >> 6) & 63u];
        out += '=';
    }
    return out;
}

// Accessors each get a buffer view of their own, 4-byte aligned, in one buffer.
class Asset {
public:
    // Float data as an accessor of `type` ("VEC3", "VEC2", ...); returns the accessor index.
    int floats(const std::vector<float>& values, const std::string& type) {
        const int components = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : type == "MAT4" ? 16 : 4;
        return add(values.data(), values.size() * 4, 5126, int(values.size()) / components, type);
    }
    // Unsigned bytes (5121, not normalised) as an accessor of `type` (JOINTS_0: "VEC4").
    int unsignedBytes(const std::vector<std::uint8_t>& values, const std::string& type) {
        const int components = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : 4;
        return add(values.data(), values.size(), 5121, int(values.size()) / components, type);
    }
    // Indices as unsigned bytes (5121), shorts (5123) or ints (5125).
    int indices(const std::vector<std::uint32_t>& values, int componentType) {
        std::vector<unsigned char> bytes;
        for (std::uint32_t v : values) {
            const int size = componentType == 5121 ? 1 : componentType == 5123 ? 2 : 4;
            for (int b = 0; b < size; ++b) bytes.push_back((unsigned char)(v >> (8 * b)));
        }
        return add(bytes.data(), bytes.size(), componentType, int(values.size()), "SCALAR");
    }
    // Normalised unsigned shorts (5123) as an accessor of `type`.
    int normalizedShorts(const std::vector<std::uint16_t>& values, const std::string& type) {
        const int components = type == "VEC2" ? 2 : type == "VEC3" ? 3 : 4;
        const int a = add(values.data(), values.size() * 2, 5123, int(values.size()) / components, type);
        accessors_.back().insert(accessors_.back().size() - 1, ",\"normalized\":true");
        return a;
    }
    // Raw bytes as a buffer view of their own (4-byte aligned); returns the view's index.
    int view(const void* bytes, std::size_t size) {
        while (data_.size() % 4) data_.push_back(0);
        const std::size_t offset = data_.size();
        data_.resize(offset + size);
        std::memcpy(data_.data() + offset, bytes, size);
        views_.push_back("{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) + ",\"byteLength\":" + std::to_string(size) + "}");
        return int(views_.size()) - 1;
    }
    // Replaces a buffer view's JSON (a compressed view's extension).
    void setView(int index, const std::string& json) { views_[std::size_t(index)] = json; }
    // The byte offset in the buffer where the next view() would start.
    std::size_t nextOffset() const { return (data_.size() + 3) & ~std::size_t(3); }
    // Raw accessor JSON (for broken ones).
    int rawAccessor(const std::string& json) {
        accessors_.push_back(json);
        return int(accessors_.size()) - 1;
    }

    std::string nodes = "[]", meshes = "[]", materials, scenes = "[{\"nodes\":[0]}]", extra;

    // The JSON with the buffer as `bufferUri` (a data URI by default; "" for a GLB's BIN chunk).
    std::string json(const std::string& bufferUri) const {
        std::string j = "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":" + scenes + ",\"nodes\":" + nodes +
                        ",\"meshes\":" + meshes;
        if (!materials.empty()) j += ",\"materials\":" + materials;
        j += ",\"buffers\":[{\"byteLength\":" + std::to_string(data_.size());
        if (!bufferUri.empty()) j += ",\"uri\":\"" + bufferUri + "\"";
        j += "}],\"bufferViews\":[";
        for (std::size_t i = 0; i < views_.size(); ++i) j += (i ? "," : "") + views_[i];
        j += "],\"accessors\":[";
        for (std::size_t i = 0; i < accessors_.size(); ++i) j += (i ? "," : "") + accessors_[i];
        j += "]" + extra + "}";
        return j;
    }
    std::string embedded() const { return json("data:application/octet-stream;base64," + base64(data_)); }
    const std::vector<unsigned char>& buffer() const { return data_; }

    // A GLB: header, JSON chunk (space-padded), BIN chunk (zero-padded).
    std::vector<unsigned char> glb() const {
        std::string j = json("");
        while (j.size() % 4) j += ' ';
        std::vector<unsigned char> bin = data_;
        while (bin.size() % 4) bin.push_back(0);
        std::vector<unsigned char> out;
        const auto u32 = [&](std::uint32_t v) {
            for (int b = 0; b < 4; ++b) out.push_back((unsigned char)(v >> (8 * b)));
        };
        u32(0x46546C67u); // "glTF"
        u32(2);
        u32(std::uint32_t(12 + 8 + j.size() + 8 + bin.size()));
        u32(std::uint32_t(j.size()));
        u32(0x4E4F534Au); // "JSON"
        out.insert(out.end(), j.begin(), j.end());
        u32(std::uint32_t(bin.size()));
        u32(0x004E4942u); // "BIN\0"
        out.insert(out.end(), bin.begin(), bin.end());
        return out;
    }

private:
    int add(const void* bytes, std::size_t size, int componentType, int count, const std::string& type) {
        while (data_.size() % 4) data_.push_back(0);
        const std::size_t offset = data_.size();
        data_.resize(offset + size);
        std::memcpy(data_.data() + offset, bytes, size);
        views_.push_back("{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) + ",\"byteLength\":" + std::to_string(size) + "}");
        accessors_.push_back("{\"bufferView\":" + std::to_string(views_.size() - 1) + ",\"componentType\":" +
                             std::to_string(componentType) + ",\"count\":" + std::to_string(count) + ",\"type\":\"" + type + "\"}");
        return int(accessors_.size()) - 1;
    }
    std::vector<unsigned char> data_;
    std::vector<std::string> views_, accessors_;
};

} // namespace sr::gltftest
