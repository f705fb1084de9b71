// Files and sessions through the GUI: every export read back and compared (points bit-exact,
// .node/.ele/.neigh, OFF, OBJ, SVG of the view, PNG on F12, an animated GIF of steps), a session
// saved and loaded (same state, same step), bad files that change nothing and show an error, and
// recovery after the process is killed (kill -9) in the middle of editing.
#include "core/engine/generators.h"
#include "core/engine/io_read.h"
#include "core/engine/mesh_build.h"
#include "tests/ui/ui_harness.h"
#include "ui/files/files.h"
#include "ui/files/gif_export.h"
#include "ui/files/session.h"
#include "ui/files/settings.h"
#include "ui/panels/panels.h"
#include "ui/platform/keys.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

using dlab::kNone;
using dlab::Vec2;
using dlab::test::sameBits;
using dlab::test::TempDir;
using dlab::test::UiHarness;
namespace fs = std::filesystem;
namespace key = dlab::ui::key;

namespace {

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Lines of a text file split into whitespace fields, comments ('#') dropped.
std::vector<std::vector<std::string>> fields(const std::string& path) {
    std::vector<std::vector<std::string>> out;
    std::istringstream in(slurp(path));
    std::string line;
    while (std::getline(in, line)) {
        if (const auto h = line.find('#'); h != std::string::npos) line.resize(h);
        std::istringstream ls(line);
        std::vector<std::string> f;
        for (std::string w; ls >> w;) f.push_back(w);
        if (!f.empty()) out.push_back(std::move(f));
    }
    return out;
}

// Points that stress an exact round trip: subnormals, huge and tiny magnitudes, -0, 0.1.
std::vector<Vec2> awkwardPoints() {
    return {{0.1, 0.2},
            {-0.0, 1e-300},
            {5e-324, 3},
            {1.7976931348623157e308, -2.5},
            {-1e308, 7e-310},
            {123456789.123456789, -0.3},
            {1.0 / 3, 2.0 / 3},
            {4, 4},
            {4, 4}};
}

}  // namespace

// ============================================================================================
// Points and meshes
// ============================================================================================

// Found by fuzz_session: a mode name with an escaped newline was quoted into the error as a
// real line break (corpus: regression_control_char_in_mode.json).
TEST(Files, ASessionErrorQuotingAControlCharacterStaysOneLine) {
    dlab::ui::AppState st;
    const std::string text =
        R"({"format": "delaunay-lab session", "version": 1, "points": [[0, 0], [1, 0], [0, 1]],
  "options": {"boundary": "sup\nper\r"}})";
    std::string error;
    const auto before = st.engine.points();
    ASSERT_FALSE(dlab::ui::loadSessionText(st, text, "bad.json", error));
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    EXPECT_EQ(error.find('\r'), std::string::npos) << error;
    EXPECT_EQ(error.rfind("bad.json:2:", 0), 0u) << error;
    EXPECT_NE(error.find("sup\\nper"), std::string::npos) << error;
    EXPECT_EQ(st.engine.points(), before);
}

TEST(Files, PipesAndDevicesAreRefusedWithoutReadingThem) {
    TempDir dir("nonregular");
    const std::string fifo = dir / "pipe.json";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::string zero = dir / "z.json";
    fs::create_symlink("/dev/zero", zero);
    dlab::ui::AppState st;
    std::string error;
    // No writer on the pipe and endless zeros: each is refused at once, in one line.
    EXPECT_FALSE(dlab::ui::loadSession(st, fifo, error));
    EXPECT_EQ(error, fifo + ": cannot read: it is a named pipe (FIFO), not a regular file");
    EXPECT_FALSE(dlab::ui::loadSession(st, zero, error));
    EXPECT_EQ(error, zero + ": cannot read: it is a device, not a regular file");
    dlab::ui::SessionSummary summary;
    EXPECT_FALSE(dlab::ui::peekSession(zero, summary, error));
    EXPECT_NE(error.find("device"), std::string::npos) << error;
    EXPECT_FALSE(dlab::ui::openFile(st, fifo));
    EXPECT_FALSE(dlab::ui::openFile(st, dir / "z.json"));
    // Settings: ignored with a warning, never waited on.
    dlab::ui::WindowOptions window;
    std::string warning;
    dlab::ui::loadSettings(fifo, st, window, warning);
    EXPECT_NE(warning.find("named pipe"), std::string::npos) << warning;
}

TEST(Files, ASessionNumberBeyondDoubleNamesItsLine) {
    dlab::ui::AppState st;
    const std::string text =
        "{\"format\": \"delaunay-lab session\", \"version\": 1,\n"
        "  \"points\": [[0, 0], [1e400, 0], [0, 1]]}";
    std::string error;
    ASSERT_FALSE(dlab::ui::loadSessionText(st, text, "big.json", error));
    EXPECT_EQ(error.rfind("big.json:2: the number 1e400 is too large", 0), 0u) << error;
    EXPECT_EQ(error.find("json.exception"), std::string::npos) << error;
}

// The error path finds the bad field's line past a value nested 200000 deep: as far as the
// parser itself reads, without a recursion per level.
TEST(Files, ASessionWithDeepNestingAndABadFieldNamesTheFieldAndItsLine) {
    constexpr int kDepth = 200000;
    const std::string text = "{\"format\": \"delaunay-lab session\", \"version\": 1,\n \"deep\": " +
                             std::string(kDepth, '[') + std::string(kDepth, ']') +
                             ",\n \"more\": [[\"]\"], {\"k\": \"[\"}],\n \"points\": \"bad\"}\n";
    dlab::ui::AppState st;
    std::string error;
    ASSERT_FALSE(dlab::ui::loadSessionText(st, text, "deep.json", error));
    EXPECT_EQ(error, "deep.json:4: points: expected an array of [x, y] pairs");
}

TEST(Files, ViewSvgEscapesControlCharactersInItsTitle) {
    UiHarness h;
    auto& st = h.state();
    st.source = "lesson \x1b[31mred\x07 <&>";
    std::ostringstream out;
    dlab::ui::writeViewSvg(out, st);
    const std::string svg = out.str();
    for (char c : svg) {
        const auto u = static_cast<unsigned char>(c);
        EXPECT_FALSE(u < 0x20 && c != '\n' && c != '\t' && c != '\r') << static_cast<int>(u);
    }
    EXPECT_NE(svg.find("lesson ?[31mred? &lt;&amp;&gt;"), std::string::npos);
}

TEST(Files, PointsRoundTripBitExactAsNodeAndCsv) {
    TempDir dir("points");
    UiHarness h;
    auto& st = h.state();
    ASSERT_TRUE(st.loadPoints(awkwardPoints(), "awkward"));
    for (const char* name : {"p.node", "p.csv"}) {
        ASSERT_TRUE(dlab::ui::savePoints(st, dir / name)) << st.files.notice;
        const dlab::PointSet back = dlab::readPointsFile(dir / name);
        EXPECT_TRUE(sameBits(back.points, awkwardPoints())) << name;
    }
    // Opened again through the GUI (as a dropped file is): the same points, bit for bit.
    ASSERT_TRUE(st.loadPoints(dlab::demoPoints(), "demo"));
    ASSERT_TRUE(dlab::ui::openFile(st, dir / "p.csv"));
    EXPECT_TRUE(sameBits(st.engine.points(), awkwardPoints()));
    EXPECT_FALSE(dlab::ui::savePoints(st, dir / "p.xyz"));  // unknown format: refused, said
    EXPECT_NE(st.files.notice.find("p.xyz"), std::string::npos);
}

TEST(Files, MeshExportsReadBackAsTheMesh) {
    TempDir dir("mesh");
    UiHarness h;
    auto& st = h.state();
    while (!st.engine.toEnd(1 << 20)) {}
    const dlab::Mesh& m = st.engine.mesh();
    ASSERT_GT(m.numTriangles(), 10);

    ASSERT_TRUE(dlab::ui::exportMesh(st, dir / "m.ele", dlab::ui::MeshFormat::Triangle));
    const dlab::PointSet node = dlab::readPointsFile(dir / "m.node");
    EXPECT_TRUE(sameBits(node.points, m.G));
    const auto ele = fields(dir / "m.ele");
    const auto neigh = fields(dir / "m.neigh");
    ASSERT_EQ(std::stoi(ele[0][0]), m.numTriangles());
    ASSERT_EQ(static_cast<int>(ele.size()), m.numTriangles() + 1);
    ASSERT_EQ(static_cast<int>(neigh.size()), m.numTriangles() + 1);
    for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(std::stoi(ele[t + 1][k + 1]), m.V[3 * t + k]);
            const std::int32_t o = m.O[3 * t + k];
            EXPECT_EQ(std::stoi(neigh[t + 1][k + 1]), o == kNone ? -1 : dlab::tri(o));
        }
    }

    ASSERT_TRUE(dlab::ui::exportMesh(st, dir / "m.off", dlab::ui::MeshFormat::Off));
    const auto off = fields(dir / "m.off");
    ASSERT_EQ(off[0][0], "OFF");
    ASSERT_EQ(std::stoi(off[1][0]), m.numVertices());
    ASSERT_EQ(std::stoi(off[1][1]), m.numTriangles());
    for (std::int32_t v = 0; v < m.numVertices(); ++v) {
        EXPECT_EQ(std::stod(off[2 + v][0]), m.G[v].x);
        EXPECT_EQ(std::stod(off[2 + v][1]), m.G[v].y);
    }
    dlab::Mesh fromOff;
    fromOff.G = m.G;
    for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
        const auto& f = off[2 + m.numVertices() + t];
        ASSERT_EQ(f[0], "3");
        for (int k = 1; k <= 3; ++k) fromOff.V.push_back(std::stoi(f[k]));
    }
    EXPECT_EQ(fromOff.V, m.V);
    dlab::computeOpposites(fromOff);  // the triangles alone rebuild the same neighbours
    EXPECT_EQ(fromOff.O, m.O);

    ASSERT_TRUE(dlab::ui::exportMesh(st, dir / "m.obj", dlab::ui::MeshFormat::Obj));
    std::vector<Vec2> objV;
    std::vector<std::int32_t> objF;
    for (const auto& f : fields(dir / "m.obj")) {
        if (f[0] == "v") objV.push_back({std::stod(f[1]), std::stod(f[2])});
        if (f[0] == "f") {
            for (int k = 1; k <= 3; ++k) objF.push_back(std::stoi(f[k]) - 1);
        }
    }
    EXPECT_TRUE(sameBits(objV, m.G));
    EXPECT_EQ(objF, m.V);

    // In the middle of the run: the real triangles of the step, ghosts left out, neighbours
    // consistent.
    st.engine.seek(60);
    ASSERT_FALSE(st.engine.inserter().done());
    ASSERT_TRUE(dlab::ui::exportMesh(st, dir / "mid.off", dlab::ui::MeshFormat::Off));
    const auto mid = fields(dir / "mid.off");
    std::int32_t real = 0;
    for (std::int32_t t = 0; t < st.engine.mesh().numTriangles(); ++t)
        real += !st.engine.inserter().isVirtualTriangle(t);
    EXPECT_EQ(std::stoi(mid[1][1]), real);
    const dlab::Mesh em = dlab::ui::exportableMesh(st.engine);
    dlab::ValidateOptions combinatorial;
    combinatorial.delaunay = false;  // mid-insertion some edges still wait for their flip
    EXPECT_TRUE(dlab::validate(em, combinatorial).empty());
}

TEST(Files, ViewSvgHasEveryVisibleEdgeAndPointWhereTheCanvasDrawsThem) {
    TempDir dir("svg");
    UiHarness h;
    auto& st = h.state();
    st.engine.seek(70);
    h.scroll(st.view.origin.x + st.view.size.x * 0.4f, st.view.origin.y + st.view.size.y * 0.5f,
             2.0f);  // zoom in: some edges leave the view
    ASSERT_TRUE(dlab::ui::exportViewSvg(st, dir / "v.svg"));
    const std::string svg = slurp(dir / "v.svg");
    std::smatch mm;
    ASSERT_TRUE(std::regex_search(svg, mm, std::regex("viewBox=\"0 0 (\\d+) (\\d+)\"")));
    EXPECT_EQ(std::stoi(mm[1]), static_cast<int>(std::lround(st.view.size.x)));
    // Edges: one <line> per edge of a real triangle that crosses the view's box.
    const auto edgesBegin = svg.find("<g id=\"edges\""), edgesEnd = svg.find("</g>", edgesBegin);
    const std::string edges = svg.substr(edgesBegin, edgesEnd - edgesBegin);
    std::set<std::pair<long, long>> drawn;  // screen-rounded endpoints
    const std::regex lineRe(
        "<line x1=\"([-0-9.]+)\" y1=\"([-0-9.]+)\" x2=\"([-0-9.]+)\" y2=\"([-0-9.]+)\"/>");
    int lines = 0;
    for (auto it = std::sregex_iterator(edges.begin(), edges.end(), lineRe);
         it != std::sregex_iterator(); ++it)
        ++lines;
    const dlab::Mesh& m = st.engine.mesh();
    const auto& ins = st.engine.inserter();
    int expected = 0;
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        if (m.O[c] != kNone && m.O[c] < c) continue;
        const std::int32_t a = m.V[dlab::next(c)], b = m.V[dlab::prev(c)];
        if (ins.isVirtual(a) || ins.isVirtual(b)) continue;
        const auto p = st.view.toScreen(m.G[a]) - st.view.origin,
                   q = st.view.toScreen(m.G[b]) - st.view.origin;
        expected += std::max(p.x, q.x) >= 0 && std::min(p.x, q.x) <= st.view.size.x &&
                    std::max(p.y, q.y) >= 0 && std::min(p.y, q.y) <= st.view.size.y;
    }
    EXPECT_EQ(lines, expected);
    EXPECT_GT(lines, 5);
    // Points: each circle maps back (through the view) to its input point.
    const std::regex circleRe("<circle data-id=\"(\\d+)\" cx=\"([-0-9.]+)\" cy=\"([-0-9.]+)\"");
    int circles = 0;
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), circleRe);
         it != std::sregex_iterator(); ++it) {
        const std::size_t i = std::stoul((*it)[1]);
        ASSERT_LT(i, st.engine.points().size());
        const Vec2 w = st.view.toWorld(
            {std::stod((*it)[2]) + st.view.origin.x, std::stod((*it)[3]) + st.view.origin.y});
        EXPECT_NEAR(w.x, st.engine.points()[i].x, 0.01 / st.view.scale);
        EXPECT_NEAR(w.y, st.engine.points()[i].y, 0.01 / st.view.scale);
        ++circles;
    }
    EXPECT_GT(circles, 3);
    EXPECT_NE(svg.find("<title>Delaunay Lab"), std::string::npos);
}

// ============================================================================================
// Sessions
// ============================================================================================

TEST(Files, SessionRoundTripRestoresTheSameStateAtTheSameStep) {
    TempDir dir("session");
    std::string path = dir / "s.json";
    std::uint64_t fingerprint = 0;
    std::vector<dlab::ui::BreakpointEntry> bps;
    std::vector<Vec2> savedPoints;
    {
        UiHarness h;
        auto& st = h.state();
        std::vector<Vec2> pts = dlab::demoPoints();
        pts.push_back({0.1, 1e-7});
        pts.push_back({-0.0, 5e-324});
        ASSERT_TRUE(st.loadPoints(pts, "demo plus two"));
        dlab::InsertOptions o = st.engine.options();
        o.order = dlab::OrderKind::Random;
        o.seed = 7;
        o.locator = dlab::LocatorKind::IdBufferCpu;
        ASSERT_TRUE(st.setOptions(o));
        st.engine.seek(57);
        h.frames(1);
        st.select(5);
        st.view.center = {123.25, -7.5};
        st.view.scale = 0.75;
        st.overlays.voronoi = true;
        st.overlays.cornerIds = false;
        ASSERT_TRUE(dlab::ui::addWatch(st, "o(o(c)) == c"));
        st.expressions.watches.back().enabled = false;
        ASSERT_TRUE(dlab::ui::evaluateExpression(st, "c.n"));
        st.run.breakpoints.push_back({*dlab::parseBreakpoint("insert:5"), true});
        h.frames(1);
        ASSERT_TRUE(dlab::ui::saveSessionFile(st, path));
        fingerprint = dlab::ui::MeshFingerprint(st.engine.mesh());
        savedPoints = st.engine.points();
        bps = st.run.breakpoints;
    }
    UiHarness h;
    auto& st = h.state();
    ASSERT_TRUE(dlab::ui::openFile(st, path)) << st.files.notice;
    h.frames(2);
    EXPECT_TRUE(sameBits(st.engine.points(), savedPoints));
    EXPECT_EQ(st.engine.options().order, dlab::OrderKind::Random);
    EXPECT_EQ(st.engine.options().seed, 7u);
    EXPECT_EQ(st.engine.options().locator, dlab::LocatorKind::IdBufferCpu);
    EXPECT_EQ(st.engine.position(), 57u);
    EXPECT_EQ(dlab::ui::MeshFingerprint(st.engine.mesh()), fingerprint);
    EXPECT_EQ(st.selection.corner, 5);
    EXPECT_EQ(st.view.center.x, 123.25);
    EXPECT_EQ(st.view.center.y, -7.5);
    EXPECT_EQ(st.view.scale, 0.75);
    EXPECT_TRUE(st.overlays.voronoi);
    EXPECT_FALSE(st.overlays.cornerIds);
    ASSERT_EQ(st.expressions.watches.size(), 1u);
    EXPECT_EQ(st.expressions.watches[0].text, "o(o(c)) == c");
    EXPECT_FALSE(st.expressions.watches[0].enabled);
    EXPECT_EQ(st.expressions.live, "c.n");
    ASSERT_EQ(st.run.breakpoints.size(), 1u);
    EXPECT_EQ(st.run.breakpoints[0].bp, bps[0].bp);
    for (const auto& msg : st.messages)
        EXPECT_NE(msg.level, dlab::ui::Message::Level::Warning) << msg.text;
    // Saving again gives the same file: nothing was lost or invented on the way.
    ASSERT_TRUE(dlab::ui::saveSessionFile(st, dir / "again.json"));
    std::string a = slurp(path), b = slurp(dir / "again.json");
    const std::regex source("\"source\": \"[^\"]*\"");
    EXPECT_EQ(std::regex_replace(a, source, ""), std::regex_replace(b, source, ""));
}

TEST(Files, ASessionWhoseMeshDiffersSaysSo) {
    TempDir dir("bugreport");
    UiHarness h;
    auto& st = h.state();
    st.engine.seek(40);
    std::string text = dlab::ui::sessionText(st);
    const auto at = text.find("\"fingerprint\": \"") + 16;
    text.replace(at, 16, "0123456789abcdef");
    std::string error;
    ASSERT_TRUE(dlab::ui::loadSessionText(st, text, "report.json", error)) << error;
    EXPECT_EQ(st.engine.position(), 40u);
    ASSERT_FALSE(st.messages.empty());
    EXPECT_EQ(st.messages.back().level, dlab::ui::Message::Level::Warning);
    EXPECT_NE(st.messages.back().text.find("differs"), std::string::npos)
        << st.messages.back().text;
}

// ============================================================================================
// Autosave and recovery after kill -9
// ============================================================================================

// The child of Files.RecoveryAfterKillRestoresEveryPoint: edits points by clicking on the canvas
// until it is killed, appending each point to a progress file once it is in the autosave.
TEST(Files, DISABLED_RecoveryChildEditsUntilKilled) {
    const char* dir = std::getenv("DLAB_RECOVERY_DIR");
    ASSERT_NE(dir, nullptr);
    UiHarness h;
    auto& st = h.state();
    dlab::ui::enableAutosave(st, dir);
    const auto canvas = h.rect("canvas");
    std::ofstream progress(std::string(dir) + "/progress.txt");
    for (int i = 0; i < 400; ++i) {
        const float x = canvas[0] + 25 + 22 * static_cast<float>(i % 12),
                    y = canvas[3] - 25 - 22 * static_cast<float>(i / 12);
        const std::size_t n = st.engine.points().size();
        h.click(x, y);                                     // the frame after the edit autosaves
        if (st.engine.points().size() != n + 1) continue;  // landed on a point: no edit
        const Vec2 p = st.engine.points().back();
        char line[96];
        std::snprintf(line, sizeof line, "%a %a\n", p.x, p.y);
        progress << line << std::flush;
    }
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));  // wait for the kill
}

TEST(Files, RecoveryAfterKillRestoresEveryPoint) {
    TempDir dir("recovery");
    const std::string progressPath = dir / "progress.txt";
    // The environment is set before fork: between fork and exec only exec is safe to call.
    ::setenv("DLAB_RECOVERY_DIR", dir.path.c_str(), 1);
    const pid_t child = ::fork();
    if (child == 0) {
        ::execl("/proc/self/exe", "dlab_ui_logic_tests", "--gtest_also_run_disabled_tests",
                "--gtest_filter=Files.DISABLED_RecoveryChildEditsUntilKilled",
                static_cast<char*>(nullptr));
        ::_exit(127);
    }
    ::unsetenv("DLAB_RECOVERY_DIR");
    ASSERT_GT(child, 0);
    // Kill it in the middle of its edits: once it has made a few, at no particular point.
    auto lines = [&] {
        std::ifstream in(progressPath);
        std::vector<std::string> out;
        for (std::string l; std::getline(in, l);) out.push_back(l);
        return out;
    };
    for (int i = 0; i < 600 && lines().size() < 8; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_EQ(::kill(child, SIGKILL), 0);
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the child ended by itself (status " << status << ")";
    const auto reported = lines();
    ASSERT_GE(reported.size(), 8u) << "the child made too few edits before the kill";

    // Start again: the autosave of the dead instance is offered, and accepting it restores every
    // point the child had added (and perhaps the one it was adding when it died).
    UiHarness h;
    auto& st = h.state();
    ASSERT_TRUE(dlab::ui::offerRecovery(st, dir.path.string()));
    h.frames(2);
    h.clickItem("recover");
    EXPECT_TRUE(st.files.recoveryPath.empty());
    const auto& pts = st.engine.points();
    const std::size_t demo = dlab::demoPoints().size();
    ASSERT_GE(pts.size(), demo + reported.size());
    EXPECT_LE(pts.size(), demo + reported.size() + 1);
    for (std::size_t k = 0; k < reported.size(); ++k) {
        double x = 0, y = 0;
        ASSERT_EQ(std::sscanf(reported[k].c_str(), "%la %la", &x, &y), 2);
        EXPECT_EQ(pts[demo + k], (Vec2{x, y})) << "point " << k;
    }
    // The dead instance's autosave is gone; a clean exit of this one leaves nothing behind.
    dlab::ui::enableAutosave(st, dir.path.string());
    std::vector<Vec2> more = pts;
    more.push_back({1, 1});
    ASSERT_TRUE(st.editPoints(more));
    h.frames(1);
    int autosaves = 0;
    for (const auto& e : fs::directory_iterator(dir.path))
        autosaves += e.path().filename().string().rfind("autosave-", 0) == 0;
    EXPECT_EQ(autosaves, 1);
    ASSERT_TRUE(fs::exists(st.files.autosavePath));
    dlab::ui::removeAutosave(st);
    EXPECT_FALSE(fs::exists(st.files.autosavePath));
    EXPECT_FALSE(dlab::ui::offerRecovery(st, dir.path.string()));
}

TEST(Files, DiscardingTheRecoveryDeletesTheAutosave) {
    TempDir dir("discard");
    // An autosave of a pid that does not run.
    std::string autosave = dir / "autosave-999999999.json";
    {
        UiHarness h;
        std::ofstream(autosave) << dlab::ui::sessionText(h.state());
    }
    UiHarness h;
    auto& st = h.state();
    ASSERT_TRUE(dlab::ui::offerRecovery(st, dir.path.string()));
    EXPECT_EQ(st.files.recoveryPoints, dlab::demoPoints().size());
    h.frames(2);
    h.clickItem("discard-recovery");
    EXPECT_FALSE(fs::exists(autosave));
    EXPECT_TRUE(st.files.recoveryPath.empty());
}

// ============================================================================================
// A session larger than the memory the process may use
// ============================================================================================

// The child of Files.ASessionBeyondTheMemoryLimitFailsInOneLine: loads the session the
// environment names and prints the error (or "loaded").
TEST(Files, DISABLED_LoadSessionNamedByTheEnvironment) {
    const char* path = std::getenv("DLAB_SESSION");
    ASSERT_NE(path, nullptr);
    dlab::ui::AppState st;
    std::string error;
    const bool ok = dlab::ui::loadSession(st, path, error);
    std::printf("%s\n", ok ? "loaded" : error.c_str());
}

TEST(Files, ASessionBeyondTheMemoryLimitFailsInOneLine) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "ASan reserves terabytes of address space: no limit can be set";
#endif
    TempDir dir("big_session");
    const std::string path = dir / "big.json";
    {
        // 3 million points, 78 MB: the text, the points and the run take about 290 MB (measured),
        // more than the 160 MB the child may map with its code.
        std::ofstream out(path, std::ios::binary);
        out << "{\"format\": \"delaunay-lab session\", \"version\": 1, \"points\": [";
        std::string block;
        for (int i = 0; i < 1000; ++i) block += "[123.456789, 987.654321],\n";
        for (int i = 0; i < 3000; ++i) out << (i ? "," : "") << block.substr(0, block.size() - 2);
        out << "]}\n";
    }
    const std::string log = dir / "child.txt";
    ::setenv("DLAB_SESSION", path.c_str(), 1);
    const pid_t child = ::fork();
    if (child == 0) {
        const rlimit limit{std::size_t{160} << 20, std::size_t{160} << 20};
        ::setrlimit(RLIMIT_AS, &limit);
        if (!std::freopen(log.c_str(), "w", stdout)) ::_exit(126);
        ::execl("/proc/self/exe", "dlab_ui_logic_tests", "--gtest_also_run_disabled_tests",
                "--gtest_filter=Files.DISABLED_LoadSessionNamedByTheEnvironment",
                static_cast<char*>(nullptr));
        ::_exit(127);
    }
    ::unsetenv("DLAB_SESSION");
    ASSERT_GT(child, 0);
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFEXITED(status)) << "the child died of signal " << WTERMSIG(status);
    const std::string out = slurp(log);
    // Out of memory reading the JSON ("... sessions up to 512 MiB are accepted)") or running its
    // points ("cannot restart the run: not enough memory to triangulate its 3000000 points").
    const auto at = out.find(path + ": ");
    ASSERT_NE(at, std::string::npos) << out;
    const std::string line = out.substr(at, out.find('\n', at) - at);
    EXPECT_NE(line.find("not enough memory to"), std::string::npos) << out;
    EXPECT_EQ(line.find("bad_alloc"), std::string::npos) << out;
}
