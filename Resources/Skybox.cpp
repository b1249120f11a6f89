// Loads a skybox: six cube-map face images from one folder.
#include "Resources/Skybox.hpp"

#include <array>
#include <filesystem>
#include <vector>

#include "Resources/Image.hpp"

namespace sr {

Result<CubeMap> loadSkybox(const std::string& dir) {
    static const char* const kNames[kCubeFaces] = {"px", "nx", "py", "ny", "pz", "nz"};
    static const char* const kExtensions[] = {".png", ".jpg", ".jpeg", ".bmp", ".tga", ".ppm", ".pgm", ".pnm"};
    std::error_code ec;
    if (!std::filesystem::is_directory(std::filesystem::u8path(dir), ec))
        return Result<CubeMap>::failure(dir + ": not a folder (--skybox wants a folder holding px, nx, py, ny, pz, nz images)");
    std::vector<Image> faces;
    int size = 0;
    std::string first;
    for (const char* name : kNames) {
        std::string path;
        for (const char* ext : kExtensions) {
            const std::string candidate = dir + "/" + name + ext;
            if (std::filesystem::is_regular_file(std::filesystem::u8path(candidate), ec)) {
                path = candidate;
                break;
            }
        }
        if (path.empty())
            return Result<CubeMap>::failure(dir + ": skybox face '" + name + "' is missing (" + name +
                                            ".png, .jpg, .bmp, .tga or .ppm)");
        auto image = loadImage(path);
        if (!image) return Result<CubeMap>::failure(image.error());
        const Image& img = image.value();
        if (img.width != img.height)
            return Result<CubeMap>::failure(path + ": a skybox face must be square (it is " + std::to_string(img.width) +
                                            " x " + std::to_string(img.height) + ")");
        if (img.width > kMaxSkyboxFace)
            return Result<CubeMap>::failure(path + ": a skybox face may be at most " + std::to_string(kMaxSkyboxFace) +
                                            " x " + std::to_string(kMaxSkyboxFace) + " (it is " + std::to_string(img.width) +
                                            " x " + std::to_string(img.height) + ")");
        if (faces.empty()) {
            size = img.width;
            first = path;
        } else if (img.width != size) {
            return Result<CubeMap>::failure(path + ": skybox faces differ in size (" + std::to_string(img.width) + " x " +
                                            std::to_string(img.height) + ", but " + first + " is " + std::to_string(size) +
                                            " x " + std::to_string(size) + ")");
        }
        faces.push_back(std::move(image.value()));
    }
    std::array<const std::uint8_t*, kCubeFaces> ptrs{};
    for (int f = 0; f < kCubeFaces; ++f) ptrs[std::size_t(f)] = faces[std::size_t(f)].rgba.data();
    return Result<CubeMap>(CubeMap::fromRgba8(size, ptrs));
}

} // namespace sr
