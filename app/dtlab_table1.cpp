// dtlab table1: the paper's experiment (Table 1, Figure 8) reproduced on headless GL (a GPU
// through EGL, or llvmpipe): uniform random points in the 1600 x 1600 box, the naive walk against
// the colour-ID buffer, with our other locators side by side; a log-log plot drawn by our own
// renderer (ImGui draw lists on the same context). Every output names the GL and the CPU.
#include "app/dtlab_common.h"

#include "core/engine/generators.h"
#include "core/engine/output_files.h"
#include "ui/gl/idbuffer_gl.h"
#include "ui/gl/imgui_gl.h"
#include "ui/gui.h"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

namespace dlab::cli {

namespace {

// ============================================================================================
// [SECTION] The methods and the paper's numbers
// ============================================================================================

struct Method {
    const char* name;  // the CSV column: exactly these names
    LocatorKind locator;
    OrderKind order;
};

// Input order is the paper's (uniform random points: input order is a random order).
constexpr Method kMethods[] = {
    {"naive", LocatorKind::Naive, OrderKind::Input},
    {"idbuffer-gl", LocatorKind::IdBufferGl, OrderKind::Input},
    {"idbuffer-gl-batched", LocatorKind::IdBufferGlBatched, OrderKind::Input},
    {"idbuffer-cpu", LocatorKind::IdBufferCpu, OrderKind::Input},
    {"walk", LocatorKind::Walk, OrderKind::Input},
    {"best", LocatorKind::Walk, OrderKind::Brio},
};
constexpr int kNumMethods = static_cast<int>(std::size(kMethods));

// Table 1 of the paper (Core 2 Duo 1.6 GHz, GeForce 8400M), ms; see shared/docs/PAPER-NOTES.md.
const std::map<std::size_t, std::pair<double, double>> kPaper = {
    {1024, {18, 67}},     {2048, {47, 125}},     {4096, {65, 219}},      {8192, {516, 453}},
    {16384, {1515, 953}}, {32768, {4531, 1959}}, {65536, {13063, 3422}}, {131072, {36766, 7469}},
};

struct Table1Args {
    std::string sizes = "1024,2048,4096,8192,16384,32768,65536,131072";
    int repeat = 3;
    std::string csv, png;
    int batch = 256;
    std::string readback = "batched";
    std::string sweep;  // batch sizes to try at the largest n
    std::string methods = "naive,idbuffer-gl,idbuffer-gl-batched,idbuffer-cpu,walk,best";
    int idBufferSize = 1600;
    std::uint64_t seed = 1;
};

// ============================================================================================
// [SECTION] Timing runs
// ============================================================================================

struct Run {
    double ms = 0;
    LocatorStats loc;
    ui::IdBufferGlStats gl;
};

ui::IdBufferGlOptions glOptionsFor(const Method& m, const Table1Args& a, int batch) {
    ui::IdBufferGlOptions g;
    g.width = g.height = a.idBufferSize;
    g.batch = batch;
    g.readback = m.locator == LocatorKind::IdBufferGl ? ui::GlReadback::OnePixel
                 : a.readback == "pipelined"          ? ui::GlReadback::Pipelined
                                                      : ui::GlReadback::Batched;
    return g;
}

// One triangulation, timed from the locator's creation (the GL buffer's allocation and clear,
// like the CPU buffer's in its reset) to the end of the run; the points are copied before.
Run runOnce(const std::vector<Vec2>& points, const Method& m, const Table1Args& a, int batch) {
    std::vector<Vec2> copy = points;
    InsertOptions o;
    o.locator = m.locator;
    o.order = m.order;
    o.seed = a.seed;
    o.locatorOptions.idBufferWidth = o.locatorOptions.idBufferHeight = a.idBufferSize;
    o.locatorOptions.idBufferBatch = batch;
    Run r;
    const auto t0 = std::chrono::steady_clock::now();
    std::unique_ptr<Locator> locator;
    ui::IdBufferGl* gl = nullptr;
    if (needsGl(m.locator)) {
        auto made = std::make_unique<ui::IdBufferGl>(headlessGl(), glOptionsFor(m, a, batch));
        gl = made.get();
        locator = std::move(made);
    }
    Inserter ins(std::move(copy), o, std::move(locator));
    if (gl) gl->followOrder(ins);
    ins.run();
    r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (ins.stats().inserted + ins.stats().duplicates != static_cast<std::int64_t>(points.size())) {
        fail(std::string(m.name) + ": the run lost points");
    }
    r.loc = ins.locator()->stats();
    if (gl) r.gl = gl->glStats();
    return r;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t k = v.size();
    return k == 0 ? 0.0 : k % 2 ? v[k / 2] : (v[k / 2 - 1] + v[k / 2]) / 2;
}

// The run whose time is the median (its statistics go into the second table).
const Run& medianRun(const std::vector<Run>& runs) {
    std::vector<std::size_t> idx(runs.size());
    for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
    std::sort(idx.begin(), idx.end(),
              [&](std::size_t x, std::size_t y) { return runs[x].ms < runs[y].ms; });
    return runs[idx[(idx.size() - 1) / 2]];
}

// A comma-separated list of counts between lo and hi, for the option `name`.
std::vector<std::size_t> parseCounts(const std::string& text, const char* name, std::size_t lo,
                                     std::size_t hi) {
    std::vector<std::size_t> sizes;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        std::size_t used = 0;
        unsigned long long v = 0;
        try {
            v = std::stoull(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != item.size() || item.empty() || v < lo || v > hi) {
            fail(std::string(name) + ": \"" + item + "\" is not a count between " +
                     std::to_string(lo) + " and " + std::to_string(hi),
                 2);
        }
        sizes.push_back(static_cast<std::size_t>(v));
    }
    if (sizes.empty()) fail(std::string(name) + ": give at least one count", 2);
    return sizes;
}

std::string fmtMs(double ms) {
    if (std::isnan(ms)) return "-";  // a method left out with --methods
    char b[32];
    std::snprintf(b, sizeof b, ms >= 100 ? "%.0f" : ms >= 10 ? "%.1f" : "%.2f", ms);
    return b;
}

// ============================================================================================
// [SECTION] The plot (Figure 8): ImGui draw lists rendered into a framebuffer object
// ============================================================================================

struct Series {
    std::string name;
    ImU32 colour;
    bool paper;                                     // dashed, hollow markers
    std::vector<std::pair<double, double>> points;  // (n, ms)
};

void dashedLine(ImDrawList* dl, ImVec2 a, ImVec2 b, ImU32 c, float width) {
    const float len = std::hypot(b.x - a.x, b.y - a.y);
    const float dash = 9, gap = 6;
    for (float s = 0; s < len; s += dash + gap) {
        const float e = std::min(len, s + dash);
        dl->AddLine(ImVec2(a.x + (b.x - a.x) * s / len, a.y + (b.y - a.y) * s / len),
                    ImVec2(a.x + (b.x - a.x) * e / len, a.y + (b.y - a.y) * e / len), c, width);
    }
}

// The plot's frame: the axes' extent in pixels and the data's, on log scales (log2 n on x,
// log10 ms on y), with the map from data to pixels.
struct PlotFrame {
    float left = 0, right = 0, top = 0, bottom = 0;
    double lx0 = 0, lx1 = 0, ly0 = 0, ly1 = 0;

    float x(double n) const {
        return static_cast<float>(left + (std::log2(n) - lx0) / (lx1 - lx0) * (right - left));
    }
    float y(double ms) const {
        return static_cast<float>(bottom - (std::log10(ms) - ly0) / (ly1 - ly0) * (bottom - top));
    }
    ImVec2 at(double n, double ms) const { return ImVec2(x(n), y(ms)); }
};

PlotFrame plotFrame(float W, float H, const std::vector<Series>& series) {
    double xmin = 1e300, xmax = 0, ymin = 1e300, ymax = 0;
    for (const Series& s : series) {
        for (auto [x, y] : s.points) {
            xmin = std::min(xmin, x);
            xmax = std::max(xmax, x);
            ymin = std::min(ymin, y);
            ymax = std::max(ymax, y);
        }
    }
    PlotFrame f;
    f.left = 110;
    f.right = W - 40;
    f.top = 90;
    f.bottom = H - 90;
    f.lx0 = std::floor(std::log2(xmin)) - 0.25;
    f.lx1 = std::ceil(std::log2(xmax)) + 0.25;
    f.ly0 = std::floor(std::log10(ymin));
    f.ly1 = std::ceil(std::log10(ymax));
    return f;
}

constexpr ImU32 kInk = IM_COL32(30, 30, 30, 255);
constexpr float kLabelSize = 17;

// Grid and ticks: decades (and 2..9 in between) on y, powers of two on x.
void drawGrid(ImDrawList* dl, ImFont* small, const PlotFrame& f) {
    const ImU32 grid = IM_COL32(225, 225, 225, 255), fine = IM_COL32(242, 242, 242, 255);
    char label[32];
    for (int d = static_cast<int>(f.ly0); d <= static_cast<int>(f.ly1); ++d) {
        for (int k = 2; k <= 9 && d < f.ly1; ++k) {
            const float y = f.y(k * std::pow(10.0, d));
            dl->AddLine(ImVec2(f.left, y), ImVec2(f.right, y), fine);
        }
        const float y = f.y(std::pow(10.0, d));
        dl->AddLine(ImVec2(f.left, y), ImVec2(f.right, y), grid);
        dl->AddLine(ImVec2(f.left - 6, y), ImVec2(f.left, y), kInk);
        if (d >= 0)
            std::snprintf(label, sizeof label, "%.0f", std::pow(10.0, d));
        else
            std::snprintf(label, sizeof label, "%g", std::pow(10.0, d));
        const ImVec2 ts = small->CalcTextSizeA(kLabelSize, 1e9f, 0, label);
        dl->AddText(small, kLabelSize, ImVec2(f.left - 10 - ts.x, y - ts.y / 2), kInk, label);
    }
    for (int e = static_cast<int>(std::ceil(f.lx0)); e <= static_cast<int>(std::floor(f.lx1));
         ++e) {
        const double n = std::ldexp(1.0, e);
        const float x = f.x(n);
        dl->AddLine(ImVec2(x, f.top), ImVec2(x, f.bottom), grid);
        dl->AddLine(ImVec2(x, f.bottom), ImVec2(x, f.bottom + 6), kInk);
        std::snprintf(label, sizeof label, "%.0f", n);
        const ImVec2 ts = small->CalcTextSizeA(kLabelSize, 1e9f, 0, label);
        dl->AddText(small, kLabelSize, ImVec2(x - ts.x / 2, f.bottom + 10), kInk, label);
    }
    dl->AddRect(ImVec2(f.left, f.top), ImVec2(f.right, f.bottom), kInk, 0, 0, 1.5f);
}

void drawAxisLabels(ImDrawList* dl, ImFont* font, const PlotFrame& f) {
    const char* xlabel = "number of points n (log scale)";
    const ImVec2 xs = font->CalcTextSizeA(20, 1e9f, 0, xlabel);
    dl->AddText(font, 20, ImVec2((f.left + f.right) / 2 - xs.x / 2, f.bottom + 40), kInk, xlabel);
    // The y label, one glyph under the other would be hard to read: write it rotated by hand.
    const char* ylabel = "time (ms, log scale)";
    const int vtxStart = dl->VtxBuffer.Size;
    const ImVec2 ys = font->CalcTextSizeA(20, 1e9f, 0, ylabel);
    const ImVec2 at(28, (f.top + f.bottom) / 2 + ys.x / 2);
    dl->AddText(font, 20, at, kInk, ylabel);
    // Rotate the glyphs just added by -90 degrees around `at`.
    for (int i = vtxStart; i < dl->VtxBuffer.Size; ++i) {
        ImDrawVert& v = dl->VtxBuffer[i];
        const float dx = v.pos.x - at.x, dy = v.pos.y - at.y;
        v.pos = ImVec2(at.x + dy, at.y - dx);
    }
}

// A series' line from a to b and its marker at c: ours solid with dots, the paper's dashed with
// hollow squares.
void drawSeriesLine(ImDrawList* dl, const Series& s, ImVec2 a, ImVec2 b) {
    if (s.paper)
        dashedLine(dl, a, b, s.colour, 2.5f);
    else
        dl->AddLine(a, b, s.colour, 2.5f);
}
void drawMarker(ImDrawList* dl, const Series& s, ImVec2 c) {
    if (s.paper)
        dl->AddRect(ImVec2(c.x - 5, c.y - 5), ImVec2(c.x + 5, c.y + 5), s.colour, 0, 0, 2.0f);
    else
        dl->AddCircleFilled(c, 5, s.colour);
}

void drawSeries(ImDrawList* dl, const PlotFrame& f, const std::vector<Series>& series) {
    dl->PushClipRect(ImVec2(f.left, f.top), ImVec2(f.right, f.bottom), true);
    for (const Series& s : series) {
        for (std::size_t i = 0; i + 1 < s.points.size(); ++i) {
            drawSeriesLine(dl, s, f.at(s.points[i].first, s.points[i].second),
                           f.at(s.points[i + 1].first, s.points[i + 1].second));
        }
        for (auto [n, ms] : s.points) drawMarker(dl, s, f.at(n, ms));
    }
    dl->PopClipRect();
}

// Legend, top left inside the plot (the curves start low on the left).
void drawLegend(ImDrawList* dl, ImFont* small, const PlotFrame& f,
                const std::vector<Series>& series) {
    float w = 0;
    for (const Series& s : series)
        w = std::max(w, small->CalcTextSizeA(kLabelSize, 1e9f, 0, s.name.c_str()).x);
    const float lx = f.left + 16, ly = f.top + 14, row = 25;
    dl->AddRectFilled(ImVec2(lx, ly), ImVec2(lx + w + 74, ly + row * series.size() + 12),
                      IM_COL32(255, 255, 255, 235));
    dl->AddRect(ImVec2(lx, ly), ImVec2(lx + w + 74, ly + row * series.size() + 12),
                IM_COL32(160, 160, 160, 255));
    for (std::size_t i = 0; i < series.size(); ++i) {
        const Series& s = series[i];
        const float y = ly + 8 + row * i + row / 2;
        drawSeriesLine(dl, s, ImVec2(lx + 10, y), ImVec2(lx + 50, y));
        drawMarker(dl, s, ImVec2(lx + 30, y));
        dl->AddText(small, kLabelSize, ImVec2(lx + 60, y - 10), kInk, s.name.c_str());
    }
}

void drawPlot(ImDrawList* dl, ImFont* font, ImFont* small, float W, float H,
              const std::vector<Series>& series, const std::string& title,
              const std::string& subtitle) {
    dl->AddRectFilled(ImVec2(0, 0), ImVec2(W, H), IM_COL32(255, 255, 255, 255));
    const PlotFrame f = plotFrame(W, H, series);
    dl->AddText(font, 26, ImVec2(f.left, 18), kInk, title.c_str());
    dl->AddText(small, kLabelSize, ImVec2(f.left, 52), IM_COL32(90, 90, 90, 255), subtitle.c_str());
    drawGrid(dl, small, f);
    drawAxisLabels(dl, font, f);
    drawSeries(dl, f, series);
    drawLegend(dl, small, f, series);
}

// Renders the plot headlessly into a framebuffer object on the process' GL context (ImGui's
// OpenGL3 backend, as in the GUI) and writes it as a PNG.
void writePlot(const std::string& path, const std::vector<Series>& series, const std::string& title,
               const std::string& subtitle) {
    const int W = 1400, H = 900;
    headlessGl();  // the context, current
    ImGuiContext* previous = ImGui::GetCurrentContext();
    ImGuiContext* ctx = ImGui::CreateContext();
    ImGui::SetCurrentContext(ctx);
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(W, H);
    io.DeltaTime = 1.0f / 60;
    ImFont* font = nullptr;
    ImFont* small = nullptr;
    const char* sans = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
    std::error_code ec;
    if (std::filesystem::is_regular_file(sans, ec)) {
        ImFontConfig cfg;
        cfg.OversampleH = 3;
        font = io.Fonts->AddFontFromFileTTF(sans, 26, &cfg);
        small = io.Fonts->AddFontFromFileTTF(sans, 17, &cfg);
    }
    if (!font) {
        font = io.Fonts->AddFontDefault();
        small = font;
    }
    std::string error;
    if (!ui::initImGuiGl(error)) fail("the plot: " + error);
    ui::newFrameImGuiGl();
    ImGui::NewFrame();
    drawPlot(ImGui::GetBackgroundDrawList(), font, small, W, H, series, title, subtitle);
    ImGui::Render();
    static constexpr float kWhite[4] = {1, 1, 1, 1};
    const std::vector<std::uint8_t> rgba =
        ui::renderImGuiOffscreenGl(ImGui::GetDrawData(), W, H, kWhite);
    ui::shutdownImGuiGl();
    ImGui::DestroyContext(ctx);
    ImGui::SetCurrentContext(previous);
    if (!ui::writePng(path, rgba, W, H, error)) fail(error);
}

// ============================================================================================
// [SECTION] The command
// ============================================================================================

using MethodSet = std::array<bool, kNumMethods>;

// --methods: the methods to time, by their CSV names.
MethodSet parseMethods(const std::string& text) {
    MethodSet on{};
    std::stringstream ss(text);
    for (std::string name; std::getline(ss, name, ',');) {
        int found = -1;
        for (int m = 0; m < kNumMethods; ++m) found = name == kMethods[m].name ? m : found;
        if (found < 0)
            fail("--methods: no method \"" + name +
                     "\" (naive, idbuffer-gl, idbuffer-gl-batched, idbuffer-cpu, walk, best)",
                 2);
        on[found] = true;
    }
    return on;
}

// --sweep: batch sizes K to time at the largest n (none when the option is absent).
std::vector<int> parseSweep(const std::string& text) {
    std::vector<int> sweep;
    if (text.empty()) return sweep;
    for (std::size_t k : parseCounts(text, "--sweep", 1, ui::IdBufferGlOptions::kMaxBatch))
        sweep.push_back(static_cast<int>(k));
    return sweep;
}

double percent(double part, double whole) { return whole > 0 ? 100.0 * part / whole : 0.0; }

// The medians of every size (ms, NaN for a method left out) and the runs they come from.
struct Timings {
    std::vector<std::array<double, kNumMethods>> table;
    std::vector<std::array<Run, kNumMethods>> detail;
};

// The CPU's model name (/proc/cpuinfo), or "an unknown CPU".
std::string cpuModel() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);) {
        const std::size_t colon = line.find(':');
        if (line.rfind("model name", 0) == 0 && colon != std::string::npos) {
            const std::size_t at = line.find_first_not_of(" \t", colon + 1);
            if (at != std::string::npos) return line.substr(at);
        }
    }
    return "an unknown CPU";
}

// Where the table was measured: "GL_RENDERER, OpenGL GL_VERSION (API); CPU MODEL, N cores".
std::string whereItRan() {
    const GlInfo& gl = glInfo();
    const unsigned cores = std::thread::hardware_concurrency();
    return gl.renderer + ", OpenGL " + gl.version + " (" + gl.api + "); " + cpuModel() + ", " +
           std::to_string(cores) + (cores == 1 ? " core" : " cores");
}

void printTableHeader(const Table1Args& args) {
    std::printf(
        "Table 1: uniform random points in the 1600 x 1600 box (seed %llu), exact boundary, %dx%d "
        "ID buffer,\n"
        "batched readback \"%s\" with K = %d; median of %d runs, ms. The paper: Core 2 Duo 1.6 "
        "GHz, GeForce "
        "8400M;\nhere: %s.\n\n",
        static_cast<unsigned long long>(args.seed), args.idBufferSize, args.idBufferSize,
        args.readback.c_str(), args.batch, args.repeat, whereItRan().c_str());
    std::printf("%8s | %11s %11s | %9s %12s %20s %13s %9s %9s\n", "n", "paper naive", "paper IDbuf",
                "naive", "idbuffer-gl", "idbuffer-gl-batched", "idbuffer-cpu", "walk", "best");
}

void printTableRow(std::size_t n, const std::array<double, kNumMethods>& row) {
    const auto paper = kPaper.find(n);
    const std::string pn = paper != kPaper.end() ? fmtMs(paper->second.first) : "-";
    const std::string pi = paper != kPaper.end() ? fmtMs(paper->second.second) : "-";
    std::printf("%8zu | %11s %11s | %9s %12s %20s %13s %9s %9s\n", n, pn.c_str(), pi.c_str(),
                fmtMs(row[0]).c_str(), fmtMs(row[1]).c_str(), fmtMs(row[2]).c_str(),
                fmtMs(row[3]).c_str(), fmtMs(row[4]).c_str(), fmtMs(row[5]).c_str());
    std::fflush(stdout);
}

// Every method on n points, `repeat` times, interleaved (load changes hit every method alike);
// appends the medians and the median runs to t.
void timeSize(const Table1Args& args, std::size_t n, const MethodSet& on, Timings& t,
              Progress& progress) {
    const std::vector<Vec2> points = generatePoints(Generator::Uniform, n, args.seed);
    std::array<std::vector<Run>, kNumMethods> runs;
    for (int r = 0; r < args.repeat; ++r) {
        for (int m = 0; m < kNumMethods; ++m) {
            if (!on[m]) continue;
            progress.advance(0, "n = " + std::to_string(n) + ", " + kMethods[m].name);
            runs[m].push_back(runOnce(points, kMethods[m], args, args.batch));
            progress.advance(static_cast<double>(n));
        }
    }
    std::array<double, kNumMethods> row{};
    std::array<Run, kNumMethods> med{};
    for (int m = 0; m < kNumMethods; ++m) {
        std::vector<double> ms;
        for (const Run& run : runs[m]) ms.push_back(run.ms);
        row[m] = on[m] ? median(ms) : std::nan("");
        if (on[m]) med[m] = medianRun(runs[m]);
    }
    t.table.push_back(row);
    t.detail.push_back(med);
}

void printLocatorLegend() {
    std::printf(
        "\nLocator statistics (the median run of each size):\n"
        "  hits    the pixel's triangle contained the point (no walk step)\n"
        "  walk    mean walk steps after a miss (including the points with no triangle under "
        "them)\n"
        "  none    points with no triangle under their pixel (outside the hull the pixels show)\n"
        "  stale   points whose id was read before earlier insertions changed the mesh (batched);\n"
        "          s.hits: such ids still right; steps: mean walk steps from such an id\n"
        "  read    share of the run's time in glReadPixels / gather / fence / map, including the "
        "wait\n"
        "          for the drawing that a read forces (as the paper measured readback)\n"
        "  draw    GL state, vertex arrays and draw calls; other: the rest (walk, split, flips)\n"
        "  painted triangles drawn into the buffer over the run, and their area in millions of\n"
        "          pixels (the buffer has 2.56 Mpx at 1600 x 1600)\n\n");
    std::printf("%8s  %-20s %7s %7s %6s %7s %7s %6s %6s %6s %6s %9s %7s\n", "n", "method", "hits",
                "walk", "none", "stale", "s.hits", "steps", "read", "draw", "other", "painted",
                "Mpx");
}

// Where the time of an ID-buffer method (m = 1..3) goes, and how good its pixels are.
void printLocatorRow(std::size_t n, int m, const Run& r) {
    const ui::IdBufferGlStats& g = r.gl;
    const LocatorStats& l = r.loc;
    const double hits = l.queries ? 100.0 * l.hits / l.queries : 0.0;
    const double walk =
        l.queries > l.hits ? static_cast<double>(l.missSteps) / (l.queries - l.hits) : 0.0;
    std::printf("%8zu  %-20s %6.1f%% %7.2f", n, kMethods[m].name, hits, walk);
    if (m == 3) {  // idbuffer-cpu: no GL
        std::printf("\n");
        return;
    }
    std::printf(" %5.1f%% %6.1f%% %6.1f%% %6.2f %5.1f%% %5.1f%% %5.1f%% %9llu %7.1f\n",
                percent(g.noPixel, l.queries), percent(g.staleQueries, l.queries),
                g.staleQueries ? 100.0 * g.staleHits / g.staleQueries : 0.0,
                g.staleQueries ? static_cast<double>(g.staleSteps) / g.staleQueries : 0.0,
                percent(g.readbackMs, r.ms), percent(g.paintMs, r.ms),
                percent(r.ms - g.readbackMs - g.paintMs, r.ms),
                static_cast<unsigned long long>(g.trianglesPainted), g.pixelsPainted / 1e6);
}

void printLocatorStats(const std::vector<std::size_t>& sizes, const MethodSet& on,
                       const Timings& t) {
    printLocatorLegend();
    for (std::size_t k = 0; k < sizes.size(); ++k) {
        for (int m = 1; m <= 3; ++m) {
            if (on[m]) printLocatorRow(sizes[k], m, t.detail[k][m]);
        }
    }
}

// At the largest size: batched readback against naive and against one pixel per insertion.
void printSpeedup(const std::vector<std::size_t>& sizes, const MethodSet& on, const Timings& t) {
    if (!(on[0] && on[1] && on[2])) return;
    const std::size_t last = sizes.size() - 1;
    const std::array<double, kNumMethods>& big = t.table[last];
    std::printf(
        "\nAt n = %zu: idbuffer-gl-batched is %.1fx faster than naive and %.1fx faster than "
        "idbuffer-gl "
        "(one pixel per insertion);\nidbuffer-gl spends %.0f%% of its time in readback (the "
        "paper: > 90%%).\n",
        sizes[last], big[0] / big[2], big[1] / big[2],
        percent(t.detail[last][1].gl.readbackMs, t.detail[last][1].ms));
}

// What one pixel read costs (idbuffer-gl at the largest size: its time in reads over its reads)
// against a naive walk's cost a point: the quantity that decides whether the paper's method, one
// read per insertion, can beat the walk, and one line that says whether it does here.
void printReadCost(const std::vector<std::size_t>& sizes, const MethodSet& on, const Timings& t) {
    if (!on[1]) return;
    const std::size_t last = sizes.size() - 1, n = sizes[last];
    const Run& one = t.detail[last][1];
    if (one.gl.reads == 0) return;
    const double readUs = 1000.0 * one.gl.readbackMs / static_cast<double>(one.gl.reads);
    std::printf("\nOne pixel read costs %.1f \u00b5s (idbuffer-gl at n = %zu: %llu reads, %.0f ms)",
                readUs, n, static_cast<unsigned long long>(one.gl.reads), one.gl.readbackMs);
    if (!on[0]) {
        std::printf(".\n");
        return;
    }
    const double walkUs = 1000.0 * t.table[last][0] / static_cast<double>(n);
    std::printf("; the naive walk %.1f \u00b5s a point.\n", walkUs);
    if (readUs < walkUs) {
        std::printf("A read costs less than a naive walk here: the paper's method can win.\n");
    } else if (on[2]) {
        const Run& batched = t.detail[last][2];
        std::printf(
            "A read costs more than a naive walk here: one read per insertion cannot win; the "
            "batched readback (%.2f \u00b5s of reading a point) %s.\n",
            1000.0 * batched.gl.readbackMs / static_cast<double>(n),
            t.table[last][2] < t.table[last][0] ? "beats the naive walk"
                                                : "does not beat it either");
    } else {
        std::printf(
            "A read costs more than a naive walk here: one read per insertion cannot "
            "win.\n");
    }
}

// idbuffer-gl-batched at n points for each batch size K of the sweep, and the fastest K.
void runSweep(const Table1Args& args, std::size_t n, const std::vector<int>& sweep) {
    const std::vector<Vec2> points = generatePoints(Generator::Uniform, n, args.seed);
    std::printf("\nBatch size K for idbuffer-gl-batched (\"%s\") at n = %zu, median of %d runs:\n",
                args.readback.c_str(), n, args.repeat);
    std::printf("%8s %10s %8s %9s %10s %8s\n", "K", "ms", "reads", "readback", "stale hit",
                "steps");
    double bestMs = 1e300;
    int bestK = 0;
    for (const int K : sweep) {
        std::vector<Run> runs;
        for (int r = 0; r < args.repeat; ++r) runs.push_back(runOnce(points, kMethods[2], args, K));
        const Run& med = medianRun(runs);
        const ui::IdBufferGlStats& b = med.gl;
        std::printf("%8d %10.1f %8llu %8.1f%% %9.1f%% %8.2f\n", K, med.ms,
                    static_cast<unsigned long long>(b.reads), percent(b.readbackMs, med.ms),
                    b.staleQueries ? 100.0 * b.staleHits / b.staleQueries : 0.0,
                    b.staleQueries ? static_cast<double>(b.staleSteps) / b.staleQueries : 0.0);
        if (med.ms < bestMs) {
            bestMs = med.ms;
            bestK = K;
        }
    }
    std::printf("best K = %d (%.1f ms)\n", bestK, bestMs);
}

void writeCsv(const std::string& path, const std::vector<std::size_t>& sizes, const MethodSet& on,
              const Timings& t) {
    writeTextFile(path, [&](std::ostream& out) {
        out << "# dtlab table1, median ms; " << whereItRan() << "\n";
        out << "n";
        for (int m = 0; m < kNumMethods; ++m) {
            if (on[m]) out << "," << kMethods[m].name;
        }
        out << "\n";
        char v[32];
        for (std::size_t k = 0; k < sizes.size(); ++k) {
            out << sizes[k];
            for (int m = 0; m < kNumMethods; ++m) {
                if (!on[m]) continue;
                std::snprintf(v, sizeof v, "%.3f", t.table[k][m]);
                out << "," << v;
            }
            out << "\n";
        }
    });
    std::printf("\nwrote %s\n", path.c_str());
}

// A method's name in the plot's legend.
std::string legendName(const Method& method, const Table1Args& args) {
    const std::string name = method.name;
    if (name == "best") return "best (brio + walk)";
    if (name == "naive") return "naive (walk from triangle 0)";
    if (name == "idbuffer-gl") return "idbuffer-gl (one pixel per insertion)";
    if (name == "idbuffer-gl-batched")
        return "idbuffer-gl-batched (K = " + std::to_string(args.batch) + ")";
    return name;
}

// The plot's curves: each method timed, then the paper's two (dashed).
std::vector<Series> plotSeries(const Table1Args& args, const std::vector<std::size_t>& sizes,
                               const MethodSet& on, const Timings& t) {
    const ImU32 colours[kNumMethods] = {IM_COL32(200, 40, 40, 255),  IM_COL32(230, 140, 20, 255),
                                        IM_COL32(30, 110, 200, 255), IM_COL32(120, 70, 170, 255),
                                        IM_COL32(40, 150, 70, 255),  IM_COL32(20, 20, 20, 255)};
    std::vector<Series> series;
    for (int m = 0; m < kNumMethods; ++m) {
        if (!on[m]) continue;
        Series s{legendName(kMethods[m], args), colours[m], false, {}};
        for (std::size_t k = 0; k < sizes.size(); ++k)
            s.points.push_back({static_cast<double>(sizes[k]), t.table[k][m]});
        series.push_back(std::move(s));
    }
    Series pn{"paper: naive walk (2008)", IM_COL32(200, 40, 40, 255), true, {}};
    Series pi{"paper: colour-ID buffer (2008)", IM_COL32(230, 140, 20, 255), true, {}};
    for (const auto& [n, v] : kPaper) {
        pn.points.push_back({static_cast<double>(n), v.first});
        pi.points.push_back({static_cast<double>(n), v.second});
    }
    series.push_back(std::move(pn));
    series.push_back(std::move(pi));
    return series;
}

void writeFigure(const Table1Args& args, const std::vector<std::size_t>& sizes, const MethodSet& on,
                 const Timings& t) {
    writePlot(args.png, plotSeries(args, sizes, on, t),
              "Incremental Delaunay: point location (the paper's Table 1 / Figure 8)",
              "uniform random points in the 1600 x 1600 box; ours: median of " +
                  std::to_string(args.repeat) + (args.repeat == 1 ? " run" : " runs") +
                  "; dashed: the paper's numbers (2008)\nours on " + whereItRan());
    std::printf("wrote %s\n", escapeControls(args.png).c_str());
}

void runTable1(const Table1Args& args) {
    const std::vector<std::size_t> sizes = parseCounts(args.sizes, "--sizes", 3, 1u << 20);
    const std::vector<int> sweep = parseSweep(args.sweep);
    const MethodSet on = parseMethods(args.methods);
    headlessGl();  // fail early, before minutes of timing, if there is no GL
    // Warm-up: each method once on a small set (llvmpipe compiles its shaders on first use).
    const std::vector<Vec2> warm = generatePoints(Generator::Uniform, 2000, args.seed + 1000);
    for (int m = 0; m < kNumMethods; ++m) {
        if (on[m] || (m == 2 && !sweep.empty())) runOnce(warm, kMethods[m], args, args.batch);
    }
    printTableHeader(args);
    Timings t;
    double work = 0;  // points inserted in all: about proportional to the time
    for (const std::size_t n : sizes)
        work += static_cast<double>(n) * args.repeat *
                static_cast<double>(std::count(on.begin(), on.end(), true));
    {
        Progress progress("table1", work);
        for (const std::size_t n : sizes) {
            timeSize(args, n, on, t, progress);
            progress.clear();  // the row on a line of its own; the progress comes back after it
            printTableRow(n, t.table.back());
        }
    }
    printLocatorStats(sizes, on, t);
    printSpeedup(sizes, on, t);
    printReadCost(sizes, on, t);
    if (!sweep.empty()) runSweep(args, sizes.back(), sweep);
    if (!args.csv.empty()) writeCsv(args.csv, sizes, on, t);
    if (!args.png.empty()) writeFigure(args, sizes, on, t);
}

}  // namespace

void addTable1(CLI::App& app) {
    auto args = std::make_shared<Table1Args>();
    CLI::App* cmd = app.add_subcommand(
        "table1",
        "The paper's Table 1 (naive walk vs colour-ID buffer) with our locators, on headless GL "
        "(--gl)");
    cmd->add_option("--sizes", args->sizes, "Point counts, comma-separated (3 .. 1048576)")
        ->capture_default_str();
    cmd->add_option("--repeat", args->repeat,
                    "Timed runs per size and method (the median is reported)")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    cmd->add_option("--csv", args->csv, "Write n and one column per method (ms) to this CSV file");
    cmd->add_option("--png", args->png,
                    "Write a log-log plot (the paper's Figure 8) to this PNG file");
    cmd->add_option("--batch", args->batch, "idbuffer-gl-batched: points per readback (K)")
        ->check(CLI::Range(1, ui::IdBufferGlOptions::kMaxBatch))
        ->capture_default_str();
    cmd->add_option("--readback", args->readback,
                    "idbuffer-gl-batched: batched | pipelined (read one batch ahead)")
        ->check(CLI::IsMember({"batched", "pipelined"}))
        ->capture_default_str();
    cmd->add_option("--methods", args->methods,
                    "Methods to time, comma-separated (the CSV has their columns)")
        ->capture_default_str();
    cmd->add_option(
        "--sweep", args->sweep,
        "Also time idbuffer-gl-batched at the largest size for these K (comma-separated)");
    cmd->add_option("--idbuffer-size", args->idBufferSize,
                    "Width and height of the ID buffers in pixels")
        ->check(CLI::Range(1, 16384))
        ->capture_default_str();
    cmd->add_option("--seed", args->seed, "Seed of the random points")->capture_default_str();
    addGlFlag(*cmd);
    cmd->parse_complete_callback(needGl);
    cmd->callback([args] { guarded([&] { runTable1(*args); }); });
}

}  // namespace dlab::cli
