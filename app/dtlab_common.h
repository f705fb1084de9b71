// Shared pieces of dtlab's subcommands: option sets, loading with one-line errors, and the
// registration function of each subcommand (one file each).
//
// Three executables share these sources: dtlab links no GL (Mesa's LLVM alone keeps ~50 MB
// resident); dtlab-gl links EGL and libOpenGL (a GPU, or Mesa's llvmpipe) and dtlab-gl-osmesa
// OSMesa (libOSMesa and libOpenGL both export the gl* functions: one executable cannot link
// both). dtlab runs every command that needs no GL itself and re-runs the others (render,
// table1, --locate idbuffer-gl*) in dtlab-gl beside it, which re-runs them in dtlab-gl-osmesa
// when --gl says so (auto: when there is no GPU). The pieces that differ are in dtlab_no_gl.cpp,
// dtlab_gl.cpp (both GL executables) and dtlab_gl_egl.cpp / dtlab_gl_osmesa.cpp.
#pragma once

#include "core/engine/halves.h"
#include "core/engine/inserter.h"
#include "core/engine/text_util.h"  // escapeControls: file names in messages
#include "core/teaching/slide_check.h"
#include "ui/gl/idbuffer_gl.h"
#include "ui/platform/platform.h"

#include <CLI/CLI.hpp>

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace dlab::cli {

// Insertion options as command-line flags (--locate, --order, --boundary, --seed).
struct EngineFlags {
    std::string locate = "walk";
    std::string order = "brio";
    std::string boundary = "exact";
    std::uint64_t seed = 1;
    int idBufferSize = 1600;
    std::string readback;  // GL ID buffer: one | batched | pipelined ("": as --locate says)
    int batch = 256;       // GL ID buffer, batched: points per readback
    void add(CLI::App& cmd);
    InsertOptions options() const;
    ui::IdBufferGlOptions glOptions() const;
    // An Inserter for these flags. The GL locators (--locate idbuffer-gl[-batched]) need a GL
    // context, which core cannot make: they are built on the headless GL context (--gl).
    // `threads`: what the insertion order's sorts may use (the run itself is one inserter's).
    std::unique_ptr<Inserter> makeInserter(std::vector<Vec2> points, int threads = 1) const;
    std::unique_ptr<Inserter> makeGlInserter(std::vector<Vec2> points) const;  // dtlab-gl only
};

// The batch triangulation on two cores (core/engine/halves.h: the halves on two threads, then
// joined; the points move into the result). Empty, the points untouched, when that path does not
// apply (another boundary or locator than exact and walk, a set too small to split, a half on
// one line, a pilot run on a sample that finds the split would cost more than it saves): run the
// inserter then. `declined`, when given, gets why in a few words (empty when it applies).
std::optional<JoinedTriangulation> triangulateOnTwoCores(std::vector<Vec2>& points,
                                                         const InsertOptions& options,
                                                         std::string* declined = nullptr);

// --gl egl | osmesa | auto: which headless OpenGL the GL commands run on (auto: EGL on a GPU
// when there is one, else OSMesa, else EGL on Mesa's llvmpipe). Every GL command has it.
void addGlFlag(CLI::App& cmd);
const std::string& glFlag();

// The process' headless GL context (--gl; made current on first use); fail()s when there is
// none. GL locators on it must be destroyed before main returns. The GL executables only.
std::shared_ptr<ui::GlContext> headlessGl();
// A headless platform of that size on the GL --gl chose (render: the whole GUI); fail()s when
// there is none. The first context made says on stderr which GL it is. The GL executables only.
std::unique_ptr<ui::Platform> headlessPlatform(int width, int height);
// Where the GL runs, once a context was made: "EGL (GPU device 0)", "OSMesa", ...; GL_RENDERER
// and GL_VERSION.
struct GlInfo {
    std::string api, renderer, version;
};
const GlInfo& glInfo();
// Destroys that context (if any) before main returns; nothing in dtlab.
void releaseGl();

// The command line as main() received it, for dtlab to hand on to dtlab-gl.
void rememberCommandLine(int argc, char** argv);
const std::vector<char*>& commandLine();
// Replaces this process with the executable `name` beside it, on the same command line; when
// that cannot start, says so (`why` needs it) and exits 1.
[[noreturn]] void execBeside(const char* name, const std::string& why);
// The command line asks for GL (called while it is parsed, before any work): dtlab replaces
// itself with dtlab-gl on the same command line; the GL executables note it for chooseGl.
void needGl();
// Called once the whole command line is parsed, before the command runs: when it needs GL, the
// GL executables settle --gl, and re-run it in the other GL executable when that one has the GL
// asked for. Nothing in dtlab.
void chooseGl();

// Each stop's slide of a lesson as drawn (1280x720, presentation mode): the text read back from
// the rendered frames (ui/render/drawn_text.h) and the canvas's marks (ui/render/drawn_marks.h).
// dtlab-gl only: dtlab runs `lesson check` there (needGl). On a lesson that cannot be opened:
// fail()s with its error.
std::vector<RenderedSlide> renderedSlides(const std::string& lessonPath);

// Loads a point file; on bad input prints "dtlab: error: FILE:LINE: what" and throws Exit.
struct LoadedPoints {
    std::vector<Vec2> points;
    int indexBase = 0;
};
LoadedPoints loadPoints(const std::string& path);

// A progress line for work that can run past a few seconds: on a terminal (stderr), redrawn in
// place at most four times a second with the share done and an estimate of the time left; nothing
// at all when stderr is not a terminal (a pipe, a file, a test). Cleared when it ends.
class Progress {
public:
    Progress(std::string what, double total);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;
    // `work` more done (in the units of `total`); `detail` says what runs now ("n = 65536").
    void advance(double work, const std::string& detail = {});
    // `done` of the total done in all (for work that counts its own progress).
    void set(double done, const std::string& detail = {}) { advance(done - m_done, detail); }
    // Takes the line off the terminal (before other output); the next advance draws it again.
    void clear();
    // The line as it would be drawn after `elapsedS` seconds with `done` of the total done.
    static std::string line(const std::string& what, double done, double total, double elapsedS,
                            const std::string& detail);

private:
    std::string m_what;
    double m_total, m_done = 0;
    bool m_tty, m_shown = false;
    std::chrono::steady_clock::time_point m_start, m_drawn;
};

// Says on stderr, before the work, when the options make a run slow (an ID buffer of many
// pixels on the CPU, a GL locator on coordinates float pixels cannot tell apart), and what is
// faster. Nothing when they do not.
void noteSlowChoices(const InsertOptions& options, const std::vector<Vec2>& points);

// Thrown to leave a subcommand with a status after printing one line to stderr.
struct Exit {
    int code;
};
[[noreturn]] void fail(const std::string& message, int code = 1);

// Runs `body`, turning Exit and exceptions into a one-line error and an exit status.
void guarded(const std::function<void()>& body);
int exitCode();

void addDemo(CLI::App& app);
void addGen(CLI::App& app);
void addTriangulate(CLI::App& app);
void addTrace(CLI::App& app);
void addBench(CLI::App& app);
void addLesson(CLI::App& app);     // dtlab_lesson.cpp
void addDiffTrace(CLI::App& app);  // dtlab_diff_trace.cpp
void addCheck(CLI::App& app);      // dtlab_check.cpp: check and repair
void addRender(CLI::App& app);
void addTable1(CLI::App& app);  // dtlab_table1.cpp

}  // namespace dlab::cli
