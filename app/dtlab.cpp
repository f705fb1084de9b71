// dtlab and dtlab-gl: the headless command line of Delaunay Lab (triangulate, trace, bench, gen,
// demo, ...); dtlab hands the commands that need GL to dtlab-gl (dtlab_common.h).
#include "app/dtlab_common.h"
#include "core/engine/stack_reserve.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <iostream>

int main(int argc, char** argv) {
    dlab::reserveStack();  // out of memory is then an error line, never a SIGSEGV
    dlab::cli::rememberCommandLine(argc, argv);
    CLI::App app{"dtlab: exact incremental Delaunay triangulation on a corner table (headless)"};
    app.require_subcommand(1);
    app.set_help_all_flag("--help-all", "Show the help of every subcommand");
    dlab::cli::addDemo(app);
    dlab::cli::addGen(app);
    dlab::cli::addTriangulate(app);
    dlab::cli::addTrace(app);
    dlab::cli::addBench(app);
    dlab::cli::addLesson(app);
    dlab::cli::addDiffTrace(app);
    dlab::cli::addCheck(app);
    dlab::cli::addRender(app);
    dlab::cli::addTable1(app);
    app.parse_complete_callback(dlab::cli::chooseGl);  // before the command runs
    int code = 0;
    try {
        app.parse(argc, argv);
        code = dlab::cli::exitCode();
    } catch (const CLI::ParseError& e) {
        code = app.exit(e) == 0 ? 0 : 2;  // --help: 0; every usage error: 2
    }
    dlab::cli::releaseGl();
    return code;
}
