// gltf::Accessors: an accessor's elements as the specification defines them (buffer views, byte strides, compressed views, sparse substitutions, zeros), validated, with one cache of decoded bytes per file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "Resources/Gltf/Document.hpp"

namespace sr::gltf {

// A validated view of an accessor's elements: element i starts at base + i * stride. The bytes
// belong to the document's buffers or to the cache that made the view.
struct View {
    const unsigned char* base = nullptr;
    std::size_t stride = 0, count = 0;
    int componentType = 0, components = 0;
    bool normalized = false;
};

// Component c of element i as a float: a float as it is; an integer normalised to [0, 1] or
// [-1, 1] when the accessor says `normalized` (glTF "Animations": max(c / 127, -1) for signed
// bytes), else its integer value (KHR_mesh_quantization's unnormalised positions, texture
// coordinates and offsets).
float readFloat(const View& v, std::size_t i, int c);
// Element i of an unsigned integer scalar accessor (indices).
std::uint32_t readIndex(const View& v, std::size_t i);
// Component c of element i of an unsigned byte or short accessor (JOINTS_n).
std::uint32_t readIndexComponent(const View& v, std::size_t i, int c);

// The accessors of one document. Views of plain accessors point into the buffers; an accessor
// that is sparse, has no buffer view, or reads a compressed buffer view
// (EXT_meshopt_compression / KHR_meshopt_compression) is decoded once into bytes the cache owns;
// a Draco primitive's decoded attributes are handed to it with `provide`.
class Accessors {
public:
    explicit Accessors(const Document& doc) : doc_(doc) {}

    // The accessor's elements, or a one-line error starting with `what`.
    Result<View> view(int index, const std::string& what);

    // Decoded elements for an accessor (Draco): tightly packed, in the accessor's component type.
    void provide(int index, std::vector<unsigned char> bytes);
    bool provided(int index) const { return provided_.count(index) != 0; }

    // The bytes of a buffer view (decoded when compressed), or a one-line error naming it.
    Result<const std::vector<unsigned char>*> bufferViewBytes(int index, std::size_t& offset, std::size_t& length);

private:
    const Document& doc_;
    std::map<int, std::shared_ptr<std::vector<unsigned char>>> decodedViews_; // compressed buffer views
    std::map<int, std::vector<unsigned char>> owned_;                          // sparse / zero-filled accessors
    std::map<int, std::vector<unsigned char>> provided_;                       // Draco
};

} // namespace sr::gltf
