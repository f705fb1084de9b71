// dtlab without GL: the commands that need GL (render, table1, --locate idbuffer-gl*) re-run in
// dtlab-gl beside this executable, so that the others never load Mesa and its LLVM (~50 MB
// resident before any work: more than the corner table of a million points).
#include "app/dtlab_common.h"

namespace dlab::cli {

void needGl() { execBeside("dtlab-gl", "this command needs OpenGL"); }

void chooseGl() {}

void releaseGl() {}

std::vector<RenderedSlide> renderedSlides(const std::string&) {
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
    addGlCommand(app, "render",
                 "Screenshot of the whole GUI after K operations (headless GL: runs in dtlab-gl)");
}

void addTable1(CLI::App& app) {
    addGlCommand(app, "table1",
                 "The paper's Table 1 (naive walk vs colour-ID buffer) with our locators, on "
                 "headless GL (runs in dtlab-gl)");
}

}  // namespace dlab::cli
