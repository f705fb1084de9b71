// GUI robustness: long seeded random sequences of user actions on the real UI, headless,
// with the mesh's invariants checked after every action, and undo back to the original points.
//
// Each seed drives one UiHarness through clicks, drags, keys, step buttons, zoom and pan, option
// changes, generated and bad files, lessons, the expression console and presentation mode. After
// every action: validate() (orientation always; the local Delaunay property whenever no insertion
// is half done), the GMP check at the end of an exact run, a bad file changed nothing; sampled:
// back to operation 0 and forward again gives the same V/O, and equals a fresh replay.
//
// A failure prints the seed and the whole action log. Replay one seed, longer or shorter:
//   DLAB_GUI_ROBUST_SEED=7 DLAB_GUI_ROBUST_ACTIONS=2000 build/tests/ui/dlab_ui_logic_tests
//       --gtest_filter='Seeds/GuiRobustness.*/0'
// Every action is also appended (flushed) to $TMPDIR/dlab_gui_robust_SEED.log, which survives a
// crash.
#include "core/engine/generators.h"
#include "core/engine/mesh.h"
#include "core/teaching/breakpoint.h"
#include "tests/exact_check.h"
#include "tests/ui/ui_harness.h"
#include "ui/files/files.h"
#include "ui/lesson_player.h"
#include "ui/panels/panels.h"
#include "ui/platform/keys.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using dlab::kNone;
using dlab::Vec2;
using dlab::test::UiHarness;
namespace fs = std::filesystem;
namespace key = dlab::ui::key;
namespace ui = dlab::ui;

namespace {

// A smaller window than the other GUI tests: software rasterisation is most of a frame's cost.
constexpr int kWidth = 1100, kHeight = 720;
constexpr int kDefaultActions = 500;  // per seed in CTest
constexpr int kUndoActions = 250;     // per seed of the undo test
constexpr int kStepBackEvery = 12;  // the costly back-to-0-and-forward check: 1 action in this many

std::size_t envCount(const char* name, std::size_t fallback) {
    const char* v = std::getenv(name);
    return v && *v ? static_cast<std::size_t>(std::strtoull(v, nullptr, 10)) : fallback;
}

struct MeshCopy {
    std::vector<Vec2> G;
    std::vector<std::int32_t> V, O;
    friend bool operator==(const MeshCopy&, const MeshCopy&) = default;
};
MeshCopy copyOf(const dlab::Mesh& m) { return {m.G, m.V, m.O}; }

// No insertion is half done: every edge that exists has been tested (or no test is due yet).
bool betweenInsertions(const dlab::Inserter& ins) {
    switch (ins.control().phase) {
        case dlab::Phase::Test:
        case dlab::Phase::Flip: return false;
        default: return true;
    }
}

// The invariants that hold after any action. "" when all hold.
std::string checkInvariants(const ui::AppState& st) {
    const ui::Engine& e = st.engine;
    const dlab::Inserter& ins = e.inserter();
    const dlab::Mesh& m = e.mesh();
    if (e.pointStates().size() != e.points().size())
        return "pointStates() and points() differ in size";
    if (!e.batch() && e.position() > e.recorded()) return "position beyond the recorded ops";
    if (ins.numInput() != static_cast<std::int32_t>(e.points().size()))
        return "the inserter runs other points than the engine shows";
    dlab::ValidateOptions vo;
    vo.firstVirtual = ins.firstVirtual();
    // Past the run, edits show the closed mesh: constrained edges need not be Delaunay, and an
    // edit in progress is not yet (the editor's own tests check each edit's end).
    vo.delaunay = betweenInsertions(ins) && !e.editing();
    const auto v = dlab::validate(m, vo);
    if (!v.empty()) {
        return std::string("validate(") + (vo.delaunay ? "with" : "without") + " Delaunay) at op " +
               std::to_string(e.position()) + ": " + v[0].message;
    }
    if (!e.showsVirtual() && e.options().boundary == dlab::Boundary::Exact) {
        if (allCollinearExact(e.points())) {
            if (m.numTriangles() != 0)
                return "all points collinear, yet " + std::to_string(m.numTriangles()) +
                       " triangles";
        } else {
            const auto distinct = firstOccurrences(e.points());
            const std::string exact = checkDelaunayExact(m, &distinct);
            if (!exact.empty()) return "GMP check at the end: " + exact;
        }
    }
    return "";
}

std::string describe(Vec2 p) {
    char buf[80];
    std::snprintf(buf, sizeof buf, "(%.17g, %.17g)", p.x, p.y);
    return buf;
}

std::vector<std::string> lessonFiles() {
    std::vector<std::string> out;
    for (const auto& entry : fs::directory_iterator(fs::path(DLAB_SOURCE_DIR) / "lessons")) {
        if (entry.path().extension() == ".toml") out.push_back(entry.path().string());
    }
    std::sort(out.begin(), out.end());
    return out;
}

// Expressions a student might type: right, wrong, and nonsense.
const char* const kExpressions[] = {"c.n.o",
                                    "o(o(c))",
                                    "c.s.s.s",
                                    "V[c]",
                                    "r(o(n(7)))",
                                    "G[V[c]]",
                                    "c.l.r.u",
                                    "t(o(c))",
                                    "V[n(o(c))] == V[p(c)]",
                                    "o(999999)",
                                    "n(-1)",
                                    "c.x",
                                    "((",
                                    "c.o.o.o.o",
                                    "G[100000]",
                                    "",
                                    "7",
                                    "c ==",
                                    "V[O[c]]",
                                    "p(p(p(c)))",
                                    "c.n.n.n == c",
                                    "\x01\x7f",
                                    "s(s(s(s(s(s(c))))))"};

// One seeded user: picks actions with weights, performs them through the harness and checks.
class RandomUser {
public:
    RandomUser(std::uint64_t seed, UiHarness& h) : m_seed(seed), m_rng(seed), m_h(h) {
        m_dir = fs::temp_directory_path() / ("dlab_gui_robust_" + std::to_string(seed));
        fs::create_directories(m_dir);
        m_logFile.open(
            fs::temp_directory_path() / ("dlab_gui_robust_" + std::to_string(seed) + ".log"),
            std::ios::trunc);
        writeBadFiles();
        ui::AppState& st = m_h.state();
        // A deterministic animation: a run at full speed goes on until its end or a breakpoint in
        // one frame (the default budget of 25 ms of wall-clock time would depend on the load).
        st.run.opsPerSecond = ui::RunControl::kFullSpeed;
        st.run.frameBudgetMs = 1e9;
        st.run.targetFrameMs = 1e9;
    }
    ~RandomUser() {
        std::error_code ec;
        fs::remove_all(m_dir, ec);
    }

    // Performs `count` actions; "" when every check held, else the failure.
    std::string run(std::size_t count, bool withLessonsAndConsole = true) {
        m_withLessons = withLessonsAndConsole;
        for (std::size_t i = 0; i < count; ++i) {
            m_step = i;
            std::string failure = act();
            // The animation keeps the deterministic speed whatever a key did to it.
            m_h.state().run.opsPerSecond = ui::RunControl::kFullSpeed;
            if (failure.empty()) failure = checkInvariants(m_h.state());
            if (failure.empty() && m_rng() % kStepBackEvery == 0) failure = checkStepBack();
            if (!failure.empty()) {
                saveScreenshot();
                return failure;
            }
        }
        return "";
    }

    // The last frame, beside the action log: what the user would have seen at the failure.
    void saveScreenshot() {
        int w = 0, h = 0;
        const auto& px = m_h.gui().lastFrame(w, h);
        std::string error;
        m_screenshot =
            (fs::temp_directory_path() / ("dlab_gui_robust_" + std::to_string(m_seed) + ".png"))
                .string();
        if (!ui::writePng(m_screenshot, px, w, h, error))
            m_screenshot = "(no screenshot: " + error + ")";
    }

    std::string report(const std::string& failure) const {
        std::ostringstream os;
        os << "seed " << m_seed << ", action " << m_step << ": " << failure << "\n"
           << "replay: DLAB_GUI_ROBUST_SEED=" << m_seed << " DLAB_GUI_ROBUST_ACTIONS=" << m_step + 1
           << " dlab_ui_tests --gtest_filter='"
           << ::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name()
           << ".*/0'\nlast frame: " << m_screenshot << "\naction log:\n";
        for (std::size_t i = 0; i < m_log.size(); ++i) os << "  " << i << ": " << m_log[i] << "\n";
        return os.str();
    }

    // Ctrl+Z (Ctrl+Y) until the undo (redo) stack stops shrinking; how many presses did something.
    std::size_t undoAll() { return pressWhileShrinking('Z', m_h.state().undoPoints); }
    std::size_t redoAll() { return pressWhileShrinking('Y', m_h.state().redoPoints); }
    std::size_t pressWhileShrinking(char letter, const std::vector<std::vector<Vec2>>& stack) {
        std::size_t done = 0;
        for (std::size_t guard = 0; guard < 100000; ++guard) {
            const std::size_t before = stack.size();
            m_h.press(key::letter(letter), false, true);
            if (stack.size() >= before) break;
            ++done;
        }
        return done;
    }

    // Leaves any text field, as a user does before using the shortcuts again.
    void leaveTextFields() {
        m_h.press(key::kEscape);
        m_h.frames(1);
    }

private:
    // ---- Random choices ----------------------------------------------------------------------
    std::uint64_t below(std::uint64_t n) { return n == 0 ? 0 : m_rng() % n; }
    bool chance(double p) { return static_cast<double>(m_rng() >> 11) * 0x1.0p-53 < p; }
    float between(float lo, float hi) {
        return lo + static_cast<float>(static_cast<double>(m_rng() >> 11) * 0x1.0p-53) * (hi - lo);
    }
    template <class T, std::size_t N>
    const T& pick(const T (&a)[N]) {
        return a[below(N)];
    }

    void note(std::string line) {
        m_logFile << m_step << ": " << line << std::endl;  // flushed: a crash keeps it
        m_log.push_back(std::move(line));
    }

    std::array<float, 4> canvas() { return m_h.rect("canvas"); }
    // A random spot on the canvas, away from its edges.
    std::pair<float, float> canvasSpot() {
        const auto r = canvas();
        return {between(r[0] + 8, r[2] - 8), between(r[1] + 8, r[3] - 8)};
    }
    // Screen position of a random queued point on the canvas, or false.
    bool queuedPointSpot(float& x, float& y, std::int32_t& index) {
        const ui::AppState& st = m_h.state();
        const auto r = canvas();
        std::vector<std::int32_t> candidates;
        const auto& states = st.engine.pointStates();
        for (std::size_t i = 0; i < states.size(); ++i) {
            if (states[i] != ui::Engine::PointState::Pending) continue;
            const auto s = st.view.toScreen(st.engine.points()[i]);
            if (s.x > r[0] + 4 && s.x < r[2] - 4 && s.y > r[1] + 4 && s.y < r[3] - 4)
                candidates.push_back(static_cast<std::int32_t>(i));
        }
        if (candidates.empty()) return false;
        index = candidates[below(candidates.size())];
        const auto s = st.view.toScreen(st.engine.points()[index]);
        x = static_cast<float>(s.x);
        y = static_cast<float>(s.y);
        return true;
    }

    // ---- The actions -------------------------------------------------------------------------
    std::string act() {
        struct Choice {
            int weight;
            std::string (RandomUser::*fn)();
        };
        static const Choice kChoices[] = {
            {8, &RandomUser::clickCanvas},        {4, &RandomUser::rightClickQueued},
            {4, &RandomUser::dragQueued},         {5, &RandomUser::clickCorner},
            {24, &RandomUser::pressKey},          {12, &RandomUser::clickStepButton},
            {3, &RandomUser::wheelZoom},          {2, &RandomUser::middlePan},
            {4, &RandomUser::changeOptions},      {3, &RandomUser::loadGenerated},
            {3, &RandomUser::loadBadFile},        {2, &RandomUser::openLessonFile},
            {4, &RandomUser::lessonStep},         {2, &RandomUser::typeExpression},
            {1, &RandomUser::togglePresentation}, {4, &RandomUser::runFrames},
            {2, &RandomUser::toggleBreakpoint},   {2, &RandomUser::clickTimeline},
            {1, &RandomUser::dismissNotice},
        };
        int total = 0;
        for (const Choice& c : kChoices) total += c.weight;
        int r = static_cast<int>(below(static_cast<std::uint64_t>(total)));
        for (const Choice& c : kChoices) {
            if (r < c.weight) return (this->*c.fn)();
            r -= c.weight;
        }
        return "";
    }

    std::string clickCanvas() {
        const auto [x, y] = canvasSpot();
        const std::size_t n = m_h.state().engine.points().size();
        note("click canvas at (" + std::to_string(x) + ", " + std::to_string(y) + ")");
        m_h.click(x, y);
        if (m_h.state().engine.points().size() > n)
            m_log.back() += " -> point " + std::to_string(n) + " " +
                            describe(m_h.state().engine.points().back());
        return "";
    }

    std::string rightClickQueued() {
        float x = 0, y = 0;
        std::int32_t i = kNone;
        if (!queuedPointSpot(x, y, i)) {
            std::tie(x, y) = canvasSpot();
            note("right-click canvas at (" + std::to_string(x) + ", " + std::to_string(y) + ")");
        } else {
            note("right-click queued point " + std::to_string(i));
        }
        m_h.click(x, y, 1);
        return "";
    }

    std::string dragQueued() {
        float x = 0, y = 0;
        std::int32_t i = kNone;
        if (!queuedPointSpot(x, y, i)) return clickCanvas();
        const auto r = canvas();
        const float tx = std::clamp(x + between(-120, 120), r[0] + 8, r[2] - 8);
        const float ty = std::clamp(y + between(-120, 120), r[1] + 8, r[3] - 8);
        note("drag queued point " + std::to_string(i) + " to (" + std::to_string(tx) + ", " +
             std::to_string(ty) + ")");
        m_h.drag(x, y, tx, ty);
        return "";
    }

    std::string clickCorner() {
        const ui::AppState& st = m_h.state();
        std::vector<std::pair<std::int32_t, std::pair<float, float>>> labelled;
        for (std::int32_t c = 0; c < st.engine.mesh().numCorners(); ++c) {
            float x = 0, y = 0;
            if (ui::cornerAnchor(st, c, x, y)) labelled.push_back({c, {x, y}});
        }
        if (labelled.empty()) return pressKey();
        const auto& [c, at] = labelled[below(labelled.size())];
        note("click corner label " + std::to_string(c));
        m_h.click(at.first, at.second);
        return "";
    }

    std::string pressKey() {
        struct Key {
            int weight;
            const char* name;
            int code;
            bool shift, ctrl;
        };
        static const Key kKeys[] = {
            {6, "Right", key::kRight, false, false},
            {4, "Left", key::kLeft, false, false},
            {3, "Shift+Right", key::kRight, true, false},
            {2, "Shift+Left", key::kLeft, true, false},
            {1, "Home", key::kHome, false, false},
            {1, "End", key::kEnd, false, false},
            {2, "Space", key::kSpace, false, false},
            {1, "N", key::letter('N'), false, false},
            {1, "P", key::letter('P'), false, false},
            {2, "O", key::letter('O'), false, false},
            {1, "L", key::letter('L'), false, false},
            {1, "R", key::letter('R'), false, false},
            {1, "S", key::letter('S'), false, false},
            {1, "U", key::letter('U'), false, false},
            {1, "F", key::letter('F'), false, false},
            {1, "V", key::letter('V'), false, false},
            {1, "C", key::letter('C'), false, false},
            {1, "G", key::letter('G'), false, false},
            {1, "Escape", key::kEscape, false, false},
            {1, "F1", key::kF1, false, false},
            {2, "Ctrl+Z", key::letter('Z'), false, true},
            {1, "Ctrl+Y", key::letter('Y'), false, true},
        };
        int total = 0;
        for (const Key& k : kKeys) total += k.weight;
        int r = static_cast<int>(below(static_cast<std::uint64_t>(total)));
        for (const Key& k : kKeys) {
            if (r < k.weight) {
                note(std::string("key ") + k.name);
                m_h.press(k.code, k.shift, k.ctrl);
                return "";
            }
            r -= k.weight;
        }
        return "";
    }

    std::string clickStepButton() {
        static const char* const kButtons[] = {">",  ">",  ">",  "<",  ">>",
                                               ">>", "<<", "|<", ">|", "run"};
        const char* b = pick(kButtons);
        note(std::string("button ") + b);
        m_h.clickItem(b);
        return "";
    }

    std::string wheelZoom() {
        static const float kWheel[] = {-2.0f, -1.0f, -0.5f, 0.5f, 1.0f, 2.0f, 3.0f};
        const auto [x, y] = canvasSpot();
        const float w = pick(kWheel);
        note("wheel " + std::to_string(w) + " at (" + std::to_string(x) + ", " + std::to_string(y) +
             ")");
        m_h.scroll(x, y, w);
        return "";
    }

    std::string middlePan() {
        const auto [x, y] = canvasSpot();
        const auto r = canvas();
        const float tx = std::clamp(x + between(-200, 200), r[0] + 2, r[2] - 2);
        const float ty = std::clamp(y + between(-200, 200), r[1] + 2, r[3] - 2);
        note("middle-drag pan");
        m_h.drag(x, y, tx, ty, 2);
        return "";
    }

    // A refused change must leave the points, options and step as they were.
    struct Before {
        std::vector<Vec2> points;
        dlab::InsertOptions options;
        std::size_t position;
        std::size_t undo;
        std::string source;
    };
    Before before() const {
        const ui::AppState& st = m_h.state();
        return {st.engine.points(), st.engine.options(), st.engine.position(), st.undoPoints.size(),
                st.source};
    }
    std::string unchanged(const Before& b, const std::string& what) const {
        const ui::AppState& st = m_h.state();
        if (st.engine.points() != b.points) return what + " changed the points";
        const dlab::InsertOptions& o = st.engine.options();
        if (o.boundary != b.options.boundary || o.locator != b.options.locator ||
            o.order != b.options.order || o.seed != b.options.seed) {
            return what + " changed the options";
        }
        if (st.engine.position() != b.position) return what + " moved the run";
        if (st.undoPoints.size() != b.undo) return what + " changed the undo history";
        if (st.source != b.source) return what + " changed the source name";
        return "";
    }

    std::string changeOptions() {
        static const dlab::Boundary kBoundaries[] = {dlab::Boundary::Exact, dlab::Boundary::Super};
        static const dlab::LocatorKind kLocators[] = {
            dlab::LocatorKind::Walk, dlab::LocatorKind::Naive, dlab::LocatorKind::Grid,
            dlab::LocatorKind::IdBufferCpu};
        static const dlab::OrderKind kOrders[] = {dlab::OrderKind::Input, dlab::OrderKind::Random,
                                                  dlab::OrderKind::Brio};
        ui::AppState& st = m_h.state();
        dlab::InsertOptions o = st.engine.options();
        o.boundary = pick(kBoundaries);
        o.locator = pick(kLocators);
        o.order = pick(kOrders);
        o.seed = 1 + below(5);
        note(std::string("setOptions boundary ") + toString(o.boundary) + ", locate " +
             toString(o.locator) + ", order " + toString(o.order) + ", seed " +
             std::to_string(o.seed));
        const Before b = before();
        const std::size_t messages = st.messages.size();
        if (!st.setOptions(o)) {
            m_log.back() += " -> refused";
            if (st.messages.size() == messages ||
                st.messages.back().level != ui::Message::Level::Error) {
                return "setOptions refused without an error message";
            }
            return unchanged(b, "a refused setOptions");
        }
        m_h.frames(2);
        if (st.engine.position() != 0) return "setOptions did not restart at operation 0";
        if (st.engine.points() != b.points) return "setOptions changed the points";
        return "";
    }

    std::string loadGenerated() {
        static const dlab::Generator kKinds[] = {
            dlab::Generator::Uniform,     dlab::Generator::Clusters,
            dlab::Generator::Grid,        dlab::Generator::RotatedGrid,
            dlab::Generator::Ngon,        dlab::Generator::Circle,
            dlab::Generator::Collinear,   dlab::Generator::NearDuplicates,
            dlab::Generator::HugeTinyBox, dlab::Generator::AllCollinear};
        static const std::size_t kSizes[] = {0, 1, 2, 3, 4, 5, 7, 10, 16, 24, 32, 40};
        const dlab::Generator kind = pick(kKinds);
        const std::size_t n = pick(kSizes);
        const std::uint64_t seed = 1 + below(1000);
        std::string name =
            std::string(toString(kind)) + " " + std::to_string(n) + " seed " + std::to_string(seed);
        note("load generated " + name);
        ui::AppState& st = m_h.state();
        const Before b = before();
        std::vector<Vec2> pts = dlab::generatePoints(kind, n, seed);
        const std::vector<Vec2> copy = pts;
        if (!st.loadPoints(std::move(pts), name)) {
            m_log.back() += " -> refused";
            return unchanged(b, "a refused load");
        }
        m_h.frames(2);
        if (st.engine.points() != copy) return "loadPoints shows other points than it was given";
        if (st.engine.position() != 0) return "loadPoints did not start at operation 0";
        return "";
    }

    void writeBadFiles() {
        auto write = [&](const std::string& name, const std::string& bytes) {
            std::ofstream(m_dir / name, std::ios::binary) << bytes;
            m_badFiles.push_back((m_dir / name).string());
        };
        write("nan.csv", "1,2\n3,nan\n5,6\n");
        write("inf.xy", "0 0\ninf 1\n2 2\n");
        write("overflow.csv", "1e400, 2\n3, 4\n5, 6\n");
        write("junk.csv", "hello world\nthis is not a point file\n");
        write("empty.csv", "");
        write("empty.node", "");
        write("short.node", "5 2 0 0\n1 0 0\n2 1 1\n");
        write("huge-count.node", "2147483647 2 0 0\n1 0 0\n2 1 1\n3 0 1\n");
        write("bad-session.json",
              "{\"format\": \"delaunay-lab session\", \"version\": 1, \"points\": [[0, 0], [1, "
              "\"x\"], [2, 2]]}\n");
        write("truncated-session.json",
              "{\"format\": \"delaunay-lab session\", \"version\": 1, \"points\": [[0, 0], [1");
        std::string binary = std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16);
        for (int i = 0; i < 300; ++i) binary.push_back(static_cast<char>(m_rng() & 0xff));
        write("binary.csv", binary);
        write("binary.node", binary);
        std::string braces = "{";
        for (int i = 0; i < 200; ++i) braces.push_back(static_cast<char>(m_rng() & 0xff));
        write("binary.json", braces);
        m_badFiles.push_back((m_dir / "does-not-exist.csv").string());
        m_badFiles.push_back(m_dir.string());  // a folder
    }

    std::string loadBadFile() {
        ui::AppState& st = m_h.state();
        const std::string path = m_badFiles[below(m_badFiles.size())];
        const bool viaOpen = chance(0.5);  // File > Open (points or session) or the point reader
        note(std::string(viaOpen ? "open" : "load points from") + " bad file " +
             fs::path(path).filename().string());
        const Before b = before();
        const std::size_t messages = st.messages.size();
        const bool loaded = viaOpen ? ui::openFile(st, path) : ui::loadPointFile(st, path);
        m_h.frames(2);
        if (loaded) return "the bad file " + path + " was accepted";
        if (std::string failure = unchanged(b, "a bad file"); !failure.empty()) return failure;
        bool named = false;
        for (std::size_t i = messages; i < st.messages.size(); ++i) {
            const ui::Message& msg = st.messages[i];
            if (msg.level != ui::Message::Level::Error) continue;
            if (msg.text.find('\n') != std::string::npos)
                return "the error for " + path + " spans several lines: " + msg.text;
            named |= msg.text.find(fs::path(path).filename().string()) != std::string::npos;
        }
        if (!named) return "no error message naming " + path;
        return "";
    }

    std::string openLessonFile() {
        if (!m_withLessons) return pressKey();
        static const std::vector<std::string> kLessons = lessonFiles();
        if (kLessons.empty()) return "no lessons found in lessons/";
        const std::string& path = kLessons[below(kLessons.size())];
        note("open lesson " + fs::path(path).filename().string());
        ui::AppState& st = m_h.state();
        if (!ui::openLesson(st, path))
            return "the lesson " + path + " did not open: " + st.messages.back().text;
        m_h.frames(2);
        return "";
    }

    std::string lessonStep() {
        ui::AppState& st = m_h.state();
        ui::LessonState& L = st.lessonPlayer;
        if (!m_withLessons || !L.lesson || L.lesson->stops.empty()) return clickStepButton();
        const std::size_t r = below(10);
        if (r < 3) {
            note("lesson Next");
            m_h.clickItem("lesson-next");
        } else if (r < 5) {
            note("lesson Previous");
            m_h.clickItem("lesson-previous");
        } else if (r < 6) {
            const std::size_t k = below(L.lesson->stops.size() + 2);  // past the end is clamped
            note("lesson go to stop " + std::to_string(k));
            ui::goToStop(st, k);
            m_h.frames(2);
            if (L.progress.stop != std::min(k, L.lesson->stops.size() - 1))
                return "goToStop did not go to the stop";
            if (st.engine.position() != L.plan.stops[L.progress.stop].position)
                return "goToStop did not seek to the stop's operation";
        } else if (r < 9) {
            // Answer through the field: the shown answer is always accepted, junk never is.
            const std::size_t k = L.progress.stop;
            st.itemRects.erase("lesson-answer");
            m_h.frames(1);
            if (k >= L.plan.stops.size() || !L.plan.stops[k].answer) {
                note("lesson: no question here");
                return "";
            }
            // The field and its button are recorded only where a user can see them: a long
            // stop text in a short column hides them below; scroll down to them, as a user would.
            for (int i = 0;
                 i < 12 && st.itemRects.count("lesson-text") &&
                 (!st.itemRects.count("lesson-answer") || !st.itemRects.count("lesson-check"));
                 ++i) {
                const auto r = m_h.rect("lesson-text");
                m_h.scroll((r[0] + r[2]) / 2, (r[1] + r[3]) / 2, -2);
                m_h.frames(1);
            }
            if (!st.itemRects.count("lesson-answer") || !st.itemRects.count("lesson-check")) {
                note("lesson: the question is scrolled out of view");
                return "";
            }
            const bool right = chance(0.5);
            const std::string text = right ? L.plan.stops[k].answer->display()
                                           : std::string("no idea #") + std::to_string(below(100));
            note("lesson answer '" + text + "'");
            closeHelp();
            // A user clears what an earlier try left in the field before typing the next one.
            m_h.frames(1);
            L.typed.clear();
            m_h.clickItem("lesson-answer");
            for (char c : text) ImGui::GetIO().AddInputCharacter(static_cast<unsigned char>(c));
            m_h.frames(2);
            m_h.clickItem("lesson-check");
            if (L.progress.stop == k && L.feedback == ui::LessonState::Feedback::None)
                return "Check gave no feedback";
            if (right && L.feedback == ui::LessonState::Feedback::Wrong)
                return "the lesson's own answer '" + text + "' was judged wrong";
            leaveTextFields();
        } else {
            note("close lesson");
            ui::closeLesson(st);
            m_h.frames(2);
            if (L.lesson) return "closeLesson left the lesson open";
        }
        return "";
    }

    std::string typeExpression() {
        if (!m_withLessons) return pressKey();
        ui::AppState& st = m_h.state();
        const std::string text = pick(kExpressions);
        note("console: '" + text + "'");
        closeHelp();
        if (!st.itemRects.count("Expressions")) {  // a lesson's stop that hides the tab
            m_log.back() += " (no Expressions tab on show)";
            return "";
        }
        m_h.clickItem("Expressions");
        m_h.frames(1);
        st.itemRects.erase("expr-input");
        m_h.frames(1);
        if (!st.itemRects.count("expr-input")) {
            m_log.back() += " (no console on show)";
            return "";
        }
        const std::size_t lines = st.expressions.history.size();
        m_h.clickItem("expr-input");
        for (char c : text) ImGui::GetIO().AddInputCharacter(static_cast<unsigned char>(c));
        m_h.frames(1);
        m_h.press(key::kEnter);
        m_h.frames(1);
        const bool printable =
            std::all_of(text.begin(), text.end(), [](char c) { return c >= 0x20 && c < 0x7f; });
        if (printable && !text.empty() && st.expressions.history.size() != lines + 1)
            return "the console did not answer '" + text + "'";
        if (!st.expressions.history.empty() &&
            st.expressions.history.back().answer.find('\n') != std::string::npos) {
            return "the console's answer spans lines: " + st.expressions.history.back().answer;
        }
        leaveTextFields();
        return "";
    }

    std::string togglePresentation() {
        ui::AppState& st = m_h.state();
        st.presentation = !st.presentation;
        note(std::string("presentation ") + (st.presentation ? "on" : "off"));
        m_h.frames(2);
        return "";
    }

    std::string runFrames() {
        const int n = 1 + static_cast<int>(below(6));
        note("run " + std::to_string(n) + " frames");
        m_h.frames(n);
        return "";
    }

    std::string toggleBreakpoint() {
        ui::AppState& st = m_h.state();
        auto& bps = st.run.breakpoints;
        if (!bps.empty() && chance(0.4)) {
            const std::size_t i = below(bps.size());
            note("remove breakpoint " + dlab::toString(bps[i].bp));
            bps.erase(bps.begin() + static_cast<std::ptrdiff_t>(i));
            return "";
        }
        static const char* const kTexts[] = {"flip",       "insertion", "degenerate", "duplicate",
                                             "split-edge", "located",   "finalize"};
        std::string text = pick(kTexts);
        if (chance(0.3))
            text = "insert:" +
                   std::to_string(below(std::max<std::size_t>(1, st.engine.points().size())));
        const auto bp = dlab::parseBreakpoint(text);
        if (!bp) return "the breakpoint text '" + text + "' does not parse";
        note("add breakpoint " + text);
        bps.push_back({*bp, true});
        return "";
    }

    std::string clickTimeline() {
        if (!m_h.state().itemRects.count("timeline")) return runFrames();
        const auto r = m_h.rect("timeline");
        const float x = between(r[0] + 2, r[2] - 2);
        note("click timeline at x " + std::to_string(x));
        m_h.click(x, (r[1] + r[3]) / 2);
        return "";
    }

    // The help window covers most of a small window: a user closes it before typing elsewhere.
    void closeHelp() {
        if (!m_h.state().showHelp) return;
        m_log.back() += " (Esc closes the help first)";
        // The first Esc may only leave a text field.
        for (int i = 0; i < 2 && m_h.state().showHelp; ++i) {
            m_h.press(key::kEscape);
            m_h.frames(1);
        }
    }

    std::string dismissNotice() {
        ui::AppState& st = m_h.state();
        if (st.files.notice.empty() || !st.itemRects.count("notice-dismiss")) return runFrames();
        note("dismiss the file notice");
        m_h.clickItem("notice-dismiss");
        return "";
    }

    // Back to operation 0 and forward again: the same V/O; and the same as a fresh replay.
    std::string checkStepBack() {
        ui::AppState& st = m_h.state();
        ui::Engine& e = st.engine;
        if (e.batch()) return "";
        const std::size_t p = e.position();
        const MeshCopy at = copyOf(e.mesh());
        e.seek(0);
        if (e.position() != 0) return "seek(0) did not reach operation 0";
        if (e.mesh().numTriangles() != 0) return "operation 0 has triangles";
        e.seek(p);
        if (e.position() != p)
            return "seek(" + std::to_string(p) + ") stopped at " + std::to_string(e.position());
        if (!(copyOf(e.mesh()) == at))
            return "back to 0 and forward to " + std::to_string(p) + " gave another V/O";
        ui::Engine fresh;
        std::string error;
        // The same run afresh: insertion, or the flip algorithm from the triangles its Start put
        // in the table (Start queues edges unless the mesh is only shown).
        bool made = false;
        if (e.repairs()) {
            e.seek(1);
            dlab::Inserter::StartMesh start{e.mesh().V, e.mesh().O};
            const bool flips = !e.inserter().flipStack().empty();
            e.seek(p);
            made = fresh.resetRepair(e.points(), std::move(start), flips, error);
            fresh.seek(p);
        } else {
            made = fresh.resetAt(e.points(), e.options(), p, error);
            for (const std::string& text : ui::editTexts(e)) {  // and the edits after the run
                const auto edit = dlab::parseEdit(text);
                if (made && (!edit || !fresh.edit(*edit, error)))
                    return "a fresh replay refused " + text + ": " + error;
            }
            fresh.seek(p);
        }
        if (!made) return "a fresh replay was refused: " + error;
        if (!(copyOf(fresh.mesh()) == at))
            return "a fresh replay to " + std::to_string(p) + " gives another V/O";
        m_h.frames(1);
        return "";
    }

    std::uint64_t m_seed;
    std::mt19937_64 m_rng;
    UiHarness& m_h;
    fs::path m_dir;
    std::ofstream m_logFile;
    std::vector<std::string> m_badFiles;
    std::vector<std::string> m_log;
    std::size_t m_step = 0;
    bool m_withLessons = true;
    std::string m_screenshot = "(none)";
};

// DLAB_GUI_ROBUST_SEED replaces the test's own seed (run one instance: --gtest_filter=.../0).
std::uint64_t seedFor(std::uint64_t param) {
    const std::size_t chosen = envCount("DLAB_GUI_ROBUST_SEED", 0);
    return chosen ? chosen : param;
}

}  // namespace

class GuiRobustness : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(GuiRobustness, RandomActionsKeepTheMeshValid) {
    const std::uint64_t seed = seedFor(GetParam());
    const std::size_t actions = envCount("DLAB_GUI_ROBUST_ACTIONS", kDefaultActions);
    std::printf("[ info ] seed %llu, %zu actions\n", static_cast<unsigned long long>(seed),
                actions);
    UiHarness h(kWidth, kHeight);
    RandomUser user(seed, h);
    const std::string failure = user.run(actions);
    ASSERT_TRUE(failure.empty()) << user.report(failure);
}

INSTANTIATE_TEST_SUITE_P(Seeds, GuiRobustness, ::testing::Values(1, 2, 3, 4, 5, 6));

class GuiRobustnessUndo : public ::testing::TestWithParam<std::uint64_t> {};

// Undoing every edit (Ctrl+Z until nothing changes) brings back the original point set exactly,
// whatever edits, loads, option changes and steps came between; Ctrl+Y redoes them all.
TEST_P(GuiRobustnessUndo, UndoingEveryEditBringsBackTheOriginalPoints) {
    {
        const std::uint64_t seed = seedFor(GetParam());
        const std::size_t actions = envCount("DLAB_GUI_ROBUST_ACTIONS", kUndoActions);
        std::printf("[ info ] seed %llu, %zu actions, then undo all\n",
                    static_cast<unsigned long long>(seed), actions);
        UiHarness h(kWidth, kHeight);
        const std::vector<Vec2> original = h.state().engine.points();
        RandomUser user(seed, h);
        const std::string failure = user.run(actions, /*withLessonsAndConsole=*/false);
        ASSERT_TRUE(failure.empty()) << user.report(failure);
        user.leaveTextFields();
        const std::vector<Vec2> last = h.state().engine.points();
        const std::size_t edits = h.state().undoPoints.size();
        const std::size_t undone = user.undoAll();
        EXPECT_EQ(undone, edits) << user.report("not every edit could be undone");
        EXPECT_TRUE(h.state().undoPoints.empty());
        ASSERT_TRUE(h.state().engine.points() == original)
            << user.report("after undoing everything the points are not the original ones (" +
                           std::to_string(h.state().engine.points().size()) + " points, " +
                           std::to_string(original.size()) + " at the start)");
        EXPECT_EQ(checkInvariants(h.state()), "");
        const std::size_t redone = user.redoAll();
        EXPECT_EQ(redone, undone);
        EXPECT_TRUE(h.state().engine.points() == last)
            << user.report("redoing everything does not give the last points back");
    }
}

INSTANTIATE_TEST_SUITE_P(Seeds, GuiRobustnessUndo, ::testing::Values(101, 102));
