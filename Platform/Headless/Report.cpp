// `softraster report`: time and error of every quality setting, as CSV, Markdown and an SVG plot.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <ostream>
#include <sstream>
#include <thread>

#include "Platform/Demo/ImageCompare.hpp"
#include "Platform/Headless/CommandArgs.hpp"
#include "Platform/Headless/Commands.hpp"
#include "Platform/Headless/Timing.hpp"
#include "Resources/FileIO.hpp"

namespace sr::headless {
namespace {

struct Setting {
    std::string knob, value; // e.g. "persp", "span16"; the reference has knob "reference"
    RenderSettings settings;
};

struct Row {
    Setting setting;
    TimingSummary time;
    demo::ImageError error;
};

// The most accurate settings (exact perspective, trilinear mipmaps, per-pixel lighting) and
// every knob varied alone from them.
std::vector<Setting> settingsToMeasure(RenderSettings base) {
    base.perspective = PerspectiveMode::Exact;
    base.filter = TextureFilter::Trilinear;
    base.shading = ShadingMode::Phong;
    std::vector<Setting> out{{"reference", "exact+trilinear+phong", base}};
    for (PerspectiveMode m : {PerspectiveMode::Affine}) {
        Setting s{"persp", perspectiveModeName(m), base};
        s.settings.perspective = m;
        out.push_back(s);
    }
    for (TextureFilter f : {TextureFilter::Bilinear, TextureFilter::Nearest}) {
        Setting s{"filter", filterName(f), base};
        s.settings.filter = f;
        out.push_back(s);
    }
    for (ShadingMode m : {ShadingMode::Gouraud, ShadingMode::Flat}) {
        Setting s{"shading", shadingModeName(m), base};
        s.settings.shading = m;
        out.push_back(s);
    }
    return out;
}

std::string fmt(double v, int decimals = 3) {
    if (std::isinf(v)) return "inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

std::string label(const Setting& s) { return s.knob == "reference" ? s.value : s.knob + "=" + s.value; }

// Points on the Pareto front: no other point is both faster and at least as accurate.
std::vector<bool> paretoFront(const std::vector<Row>& rows) {
    std::vector<bool> front(rows.size(), true);
    for (std::size_t i = 0; i < rows.size(); ++i)
        for (std::size_t j = 0; j < rows.size(); ++j) {
            if (i == j) continue;
            const bool faster = rows[j].time.median <= rows[i].time.median;
            const bool better = rows[j].error.psnrDb >= rows[i].error.psnrDb;
            const bool strictly = rows[j].time.median < rows[i].time.median || rows[j].error.psnrDb > rows[i].error.psnrDb;
            if (faster && better && strictly) front[i] = false;
        }
    return front;
}

// Error (PSNR, higher = better; identical images drawn at the top) against time per frame.
std::string svgPlot(const std::vector<Row>& rows, const std::vector<bool>& front, const std::string& title) {
    const double W = 760, H = 480, left = 70, right = 200, top = 40, bottom = 60;
    double tMin = 1e300, tMax = 0, pMin = 1e300, pMax = 0;
    for (const Row& r : rows) {
        tMin = std::min(tMin, r.time.median);
        tMax = std::max(tMax, r.time.median);
        if (std::isfinite(r.error.psnrDb)) {
            pMin = std::min(pMin, r.error.psnrDb);
            pMax = std::max(pMax, r.error.psnrDb);
        }
    }
    if (pMax < pMin) pMin = pMax = 40;
    const double pTop = pMax + 6; // "identical" line
    pMin = std::max(0.0, pMin - 3);
    if (tMax <= tMin) tMax = tMin + 1;
    const double tPad = 0.08 * (tMax - tMin);
    tMin = std::max(0.0, tMin - tPad);
    tMax += tPad;
    auto X = [&](double t) { return left + (t - tMin) / (tMax - tMin) * (W - left - right); };
    auto Y = [&](double p) { return top + (pTop - std::min(p, pTop)) / (pTop - pMin) * (H - top - bottom); };
    std::ostringstream s;
    s << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H
      << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' fill='white'/>\n";
    s << "<text x='" << W / 2 << "' y='22' text-anchor='middle' font-size='15'>" << title << "</text>\n";
    s << "<line x1='" << left << "' y1='" << H - bottom << "' x2='" << W - right << "' y2='" << H - bottom
      << "' stroke='black'/>\n<line x1='" << left << "' y1='" << top << "' x2='" << left << "' y2='" << H - bottom
      << "' stroke='black'/>\n";
    for (int k = 0; k <= 4; ++k) {
        const double t = tMin + (tMax - tMin) * k / 4, p = pMin + (pMax + 6 - pMin) * k / 4;
        s << "<text x='" << X(t) << "' y='" << H - bottom + 18 << "' text-anchor='middle'>" << fmt(t, 2) << "</text>\n";
        s << "<text x='" << left - 8 << "' y='" << Y(p) + 4 << "' text-anchor='end'>" << fmt(p, 1) << "</text>\n";
    }
    s << "<text x='" << (left + W - right) / 2 << "' y='" << H - 15 << "' text-anchor='middle'>ms per frame (median)</text>\n";
    s << "<text transform='translate(18," << (top + H - bottom) / 2 << ") rotate(-90)' text-anchor='middle'>"
      << "PSNR vs most accurate (dB, top = identical)</text>\n";
    // The Pareto front as a step line through its points, fastest first.
    std::vector<std::size_t> idx;
    for (std::size_t i = 0; i < rows.size(); ++i)
        if (front[i]) idx.push_back(i);
    std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return rows[a].time.median < rows[b].time.median; });
    s << "<polyline fill='none' stroke='#2a7' stroke-width='2' points='";
    for (std::size_t i : idx) s << X(rows[i].time.median) << "," << Y(rows[i].error.psnrDb) << " ";
    s << "'/>\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const double x = X(rows[i].time.median), y = Y(rows[i].error.psnrDb);
        s << "<circle cx='" << x << "' cy='" << y << "' r='5' fill='" << (front[i] ? "#2a7" : "#888") << "'/>\n";
        s << "<text x='" << x + 8 << "' y='" << y - 6 << "'>" << label(rows[i].setting) << (front[i] ? " *" : "")
          << "</text>\n";
    }
    s << "<text x='" << W - right + 10 << "' y='" << top + 10 << "'>green, *: Pareto front</text>\n</svg>\n";
    return s.str();
}

Status writeText(const std::string& path, const std::string& text) { return writeFileBytes(path, text.data(), text.size()); }

} // namespace

int runReport(const std::vector<std::string>& args, Streams io) {
    auto parsed = parseCommandArgs(Subcommand::Report, args, io.err);
    if (!parsed) return parsed.exitCode;
    CommandArgs& a = *parsed.args;
    if (a.help) {
        io.out << usage(Subcommand::Report);
        return kExitOk;
    }
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::u8path(a.outDir), ec);
    if (ec) {
        io.err << "softraster report: cannot create " << a.outDir << ": " << ec.message() << "\n";
        return kExitFailure;
    }
    auto prepared = prepareScene(a, io.err);
    if (!prepared) return kExitFailure;
    PreparedScene& p = *prepared;

    const std::vector<Setting> settings = settingsToMeasure(p.settings);
    FrameBuffer reference;
    std::vector<Row> rows;
    for (std::size_t k = 0; k < settings.size(); ++k) {
        const Setting& s = settings[k];
        if (!a.quiet) {
            io.err << (io.progress ? "\r" : "") << "softraster report: [" << (k + 1) << "/" << settings.size() << "] "
                   << label(s) << (io.progress ? "                    " : "\n");
            io.err.flush();
        }
        auto frame = [&] { demo::renderFrame(p.context, p.scene, p.view, s.settings); };
        Row row{s, summarise(timeFrames(a.warmup, a.frames, frame)), {}};
        frame();
        if (k == 0) reference = p.framebuffer;
        row.error = demo::compareImages(reference, p.framebuffer);
        rows.push_back(row);
    }
    if (!a.quiet && io.progress) io.err << "\n";

    const std::vector<bool> front = paretoFront(rows);
    const std::string scene = a.scene.obj.empty() ? std::string("built-in scene") : a.scene.obj;
    const std::string machine = std::to_string(std::thread::hardware_concurrency()) + " hardware threads, " +
                                std::to_string(p.threadsUsed) + " render thread";
    std::ostringstream csv, md;
    csv << "knob,value,ms_median,ms_min,psnr_db,max_abs,differing_share,pareto\n";
    md << "# SoftRaster quality report\n\n"
       << "Scene: " << scene << ", " << a.scene.width << "x" << a.scene.height << ", "
       << p.scene.scene.triangleCount() << " triangles, cull " << cullModeName(p.settings.cull) << ". "
       << "Machine: " << machine << ". Median of " << a.frames << " frames after " << a.warmup
       << " warm-up frames per setting.\n\n"
       << "Each knob is varied alone from the most accurate setting (exact perspective, trilinear "
          "filtering, Phong shading); errors are against that image.\n\n"
       << "| setting | ms/frame (median) | ms/frame (min) | PSNR dB | max abs | differing pixels | Pareto |\n"
       << "|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const Row& r = rows[i];
        csv << r.setting.knob << "," << r.setting.value << "," << fmt(r.time.median) << "," << fmt(r.time.min) << ","
            << fmt(r.error.psnrDb, 2) << "," << r.error.maxAbs << "," << fmt(r.error.differingShare, 5) << ","
            << (front[i] ? 1 : 0) << "\n";
        md << "| " << label(r.setting) << " | " << fmt(r.time.median) << " | " << fmt(r.time.min) << " | "
           << fmt(r.error.psnrDb, 2) << " | " << r.error.maxAbs << " | " << fmt(100.0 * r.error.differingShare, 2)
           << "% | " << (front[i] ? "yes" : "") << " |\n";
    }
    md << "\nPlot: `report.svg` (error against time, the Pareto front labelled). Depth format (reversed-Z float32) and "
          "sub-pixel precision (8 bits) are fixed by design and have no setting.\n";
    const std::string base = a.outDir + "/report";
    for (const auto& [path, text] : {std::pair<std::string, std::string>{base + ".csv", csv.str()},
                                     {base + ".md", md.str()},
                                     {base + ".svg", svgPlot(rows, front, "SoftRaster: error vs time, " + scene)}}) {
        const Status s = writeText(path, text);
        if (!s) {
            io.err << "softraster report: " << s.error() << "\n";
            return kExitFailure;
        }
        io.out << path << "\n";
    }
    return kExitOk;
}

} // namespace sr::headless
