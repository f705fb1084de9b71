// The menu bar: File (open a point file, the demo, quit), View (overlays, presentation mode),
// Generate (the inputs that broke other triangulators), Help.
#include "core/engine/generators.h"
#include "core/engine/io_read.h"
#include "core/teaching/lesson.h"
#include "ui/files/files.h"
#include "ui/lesson_player.h"
#include "ui/panels/panels.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <filesystem>
#include <string>

namespace dlab::ui {

namespace {

struct GeneratorChoice {
    Generator kind;
    const char* label;
    int defaultCount;
};

constexpr GeneratorChoice kGenerators[] = {
    {Generator::Uniform, "Uniform (the paper's 1600 box)", 200},
    {Generator::Clusters, "Clusters", 300},
    {Generator::Grid, "Grid (cocircular quadruples)", 100},
    {Generator::RotatedGrid, "Rotated grid", 100},
    {Generator::Ngon, "Regular N-gon (all cocircular)", 24},
    {Generator::Circle, "Points on a circle", 40},
    {Generator::Collinear, "Collinear runs", 60},
    {Generator::NearDuplicates, "Near-duplicates (1-4 ulps apart)", 60},
    {Generator::HugeTinyBox, "Tiny box at huge coordinates", 60},
    {Generator::AllCollinear, "All on one line", 20},
    {Generator::Gaussian, "Gaussian", 300},
    {Generator::UnevenClusters, "Clusters of very different sizes", 400},
    {Generator::Kuzmin, "Kuzmin (heavy-tailed)", 300},
    {Generator::LogRadial, "Radii over 12 decades", 300},
    {Generator::DiscInBox, "Dense disc in a sparse box", 300},
    {Generator::Curves, "On curves, bunched", 200},
    {Generator::Parabola, "On a parabola (all on the hull)", 60},
    {Generator::FacingArcs, "Two facing arcs", 80},
    {Generator::Spiral, "On a spiral", 120},
    {Generator::ConvexHull, "Convex position, exact", 60},
};

}  // namespace

namespace {

bool isPolyPath(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".poly";
}

// A planar straight-line graph: its points run with the user's options (the exact boundary: its
// segments are constrained on it), and each segment is an edit after the run, stepped like it.
bool loadPolyFile(AppState& st, const std::string& path) {
    PolyFile poly = readPolyFile(path);
    for (const std::string& w : poly.points.warnings) st.log(Message::Level::Warning, w);
    if (!poly.segments.empty() && st.userOptions.boundary != Boundary::Exact) {
        st.userOptions.boundary = Boundary::Exact;
        st.log(Message::Level::Info, path + ": segments are constrained on the exact boundary");
    }
    if (!st.loadUserPoints(std::move(poly.points.points), path)) return false;
    std::size_t constrained = 0;
    for (const auto& [a, b] : poly.segments) {
        std::string message;
        if (st.engine.edit(makeEdit(EditKind::Constrain, a, b), message))
            ++constrained;
        else
            st.log(Message::Level::Warning, path + ": segment " + std::to_string(a) + "-" +
                                                std::to_string(b) + " refused: " + message);
    }
    st.engine.seek(0);  // from the start: the insertions, then the segments
    if (!poly.segments.empty())
        st.log(Message::Level::Info, path + ": " + std::to_string(constrained) + " of " +
                                         std::to_string(poly.segments.size()) +
                                         " segments constrained after the run (End plays it all)");
    return true;
}

}  // namespace

bool loadPointFile(AppState& st, const std::string& path) {
    try {
        if (isPolyPath(path)) return loadPolyFile(st, path);
        PointSet set = readPointsFile(path);
        for (const std::string& w : set.warnings) st.log(Message::Level::Warning, w);
        return st.loadUserPoints(std::move(set.points), path);
    } catch (const InputError& e) {
        st.log(Message::Level::Error, std::string(e.what()) + " (nothing was changed)");
    } catch (const std::exception& e) {
        st.log(Message::Level::Error, path + ": " + e.what() + " (nothing was changed)");
    }
    return false;
}

namespace {

void ShowFileMenu(AppState& st) {
    if (!ImGui::BeginMenu("File")) return;
    if (ImGui::MenuItem("Open points, a session, a lesson or a trace...", "Ctrl+O"))
        st.files.dialog = FileState::Dialog::OpenFile;
    if (ImGui::MenuItem("Built-in demo")) loadDemo(st);
    ImGui::Separator();
    if (ImGui::MenuItem("Save points as .node / .csv..."))
        st.files.dialog = FileState::Dialog::SavePoints;
    if (ImGui::MenuItem("Save session...", "Ctrl+S"))
        st.files.dialog = FileState::Dialog::SaveSession;
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "Points, options, the step, view, selection and overlays in one JSON file:\nattach "
            "it to a bug report, or share a class");
    if (ImGui::MenuItem("Export mesh (.ele/.neigh, OFF, OBJ)..."))
        st.files.dialog = FileState::Dialog::ExportMesh;
    if (ImGui::MenuItem("Export SVG of the view..."))
        st.files.dialog = FileState::Dialog::ExportSvg;
    if (ImGui::MenuItem("Screenshot (PNG)", "F12")) st.files.screenshotRequested = true;
    if (ImGui::MenuItem("Animated GIF of steps...")) st.files.dialog = FileState::Dialog::ExportGif;
    ImGui::Separator();
    if (ImGui::MenuItem("Undo point edit", "Ctrl+Z", false, !st.undoPoints.empty())) st.undoEdit();
    if (ImGui::MenuItem("Redo point edit", "Ctrl+Y", false, !st.redoPoints.empty())) st.redoEdit();
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) st.quitRequested = true;
    ImGui::EndMenu();
}

void ShowViewMenu(AppState& st) {
    if (!ImGui::BeginMenu("View")) return;
    Overlays& o = st.overlays;
    ImGui::MenuItem("Fill triangles", nullptr, &o.fill);
    ImGui::MenuItem("Vertex ids", nullptr, &o.vertexIds);
    ImGui::MenuItem("Corner ids", nullptr, &o.cornerIds);
    ImGui::MenuItem("Triangle ids", nullptr, &o.triangleIds);
    ImGui::MenuItem("Walk path and line L", nullptr, &o.walk);
    ImGui::MenuItem("Edges still to test", nullptr, &o.flipQueue);
    ImGui::MenuItem("Their order (1 = tested next)", nullptr, &o.queueOrder);
    ImGui::MenuItem("The order they were pushed in (1 = first)", nullptr, &o.queuePushed);
    ImGui::MenuItem("Flipped edges", nullptr, &o.flipped);
    ImGui::MenuItem("Circumcircles", "C", &o.circumcircles);
    ImGui::MenuItem("Voronoi diagram", "V", &o.voronoi);
    ImGui::MenuItem("ID-buffer pixels (their centres)", nullptr, &o.idBufferGrid);
    ImGui::MenuItem("Queued points", nullptr, &o.pendingPoints);
    ImGui::MenuItem("Super-triangle (super mode)", nullptr, &o.virtualTriangles);
    ImGui::MenuItem("Validation marks (broken rules, edges not Delaunay yet)", nullptr,
                    &o.violations);
    ImGui::MenuItem("Legend", "L", &o.legend);
    ImGui::Separator();
    ImGui::MenuItem("Snap new points to grid", "G", &st.snapToGrid);
    ImGui::SetNextItemWidth(100);
    ImGui::InputDouble("Grid step", &st.gridStep, 0, 0, "%g");
    st.gridStep = std::max(st.gridStep, 1e-9);
    if (ImGui::MenuItem("Fit to data", "F")) st.fitPending = true;
    ImGui::Separator();
    ImGui::MenuItem("Presentation mode (large, high contrast)", nullptr, &st.presentation);
    ImGui::EndMenu();
}

// Every generator with its point count, and one seed for all.
void ShowGenerateMenu(AppState& st) {
    if (!ImGui::BeginMenu("Generate")) return;
    std::vector<int>& counts = st.dialogs.generatorCounts;
    counts.resize(std::size(kGenerators), 0);
    int& seed = st.dialogs.generatorSeed;
    ImGui::SetNextItemWidth(120);
    ImGui::InputInt("Seed", &seed);
    ImGui::Separator();
    for (std::size_t i = 0; i < std::size(kGenerators); ++i) {
        const GeneratorChoice& g = kGenerators[i];
        if (counts[i] == 0) counts[i] = g.defaultCount;
        ImGui::PushID(static_cast<int>(i));
        ImGui::SetNextItemWidth(120);
        ImGui::InputInt("##n", &counts[i], 10, 100);
        counts[i] = std::clamp(counts[i], 1, 5000000);
        ImGui::SameLine();
        if (ImGui::MenuItem(g.label)) {
            st.loadUserPoints(generatePoints(g.kind, static_cast<std::size_t>(counts[i]),
                                             static_cast<std::uint64_t>(std::max(0, seed))),
                              std::string(toString(g.kind)) + " (" + std::to_string(counts[i]) +
                                  " points, seed " + std::to_string(seed) + ")");
        }
        ImGui::PopID();
    }
    ImGui::EndMenu();
}

// The lessons in DLAB_LESSONS_DIR as (path, title), sorted by path.
std::vector<std::pair<std::string, std::string>> findLessons() {
    std::vector<std::pair<std::string, std::string>> list;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(DLAB_LESSONS_DIR, ec)) {
        if (entry.path().extension() != ".toml") continue;
        std::string title = entry.path().filename().string();
        try {
            const std::string p = entry.path().string();
            title = isTrackFile(p) ? "Lecture: " + loadTrack(p).title : loadLesson(p).title;
        } catch (const std::exception&) {
            title += " (cannot be read)";
        }
        list.emplace_back(entry.path().string(), title);
    }
    std::sort(list.begin(), list.end());
    return list;
}

void ShowLessonsMenu(AppState& st) {
    if (!ImGui::BeginMenu("Lessons")) return;
    auto& list = st.dialogs.lessons;
    if (list.empty()) list = findLessons();
    for (const auto& [path, title] : list) {
        const LessonState& L = st.lessonPlayer;
        const bool current =
            L.track ? L.track->file == path : L.lesson && L.progress.lesson == path;
        if (ImGui::MenuItem(title.c_str(), nullptr, current)) openLesson(st, path);
    }
    if (list.empty()) ImGui::TextDisabled("no lessons in %s", DLAB_LESSONS_DIR);
    ImGui::Separator();
    if (ImGui::MenuItem("Close the lesson", nullptr, false, st.lessonPlayer.lesson != nullptr))
        closeLesson(st);
    ImGui::EndMenu();
}

}  // namespace

void ShowMenuBar(AppState& st) {
    if (!ImGui::BeginMenuBar()) return;
    ShowFileMenu(st);
    ShowViewMenu(st);
    ShowGenerateMenu(st);
    ShowLessonsMenu(st);
    if (ImGui::BeginMenu("Help")) {
        if (ImGui::MenuItem("Shortcuts and conventions", "F1")) st.showHelp = true;
        ImGui::EndMenu();
    }
    ImGui::EndMenuBar();
}

}  // namespace dlab::ui
