// Output files written as a set: each to a temporary beside it, then all renamed in together.
//
// A set is all new or all old. Every write, flush, fsync, close and rename is checked, and a
// failure is "cannot write PATH: <the system's reason>" (std::runtime_error) with the old files
// left as they were. Two processes writing the same files commit one after the other (a lock
// on each folder while renaming), so a set is never half one's and half the other's. A
// temporary is removed when the process is stopped by SIGINT, SIGTERM, SIGHUP or SIGPIPE.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace dlab {

// One output and what to write into it: a file (body writes its bytes to a stream) or, when
// `fill` is set, a folder (fill writes its files into `dir`, a new empty folder beside path
// that then replaces path, an old folder of that name included).
struct OutputFile {
    std::string path;
    std::function<void(std::ostream&)> body;
    std::function<void(const std::string& dir)> fill = {};
};

// Writes several outputs so that either all of them replace their files or none does: every
// body is written to a unique temporary beside its file (".NAME.tmp.XXXXXX", the user's own
// NAME.tmp untouched), then all are renamed over their files (atomic on POSIX: readers see the
// old file or the new one). A symbolic link is followed (its target is replaced, not the link);
// a device or pipe (/dev/null, a terminal, /dev/stdout into a pipe) is written straight
// through; a directory is refused. Before anything is written, refuses (std::runtime_error
// "cannot write PATH: why") an empty file name, an output that is one of `inputs` (also through
// a link), and two outputs that are the same file. Throws the same on any failure to create,
// write or rename, after removing the temporaries; an exception from a body is passed on, the
// temporaries removed.
void writeTextFiles(const std::vector<OutputFile>& outputs,
                    const std::vector<std::string>& inputs = {});
// writeTextFiles' checks alone (the bodies are not called): to refuse before any work.
void checkOutputFiles(const std::vector<OutputFile>& outputs,
                      const std::vector<std::string>& inputs = {});
// writeTextFiles with one output.
void writeTextFile(const std::string& path, const std::function<void(std::ostream&)>& body);

// Removes the temporaries of the writes in progress. Async-signal-safe: for a program's own
// handler of a signal that ends it (SIGINT, SIGTERM, SIGHUP and SIGPIPE, when nobody handles
// them, are handled here already).
void removeOutputTemporaries();

}  // namespace dlab
