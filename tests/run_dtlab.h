// Runs the dtlab executable built with the tests and captures its exit status and output
// (stdout and stderr together): the end-to-end checks of lesson check and diff-trace use it.
#pragma once

#include <sys/wait.h>
#include <cstdio>
#include <string>

namespace dlab::testutil {

struct DtlabResult {
    int status = -1;  // exit status; -1 when it did not exit normally
    std::string out;
};

// `prefix` goes before the executable (e.g. "timeout 20 ").
inline DtlabResult runDtlab(const std::string& args, const std::string& prefix = "") {
    DtlabResult r;
    FILE* pipe = popen((prefix + std::string(DLAB_DTLAB_PATH) + " " + args + " 2>&1").c_str(), "r");
    if (!pipe) return r;
    char buf[4096];
    std::size_t n;
    while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) r.out.append(buf, n);
    const int st = pclose(pipe);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return r;
}

}  // namespace dlab::testutil
