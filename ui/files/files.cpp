// Files: opening and saving points, sessions, mesh and view exports, captures, autosave and
// recovery.
//
// Index
//   [SECTION] Errors, opening, saving points and sessions
//   [SECTION] Mesh exports
//   [SECTION] SVG of the current view
//   [SECTION] Captures (PNG, GIF)
//   [SECTION] Autosave and recovery
#include "ui/files/files.h"

#include "core/engine/text_util.h"

#include "core/engine/io_write.h"
#include "core/engine/mesh_build.h"
#include "core/engine/mesh_read.h"
#include "core/teaching/describe.h"
#include "ui/files/gif_export.h"
#include "ui/files/session.h"
#include "ui/gui.h"
#include "ui/lesson_player.h"
#include "ui/panels/panels.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <ostream>

namespace dlab::ui {

namespace fs = std::filesystem;

namespace {

std::string lowerExtension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

// Whether the file's first non-blank character is '{' (a session whatever its name).
bool looksLikeJson(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    char c = 0;
    while (in.get(c)) {
        if (!std::isspace(static_cast<unsigned char>(c))) return c == '{';
    }
    return false;
}

// A corner table {"G", "V", ...} or Delaunator's {"coords", "triangles", ...}, by the keys in
// its first 64 KiB (a session has neither pair).
bool looksLikeMeshJson(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string head(64 * 1024, '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
    auto has = [&](const char* key) { return head.find(key) != std::string::npos; };
    return (has("\"coords\"") && has("\"triangles\"")) || (has("\"G\"") && has("\"V\""));
}

// Runs a writer; a failure becomes one fileError line.
bool writeFile(AppState& st, const std::string& path,
               const std::function<void(std::ostream&)>& body) {
    try {
        std::error_code ec;
        const fs::path parent = fs::path(path).parent_path();
        if (!parent.empty()) fs::create_directories(parent, ec);
        writeTextFile(path, body);
    } catch (const std::exception& e) {
        fileError(st, e.what());
        return false;
    }
    return true;
}

}  // namespace

// ============================================================================================
// [SECTION] Errors, opening, saving points and sessions
// ============================================================================================

void fileError(AppState& st, const std::string& line) {
    st.log(Message::Level::Error, line);
    st.files.notice = line;
}

bool openFile(AppState& st, const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) {
        fileError(st, path + ": no such file");
        return false;
    }
    const fs::file_status status = fs::status(path, ec);
    if (fs::is_directory(status)) {
        fileError(st, path + ": is a folder, not a file");
        return false;
    }
    if (!ec && !fs::is_regular_file(status)) {  // a FIFO would block, a device never end
        fileError(st, path + ": is a pipe, device or socket, not a regular file");
        return false;
    }
    bool ok = false;
    if (lowerExtension(path) == ".toml") {
        const std::size_t before = st.messages.size();
        ok = openLesson(st, path);
        if (!ok)
            st.files.notice =
                st.messages.size() > before ? st.messages.back().text : path + ": cannot be read";
    } else if (lowerExtension(path) == ".jsonl") {
        ok = openStudentTrace(st, path);  // it reported its own error
    } else if (isMeshPath(path) && lowerExtension(path) != ".json") {
        const std::size_t before = st.messages.size();
        ok = openMeshFile(st, path);
        if (!ok)
            st.files.notice =
                st.messages.size() > before ? st.messages.back().text : path + ": cannot be read";
    } else if (lowerExtension(path) == ".json" || looksLikeJson(path)) {
        // A session, or a mesh as JSON (a corner table, Delaunator's output): told apart by
        // their keys.
        std::string error;
        ok = looksLikeMeshJson(path) ? openMeshFile(st, path) : loadSession(st, path, error);
        if (!ok && !error.empty()) fileError(st, error + " (nothing was changed)");
        if (!ok && error.empty()) st.files.notice = st.messages.back().text;
    } else {
        const std::size_t before = st.messages.size();
        ok = loadPointFile(st, path);
        // loadPointFile logged the error line: show it over the canvas too.
        if (!ok)
            st.files.notice =
                st.messages.size() > before ? st.messages.back().text : path + ": cannot be read";
    }
    if (ok) st.files.notice.clear();
    return ok;
}

bool savePoints(AppState& st, const std::string& path) {
    const std::vector<Vec2>& pts = st.engine.points();
    const std::string ext = lowerExtension(path);
    bool ok = false;
    if (ext == ".node") {
        ok = writeFile(st, path, [&](std::ostream& os) { writeNode(os, pts); });
    } else if (ext == ".csv" || ext == ".xy" || ext == ".txt") {
        ok = writeFile(st, path, [&](std::ostream& os) {
            os << "# Delaunay Lab points: x,y (shortest decimals that read back bit-exact)\n";
            std::string line;
            for (const Vec2& p : pts) {
                line.clear();
                appendShortest(line, p.x);
                line += ',';
                appendShortest(line, p.y);
                line += '\n';
                os << line;
            }
        });
    } else {
        fileError(st, path + ": unknown point format \"" + ext + "\" (save as .node or .csv)");
        return false;
    }
    if (ok)
        st.log(Message::Level::Info, "saved " + std::to_string(pts.size()) + " points to " + path);
    return ok;
}

bool saveSessionFile(AppState& st, const std::string& path) {
    std::string error;
    if (!saveSession(st, path, error)) {
        fileError(st, error);
        return false;
    }
    st.log(Message::Level::Info, "saved the session (" + std::to_string(st.engine.points().size()) +
                                     " points, operation " + std::to_string(st.engine.position()) +
                                     ") to " + path);
    return true;
}

// ============================================================================================
// [SECTION] Mesh exports
// ============================================================================================

Mesh exportableMesh(const Engine& e) {
    const Mesh& m = e.mesh();
    const Inserter& ins = e.inserter();
    if (!e.showsVirtual()) return m;
    Mesh out;
    out.G.assign(m.G.begin(),
                 m.G.begin() + std::min<std::ptrdiff_t>(m.numVertices(), ins.firstVirtual()));
    for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
        if (e.isVirtualTriangle(t)) continue;
        out.V.insert(out.V.end(), m.V.begin() + 3 * t, m.V.begin() + 3 * t + 3);
    }
    computeOpposites(out);
    return out;
}

bool exportMesh(AppState& st, const std::string& path, MeshFormat format) {
    Mesh m;
    try {
        m = exportableMesh(st.engine);
    } catch (const std::exception& e) {
        fileError(st, path + ": cannot export this mesh: " + e.what());
        return false;
    }
    std::string what;
    bool ok = false;
    switch (format) {
        case MeshFormat::Triangle: {
            fs::path base(path);
            const std::string ext = lowerExtension(path);
            if (ext == ".ele" || ext == ".node" || ext == ".neigh") base.replace_extension();
            const std::string b = base.string();
            ok = writeFile(st, b + ".node", [&](std::ostream& os) { writeNode(os, m.G); }) &&
                 writeFile(st, b + ".ele", [&](std::ostream& os) { writeEle(os, m); }) &&
                 writeFile(st, b + ".neigh", [&](std::ostream& os) { writeNeigh(os, m); });
            what = b + ".node, .ele and .neigh";
            break;
        }
        case MeshFormat::Off:
            ok = writeFile(st, path, [&](std::ostream& os) { writeOff(os, m); });
            what = path;
            break;
        case MeshFormat::Obj:
            ok = writeFile(st, path, [&](std::ostream& os) { writeObj(os, m); });
            what = path;
            break;
    }
    if (ok) {
        st.log(Message::Level::Info,
               "exported " + std::to_string(m.numTriangles()) + " triangles to " + what +
                   (!st.engine.showsVirtual()
                        ? ""
                        : " (the mesh at this step, virtual triangles left out)"));
    }
    return ok;
}

// ============================================================================================
// [SECTION] SVG of the current view
// ============================================================================================

namespace {

struct SvgScene {
    const AppState& st;
    std::ostream& os;
    double w, h;
    bool inView(glm::dvec2 a, glm::dvec2 b) const {
        return std::max(a.x, b.x) >= 0 && std::min(a.x, b.x) <= w && std::max(a.y, b.y) >= 0 &&
               std::min(a.y, b.y) <= h;
    }
    glm::dvec2 at(Vec2 p) const { return st.view.toScreen(p) - st.view.origin; }
    bool drawable(std::int32_t v) const {
        const Engine& e = st.engine;
        if (v < 0 || v >= e.mesh().numVertices()) return false;
        if (!e.showsVirtual() || !e.isVirtual(v)) return true;
        return st.engine.options().boundary == Boundary::Super &&
               st.overlays.virtualTriangles;  // ghosts have no place
    }
    void line(std::int32_t a, std::int32_t b) const {
        if (!drawable(a) || !drawable(b)) return;
        const Mesh& m = st.engine.mesh();
        const glm::dvec2 p = at(m.G[a]), q = at(m.G[b]);
        if (!inView(p, q)) return;
        char buf[160];
        std::snprintf(buf, sizeof buf, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>\n",
                      p.x, p.y, q.x, q.y);
        os << buf;
    }
    void triangle(std::int32_t t, const char* fill) const {
        const Mesh& m = st.engine.mesh();
        if (t < 0 || t >= m.numTriangles()) return;
        glm::dvec2 p[3];
        for (int k = 0; k < 3; ++k) {
            if (!drawable(m.V[3 * t + k])) return;
            p[k] = at(m.G[m.V[3 * t + k]]);
        }
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "<polygon points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f\" fill=\"%s\"/>\n", p[0].x,
                      p[0].y, p[1].x, p[1].y, p[2].x, p[2].y, fill);
        os << buf;
    }
};

// The current operation's triangles, under the edges (as on the canvas).
void writeHighlight(const SvgScene& s, const Op* op) {
    const Engine& e = s.st.engine;
    const Mesh& m = e.mesh();
    s.os << "<g id=\"highlight\" stroke=\"none\">\n";
    if (op && s.st.overlays.walk) {
        switch (op->type) {
            case OpType::LocateStep:
            case OpType::Located:
                for (std::int32_t t : e.walkPath()) s.triangle(t, "#fff4be");
                break;
            case OpType::Split:
                s.triangle(op->a, "#d6eac8");
                s.triangle(op->trianglesBefore, "#c8e0f8");
                s.triangle(op->trianglesBefore + 1, "#f0d6ec");
                break;
            case OpType::SplitEdge:
                s.triangle(tri(op->a), "#d6eac8");
                s.triangle(op->trianglesBefore, "#c8e0f8");
                if (op->b != kNone) {
                    s.triangle(tri(op->b), "#f0d6ec");
                    s.triangle(op->trianglesBefore + 1, "#d6eac8");
                }
                break;
            case OpType::Flip:
                if (op->a >= 0 && op->a < m.numCorners()) s.triangle(tri(op->a), "#c8e0f8");
                if (op->b >= 0 && op->b < m.numCorners()) s.triangle(tri(op->b), "#f0d6ec");
                break;
            default: break;
        }
    }
    s.os << "</g>\n";
}

// Every edge once, then the edges flipped so far.
void writeEdges(const SvgScene& s) {
    const Mesh& m = s.st.engine.mesh();
    s.os << "<g id=\"edges\" stroke=\"#464e60\" stroke-width=\"1\">\n";
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        const std::int32_t o = m.O[c];
        if (o != kNone && o < c) continue;  // each interior edge once
        s.line(m.V[next(c)], m.V[prev(c)]);
    }
    s.os << "</g>\n<g id=\"flipped\" stroke=\"#d72828\" stroke-width=\"2.5\">\n";
    if (s.st.overlays.flipped) {
        for (const VertexEdge& fe : s.st.engine.flippedEdges()) s.line(fe.a, fe.b);
    }
    s.os << "</g>\n";
}

// An in-circle test: the edge tested, and the circle of the triangle across it in the verdict's
// colour.
void writeInCircleTest(const SvgScene& s, const Op& op) {
    const Mesh& m = s.st.engine.mesh();
    s.os << "<g id=\"test\" stroke=\"#f07800\" stroke-width=\"3.5\" fill=\"none\">\n";
    s.line(m.V[next(op.a)], m.V[prev(op.a)]);
    const std::int32_t b = op.b;
    if (b >= 0 && b < m.numCorners()) {
        const std::int32_t t = tri(b);
        bool real = true;  // a ghost triangle's "circle" is a half-plane: not drawn
        for (int k = 0; k < 3; ++k) real &= s.drawable(m.V[3 * t + k]);
        if (real) {
            const Vec2 cc = circumcenter(m.G[m.V[3 * t]], m.G[m.V[3 * t + 1]], m.G[m.V[3 * t + 2]]);
            const double r =
                std::hypot(cc.x - m.G[m.V[3 * t]].x, cc.y - m.G[m.V[3 * t]].y) * s.st.view.scale;
            const glm::dvec2 q = s.at(cc);
            if (std::isfinite(r) && std::isfinite(q.x) && std::isfinite(q.y) && r < 1e7) {
                char buf[200];
                std::snprintf(buf, sizeof buf,
                              "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" stroke=\"%s\"/>\n", q.x,
                              q.y, r, op.sign > 0 ? "#d72828" : "#1e963c");
                s.os << buf;
            }
        }
    }
    s.os << "</g>\n";
}

// Points: inserted (filled), queued (hollow), the one being inserted (orange), duplicates
// (red); their ids when the overlay shows them and they are few.
void writePoints(const SvgScene& s) {
    const Engine& e = s.st.engine;
    s.os << "<g id=\"points\">\n";
    const auto& states = e.pointStates();
    const auto& pts = e.points();
    const bool ids = s.st.overlays.vertexIds && pts.size() <= 2000;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const glm::dvec2 q = s.at(pts[i]);
        if (q.x < -10 || q.y < -10 || q.x > s.w + 10 || q.y > s.h + 10) continue;
        const char* style = "fill=\"#14141e\"";
        switch (states[i]) {
            case Engine::PointState::Inserted: break;
            case Engine::PointState::Pending:
                if (!s.st.overlays.pendingPoints) continue;
                style = "fill=\"none\" stroke=\"#8c8c96\" stroke-width=\"1.5\"";
                break;
            case Engine::PointState::Current: style = "fill=\"#f07800\""; break;
            case Engine::PointState::Skipped: style = "fill=\"#c81e1e\""; break;
            case Engine::PointState::Removed: continue;  // no longer in the mesh
        }
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "<circle data-id=\"%zu\" cx=\"%.2f\" cy=\"%.2f\" r=\"4\" %s/>\n", i, q.x, q.y,
                      style);
        s.os << buf;
        if (ids) {
            std::snprintf(
                buf, sizeof buf,
                "<text x=\"%.2f\" y=\"%.2f\" font-size=\"13\" fill=\"#193ca0\">%zu</text>\n",
                q.x + 6, q.y - 6, i);
            s.os << buf;
        }
    }
    s.os << "</g>\n";
}

}  // namespace

void writeViewSvg(std::ostream& os, const AppState& st) {
    const Engine& e = st.engine;
    const Mesh& m = e.mesh();
    const SvgScene s{st, os, std::max(1.0, st.view.size.x), std::max(1.0, st.view.size.y)};
    const Op* op = e.current();
    const std::string caption =
        op ? "[" + std::to_string(e.position() - 1) + "] " + toString(op->type) + ": " +
                 describe(*op, e.inserter())
           : std::to_string(e.points().size()) + " points, nothing inserted yet";
    char head[256];
    std::snprintf(head, sizeof head,
                  "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
                  "viewBox=\"0 0 %.0f %.0f\">\n",
                  s.w, s.h, s.w, s.h);
    os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" << head;
    os << "<title>" << xmlEscape("Delaunay Lab - " + st.source + " - " + caption) << "</title>\n";
    os << "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
    writeHighlight(s, op);
    writeEdges(s);
    if (op && op->type == OpType::InCircleTest && op->a >= 0 && op->a < m.numCorners())
        writeInCircleTest(s, *op);
    writePoints(s);
    os << "<text x=\"8\" y=\"20\" font-family=\"sans-serif\" font-size=\"16\" fill=\"#000000\">"
       << xmlEscape(caption) << "</text>\n";
    os << "</svg>\n";
}

bool exportViewSvg(AppState& st, const std::string& path) {
    const bool ok = writeFile(st, path, [&](std::ostream& os) { writeViewSvg(os, st); });
    if (ok) st.log(Message::Level::Info, "wrote the view to " + escapeControls(path));
    return ok;
}

// ============================================================================================
// [SECTION] Captures (PNG, GIF)
// ============================================================================================

bool saveScreenshotFile(Gui& gui, std::string path) {
    AppState& st = gui.state();
    if (path.empty()) {
        const std::time_t now = std::time(nullptr);
        char stamp[32];
        std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
        const fs::path folder =
            st.files.screenshotFolder.empty() ? fs::path(".") : fs::path(st.files.screenshotFolder);
        std::error_code ec;
        fs::path p = folder / (std::string("delaunay-lab-") + stamp + ".png");
        for (int k = 2; fs::exists(p, ec); ++k)
            p = folder / (std::string("delaunay-lab-") + stamp + "-" + std::to_string(k) + ".png");
        path = p.string();
    }
    // The message names the file wherever the program was started from.
    std::error_code ec;
    if (const fs::path full = fs::absolute(path, ec); !ec) path = full.lexically_normal().string();
    std::string error;
    if (!gui.saveScreenshot(path, error)) {
        fileError(st, error.find(path) == std::string::npos ? path + ": " + error : error);
        return false;
    }
    st.log(Message::Level::Info, "screenshot: " + path);
    return true;
}

void serviceCaptures(Gui& gui) {
    AppState& st = gui.state();
    if (st.files.screenshotRequested) {
        st.files.screenshotRequested = false;
        saveScreenshotFile(gui);
    }
    if (st.files.gif) {
        const GifRequest req = *st.files.gif;
        st.files.gif.reset();
        std::string error;
        const int frames = exportStepsGif(gui, req, error);
        if (frames == 0)
            fileError(st, error);
        else
            st.log(Message::Level::Info, "wrote " + escapeControls(req.path) + ": " +
                                             std::to_string(frames) + " frames, operations " +
                                             std::to_string(req.from) + " to " +
                                             std::to_string(req.to));
    }
}

// ============================================================================================
// [SECTION] Autosave and recovery
// ============================================================================================

namespace {

// Above this many points the autosave is skipped (a file of several 10 MB after every edit).
constexpr std::size_t kAutosaveLimit = Engine::kHistoryLimit;

std::string commOf(const std::string& pid) {
    std::ifstream in("/proc/" + pid + "/comm");
    std::string s;
    std::getline(in, s);
    return s;
}

// Whether another instance of this program still runs as `pid` (its autosave is not orphaned).
bool instanceAlive(long pid) {
    if (pid <= 0) return false;
    if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno != EPERM) return false;
    // A live pid may have been reused by an unrelated program.
    return commOf(std::to_string(pid)) == commOf("self");
}

}  // namespace

std::string defaultAutosaveFolder() {
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x)
        return std::string(x) + "/delaunay-lab";
    if (const char* h = std::getenv("HOME"); h && *h)
        return std::string(h) + "/.cache/delaunay-lab";
    return {};
}

void enableAutosave(AppState& st, const std::string& folder) {
    FileState& f = st.files;
    if (folder.empty()) {
        f.autosavePath.clear();
        return;
    }
    std::error_code ec;
    fs::create_directories(folder, ec);
    f.autosavePath =
        (fs::path(folder) / ("autosave-" + std::to_string(::getpid()) + ".json")).string();
    f.autosaved = st.engine.points();
}

void saveAutosave(AppState& st) {
    FileState& f = st.files;
    if (f.autosavePath.empty() || !f.recoveryPath.empty()) return;
    const std::vector<Vec2>& pts = st.engine.points();
    if (pts.size() > kAutosaveLimit) {
        if (!f.autosaveTooBig) {
            st.log(Message::Level::Info,
                   "autosave is off above " + std::to_string(kAutosaveLimit) + " points");
            f.autosaveTooBig = true;
        }
        return;
    }
    f.autosaveTooBig = false;
    std::vector<std::string> edits = editTexts(st.engine);
    if (pts == f.autosaved && edits == f.autosavedEdits) return;
    f.autosaved = pts;  // also on failure: one warning per change, not one per frame
    f.autosavedEdits = std::move(edits);
    try {
        const std::string body = sessionText(st);
        writeTextFile(f.autosavePath, [&](std::ostream& os) { os << body; });
    } catch (const std::exception& e) {
        st.log(Message::Level::Warning, std::string("autosave failed: ") + e.what());
    }
}

bool offerRecovery(AppState& st, const std::string& folder) {
    FileState& f = st.files;
    std::error_code ec;
    if (folder.empty() || !fs::is_directory(folder, ec)) return false;
    fs::path best;
    fs::file_time_type bestTime{};
    const std::string self = std::to_string(::getpid());
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("autosave-", 0) != 0 || entry.path().extension() != ".json") continue;
        const std::string pid = name.substr(9, name.size() - 9 - 5);
        if (pid == self || pid.empty() || !std::all_of(pid.begin(), pid.end(), ::isdigit)) continue;
        if (instanceAlive(std::strtol(pid.c_str(), nullptr, 10))) continue;
        const auto t = entry.last_write_time(ec);
        if (best.empty() || t > bestTime) {
            best = entry.path();
            bestTime = t;
        }
    }
    if (best.empty()) return false;
    SessionSummary summary;
    std::string error;
    if (!peekSession(best.string(), summary, error)) {
        st.log(Message::Level::Warning,
               "an autosave from a crashed session cannot be read: " + error);
        return false;
    }
    f.recoveryPath = best.string();
    f.recoveryPoints = summary.points;
    f.recoverySource = summary.source;
    return true;
}

bool acceptRecovery(AppState& st) {
    FileState& f = st.files;
    if (f.recoveryPath.empty()) return false;
    const std::string path = f.recoveryPath;
    std::string error;
    if (!loadSession(st, path, error)) {
        fileError(st, error + " (nothing was changed)");
        return false;
    }
    std::error_code ec;
    fs::remove(path, ec);
    f.recoveryPath.clear();
    f.autosaved.clear();  // write our own autosave of the recovered points at once
    st.log(Message::Level::Info, "recovered " + std::to_string(st.engine.points().size()) +
                                     " points from the session that ended unexpectedly");
    return true;
}

void declineRecovery(AppState& st) {
    FileState& f = st.files;
    if (f.recoveryPath.empty()) return;
    std::error_code ec;
    fs::remove(f.recoveryPath, ec);
    st.log(Message::Level::Info, "discarded the autosave " + f.recoveryPath);
    f.recoveryPath.clear();
}

void removeAutosave(AppState& st) {
    if (st.files.autosavePath.empty()) return;
    std::error_code ec;
    fs::remove(st.files.autosavePath, ec);
}

}  // namespace dlab::ui
