// delaunay-lab: the step-through GUI in a real window (GLFW + libGL). With no display it says
// so and renders the same view headlessly to a PNG (through `dtlab render`, which uses EGL or
// OSMesa: one GL provider per executable).
#include "core/engine/stack_reserve.h"
#include "core/engine/text_util.h"
#include "ui/files/files.h"
#include "ui/files/settings.h"
#include "ui/gui.h"
#include "ui/lesson_player.h"
#include "ui/panels/panels.h"

#include <CLI/CLI.hpp>

#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

// SIGTERM, SIGHUP or SIGINT (a logout, a shutdown, Ctrl+C in the terminal): the frame loop ends
// and the exit is a clean one (settings written, the autosave removed).
volatile sig_atomic_t g_stop = 0;

void requestStop(int) { g_stop = 1; }

void stopOnSignals() {
    struct sigaction sa {};
    sa.sa_handler = requestStop;
    sigemptyset(&sa.sa_mask);
    for (const int sig : {SIGTERM, SIGHUP, SIGINT}) sigaction(sig, &sa, nullptr);
}

// Runs `dtlab render` (beside this executable) on the same input; returns its exit status.
int renderHeadless(const std::string& input, const std::string& png, const std::string& reason) {
    std::error_code ec;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
    const std::string dtlab = (ec ? std::filesystem::path(".") : self.parent_path()) / "dtlab";
    std::cerr << "delaunay-lab: " << reason << "\n"
              << "delaunay-lab: rendering " << (input.empty() ? "the built-in demo" : input)
              << " headlessly to " << png << " instead (" << dtlab << " render)\n";
    std::vector<std::string> args = {dtlab, "render"};
    if (!input.empty()) args.push_back(input);
    args.insert(args.end(), {"--steps", "40", "-o", png});
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(dtlab.c_str(), argv.data());
    std::cerr << "delaunay-lab: cannot run " << dtlab << "\n";
    return 1;
}

// For tests that drive the real window from outside (tests/ui/xvfb_lesson_slides.sh): the
// lesson's state and where the widgets are, as JSON, rewritten (whole, by rename) when it changes.
void writeTestInfo(const std::string& path, const dlab::ui::AppState& st, std::string& last) {
    std::ostringstream j;
    const auto& L = st.lessonPlayer;
    static const char* const kFeedback[] = {"none", "right", "wrong", "shown"};
    j << "{\"presentation\": " << (st.presentation ? "true" : "false")
      << ", \"slide\": " << (dlab::ui::slideMode(st) ? "true" : "false")
      << ", \"stop\": " << (L.lesson ? L.progress.stop + 1 : 0)
      << ", \"position\": " << st.engine.position() << ", \"feedback\": \""
      << kFeedback[static_cast<int>(L.feedback)] << "\", \"rects\": {";
    const char* sep = "";
    for (const auto& [name, r] : st.itemRects) {
        if (name.find_first_of("\"\\") != std::string::npos) continue;
        j << sep << "\"" << name << "\": [" << r[0] << ", " << r[1] << ", " << r[2] << ", " << r[3]
          << "]";
        sep = ", ";
    }
    j << "}}\n";
    if (j.str() == last) return;
    last = j.str();
    const std::string tmp = path + ".tmp";
    std::ofstream(tmp) << last;
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
}

}  // namespace

int main(int argc, char** argv) {
    dlab::reserveStack();  // out of memory opening a file is then a message, never a SIGSEGV
    CLI::App cli{"Delaunay Lab: step through incremental Delaunay triangulation on a corner table"};
    std::string input, screenshot, testInfo, fallbackPng = "delaunay-lab.png";
    int frames = 0;
    bool noSettings = false, noAutosave = false;
    cli.add_option(
        "input", input,
        "Point file (.node, .csv, .xy, .pts) or session (.json); the built-in demo when absent");
    cli.add_option("--screenshot", screenshot,
                   "Save a PNG of the window after --frames frames, then quit");
    cli.add_option("--frames", frames, "Quit after this many frames (0: run until closed)")
        ->check(CLI::NonNegativeNumber);
    cli.add_option("--headless-png", fallbackPng, "Where to render when there is no display")
        ->capture_default_str();
    cli.add_option("--test-info", testInfo,
                   "Keep FILE up to date with the lesson's state and the widgets' places (JSON), "
                   "for tests that drive the window");
    cli.add_flag("--no-settings", noSettings, "Neither read nor write the remembered settings");
    cli.add_flag("--no-autosave", noAutosave,
                 "Neither autosave the points nor offer to recover a crashed session's");
    CLI11_PARSE(cli, argc, argv);

    dlab::ui::AppState state;
    dlab::ui::WindowOptions window;
    const std::string settingsPath = noSettings ? std::string() : dlab::ui::defaultSettingsPath();
    std::string warning;
    dlab::ui::loadSettings(settingsPath, state, window, warning);
    if (!warning.empty()) state.log(dlab::ui::Message::Level::Warning, warning);
    state.lessonPlayer.settingsPath = settingsPath;  // progress saved as it is made

    std::string error;
    auto platform = dlab::ui::makeGlfwPlatform(window, error);
    if (!platform) return renderHeadless(input, fallbackPng, error);

    dlab::ui::Gui gui(*platform, state);
    if (!dlab::ui::openStartupInput(state, input))
        std::cerr << "delaunay-lab: " << state.files.notice << "\n";
    // The user's points are autosaved after every change; a session that did not exit cleanly
    // left its autosave behind, and the first frame offers it.
    const std::string autosaveFolder =
        noAutosave ? std::string() : dlab::ui::defaultAutosaveFolder();
    dlab::ui::offerRecovery(state, autosaveFolder);
    dlab::ui::enableAutosave(state, autosaveFolder);
    gui.captureFrames(!screenshot.empty());
    stopOnSignals();
    std::string lastInfo;
    for (int frame = 1; !g_stop; ++frame) {
        for (const std::string& dropped : platform->takeDroppedFiles())
            dlab::ui::openFile(state, dropped);
        platform->setTitle("Delaunay Lab - " + state.source);
        if (!gui.frame()) break;
        dlab::ui::serviceCaptures(gui);  // F12 screenshots, GIF exports
        if (!testInfo.empty()) writeTestInfo(testInfo, state, lastInfo);
        if (frames > 0 && frame >= frames) break;
        if (!state.run.running) platform->waitForEvents(0.25);
    }
    int status = 0;
    if (!screenshot.empty()) {
        if (!gui.saveScreenshot(screenshot, error)) {
            std::cerr << "delaunay-lab: " << error << "\n";
            status = 1;
        } else {
            std::cout << "wrote " << dlab::escapeControls(screenshot) << "\n";
        }
    }
    dlab::ui::removeAutosave(state);  // a clean exit: nothing to recover
    dlab::ui::windowPlacement(*platform, window);
    if (!dlab::ui::saveSettings(settingsPath, state, window, error))
        std::cerr << "delaunay-lab: " << error << "\n";
    return status;
}
