// dtlab without GL: the commands that need GL (render, table1, --locate idbuffer-gl*) re-run in
// dtlab-gl beside this executable, so that the others never load OSMesa and its LLVM (~50 MB
// resident before any work: more than the corner table of a million points).
#include "app/dtlab_common.h"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>

namespace dlab::cli {

void needGl() {
    std::error_code ec;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
    const std::string gl = ((ec ? std::filesystem::path(".") : self.parent_path()) / "dtlab-gl");
    std::vector<char*> argv = commandLine();  // argv[0] as typed: help texts say "dtlab"
    argv.push_back(nullptr);
    std::cout.flush();
    execv(gl.c_str(), argv.data());
    std::cerr << "dtlab: error: this command needs OpenGL, which runs in " << gl
              << ", and that cannot be started: " << std::strerror(errno) << "\n";
    std::exit(1);
}

void releaseGl() {}

std::vector<std::vector<std::string>> renderedSlideText(const std::string&) {
    needGl();
    return {};
}

std::unique_ptr<Inserter> EngineFlags::makeGlInserter(std::vector<Vec2>) const {
    needGl();
    return nullptr;
}

namespace {

// The subcommand's name and summary, so that dtlab --help lists it; everything after the name,
// --help included, goes to dtlab-gl unread.
void addGlCommand(CLI::App& app, const char* name, const char* summary) {
    CLI::App* cmd = app.add_subcommand(name, summary);
    cmd->set_help_flag();
    cmd->prefix_command();
    cmd->parse_complete_callback(needGl);
}

}  // namespace

void addRender(CLI::App& app) {
    addGlCommand(
        app, "render",
        "Screenshot of the whole GUI after K operations (headless, OSMesa: runs in dtlab-gl)");
}

void addTable1(CLI::App& app) {
    addGlCommand(app, "table1",
                 "The paper's Table 1 (naive walk vs colour-ID buffer) with our locators, on "
                 "OSMesa (runs in dtlab-gl)");
}

}  // namespace dlab::cli
