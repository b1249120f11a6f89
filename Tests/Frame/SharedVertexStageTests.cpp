// One vertex stage per mesh, shared by its draws inside renderScene: same images, fewer transforms.
#include "TestFramework.hpp"

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "GeneralRenderer.hpp" // opaqueOnly
#include "Platform/App/SceneSetup.hpp"
#include "RenderTestUtil.hpp"
#include "Resources/Image.hpp"
#include "Resources/ObjTestUtil.hpp" // Tests/Resources: the OBJ tests' temporary files

using namespace sr;
using sr::test::differingPixels;

namespace {

// The scene with each draw of n triangles cut into consecutive draws of the same mesh, piece p
// taking triangles [n * ends[p - 1] / of, n * ends[p] / of) (ends ascending, the last == of; empty
// pieces dropped); with `recolour` the odd pieces' flat colour differs (a model whose faces switch
// material often). The triangles and their order are unchanged.
Scene cutDraws(const Scene& in, const std::vector<std::uint32_t>& ends, std::uint32_t of, bool recolour) {
    Scene out = in;
    out.draws.clear();
    for (const SceneDraw& d : in.draws) {
        const std::uint32_t triangles = d.indexCount / 3;
        for (std::size_t p = 0; p < ends.size(); ++p) {
            const std::uint32_t t0 = p == 0 ? 0 : triangles * ends[p - 1] / of, t1 = triangles * ends[p] / of;
            if (t0 == t1) continue;
            SceneDraw piece = d;
            piece.firstIndex = d.firstIndex + 3 * t0;
            piece.indexCount = 3 * (t1 - t0);
            if (recolour && p % 2 == 1) piece.kd = Color{0.2f, 0.7f, 0.3f, 1.0f};
            out.draws.push_back(piece);
        }
    }
    return out;
}

// `pieces` equal pieces per draw, recoloured.
Scene splitDraws(const Scene& in, int pieces) {
    std::vector<std::uint32_t> ends;
    for (int p = 1; p <= pieces; ++p) ends.push_back(std::uint32_t(p));
    return cutDraws(in, ends, std::uint32_t(pieces), true);
}

// The same draws with nothing to share: each draw gets a copy of its mesh of its own, so
// renderScene transforms the whole mesh once per draw (the reference the shared stage must match).
Scene meshPerDraw(const Scene& in) {
    Scene out = in;
    out.meshes.clear();
    for (SceneDraw& d : out.draws) {
        out.meshes.push_back(in.meshes[std::size_t(d.mesh)]);
        d.mesh = int(out.meshes.size()) - 1;
    }
    return out;
}

// An n x n quad grid as OBJ text, every quad textured by material a, or by a and b in a
// checkerboard ('usemtl' before every quad: a switch per quad).
std::string gridObj(int n, bool alternate) {
    std::string obj = "mtllib grid.mtl\n";
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) obj += "v " + std::to_string(x) + " " + std::to_string(y) + " 0\n";
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) obj += "vt " + std::to_string(x) + " " + std::to_string(y) + "\n";
    auto at = [&](int x, int y) { return std::to_string(y * (n + 1) + x + 1); };
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            obj += std::string("usemtl ") + (alternate && (x + y) % 2 == 1 ? "b" : "a") + "\n";
            const std::string c[4] = {at(x, y), at(x + 1, y), at(x + 1, y + 1), at(x, y + 1)};
            obj += "f";
            for (const std::string& v : c) obj += " " + v + "/" + v;
            obj += "\n";
        }
    return obj;
}

app::SceneOptions smallBuiltIn() {
    app::SceneOptions options;
    options.width = 160;
    options.height = 120;
    return options;
}

} // namespace

TEST_CASE("draws of one mesh share its vertex stage: the same image, the vertices transformed once",
          "[render][vertexshare]") {
    const app::SceneOptions options = smallBuiltIn();
    auto loaded = app::loadScene(options);
    REQUIRE(loaded.ok());
    // Opaque draws only: the transparent pass draws sorted runs of triangles, which may come back
    // to a mesh after another one (and transform it again); the counts below are per draw.
    const Scene whole = test::opaqueOnly(loaded.value().scene);
    const Scene split = splitDraws(whole, 8);
    REQUIRE(split.draws.size() > 4 * whole.draws.size()); // the split really made more draws
    const FrameView view =
        app::makeFrameView(app::resolveCamera(options, loaded.value()), options.width, options.height, options.light,
                            loaded.value().lights);
    for (ShadingMode mode : {ShadingMode::Unlit, ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong})
        for (int threads : {1, 2}) {
            INFO(shadingModeName(mode) << ", " << threads << " thread(s)");
            RenderSettings settings = app::makeRenderSettings(options);
            settings.shading = mode;
            FrameBuffer shared(options.width, options.height), alone(options.width, options.height),
                unsplit(options.width, options.height);
            RenderContext cs(shared), ca(alone), cu(unsplit);
            for (RenderContext* c : {&cs, &ca, &cu}) c->setThreads(threads);
            renderSceneFrame(cs, split, view, settings);
            renderSceneFrame(ca, meshPerDraw(split), view, settings);
            renderSceneFrame(cu, whole, view, settings);
            CHECK(differingPixels(shared, alone) == 0);
            CHECK(cs.stats.fragmentsShaded == ca.stats.fragmentsShaded);
            CHECK(cs.stats.rasterized == ca.stats.rasterized);
            // Without sharing every piece transforms its whole mesh again; with it, cutting draws
            // into pieces adds no vertex work at all.
            std::uint64_t perDraw = 0;
            for (const SceneDraw& d : split.draws) perDraw += split.meshes[std::size_t(d.mesh)].vertexCount();
            CHECK(ca.stats.verticesTransformed == perDraw);
            CHECK(cs.stats.verticesTransformed == cu.stats.verticesTransformed);
            CHECK(cs.stats.verticesTransformed * 4 < perDraw);
        }
}

TEST_CASE("shared vertices serve binned and unbinned draws alike: the same image, no second transform",
          "[render][vertexshare][threads]") {
    // A binned draw screens from the vertices' snapped positions: the vertex stage of a draw on
    // several lanes makes them whether or not that draw bins, so a later draw of the mesh that
    // does bin reuses the vertices as they are.
    const app::SceneOptions options = smallBuiltIn();
    auto loaded = app::loadScene(options);
    REQUIRE(loaded.ok());
    // Each draw cut into pieces of 10%, 30% and 60% of its triangles: with the threshold at the
    // median piece, most meshes have draws on both sides of it.
    const Scene split = cutDraws(test::opaqueOnly(loaded.value().scene), {1, 4, 10}, 10, false);
    std::vector<std::uint32_t> sizes;
    for (const SceneDraw& d : split.draws) sizes.push_back(d.indexCount / 3);
    std::sort(sizes.begin(), sizes.end());
    const FrameView view =
        app::makeFrameView(app::resolveCamera(options, loaded.value()), options.width, options.height, options.light,
                            loaded.value().lights);
    const RenderSettings settings = app::makeRenderSettings(options);
    FrameBuffer reference(options.width, options.height);
    RenderContext cr(reference);
    renderSceneFrame(cr, split, view, settings); // one thread: nothing binned
    // Every draw binned; about half of them (the larger pieces); none.
    for (std::size_t binMin : {std::size_t(1), std::size_t(sizes[sizes.size() / 2]), std::numeric_limits<std::size_t>::max()}) {
        INFO("binning from " << binMin << " triangles");
        FrameBuffer fb(options.width, options.height);
        RenderContext ctx(fb);
        ctx.setThreads(2);
        ctx.binningMinTriangles = binMin;
        renderSceneFrame(ctx, split, view, settings);
        CHECK(differingPixels(fb, reference) == 0);
        CHECK(ctx.stats.rasterized == cr.stats.rasterized);
        CHECK(ctx.stats.fragmentsShaded == cr.stats.fragmentsShaded);
        CHECK(ctx.stats.verticesTransformed == cr.stats.verticesTransformed);
    }
}

TEST_CASE("Gouraud draws with different specular constants do not share vertices; other programs still do",
          "[render][vertexshare][materials]") {
    // Gouraud lights per vertex, so its vertex stage reads the material's shininess (and whether
    // it has a specular term at all): a cache shared across a change of either would shade the
    // second draw with the first one's exponent. Phong's vertices do not depend on it.
    const app::SceneOptions options = smallBuiltIn();
    auto loaded = app::loadScene(options);
    REQUIRE(loaded.ok());
    Scene split = splitDraws(test::opaqueOnly(loaded.value().scene), 8); // opaque: one vertex stage per draw at most
    for (std::size_t i = 0; i < split.draws.size(); ++i) {
        Specular& sp = split.draws[i].specular;
        if (i % 3 == 1) sp.shininess = 5.0f;
        if (i % 3 == 2) sp.ks = Color{0.0f, 0.0f, 0.0f, 1.0f}; // no specular term
    }
    const FrameView view =
        app::makeFrameView(app::resolveCamera(options, loaded.value()), options.width, options.height, options.light,
                            loaded.value().lights);
    std::uint64_t perDraw = 0;
    for (const SceneDraw& d : split.draws) perDraw += split.meshes[std::size_t(d.mesh)].vertexCount();
    for (ShadingMode mode : {ShadingMode::Gouraud, ShadingMode::Phong}) {
        INFO(shadingModeName(mode));
        RenderSettings settings = app::makeRenderSettings(options);
        settings.shading = mode;
        FrameBuffer shared(options.width, options.height), alone(options.width, options.height);
        RenderContext cs(shared), ca(alone);
        renderSceneFrame(cs, split, view, settings);
        renderSceneFrame(ca, meshPerDraw(split), view, settings);
        CHECK(differingPixels(shared, alone) == 0);
        // Consecutive draws always differ in their specular constants here: Gouraud transforms
        // every draw, Phong far fewer.
        if (mode == ShadingMode::Gouraud) CHECK(cs.stats.verticesTransformed == perDraw);
        else CHECK(cs.stats.verticesTransformed * 4 < perDraw);
    }
}

TEST_CASE("the shared vertex stage never outlives renderScene: a new view is transformed anew", "[render][vertexshare]") {
    // Same context, same scene, same program and viewport, a different camera each frame: were
    // the cache kept across frames, the second frame would be drawn with the first one's vertices.
    const app::SceneOptions options = smallBuiltIn();
    auto loaded = app::loadScene(options);
    REQUIRE(loaded.ok());
    // One mesh only, so that the first draw of a frame meets the cache the last one left.
    Scene split = splitDraws(loaded.value().scene, 4);
    const int firstMesh = split.draws.front().mesh;
    split.draws.erase(std::remove_if(split.draws.begin(), split.draws.end(),
                                     [&](const SceneDraw& d) { return d.mesh != firstMesh; }),
                      split.draws.end());
    REQUIRE(split.draws.size() >= 2);
    app::CameraSetup camera = app::resolveCamera(options, loaded.value());
    const RenderSettings settings = app::makeRenderSettings(options);
    FrameBuffer fb(options.width, options.height);
    RenderContext ctx(fb);
    for (int frame = 0; frame < 3; ++frame) {
        INFO("frame " << frame);
        camera.eye = camera.eye + Vec3{0.3f, 0.1f * float(frame), -0.2f};
        const FrameView view = app::makeFrameView(camera, options.width, options.height, options.light, loaded.value().lights);
        renderSceneFrame(ctx, split, view, settings);
        FrameBuffer fresh(options.width, options.height);
        RenderContext cf(fresh);
        renderSceneFrame(cf, split, view, settings);
        CHECK(differingPixels(fb, fresh) == 0);
    }
    // Outside renderScene nothing is reused, even for the very same draw twice.
    const FrameView view = app::makeFrameView(camera, options.width, options.height, options.light, loaded.value().lights);
    const SceneDraw& d = split.draws.front();
    const Mesh& mesh = split.meshes[std::size_t(d.mesh)];
    ctx.stats = {};
    for (int i = 0; i < 2; ++i)
        drawMesh(ctx, view, settings, mesh, mesh.indices.data() + d.firstIndex, d.indexCount, SurfaceMaterial{});
    CHECK(ctx.stats.verticesTransformed == 2 * mesh.vertexCount());
}

TEST_CASE("a model's materials share one mesh: a checkerboard of two materials costs the vertices of one",
          "[render][vertexshare][obj]") {
    // The corners of the grid belong to quads of both materials. Split into one mesh per material
    // they were stored and transformed twice; in one mesh of the textured ranges, once.
    using namespace sr::objtest;
    const std::string dir = freshDir("vertex-share-grid");
    REQUIRE(writeImage(dir + "/a.png", rampImage(4, 4)).ok());
    REQUIRE(writeImage(dir + "/b.png", rampImage(8, 2)).ok());
    writeText(dir, "grid.mtl", "newmtl a\nmap_Kd a.png\nnewmtl b\nmap_Kd b.png\n");
    const int n = 24;
    writeText(dir, "alternate.obj", gridObj(n, true));
    writeText(dir, "one.obj", gridObj(n, false));
    app::SceneOptions options;
    options.width = 96;
    options.height = 96;
    options.obj = dir + "/alternate.obj";
    auto alternate = app::loadScene(options);
    options.obj = dir + "/one.obj";
    auto one = app::loadScene(options);
    REQUIRE(alternate.ok());
    REQUIRE(one.ok());
    const Scene& sa = alternate.value().scene;
    const Scene& so = one.value().scene;
    REQUIRE(sa.draws.size() == 2); // one per material
    REQUIRE(sa.meshes.size() == 1);
    CHECK(sa.draws[0].mesh == 0);
    CHECK(sa.draws[1].mesh == 0);
    CHECK(sa.meshes[0].vertexCount() == std::size_t((n + 1) * (n + 1)));
    CHECK(sa.meshes[0].vertexCount() == so.meshes[0].vertexCount());
    CHECK(sa.triangleCount() == so.triangleCount());

    const FrameView view =
        app::makeFrameView(app::resolveCamera(options, one.value()), options.width, options.height, options.light,
                            one.value().lights);
    for (ShadingMode mode : {ShadingMode::Unlit, ShadingMode::Phong}) {
        INFO(shadingModeName(mode));
        RenderSettings settings = app::makeRenderSettings(options);
        settings.shading = mode;
        FrameBuffer fa(options.width, options.height), fo(options.width, options.height),
            alone(options.width, options.height);
        RenderContext ca(fa), co(fo), cal(alone);
        renderSceneFrame(ca, sa, view, settings);
        renderSceneFrame(co, so, view, settings);
        renderSceneFrame(cal, meshPerDraw(sa), view, settings);
        CHECK(differingPixels(fa, alone) == 0);
        CHECK(ca.stats.verticesTransformed == co.stats.verticesTransformed);
        CHECK(cal.stats.verticesTransformed == 2 * co.stats.verticesTransformed);
        CHECK(ca.stats.fragmentsShaded == co.stats.fragmentsShaded);
    }
}
