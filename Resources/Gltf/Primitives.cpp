// gltfimport primitives: one primitive of a node as world-space triangles (strips and fans unrolled, flat normals where none are given, tangents) or as lines and points.
#include <algorithm>
#include <cmath>

#include "Resources/Gltf/Codecs.hpp"
#include "Resources/Gltf/Import.hpp"

namespace sr::gltfimport {

namespace {

// Vertex i of a POSITION accessor through the node's world transform (double, rounded to float).
Result<Vec3> worldPosition(const View& pos, std::size_t i, const Mat4d& world, const std::string& what) {
    const double x = readFloat(pos, i, 0), y = readFloat(pos, i, 1), z = readFloat(pos, i, 2);
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
        return Result<Vec3>::failure(what + " POSITION: vertex " + std::to_string(i) + " is not finite");
    const double px = world.m[0][0] * x + world.m[0][1] * y + world.m[0][2] * z + world.m[0][3];
    const double py = world.m[1][0] * x + world.m[1][1] * y + world.m[1][2] * z + world.m[1][3];
    const double pz = world.m[2][0] * x + world.m[2][1] * y + world.m[2][2] * z + world.m[2][3];
    const Vec3 pf{float(px), float(py), float(pz)};
    if (!std::isfinite(pf.x) || !std::isfinite(pf.y) || !std::isfinite(pf.z))
        return Result<Vec3>::failure(what + " POSITION: vertex " + std::to_string(i) + " is not finite after the node transforms");
    return Result<Vec3>(pf);
}

// POINTS, LINES, LINE_LOOP and LINE_STRIP: a LineSet in world space (glTF "Meshes": a loop
// closes last -> first, a strip joins consecutive vertices).
Status addLines(Builder& b, const gltf::Primitive& prim, const View& pos,
                const std::vector<std::uint32_t>& order, const Mat4d& world, const std::string& what,
                const LoadLimits& limits) {
    const gltf::Document& g = *b.doc;
    LineSet set;
    set.points = prim.mode == gltf::kModePoints;
    set.material = prim.material >= 0 && std::size_t(prim.material) < g.materials.size() ? prim.material : -1;
    if (prim.material >= 0 && set.material < 0)
        return Status::failure(what + ": material " + std::to_string(prim.material) + " does not exist");
    const std::size_t n = order.size();
    if (set.points) {
        set.indices = order;
    } else if (prim.mode == gltf::kModePoints + 1) { // LINES (a whole number of pairs: checked)
        set.indices = order;
    } else {
        for (std::size_t i = 0; i + 1 < n; ++i) set.indices.insert(set.indices.end(), {order[i], order[i + 1]});
        if (prim.mode == gltf::kModePoints + 2 && n >= 2) set.indices.insert(set.indices.end(), {order[n - 1], order[0]}); // LOOP
    }
    b.lineElements += set.indices.size();
    if (b.lineElements > limits.maxTriangles * 3) return Status::failure("more line and point elements than the triangle limit allows");
    if (b.model.mesh.vertexCount() + b.lineVertices + pos.count > limits.maxVertices)
        return Status::failure("more than " + std::to_string(limits.maxVertices) + " vertices");
    b.lineVertices += pos.count;
    set.positions.reserve(pos.count);
    for (std::size_t i = 0; i < pos.count; ++i) {
        auto p = worldPosition(pos, i, world, what);
        if (!p) return Status::failure(p.error());
        set.positions.push_back(p.value());
    }
    if (!set.indices.empty()) b.model.lineSets.push_back(std::move(set));
    return success();
}

} // namespace

Status addPrimitive(Builder& b, const gltf::Primitive& prim, const Mat4d& world, const std::string& what, const LoadLimits& limits) {
    const gltf::Document& g = *b.doc;
    // A Draco-compressed primitive: decoded once (an instanced node meets it again), its
    // attributes and indices then read like any others.
    if (const auto draco = prim.extensions.find("KHR_draco_mesh_compression"); draco != prim.extensions.end()) {
        const auto pi = prim.attributes.find("POSITION");
        if (pi == prim.attributes.end() || !b.accessors->provided(pi->second)) {
            const Status s = gltf::decodeDracoPrimitive(g, prim, *draco, *b.accessors, what);
            if (!s) return s;
        }
    }
    if (prim.mode < gltf::kModePoints || prim.mode > gltf::kModeFan) return Status::failure(what + ": unknown mode " + std::to_string(prim.mode));
    const auto attribute = [&](const char* name) {
        const auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -1 : it->second;
    };
    const int posIndex = attribute("POSITION");
    if (posIndex < 0) return Status::failure(what + ": no POSITION attribute");
    auto pos = b.accessors->view(posIndex, what + " POSITION");
    if (!pos) return Status::failure(pos.error());
    // Float, or (KHR_mesh_quantization) byte or short, signed or not, normalised or not.
    const auto quantized = [](const View& v) {
        return v.componentType == gltf::kByte || v.componentType == gltf::kUnsignedByte || v.componentType == gltf::kShort ||
               v.componentType == gltf::kUnsignedShort;
    };
    const auto signedNormalized = [](const View& v) {
        return v.normalized && (v.componentType == gltf::kByte || v.componentType == gltf::kShort);
    };
    if ((pos.value().componentType != gltf::kFloat && !quantized(pos.value())) || pos.value().components != 3)
        return Status::failure(what + " POSITION: must be float, byte or short VEC3");
    const std::size_t count = pos.value().count;
    std::optional<View> normals, uvs, tangents;
    if (const int ti = attribute("TANGENT"); ti >= 0) {
        auto v = b.accessors->view(ti, what + " TANGENT");
        if (!v) return Status::failure(v.error());
        if ((v.value().componentType != gltf::kFloat && !signedNormalized(v.value())) || v.value().components != 4)
            return Status::failure(what + " TANGENT: must be float or normalised byte/short VEC4");
        if (v.value().count != count) return Status::failure(what + " TANGENT: count differs from POSITION's");
        tangents = v.value();
    }
    if (const int ni = attribute("NORMAL"); ni >= 0) {
        auto v = b.accessors->view(ni, what + " NORMAL");
        if (!v) return Status::failure(v.error());
        if ((v.value().componentType != gltf::kFloat && !signedNormalized(v.value())) || v.value().components != 3)
            return Status::failure(what + " NORMAL: must be float or normalised byte/short VEC3");
        if (v.value().count != count) return Status::failure(what + " NORMAL: count differs from POSITION's");
        normals = v.value();
    }
    // The uv set the material's maps read (materialUvSource), with its transform; where its maps
    // have addresses of their own (materialAddressing), also the raw sets TEXCOORD_0 and _1.
    UvSource uvSource;
    std::optional<MapAddressing> addressing;
    if (prim.material >= 0 && std::size_t(prim.material) < g.materials.size()) {
        uvSource = materialUvSource(g.materials[std::size_t(prim.material)]);
        addressing = materialAddressing(g, g.materials[std::size_t(prim.material)], nullptr, b.transformsMove(prim.material));
    }
    const bool addressed = addressing.has_value();
    const auto uvSet = [&](int set) -> Result<std::optional<View>> {
        const std::string uvName = "TEXCOORD_" + std::to_string(set);
        const int ti = attribute(uvName.c_str());
        if (ti < 0) return std::optional<View>();
        auto v = b.accessors->view(ti, what + " " + uvName);
        if (!v) return Result<std::optional<View>>::failure(v.error());
        const View& t = v.value();
        // Float, normalised unsigned byte/short, and under KHR_mesh_quantization any byte or short.
        const bool ok = t.components == 2 && (t.componentType == gltf::kFloat || quantized(t));
        if (!ok) return Result<std::optional<View>>::failure(what + " " + uvName + ": must be float, byte or short VEC2");
        if (t.count != count) return Result<std::optional<View>>::failure(what + " " + uvName + ": count differs from POSITION's");
        return std::optional<View>(t);
    };
    if (auto v = uvSet(uvSource.texCoord); !v) return Status::failure(v.error());
    else uvs = v.value();
    std::optional<View> rawSets[MapAddressing::kUvSets];
    for (int set = 0; uvs && addressed && set < MapAddressing::kUvSets; ++set) {
        auto v = uvSet(set);
        if (!v) return Status::failure(v.error());
        rawSets[set] = v.value();
    }
    // COLOR_0 (glTF "Meshes"): RGB or RGBA, float or normalised unsigned byte/short, linear.
    std::optional<View> colours;
    if (const int ci = attribute("COLOR_0"); ci >= 0) {
        auto v = b.accessors->view(ci, what + " COLOR_0");
        if (!v) return Status::failure(v.error());
        const View& c = v.value();
        const bool unorm = c.normalized && (c.componentType == gltf::kUnsignedByte || c.componentType == gltf::kUnsignedShort);
        if ((c.components != 3 && c.components != 4) || (c.componentType != gltf::kFloat && !unorm))
            return Status::failure(what + " COLOR_0: must be float or normalised unsigned byte/short VEC3 or VEC4");
        if (c.count != count) return Status::failure(what + " COLOR_0: count differs from POSITION's");
        colours = c;
    }
    // The primitive's vertex order: indices, or 0..count-1.
    std::vector<std::uint32_t> order;
    if (prim.indices >= 0) {
        auto v = b.accessors->view(prim.indices, what + " indices");
        if (!v) return Status::failure(v.error());
        const View& iv = v.value();
        if (iv.components != 1 || (iv.componentType != gltf::kUnsignedByte && iv.componentType != gltf::kUnsignedShort &&
                                   iv.componentType != gltf::kUnsignedInt))
            return Status::failure(what + " indices: must be unsigned byte, short or int scalars");
        if (iv.count > limits.maxTriangles * 3) return Status::failure(what + ": more indices than the triangle limit allows");
        order.resize(iv.count);
        for (std::size_t i = 0; i < iv.count; ++i) {
            order[i] = readIndex(iv, i);
            if (order[i] >= count)
                return Status::failure(what + ": index " + std::to_string(order[i]) + " (entry " + std::to_string(i) +
                                       ") is out of range (" + std::to_string(count) + " vertices)");
        }
    } else {
        order.resize(count);
        for (std::size_t i = 0; i < count; ++i) order[i] = std::uint32_t(i);
    }
    // The specification's vertex counts: whole triangles and whole segments (strips, fans and
    // loops take any count; too few draw nothing).
    if (prim.mode == gltf::kModeTriangles && order.size() % 3 != 0)
        return Status::failure(what + ": TRIANGLES with " + std::to_string(order.size()) + " vertices, not a multiple of 3");
    if (prim.mode == gltf::kModePoints + 1 && order.size() % 2 != 0)
        return Status::failure(what + ": LINES with " + std::to_string(order.size()) + " vertices, not a multiple of 2");
    if (prim.mode < gltf::kModeTriangles) return addLines(b, prim, pos.value(), order, world, what, limits);
    // Triangles of the mode, in the primitive's vertex numbering.
    std::vector<std::uint32_t> tris;
    const std::size_t n = order.size();
    if (prim.mode == gltf::kModeTriangles) { // a whole number of triangles: checked above
        tris = order;
    } else if (prim.mode == gltf::kModeStrip) {
        for (std::size_t i = 2; i < n; ++i) {
            const bool even = i % 2 == 0; // glTF: triangle i - 2 is (i-2, i-1, i) or (i-1, i-2, i)
            tris.insert(tris.end(), {order[even ? i - 2 : i - 1], order[even ? i - 1 : i - 2], order[i]});
        }
    } else {
        for (std::size_t i = 2; i < n; ++i) tris.insert(tris.end(), {order[i - 1], order[i], order[0]});
    }
    if (b.triangles + tris.size() / 3 > limits.maxTriangles)
        return Status::failure("more than " + std::to_string(limits.maxTriangles) + " triangles");
    // A primitive without NORMAL is drawn with flat normals (glTF "Meshes": "client
    // implementations MUST calculate flat normals"): each triangle gets vertices of its own, so
    // the area-weighted normal below is its face normal. vertex k of the primitive reads element
    // source[k] of the accessors (itself when the vertices stay shared).
    std::vector<std::uint32_t> source;
    std::size_t vertices = count;
    if (!normals) {
        source = tris;
        vertices = tris.size();
        for (std::size_t k = 0; k < tris.size(); ++k) tris[k] = std::uint32_t(k);
    }
    const auto src = [&](std::size_t k) { return source.empty() ? k : std::size_t(source[k]); };
    if (b.model.mesh.vertexCount() + vertices > limits.maxVertices)
        return Status::failure("more than " + std::to_string(limits.maxVertices) + " vertices");

    // Vertices in world space.
    Mesh& mesh = b.model.mesh;
    const auto base = std::uint32_t(mesh.positions.size());
    std::vector<Vec3d> world3(vertices);
    for (std::size_t i = 0; i < vertices; ++i) {
        auto pf = worldPosition(pos.value(), src(i), world, what);
        if (!pf) return Status::failure(pf.error());
        world3[i] = Vec3d(pf.value());
        mesh.positions.push_back(pf.value());
    }
    // Normals: the inverse transpose of the upper 3x3 (its cofactor matrix; the scale drops out
    // with the renormalisation), or area-weighted from the world-space triangles.
    const double (*a)[4] = world.m;
    const double cof[3][3] = {{a[1][1] * a[2][2] - a[1][2] * a[2][1], a[1][2] * a[2][0] - a[1][0] * a[2][2], a[1][0] * a[2][1] - a[1][1] * a[2][0]},
                              {a[0][2] * a[2][1] - a[0][1] * a[2][2], a[0][0] * a[2][2] - a[0][2] * a[2][0], a[0][1] * a[2][0] - a[0][0] * a[2][1]},
                              {a[0][1] * a[1][2] - a[0][2] * a[1][1], a[0][2] * a[1][0] - a[0][0] * a[1][2], a[0][0] * a[1][1] - a[0][1] * a[1][0]}};
    const double det = a[0][0] * cof[0][0] + a[0][1] * cof[0][1] + a[0][2] * cof[0][2];
    std::vector<Vec3d> accum;
    if (!normals) {
        accum.assign(vertices, Vec3d{});
        for (std::size_t t = 0; t + 2 < tris.size(); t += 3) {
            const Vec3d p0 = world3[tris[t]], p1 = world3[tris[t + 1]], p2 = world3[tris[t + 2]];
            Vec3d fn = cross(p1 - p0, p2 - p0);
            if (det < 0) fn = fn * -1.0; // the winding is reversed below
            for (int k = 0; k < 3; ++k) accum[tris[t + std::size_t(k)]] = accum[tris[t + std::size_t(k)]] + fn;
        }
        b.anyComputedNormal = true;
    } else {
        b.anyFileNormal = true;
    }
    for (std::size_t i = 0; i < vertices; ++i) {
        Vec3d nv;
        if (normals) {
            const double x = readFloat(*normals, i, 0), y = readFloat(*normals, i, 1), z = readFloat(*normals, i, 2);
            // cof = det x the inverse transpose: its sign flips with a mirror, the normal must not.
            nv = Vec3d{cof[0][0] * x + cof[0][1] * y + cof[0][2] * z, cof[1][0] * x + cof[1][1] * y + cof[1][2] * z,
                       cof[2][0] * x + cof[2][1] * y + cof[2][2] * z} *
                 (det < 0 ? -1.0 : 1.0);
        } else {
            nv = accum[i];
        }
        const double l = length(nv);
        nv = l > 0.0 && std::isfinite(l) ? nv / l : Vec3d{0, 0, 1};
        mesh.normals.emplace_back(float(nv.x), float(nv.y), float(nv.z));
    }
    if (uvs) {
        if (!b.model.hasUvs) {
            mesh.uvs.assign(base, Vec2{}); // earlier vertices had none: (0, 0)
            b.model.hasUvs = true;
        }
        const UvTransform& transform = uvSource.transform;
        for (std::size_t i = 0; i < vertices; ++i) {
            float u = readFloat(*uvs, src(i), 0), v = readFloat(*uvs, src(i), 1);
            if (transform.found) {
                const double tu = transform.m[0][0] * u + transform.m[0][1] * v + transform.m[0][2];
                const double tv = transform.m[1][0] * u + transform.m[1][1] * v + transform.m[1][2];
                u = float(tu);
                v = float(tv);
            }
            mesh.uvs.emplace_back(std::isfinite(u) ? u : 0.0f, std::isfinite(v) ? 1.0f - v : 0.0f);
        }
    } else if (b.model.hasUvs) {
        mesh.uvs.resize(mesh.positions.size(), Vec2{});
    }
    // The raw sets, once any primitive has them: (0, 0) where a primitive has none.
    if ((uvs && addressed) || !mesh.uvSets[0].empty()) {
        for (int set = 0; set < MapAddressing::kUvSets; ++set) {
            std::vector<Vec2>& out = mesh.uvSets[set];
            out.resize(base, Vec2{});
            for (std::size_t i = 0; rawSets[set] && i < vertices; ++i) {
                const float u = readFloat(*rawSets[set], src(i), 0), v = readFloat(*rawSets[set], src(i), 1);
                out.emplace_back(std::isfinite(u) ? u : 0.0f, std::isfinite(v) ? 1.0f - v : 0.0f);
            }
            out.resize(mesh.positions.size(), Vec2{});
        }
    }
    // Vertex colours: once one primitive has them, every vertex does (white where none is given,
    // which multiplies the base colour by 1). A non-finite component reads as 1.
    if (colours || !mesh.colours.empty()) {
        mesh.colours.resize(base, Color{1.0f, 1.0f, 1.0f, 1.0f});
        for (std::size_t i = 0; colours && i < vertices; ++i) {
            float c[4] = {1.0f, 1.0f, 1.0f, 1.0f};
            for (int k = 0; k < colours->components; ++k) {
                const float x = readFloat(*colours, src(i), k);
                c[k] = std::isfinite(x) ? x : 1.0f;
            }
            mesh.colours.push_back(Color{c[0], c[1], c[2], c[3]});
        }
        mesh.colours.resize(mesh.positions.size(), Color{1.0f, 1.0f, 1.0f, 1.0f});
    }
    // Tangents, for a material with a normal map: the file's TANGENT through the node's transform,
    // else generated from the uvs (addTangents). Vertices without any get (1, 0, 0, 1).
    // Tangents for a normal map, the base's or the clear coat's (KHR_materials_clearcoat).
    const bool normalMapped = uvs && prim.material >= 0 && std::size_t(prim.material) < g.materials.size() &&
                              (textureInfoOf(g.materials[std::size_t(prim.material)], MapSlot::Normal).index >= 0 ||
                               textureInfoOf(g.materials[std::size_t(prim.material)], MapSlot::ClearcoatNormal).index >= 0);
    if (addressed && normalMapped && colours) {
        const auto white = [](const Color& c) { return c.r == 1.0f && c.g == 1.0f && c.b == 1.0f; };
        const std::string note = b.path + ": material " + std::to_string(prim.material) +
                                 ": its maps read their own uv sets or transforms and it has a normal map: its primitives' "
                                 "vertex colours (COLOR_0) are not drawn (one varying more than a draw interpolates)";
        if (!std::all_of(mesh.colours.begin() + base, mesh.colours.end(), white) &&
            std::find(b.model.warnings.begin(), b.model.warnings.end(), note) == b.model.warnings.end())
            b.model.warnings.push_back(note);
    }
    if (normalMapped || !mesh.tangents.empty()) {
        mesh.tangents.resize(base, Vec4{1.0f, 0.0f, 0.0f, 1.0f});
        if (normalMapped && tangents && normals) {
            for (std::size_t i = 0; i < vertices; ++i) {
                const double x = readFloat(*tangents, i, 0), y = readFloat(*tangents, i, 1), z = readFloat(*tangents, i, 2);
                const double w = readFloat(*tangents, i, 3);
                const Vec3d t{a[0][0] * x + a[0][1] * y + a[0][2] * z, a[1][0] * x + a[1][1] * y + a[1][2] * z,
                              a[2][0] * x + a[2][1] * y + a[2][2] * z};
                // The bitangent w (n x t) in world space is the transformed one: a mirror flips w.
                const double nx = readFloat(*normals, i, 0), ny = readFloat(*normals, i, 1), nz = readFloat(*normals, i, 2);
                const Vec3d bObj = cross(Vec3d{nx, ny, nz}, Vec3d{x, y, z}) * (w < 0 ? -1.0 : 1.0);
                const Vec3d bWorld{a[0][0] * bObj.x + a[0][1] * bObj.y + a[0][2] * bObj.z, a[1][0] * bObj.x + a[1][1] * bObj.y + a[1][2] * bObj.z,
                                   a[2][0] * bObj.x + a[2][1] * bObj.y + a[2][2] * bObj.z};
                const Vec3 n = mesh.normals[base + i];
                const double l = length(t);
                const Vec3d tn = l > 0.0 && std::isfinite(l) ? t / l : Vec3d{1, 0, 0};
                const double sign = dot(cross(Vec3d(n), tn), bWorld) < 0.0 ? -1.0 : 1.0;
                mesh.tangents.emplace_back(float(tn.x), float(tn.y), float(tn.z), float(sign));
            }
        } else if (normalMapped) {
            // Along the normal map's uvs: its own set and transform where the material's maps
            // have addresses of their own (the base's normal map, else the coat's).
            std::vector<Vec2> mapUvs;
            if (addressed) {
                const gltf::Material& gm = g.materials[std::size_t(prim.material)];
                const MapSlot slot = textureInfoOf(gm, MapSlot::Normal).index >= 0 ? MapSlot::Normal : MapSlot::ClearcoatNormal;
                const MapAddress& a = (*addressing)[slot];
                for (std::size_t k = base; k < mesh.positions.size(); ++k) mapUvs.push_back(a.apply(mesh.uvSets[a.uvSet][k]));
            }
            addTangents(mesh, base, tris, mapUvs.empty() ? nullptr : &mapUvs);
        } else {
            mesh.tangents.resize(mesh.positions.size(), Vec4{1.0f, 0.0f, 0.0f, 1.0f});
        }
    }
    if (b.animation) {
        const Status s = addAnimatedBlock(b, prim, pos.value(), normals, tangents && normalMapped && normals, base, vertices, source,
                                          det < 0, what, limits);
        if (!s) return s;
    }
    // Triangles into their material's list.
    const int material = prim.material >= 0 && std::size_t(prim.material) < g.materials.size() ? prim.material : -1;
    if (prim.material >= 0 && material < 0) return Status::failure(what + ": material " + std::to_string(prim.material) + " does not exist");
    b.triangles += tris.size() / 3;
    if (b.placing) { // in the mesh's own space: no mirror (det > 0)
        Builder::PlacedPrimitive& placed = b.placed.emplace_back();
        placed.material = material;
        placed.firstVertex = base;
        placed.vertexCount = std::uint32_t(vertices);
        for (const std::uint32_t v : tris) placed.triangles.push_back(base + v);
        return success();
    }
    auto& list = b.trianglesOf[std::size_t(material + 1)];
    if (list.empty() && !tris.empty()) b.firstUse.push_back(material + 1);
    for (std::size_t t = 0; t + 2 < tris.size(); t += 3) {
        const std::uint32_t i0 = base + tris[t], i1 = base + tris[t + 1], i2 = base + tris[t + 2];
        if (det < 0) list.insert(list.end(), {i0, i2, i1});
        else list.insert(list.end(), {i0, i1, i2});
    }
    return success();
}

} // namespace sr::gltfimport
