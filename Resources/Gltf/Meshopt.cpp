// EXT_meshopt_compression / KHR_meshopt_compression: a compressed buffer view decoded by libmeshoptimizer (its decoders check every read against the stream's size).
#include <cmath>

#include <meshoptimizer.h>

#include "Resources/Gltf/Codecs.hpp"

namespace sr::gltf {

Result<std::vector<unsigned char>> decodeMeshoptView(const Document& doc, const Json& ext, const std::string& what) {
    using R = Result<std::vector<unsigned char>>;
    if (!ext.is_object()) return R::failure(what + ": the extension must be an object");
    const auto number = [&](const char* key, double fallback) {
        const auto it = ext.find(key);
        return it != ext.end() && it->is_number() ? it->get<double>() : fallback;
    };
    const auto text = [&](const char* key, const char* fallback) {
        const auto it = ext.find(key);
        return it != ext.end() && it->is_string() ? it->get<std::string>() : std::string(fallback);
    };
    const double buffer = number("buffer", -1), offset = number("byteOffset", 0), length = number("byteLength", -1);
    const double stride = number("byteStride", -1), count = number("count", -1);
    const std::string mode = text("mode", ""), filter = text("filter", "NONE");
    const auto whole = [](double d, double max) { return d >= 0.0 && d <= max && d == std::floor(d); };
    if (!whole(buffer, 1e9) || std::size_t(buffer) >= doc.buffers.size()) return R::failure(what + ": buffer does not exist");
    if (!whole(offset, 1e18) || !whole(length, 1e18) || !whole(count, 1e9) || !whole(stride, 256) || stride < 1)
        return R::failure(what + ": byteOffset, byteLength, byteStride and count must be whole numbers in range");
    const std::vector<unsigned char>& data = doc.buffers[std::size_t(buffer)].data;
    if (offset > double(data.size()) || length > double(data.size()) - offset)
        return R::failure(what + ": the compressed bytes lie outside buffer " + std::to_string(std::size_t(buffer)) + " (" +
                          std::to_string(data.size()) + " bytes)");
    const std::size_t n = std::size_t(count), size = std::size_t(stride);
    // The decoded size is bounded like an accessor's: at most 2^32 bytes.
    if (double(n) * double(size) > 4294967296.0) return R::failure(what + ": count x byteStride is more than 4 GiB");
    const unsigned char* src = data.data() + std::size_t(offset);
    std::vector<unsigned char> out(n * size);
    int rc;
    if (mode == "ATTRIBUTES") {
        if (size % 4 != 0) return R::failure(what + ": ATTRIBUTES need a byteStride that is a multiple of 4");
        rc = meshopt_decodeVertexBuffer(out.data(), n, size, src, std::size_t(length));
    } else if (mode == "TRIANGLES" || mode == "INDICES") {
        if (size != 2 && size != 4) return R::failure(what + ": " + mode + " need a byteStride of 2 or 4");
        if (mode == "TRIANGLES" && n % 3 != 0) return R::failure(what + ": TRIANGLES with a count that is not a multiple of 3");
        rc = mode == "TRIANGLES" ? meshopt_decodeIndexBuffer(out.data(), n, size, src, std::size_t(length))
                                 : meshopt_decodeIndexSequence(out.data(), n, size, src, std::size_t(length));
    } else {
        return R::failure(what + ": mode '" + mode + "' is not ATTRIBUTES, TRIANGLES or INDICES");
    }
    if (rc != 0)
        return R::failure(what + ": the compressed stream is corrupt or of a newer meshopt version (meshoptimizer error " + std::to_string(rc) + ")");
    // Filters run in place on the decoded elements (the extension's "Filters").
    if (filter == "OCTAHEDRAL") {
        if (size != 4 && size != 8) return R::failure(what + ": the OCTAHEDRAL filter needs a byteStride of 4 or 8");
        meshopt_decodeFilterOct(out.data(), n, size);
    } else if (filter == "QUATERNION") {
        if (size != 8) return R::failure(what + ": the QUATERNION filter needs a byteStride of 8");
        meshopt_decodeFilterQuat(out.data(), n, size);
    } else if (filter == "EXPONENTIAL") {
        if (size % 4 != 0) return R::failure(what + ": the EXPONENTIAL filter needs a byteStride that is a multiple of 4");
        meshopt_decodeFilterExp(out.data(), n, size);
    } else if (filter != "NONE") {
        return R::failure(what + ": filter '" + filter + "' is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
    }
    if (mode != "ATTRIBUTES" && filter != "NONE") return R::failure(what + ": index data cannot be filtered");
    return R(std::move(out));
}

} // namespace sr::gltf
