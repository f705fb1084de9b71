// Shared pieces of dtlab's subcommands: option sets, loading with one-line errors, and the
// registration function of each subcommand (one file each).
#pragma once

#include "core/inserter.h"

#include <CLI/CLI.hpp>

#include <functional>
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
    void add(CLI::App& cmd);
    InsertOptions options() const;
};

// Loads a point file; on bad input prints "dtlab: error: FILE:LINE: what" and throws Exit.
struct LoadedPoints {
    std::vector<Vec2> points;
    int indexBase = 0;
};
LoadedPoints loadPoints(const std::string& path);

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
void addRender(CLI::App& app);

}  // namespace dlab::cli
