// dtlab render: a screenshot of the whole GUI after K operations, rendered headlessly (EGL or
// OSMesa: --gl).
#include "app/dtlab_common.h"

#include "core/engine/generators.h"
#include "core/engine/mesh_read.h"
#include "core/engine/output_files.h"
#include "core/engine/text_util.h"
#include "ui/gl/mesh_renderer.h"
#include "ui/gui.h"
#include "ui/lesson_player.h"
#include "ui/panels/panels.h"
#include "ui/render/drawn_marks.h"
#include "ui/render/drawn_text.h"

#include <imgui.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iostream>

namespace dlab::cli {

namespace {

struct RenderArgs {
    std::string input;
    std::string output;
    std::string size = "1600x1000";
    long long steps = -1;
    bool toEnd = false;
    long long select = -1;
    bool presentation = false;
    std::vector<std::string> overlays;
    int benchFrames = 0;
    std::string tab;
    bool slideText = false;
    std::string lesson;
    int stop = 1;
    std::string slides;
    bool handout = false;
    std::vector<std::string> edits;  // after the run's end, in order
    long long editSteps = -1;        // ops of the last edit done (-1: all)
    EngineFlags engine;
};

double cpuMs(clockid_t clock) {
    timespec t{};
    clock_gettime(clock, &t);
    return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) / 1e6;
}
double processCpuMs() { return cpuMs(CLOCK_PROCESS_CPUTIME_ID); }
double mainThreadCpuMs() { return cpuMs(CLOCK_THREAD_CPUTIME_ID); }

// Frame times: idle (nothing changes), then running at full speed (the mesh changes every
// frame), then scrolling the corner table. Wall-clock ms per frame, mean over the frames.
void benchFrames(ui::Gui& gui, ui::AppState& state, int frames) {
    using Clock = std::chrono::steady_clock;
    double buildMs = 0, cpuMs = 0, mainMs = 0;
    auto timeFrames = [&](int n, auto&& before) {
        double total = 0, worst = 0;
        buildMs = cpuMs = mainMs = 0;
        for (int i = 0; i < n; ++i) {
            before(i);
            const auto t0 = Clock::now();
            const double c0 = processCpuMs(), m0 = mainThreadCpuMs();
            gui.frame();
            cpuMs += processCpuMs() - c0;
            mainMs += mainThreadCpuMs() - m0;
            const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
            total += ms;
            worst = std::max(worst, ms);
            buildMs += state.frameStats.meshBuildMs;
        }
        return std::pair{total / std::max(1, n), worst};
    };
    const auto idle = timeFrames(frames, [](int) {});
    std::printf(
        "frame ms, idle:       mean %.1f, worst %.1f, cpu %.1f (%zu points, %d triangles)\n",
        idle.first, idle.second, cpuMs / frames, state.engine.points().size(),
        state.engine.mesh().numTriangles());
    if (!state.engine.batch() && !state.engine.atEnd()) {
        state.run.running = true;
        state.run.opsPerSecond = ui::RunControl::kFullSpeed;
        // One frame first: llvmpipe compiles its shaders the first time a mesh is drawn (~1 s).
        const auto w0 = Clock::now();
        gui.frame();
        const double warmMs = std::chrono::duration<double, std::milli>(Clock::now() - w0).count();
        const std::size_t p0 = state.engine.position();
        // Only frames of a running animation count (a short run may end before `frames`).
        int timed = 0;
        const auto running = timeFrames(frames, [&](int) { timed += state.run.running ? 1 : 0; });
        const int n = std::max(1, timed);
        std::printf(
            "frame ms, full speed: mean %.1f, worst %.1f, cpu %.1f (main thread %.1f) over %d "
            "running frames (%.0f operations and %.1f ms of mesh rebuild per frame; the first "
            "frame, with shader compilation: %.0f ms)\n",
            running.first * frames / n, running.second, cpuMs / n, mainMs / n, timed,
            static_cast<double>(state.engine.position() - p0) / n, buildMs / n, warmMs);
        state.run.running = false;
    }
    ImGuiIO& io = ImGui::GetIO();
    const auto r = state.itemRects["corner-table"];
    io.MousePos = ImVec2((r[0] + r[2]) / 2, (r[1] + r[3]) / 2);
    const auto scrolling = timeFrames(frames, [&](int) { io.MouseWheel = -3; });
    io.MouseWheel = 0;
    std::printf("frame ms, scrolling the corner table (%d rows): mean %.1f, worst %.1f\n",
                state.engine.mesh().numCorners(), scrolling.first, scrolling.second);
}

// The drawing of a changing mesh alone: before each frame the run moves `ops` operations on
// (outside the frame's time), from the same position with the raster patched and redrawn whole.
// Wall-clock and process CPU ms (all threads, llvmpipe's included: steadier on a loaded machine).
void benchChangingFrames(ui::Gui& gui, ui::AppState& state, int frames, std::size_t ops) {
    if (state.engine.batch()) return;
    state.run.running = false;
    const std::size_t was = state.engine.position();
    const std::size_t start = state.engine.recorded() / 2;
    for (const bool patch : {true, false}) {
        ui::MeshRenderer::setPatching(patch);
        state.engine.seek(start);
        gui.frame();
        double wall = 0, cpu = 0, mainCpu = 0, build = 0, vertices = 0;
        for (int i = 0; i < frames; ++i) {
            state.engine.seek(state.engine.position() + ops);
            const auto t0 = std::chrono::steady_clock::now();
            const double c0 = processCpuMs(), m0 = mainThreadCpuMs();
            gui.frame();
            cpu += processCpuMs() - c0;
            mainCpu += mainThreadCpuMs() - m0;
            vertices += ImGui::GetDrawData() ? ImGui::GetDrawData()->TotalVtxCount : 0;
            wall += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                        .count();
            build += state.frameStats.meshBuildMs;
        }
        std::printf(
            "frame ms, %zu more operations each, %s: wall mean %.1f, cpu mean %.1f (main "
            "thread %.1f; mesh update %.1f ms wall; %.0f ImGui vertices)\n",
            ops, patch ? "raster patched" : "raster redrawn whole", wall / frames, cpu / frames,
            mainCpu / frames, build / frames, vertices / frames);
    }
    ui::MeshRenderer::setPatching(true);
    state.engine.seek(was);
}

// The window size from --size, after checking that the options make a command.
std::pair<int, int> checkRenderArgs(const RenderArgs& args) {
    if (args.slideText && args.lesson.empty()) fail("--slide-text needs --lesson", 2);
    if (args.output.empty() && !args.slideText && (args.slides.empty() || args.lesson.empty()))
        fail("render needs -o FILE.png (or --lesson L --slides DIR)", 2);
    if (!args.slides.empty() && args.lesson.empty()) fail("--slides needs --lesson", 2);
    int width = 0, height = 0;
    if (std::sscanf(args.size.c_str(), "%dx%d", &width, &height) != 2 || width < 320 ||
        height < 240 || width > 8192 || height > 8192) {
        fail("--size must be WIDTHxHEIGHT between 320x240 and 8192x8192, not \"" + args.size + "\"",
             2);
    }
    return {width, height};
}

// One slide per stop of the open lesson (or per slide of the open track): DIR/01.png,
// DIR/02.png, ..., written as one set (all of them, or none and the old ones kept).
void writeSlides(ui::Gui& gui, ui::AppState& state, const RenderArgs& args, int height) {
    const std::size_t stops = ui::slideCount(state);
    std::error_code ec;
    std::filesystem::create_directories(args.slides, ec);
    std::vector<std::string> pngs(stops);
    std::vector<OutputFile> files;
    for (std::size_t k = 0; k < stops; ++k) {
        ui::goToSlide(state, k);
        for (int i = 0; i < 3; ++i) gui.frame();
        if (const auto q = state.itemRects.find("slide-question");
            q != state.itemRects.end() &&
            (q->second[3] > static_cast<float>(height) || q->second[1] < 0))
            std::cout << "stop " << k + 1 << ": the question does not fit the slide\n";
        const auto box = state.itemRects.find("slide-text"),
                   content = state.itemRects.find("slide-text-content");
        if (box != state.itemRects.end() && content != state.itemRects.end() &&
            content->second[3] > box->second[3] + 1)
            std::cout << "stop " << k + 1 << ": the text does not fit the slide (it scrolls)\n";
        char name[32];
        std::snprintf(name, sizeof name, "/%02zu.png", k + 1);
        pngs[k] = gui.screenshotPng();
        if (pngs[k].empty()) fail("cannot write " + args.slides + name + ": no image to write");
        files.push_back({args.slides + name, [&png = pngs[k]](std::ostream& os) {
                             os.write(png.data(), std::ssize(png));
                         }});
    }
    writeTextFiles(files);
    std::cout << "wrote " << stops << " slides to " << escapeControls(args.slides) << "\n";
}

// The open lesson at the stop --stop names.
void goToLessonStop(ui::AppState& state, const RenderArgs& args) {
    const std::size_t stops = ui::slideCount(state);
    if (args.stop < 1 || static_cast<std::size_t>(args.stop) > std::max<std::size_t>(stops, 1)) {
        fail("--stop must be between 1 and " + std::to_string(stops) + " for " + args.lesson, 2);
    }
    ui::goToSlide(state, static_cast<std::size_t>(args.stop - 1));
}

// The points: the input file, or the built-in demo.
void loadRenderInput(ui::AppState& state, const RenderArgs& args) {
    if (args.input.empty()) {
        state.loadPoints(demoPoints(), "built-in demo");
        return;
    }
    const std::string ext = lowered(std::filesystem::path(args.input).extension().string());
    if (isMeshPath(args.input) && ext != ".json") {  // checked, then repaired by flips
        if (!ui::openMeshFile(state, args.input)) fail(state.messages.back().text);
        return;
    }
    LoadedPoints loaded = loadPoints(args.input);
    if (!state.loadPoints(std::move(loaded.points), args.input)) fail(state.messages.back().text);
}

// The overlays' names, "fill, vertex-ids, ...", for the help and the error.
std::string overlayNames() {
    std::string out;
    for (const OverlaySwitch& s : kOverlaySwitches)
        out += (out.empty() ? "" : ", ") + std::string(s.name);
    return out;
}

// NAME turns an overlay on, no-NAME off.
void applyOverlays(ui::Overlays& ov, const std::vector<std::string>& overlays) {
    for (const std::string& o : overlays) {
        const bool off = o.rfind("no-", 0) == 0;
        bool* flag = overlaySwitch(ov, off ? std::string_view(o).substr(3) : std::string_view(o));
        if (!flag)
            fail("unknown --overlay \"" + o + "\" (" + overlayNames() + ", or no- before one)", 2);
        *flag = !off;
    }
}

// --edit: each edit after the run's end, done in full but the last, which is done up to
// --edit-steps of its ops (all without).
void applyEdits(ui::Engine& engine, const RenderArgs& args) {
    for (std::size_t k = 0; k < args.edits.size(); ++k) {
        const auto edit = parseEdit(args.edits[k]);
        if (!edit) {
            fail("--edit \"" + args.edits[k] +
                     "\": expected \"remove vertex V\", \"constrain A-B\" or \"unconstrain A-B\"",
                 2);
        }
        std::string message;
        if (!engine.edit(*edit, message)) fail("--edit \"" + args.edits[k] + "\": " + message, 2);
        const std::size_t start = engine.position();
        const bool last = k + 1 == args.edits.size();
        engine.seek(last && args.editSteps >= 0 ? start + static_cast<std::size_t>(args.editSteps)
                                                : engine.recorded());
    }
}

// Without a lesson (which decides the position and the selection itself): --to-end or --steps,
// then --select.
void moveAndSelect(ui::AppState& state, const RenderArgs& args) {
    if (!args.lesson.empty()) return;
    if (!args.edits.empty()) {
        applyEdits(state.engine, args);
    } else if (args.toEnd) {
        while (!state.engine.toEnd(1 << 20)) {}
    } else if (args.steps >= 0) {
        state.engine.seek(static_cast<std::size_t>(args.steps));
    }
    if (args.select < 0) return;
    const std::int32_t corners = state.engine.mesh().numCorners();
    if (args.select >= corners) {
        fail("--select " + std::to_string(args.select) + ": the mesh at operation " +
                 std::to_string(state.engine.position()) + " has corners 0 to " +
                 std::to_string(corners - 1),
             2);
    }
    state.select(static_cast<std::int32_t>(args.select));
}

// What `lesson check` reads on each slide: the lines of text drawn, stop by stop.
void printSlideText(const std::string& lesson) {
    const auto slides = renderedSlides(lesson);
    for (std::size_t k = 0; k < slides.size(); ++k) {
        std::cout << "## stop " << k + 1 << "\n";
        for (const std::string& line : slides[k].lines) std::cout << escapeControls(line) << "\n";
    }
}

void runRender(const RenderArgs& args) {
    const auto [width, height] = checkRenderArgs(args);
    if (args.slideText) return printSlideText(args.lesson);
    ui::AppState state;
    std::string error;
    auto platform = headlessPlatform(width, height);
    ui::Gui gui(*platform, state);
    state.presentation = args.presentation || args.handout;
    state.handoutSlides = args.handout;
    state.setUserOptions(args.engine.options());  // the defaults its help states (order brio)
    if (!args.lesson.empty()) {
        if (!ui::openLesson(state, args.lesson)) fail(state.messages.back().text, 2);
        if (!args.slides.empty()) {
            writeSlides(gui, state, args, height);
            return;
        }
        goToLessonStop(state, args);
    } else {
        loadRenderInput(state, args);
    }
    applyOverlays(state.overlays, args.overlays);
    moveAndSelect(state, args);
    state.pendingTab = args.tab;
    // ImGui lays out in the first frames (tables measure their columns): render a few.
    for (int i = 0; i < 3; ++i) gui.frame();
    if (args.benchFrames > 0) {
        benchFrames(gui, state, args.benchFrames);
        for (const std::size_t ops : {std::size_t{1}, std::size_t{20000}})
            benchChangingFrames(gui, state, args.benchFrames, ops);
    }
    if (!gui.saveScreenshot(args.output, error)) fail(error);
    std::cout << "wrote " << escapeControls(args.output) << " (" << width << "x" << height
              << ", operation " << state.engine.position() << " of " << state.engine.recorded()
              << ", " << state.engine.mesh().numTriangles() << " triangles)\n";
}

}  // namespace

std::vector<RenderedSlide> renderedSlides(const std::string& lessonPath) {
    ui::AppState state;
    auto platform = headlessPlatform(1280, 720);
    ui::Gui gui(*platform, state);
    state.presentation = true;
    if (!ui::openLesson(state, lessonPath)) fail(state.messages.back().text, 2);
    std::vector<RenderedSlide> out;
    for (std::size_t k = 0; k < state.lessonPlayer.lesson->stops.size(); ++k) {
        ui::goToStop(state, k);
        for (int i = 0; i < 2; ++i) gui.frame();  // as the slides are: laid out, then drawn
        RenderedSlide slide;
        {
            const ui::MarkRecording recording(slide.marks);
            gui.frame();
        }
        for (ui::DrawnText& r : ui::drawnText(ImGui::GetDrawData()))
            slide.runs.push_back({std::move(r.text), {r.x0, r.y0, r.x1, r.y1}, r.list});
        std::vector<ui::DrawnText> runs;
        for (const SlideRun& r : slide.runs)
            runs.push_back({r.text, r.box.x0, r.box.y0, r.box.x1, r.box.y1, r.list});
        slide.lines = ui::drawnLines(runs);
        out.push_back(std::move(slide));
    }
    return out;
}

void addRender(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand(
        "render", "Screenshot of the whole GUI after K operations (headless GL: --gl)");
    cmd->add_option("input", args->input,
                    "Point file (.node, .csv, .xy, .pts); the built-in demo when absent");
    cmd->add_option("-o,--output", args->output,
                    "PNG file to write (not needed with --lesson L --slides DIR)");
    auto* steps = cmd->add_option("--steps,--step", args->steps,
                                  "Operations to perform before the screenshot")
                      ->check(CLI::Validator(
                          [](std::string& v) {
                              return !v.empty() && v[0] == '-'
                                         ? "--steps must be 0 or more, not " + v
                                         : std::string();
                          },
                          "N >= 0"));
    cmd->add_flag("--to-end", args->toEnd, "Run to the end before the screenshot")->excludes(steps);
    cmd->add_option("--size", args->size, "Window size WIDTHxHEIGHT")->capture_default_str();
    auto* edits =
        cmd->add_option("--edit", args->edits,
                        "An edit after the run's end (repeatable, in order): \"remove "
                        "vertex V\", \"constrain A-B\", \"unconstrain A-B\", \"move vertex V to X, "
                        "Y\"")
            ->excludes(steps);
    cmd->add_option("--edit-steps", args->editSteps,
                    "Operations of the last --edit done before the screenshot (all without)")
        ->needs(edits)
        ->check(CLI::Range(0LL, 1LL << 40));
    cmd->add_option("--select", args->select, "Select this corner (inspector, highlights)")
        ->check(CLI::Validator(
            [](std::string& v) {
                return !v.empty() && v[0] == '-' ? "--select must be a corner, 0 or more, not " + v
                                                 : std::string();
            },
            "C >= 0"));
    cmd->add_flag("--presentation", args->presentation,
                  "Presentation mode (large fonts, high contrast)");
    cmd->add_option("--lesson", args->lesson,
                    "A lesson (.toml) or a track of lessons' stops: render one of its stops");
    cmd->add_flag("--handout", args->handout,
                  "Slides for a handout: the canvas and the text only (no menus, buttons, answer "
                  "box or side tab); implies --presentation");
    cmd->add_option("--stop", args->stop, "The lesson's stop to render (1-based)")
        ->capture_default_str();
    cmd->add_option("--slides", args->slides,
                    "Render every stop of the lesson to DIR/01.png, DIR/02.png, ... (slides with "
                    "--presentation)");
    cmd->add_flag("--slide-text", args->slideText,
                  "With --lesson: print the text drawn on each stop's slide (1280x720, "
                  "presentation), as `lesson check` reads it");
    cmd->add_option("--bench-frames", args->benchFrames,
                    "Also time this many frames idle, running and scrolling (at most 1000: the "
                    "running frames record the run's history as they go)")
        ->check(CLI::Range(0, 1000));
    cmd->add_option("--tab", args->tab, "The side tab to show")
        ->check(CLI::IsMember(ui::sideTabIds()));
    cmd->add_option("--overlay", args->overlays,
                    "An overlay to turn on (" + overlayNames() +
                        "), or off with no- before its name (repeatable)");
    args->engine.add(*cmd);
    cmd->parse_complete_callback(needGl);
    cmd->callback([args] { guarded([&] { runRender(*args); }); });
}

}  // namespace dlab::cli
