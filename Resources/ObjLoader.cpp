// ObjLoader: read + validate the OBJ, parse it with tinyobjloader from memory, then build the indexed Mesh (as glref does) and one draw range per texture.
#include "Resources/ObjLoader.hpp"

#include <cassert>
#include <cmath>
#include <cstdint>
#include <istream>
#include <unordered_map>

#include "Math/DoubleMath.hpp"
#include "Resources/FileIO.hpp"
#include "Resources/ObjMaterials.hpp"
#include "Resources/ObjScan.hpp"

namespace sr {

namespace {

// glref's normalize_or (normals in double, as glref's V3): a / |a|, or the fallback when the
// length is zero or not finite.
Vec3d normalizeOr(Vec3d a, Vec3d fallback) {
    const double l = length(a);
    if (!(l > 0.0) || !std::isfinite(l)) return fallback;
    return a * (1.0 / l);
}

// De-duplication key: the (v, vn, vt) triple of a face-vertex, hashed as glref does.
struct Key {
    int v, n, t;
    bool operator==(const Key& o) const { return v == o.v && n == o.n && t == o.t; }
};
struct KeyHash {
    std::size_t operator()(const Key& k) const {
        std::uint64_t h = std::uint64_t(std::uint32_t(k.v)) * 0x9E3779B97F4A7C15ull;
        h ^= std::uint64_t(std::uint32_t(k.n)) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
        h ^= std::uint64_t(std::uint32_t(k.t)) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
        return std::size_t(h);
    }
};

// Appends tinyobjloader's multi-line warning text, one warning per line, prefixed by the file.
void addWarnings(std::vector<std::string>& out, const std::string& text, const std::string& path) {
    std::size_t start = 0, added = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        const std::string line = text.substr(start, end - start);
        start = end + 1;
        if (line.empty() || line == ".") continue;
        if (++added > 20) {
            out.push_back(path + ": (more tinyobjloader warnings not shown)");
            return;
        }
        out.push_back(path + ": " + line);
    }
}

// Every value of an attribute array must be finite (tinyobjloader turns 1e39 into inf).
Status checkFinite(const std::vector<tinyobj::real_t>& values, int perEntry, ObjEntry kind, const char* what,
                   TextSpan text, const std::string& path) {
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (std::isfinite(values[i])) continue;
        const std::size_t entry = i / std::size_t(perEntry);
        const std::size_t line = lineOfEntry(text, kind, entry);
        return Status::failure(path + ":" + std::to_string(line) + ": " + what + " " + std::to_string(entry + 1) +
                               ": coordinate is not finite as a float (" + std::to_string(values[i]) +
                               "; |value| must be <= 3.4e38)");
    }
    return success();
}

} // namespace

Result<Model> loadObj(const std::string& path, const LoadOptions& options) {
    // 1. Read the file (refusing directories and files above the limit).
    auto bytes = readFileBytes(path, options.limits.maxFileBytes);
    if (!bytes) return Result<Model>::failure(bytes.error());
    return loadObjFromMemory(bytes.value().data(), bytes.value().size(), path, options);
}

Result<Model> loadObjFromMemory(const unsigned char* data, std::size_t size, const std::string& path,
                                const LoadOptions& options) {
    using R = Result<Model>;
    const LoadLimits& limits = options.limits;

    // 1b. Validate the text before any parser sees it.
    if (size > limits.maxFileBytes)
        return R::failure(path + ": file is " + std::to_string(size) + " bytes, above the limit of " +
                          std::to_string(limits.maxFileBytes) + " bytes");
    if (size == 0) return R::failure(path + ": empty file (no triangles)");
    auto text = checkText(data, size, path);
    if (!text) return R::failure(text.error());
    auto stats = scanObj(text.value(), path, limits);
    if (!stats) return R::failure(stats.error());

    // 2. Parse from memory; .mtl files come through MtlFileReader (readFileBytes as well).
    Model model;
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    {
        TextStreamBuffer buffer(text.value());
        std::istream in(&buffer);
        MtlFileReader mtlReader(objDirectory(path), limits, model.warnings);
        const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &mtlReader,
                                         /*triangulate=*/true);
        if (!ok) return R::failure(path + ": " + err.substr(0, err.find('\n')));
    }
    addWarnings(model.warnings, warn, path);
    addWarnings(model.warnings, err, path);

    const std::size_t nv = attrib.vertices.size() / 3, nn = attrib.normals.size() / 3,
                      nt = attrib.texcoords.size() / 2;
    if (nv == 0) return R::failure(path + ": no vertices ('v' lines): not an OBJ model");
    for (auto status : {checkFinite(attrib.vertices, 3, ObjEntry::Position, "vertex", text.value(), path),
                        checkFinite(attrib.normals, 3, ObjEntry::Normal, "normal", text.value(), path),
                        checkFinite(attrib.texcoords, 2, ObjEntry::TexCoord, "texture coordinate", text.value(), path)}) {
        if (!status) return R::failure(status.error());
    }

    // 3. Check every index once more before use (the scan guarantees it; this guards the library).
    std::size_t triangles = 0;
    bool anyFaceWithoutMaterial = false;
    for (const auto& sh : shapes) {
        const auto& idx = sh.mesh.indices;
        for (std::size_t i = 0; i < idx.size(); ++i) {
            if (idx[i].vertex_index < 0 || std::size_t(idx[i].vertex_index) >= nv ||
                idx[i].normal_index < -1 || (idx[i].normal_index >= 0 && std::size_t(idx[i].normal_index) >= nn) ||
                idx[i].texcoord_index < -1 || (idx[i].texcoord_index >= 0 && std::size_t(idx[i].texcoord_index) >= nt)) {
                return R::failure(path + ": triangle " + std::to_string(triangles + i / 3 + 1) +
                                  " references a vertex, normal or texture coordinate out of range");
            }
        }
        const std::size_t nf = idx.size() / 3;
        for (std::size_t f = 0; f < nf; ++f) {
            const int mid = f < sh.mesh.material_ids.size() ? sh.mesh.material_ids[f] : -1;
            if (mid < 0 || std::size_t(mid) >= materials.size()) anyFaceWithoutMaterial = true;
        }
        triangles += nf;
    }
    if (triangles == 0) return R::failure(path + ": no triangles (no face with 3 or more vertices)");
    if (triangles > limits.maxTriangles)
        return R::failure(path + ": " + std::to_string(triangles) + " triangles, above the limit of " +
                          std::to_string(limits.maxTriangles));

    const auto P = [&](int i) {
        const std::size_t k = std::size_t(i) * 3;
        return Vec3d{attrib.vertices[k], attrib.vertices[k + 1], attrib.vertices[k + 2]};
    };

    // 4. Bounds of ALL 'v' entries (the auto-fit camera's sphere uses them, used or not).
    model.boundsMin = model.boundsMax = Vec3(attrib.vertices[0], attrib.vertices[1], attrib.vertices[2]);
    for (std::size_t i = 0; i < nv; ++i) {
        const float* v = &attrib.vertices[i * 3];
        model.boundsMin = Vec3(std::fmin(model.boundsMin.x, v[0]), std::fmin(model.boundsMin.y, v[1]),
                               std::fmin(model.boundsMin.z, v[2]));
        model.boundsMax = Vec3(std::fmax(model.boundsMax.x, v[0]), std::fmax(model.boundsMax.y, v[1]),
                               std::fmax(model.boundsMax.z, v[2]));
    }

    // 5. Area-weighted vertex normals per position index, for face-vertices without a 'vn'.
    std::vector<Vec3d> accum(nv);
    bool anyMissingNormal = false, anyFileNormal = false;
    for (const auto& sh : shapes) {
        const auto& idx = sh.mesh.indices;
        for (std::size_t f = 0; f + 2 < idx.size(); f += 3) {
            const Vec3d a = P(idx[f].vertex_index), b = P(idx[f + 1].vertex_index), c = P(idx[f + 2].vertex_index);
            const Vec3d n = cross(b - a, c - a);
            for (int k = 0; k < 3; ++k) {
                Vec3d& acc = accum[std::size_t(idx[f + k].vertex_index)];
                acc = acc + n;
                (idx[f + k].normal_index < 0 ? anyMissingNormal : anyFileNormal) = true;
            }
        }
    }
    for (auto& n : accum) n = normalizeOr(n, Vec3d{0, 0, 1});
    model.normalsFromFile = anyFileNormal && !anyMissingNormal;
    model.hasUvs = nt > 0;

    // 6. Materials and textures.
    auto overrideMaterial = assignMaterials(model, materials, path, options, anyFaceWithoutMaterial);
    if (!overrideMaterial) return R::failure(overrideMaterial.error());

    // 7a. Draw ranges: one per material (faces without one form the material -1 range), ordered
    //     by the material's first face in the file (ObjLoader.hpp: "Draw order"). A counting pass
    //     sizes the ranges, so every face is written straight into its range below: O(faces)
    //     whatever the material order, and a checkerboard of two materials is two draws, not one
    //     per quad (as a range per material switch would make it).
    const auto materialOfFace = [&](const tinyobj::shape_t& sh, std::size_t f) {
        const int mid = f < sh.mesh.material_ids.size() ? sh.mesh.material_ids[f] : -1;
        return mid < 0 || std::size_t(mid) >= materials.size() ? overrideMaterial.value() : mid;
    };
    std::vector<int> rangeOfMaterial(model.materials.size() + 1, -1); // [material + 1] -> range
    for (const auto& sh : shapes) {
        const std::size_t nf = sh.mesh.indices.size() / 3;
        for (std::size_t f = 0; f < nf; ++f) {
            const int mid = materialOfFace(sh, f);
            int& range = rangeOfMaterial[std::size_t(mid + 1)];
            if (range < 0) {
                range = int(model.ranges.size());
                DrawRange r;
                r.material = mid;
                r.texture = model.hasUvs && mid >= 0 ? model.materials[std::size_t(mid)].texture : -1;
                assert(r.texture >= -1 && r.texture < int(model.textures.size()));
                model.ranges.push_back(r);
            }
            model.ranges[std::size_t(range)].indexCount += 3;
        }
    }
    std::vector<std::uint32_t> cursor(model.ranges.size()); // next index to write in each range
    for (std::size_t r = 0, first = 0; r < model.ranges.size(); first += model.ranges[r].indexCount, ++r) {
        model.ranges[r].firstIndex = std::uint32_t(first);
        cursor[r] = std::uint32_t(first);
    }

    // 7b. Indexed vertices, de-duplicated and numbered in file order (the first face-vertex that
    //     uses a triple creates it); each face's three indices go to the end of its range so far.
    Mesh& mesh = model.mesh;
    mesh.indices.resize(triangles * 3);
    std::unordered_map<Key, std::uint32_t, KeyHash> dedup;
    dedup.reserve(std::min<std::size_t>(triangles * 3, nv * 2 + 16));
    for (const auto& sh : shapes) {
        const auto& idx = sh.mesh.indices;
        const std::size_t nf = idx.size() / 3;
        for (std::size_t f = 0; f < nf; ++f) {
            const int mid = materialOfFace(sh, f);
            std::uint32_t& out = cursor[std::size_t(rangeOfMaterial[std::size_t(mid + 1)])];
            for (int k = 0; k < 3; ++k) {
                const tinyobj::index_t& ix = idx[f * 3 + std::size_t(k)];
                const Key key{ix.vertex_index, ix.normal_index >= 0 ? ix.normal_index : -1,
                              model.hasUvs ? ix.texcoord_index : -1};
                const auto found = dedup.find(key);
                if (found != dedup.end()) {
                    mesh.indices[out++] = found->second;
                    continue;
                }
                const auto vi = std::uint32_t(mesh.positions.size());
                dedup.emplace(key, vi);
                mesh.indices[out++] = vi;
                const Vec3d p = P(ix.vertex_index);
                mesh.positions.emplace_back(float(p.x), float(p.y), float(p.z));
                const Vec3d vnorm = accum[std::size_t(ix.vertex_index)];
                Vec3d n = vnorm;
                if (ix.normal_index >= 0) {
                    const std::size_t ni = std::size_t(ix.normal_index) * 3;
                    n = normalizeOr(Vec3d{attrib.normals[ni], attrib.normals[ni + 1], attrib.normals[ni + 2]}, vnorm);
                }
                mesh.normals.emplace_back(float(n.x), float(n.y), float(n.z));
                if (model.hasUvs) {
                    Vec2 uv;
                    if (ix.texcoord_index >= 0) {
                        const std::size_t ti = std::size_t(ix.texcoord_index) * 2;
                        uv = Vec2(attrib.texcoords[ti], attrib.texcoords[ti + 1]);
                    }
                    mesh.uvs.push_back(uv);
                }
            }
        }
    }
    return R(std::move(model));
}

} // namespace sr
