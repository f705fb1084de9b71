// dtlab's outputs when writing fails or races: /dev/full, a full disk, a read-only folder, a
// sticky folder with someone else's file, two writers of one set, a signal in the middle of a
// write, and /dev/stdout into a pipe. Each must end with the old files intact, one line naming
// the file and the system's reason, and a non-zero status.
#include "tests/full_disk.h"
#include "tests/run_dtlab.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace fs = std::filesystem;
using dlab::testutil::countLines;
using dlab::testutil::leftovers;
using dlab::testutil::runDtlab;
using dlab::testutil::slurpFile;
using dlab::testutil::SmallDisk;

namespace {

const std::string kNoSpace = std::strerror(ENOSPC);
const std::string kLesson = std::string(DLAB_SOURCE_DIR) + "/lessons/07_super_triangle.toml";

fs::path freshDir(const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("dlab_out_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string put(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
}

// The lines of `out` that hold `word`.
std::vector<std::string> linesWith(const std::string& out, const std::string& word) {
    std::vector<std::string> found;
    std::size_t at = 0;
    while (at < out.size()) {
        const std::size_t end = std::min(out.find('\n', at), out.size());
        const std::string line = out.substr(at, end - at);
        if (line.find(word) != std::string::npos) found.push_back(line);
        at = end + 1;
    }
    return found;
}

// A failed write: a non-zero status, one error line naming the file and the reason, no "wrote"
// (table1 prints its table before it writes: the error is then its only other line).
void expectOneLineFailure(const dlab::testutil::DtlabResult& r, const std::string& file,
                          const std::string& reason, const std::string& what) {
    EXPECT_NE(r.status, 0) << what << ": " << r.out;
    if (what.rfind("table1", 0) != 0) {
        EXPECT_EQ(countLines(r.out), 1) << what << ": " << r.out;
    }
    const std::vector<std::string> errors = linesWith(r.out, "error");
    ASSERT_EQ(errors.size(), 1u) << what << ": " << r.out;
    EXPECT_NE(errors[0].find(file), std::string::npos) << what << ": " << r.out;
    EXPECT_NE(errors[0].find(reason), std::string::npos) << what << ": " << r.out;
    EXPECT_EQ(r.out.find("wrote"), std::string::npos) << what << ": " << r.out;
}

// Starts dtlab with `args`, its output thrown away, the ending signals at their defaults (a test
// runner may ignore some, and an ignored signal stays ignored across exec).
pid_t spawnDtlab(const std::vector<std::string>& args) {
    std::vector<std::string> all = {DLAB_DTLAB_PATH};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_addopen(&files, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&files, 2, "/dev/null", O_WRONLY, 0);
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    sigset_t defaults, none;
    sigemptyset(&defaults);
    sigemptyset(&none);
    for (const int s : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) sigaddset(&defaults, s);
    posix_spawnattr_setsigdefault(&attr, &defaults);
    posix_spawnattr_setsigmask(&attr, &none);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
    pid_t pid = -1;
    if (posix_spawn(&pid, all[0].c_str(), &files, &attr, argv.data(), environ) != 0) pid = -1;
    posix_spawn_file_actions_destroy(&files);
    posix_spawnattr_destroy(&attr);
    return pid;
}

int waitStatus(pid_t pid) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
    return status;
}

bool hasTemporary(const fs::path& dir) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        if (e.path().filename().string().find(".tmp.") != std::string::npos) return true;
    }
    return false;
}

}  // namespace

// ============================================================================================
// Every writer on /dev/full
// ============================================================================================

TEST(CliOutputs, EveryWriterOnDevFullFailsInOneLineWithTheReason) {
    const fs::path dir = freshDir("devfull");
    const std::string in = (dir / "in.node").string();
    ASSERT_EQ(runDtlab("gen uniform 500 --seed 2 -o " + in).status, 0);
    const std::string base = (dir / "m").string();
    const std::vector<std::string> commands = {
        "gen uniform 100 -o /dev/full",
        "trace " + in + " -o /dev/full",
        "triangulate " + in + " -o " + base + " --off /dev/full",
        "triangulate " + in + " -o " + base + " --svg /dev/full",
        "render " + in + " --size 640x400 -o /dev/full",
        "lesson handout " + kLesson + " -o /dev/full",
        "table1 --sizes 100 --repeat 1 --methods best --csv /dev/full",
        "table1 --sizes 100 --repeat 1 --methods best --png /dev/full",
    };
    for (const std::string& c : commands)
        expectOneLineFailure(runDtlab(c), "/dev/full", kNoSpace, c);
    EXPECT_FALSE(fs::exists(base + ".node"));  // the set is none of its files
    EXPECT_TRUE(leftovers(dir).empty());
    fs::remove_all(dir);
}

// ============================================================================================
// A full disk and a read-only one: the old files stay
// ============================================================================================

TEST(CliOutputs, EveryWriterOnAFullDiskKeepsTheOldFiles) {
    const SmallDisk disk("full");
    if (!disk.ok()) GTEST_SKIP() << disk.why();
    const fs::path inDir = freshDir("fullin");
    const std::string in = (inDir / "in.node").string();
    ASSERT_EQ(runDtlab("gen uniform 500 --seed 2 -o " + in).status, 0);
    const fs::path d = disk.dir();
    const std::vector<std::string> olds = {"m.node",  "m.ele",  "m.neigh", "p.node",
                                           "t.jsonl", "r.png",  "h.md",    "h.html",
                                           "t1.csv",  "t1.png", "s/01.png"};
    fs::create_directories(d / "s");
    fs::create_directories(d / "h_files");
    put(d / "h_files" / "01.png", "old picture");
    for (const std::string& o : olds) put(d / o, "old " + o);
    disk.fill();
    const std::string p = d.string() + "/";
    const std::vector<std::pair<std::string, std::string>> commands = {
        {"gen uniform 100 -o " + p + "p.node", "p.node"},
        {"trace " + in + " -o " + p + "t.jsonl", "t.jsonl"},
        {"triangulate " + in + " -o " + p + "m", "m."},
        {"render " + in + " --size 640x400 -o " + p + "r.png", "r.png"},
        {"render --lesson " + kLesson + " --slides " + p + "s --size 640x400", "s/"},
        {"lesson handout " + kLesson + " -o " + p + "h.md", "h.md"},
        {"lesson handout " + kLesson + " -o " + p + "h.html", "h.html"},
        {"table1 --sizes 100 --repeat 1 --methods best --csv " + p + "t1.csv", "t1.csv"},
        {"table1 --sizes 100 --repeat 1 --methods best --png " + p + "t1.png", "t1.png"},
    };
    for (const auto& [c, file] : commands) expectOneLineFailure(runDtlab(c), p + file, kNoSpace, c);
    for (const std::string& o : olds) EXPECT_EQ(slurpFile(d / o), "old " + o) << o;
    EXPECT_EQ(slurpFile(d / "h_files" / "01.png"), "old picture");
    EXPECT_FALSE(fs::exists(d / "s" / "02.png"));
    EXPECT_EQ(leftovers(d), std::vector<std::string>{});
    fs::remove_all(inDir);
}

TEST(CliOutputs, AReadOnlyFolderIsNamedWithTheReason) {
    const SmallDisk disk("ro", 64 << 10);
    if (!disk.ok()) GTEST_SKIP() << disk.why();
    const fs::path inDir = freshDir("roin");
    const std::string in = (inDir / "in.node").string();
    ASSERT_EQ(runDtlab("gen uniform 200 --seed 2 -o " + in).status, 0);
    ASSERT_TRUE(disk.readOnly());
    const std::string p = disk.dir().string() + "/";
    const std::string reason = std::strerror(EROFS);
    expectOneLineFailure(runDtlab("lesson handout " + kLesson + " -o " + p + "h.md"), p + "h.md",
                         reason, "handout");
    expectOneLineFailure(runDtlab("render " + in + " --size 640x400 -o " + p + "r.png"),
                         p + "r.png", reason, "render");
    expectOneLineFailure(
        runDtlab("table1 --sizes 100 --repeat 1 --methods best --png " + p + "t.png"), p + "t.png",
        reason, "table1");
    fs::remove_all(inDir);
}

// ============================================================================================
// Pipes and devices through their links
// ============================================================================================

TEST(CliOutputs, DevStdoutAndProcSelfFdIntoAPipeAreWrittenThrough) {
    const fs::path dir = freshDir("stdout");
    const std::string in = put(dir / "in.csv", "0,0\n1,0\n0,1\n1,1\n");
    // runDtlab reads the output through a pipe: stdout is one.
    const auto svg = runDtlab("triangulate " + in + " -o " + (dir / "m").string() +
                              " --svg /dev/stdout --quiet");
    EXPECT_EQ(svg.status, 0) << svg.out;
    EXPECT_NE(svg.out.find("</svg>"), std::string::npos) << svg.out;
    const auto off = runDtlab("triangulate " + in + " -o " + (dir / "m").string() +
                              " --off /proc/self/fd/1 --quiet");
    EXPECT_EQ(off.status, 0) << off.out;
    EXPECT_EQ(off.out.rfind("OFF\n4 2 0\n", 0), 0u) << off.out;
    const auto png = runDtlab("render " + in + " --size 640x400 -o /dev/stdout");
    EXPECT_EQ(png.status, 0) << png.out;
    EXPECT_EQ(png.out.rfind("\x89PNG", 0), 0u) << png.out.substr(0, 80);
    const auto gen = runDtlab("gen uniform 10 -o /dev/stdout");
    EXPECT_EQ(gen.status, 0) << gen.out;
    EXPECT_EQ(gen.out.rfind("10 2 0 0\n", 0), 0u) << gen.out;
    fs::remove_all(dir);
}

// ============================================================================================
// A set of files: a sticky folder, two writers
// ============================================================================================

namespace {

// dtlab as user nobody (setpriv), or why that cannot be done here.
std::string asNobody(const std::string& args, int& status) {
    const std::string cmd = "setpriv --reuid=65534 --regid=65534 --clear-groups " +
                            std::string(DLAB_DTLAB_PATH) + " " + args + " 2>&1";
    std::string out;
    FILE* pipe = ::popen(cmd.c_str(), "r");
    if (!pipe) return out;
    char buf[4096];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, pipe)) > 0;) out.append(buf, n);
    const int st = ::pclose(pipe);
    status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return out;
}

}  // namespace

TEST(CliOutputs, ASetInAStickyFolderWithSomeoneElsesFileStaysWhole) {
    if (::geteuid() != 0) GTEST_SKIP() << "needs root, to act as a second user (nobody)";
    const fs::path dir = freshDir("sticky");
    ASSERT_EQ(::chmod(dir.c_str(), 01777), 0);
    const std::string a = (dir / "a.node").string(), b = (dir / "b.node").string();
    ASSERT_EQ(runDtlab("gen uniform 300 --seed 1 -o " + a).status, 0);
    ASSERT_EQ(runDtlab("gen uniform 200 --seed 2 -o " + b).status, 0);
    ::chmod(a.c_str(), 0644);
    ::chmod(b.c_str(), 0644);
    const std::string base = (dir / "out").string();
    int status = -1;
    const std::string first = asNobody("triangulate " + a + " -o " + base + " --quiet", status);
    if (status != 0) GTEST_SKIP() << "cannot run dtlab as nobody here: " << first;
    const std::string node = slurpFile(base + ".node"), ele = slurpFile(base + ".ele");
    // root's .neigh in the sticky folder: nobody may not replace it, whatever its mode.
    for (const mode_t mode : {0644, 0666, 0600}) {
        fs::remove(base + ".neigh");
        put(base + ".neigh", "root's");
        ::chmod((base + ".neigh").c_str(), mode);
        const std::string out = asNobody("triangulate " + b + " -o " + base, status);
        EXPECT_NE(status, 0) << mode << ": " << out;
        EXPECT_EQ(countLines(out), 1) << out;
        EXPECT_NE(out.find(base + ".neigh: " + std::strerror(EPERM)), std::string::npos) << out;
        EXPECT_EQ(slurpFile(base + ".node"), node) << std::oct << mode;
        EXPECT_EQ(slurpFile(base + ".ele"), ele) << std::oct << mode;
        EXPECT_EQ(slurpFile(base + ".neigh"), "root's") << std::oct << mode;
        EXPECT_EQ(leftovers(dir), std::vector<std::string>{});
    }
    fs::remove_all(dir);
}

// The last rename of a set fails (its file is a mount point, and can be neither linked nor read
// to keep it): the renames done before it are undone, the set is the old one.
TEST(CliOutputs, ARenameThatFailsLastUndoesTheOnesBeforeIt) {
    if (::geteuid() != 0) GTEST_SKIP() << "needs root, to mount and to act as nobody";
    const fs::path dir = freshDir("undo");
    const std::string a = (dir / "a.node").string(), b = (dir / "b.node").string();
    ASSERT_EQ(runDtlab("gen uniform 300 --seed 1 -o " + a).status, 0);
    ASSERT_EQ(runDtlab("gen uniform 200 --seed 2 -o " + b).status, 0);
    const fs::path out = dir / "out";
    fs::create_directories(out);
    ASSERT_EQ(::chown(out.c_str(), 65534, 65534), 0);
    const std::string base = (out / "m").string();
    int status = -1;
    const std::string first = asNobody("triangulate " + a + " -o " + base + " --quiet", status);
    if (status != 0) GTEST_SKIP() << "cannot run dtlab as nobody here: " << first;
    const std::string node = slurpFile(base + ".node"), ele = slurpFile(base + ".ele"),
                      neigh = slurpFile(base + ".neigh");
    const std::string secret = put(dir / "secret", "root's");
    ::chmod(secret.c_str(), 0600);
    if (::mount(secret.c_str(), (base + ".neigh").c_str(), nullptr, MS_BIND, nullptr) != 0)
        GTEST_SKIP() << "cannot bind-mount a file here: " << std::strerror(errno);
    const std::string said = asNobody("triangulate " + b + " -o " + base, status);
    ::umount2((base + ".neigh").c_str(), MNT_DETACH);
    EXPECT_NE(status, 0) << said;
    EXPECT_EQ(countLines(said), 1) << said;
    EXPECT_NE(said.find(base + ".neigh: " + std::strerror(EBUSY)), std::string::npos) << said;
    EXPECT_EQ(slurpFile(base + ".node"), node);
    EXPECT_EQ(slurpFile(base + ".ele"), ele);
    EXPECT_EQ(slurpFile(base + ".neigh"), neigh);
    EXPECT_EQ(leftovers(dir), std::vector<std::string>{});
    fs::remove_all(dir);
}

TEST(CliOutputs, TwoWritersOfOneSetLeaveOneOfTheirWholeSets) {
    const fs::path dir = freshDir("race");
    const std::string a = (dir / "a.node").string(), b = (dir / "b.node").string();
    ASSERT_EQ(runDtlab("gen uniform 3000 --seed 1 -o " + a).status, 0);
    ASSERT_EQ(runDtlab("gen uniform 2000 --seed 2 -o " + b).status, 0);
    const char* exts[] = {".node", ".ele", ".neigh"};
    std::vector<std::string> setA, setB;
    for (const auto& [in, set] : {std::pair{a, &setA}, std::pair{b, &setB}}) {
        const std::string ref = (dir / "ref").string();
        ASSERT_EQ(runDtlab("triangulate " + in + " -o " + ref).status, 0);
        for (const char* e : exts) set->push_back(slurpFile(ref + e));
    }
    const std::string base = (dir / "out").string();
    int mixed = 0, failed = 0;
    const int rounds = 40;
    for (int k = 0; k < rounds; ++k) {
        const pid_t pa = spawnDtlab({"triangulate", a, "-o", base});
        const pid_t pb = spawnDtlab({"triangulate", b, "-o", base});
        ASSERT_GT(pa, 0);
        ASSERT_GT(pb, 0);
        const int sa = waitStatus(pa), sb = waitStatus(pb);
        failed +=
            !(WIFEXITED(sa) && WEXITSTATUS(sa) == 0) + !(WIFEXITED(sb) && WEXITSTATUS(sb) == 0);
        std::vector<std::string> now;
        for (const char* e : exts) now.push_back(slurpFile(base + e));
        mixed += now != setA && now != setB;
    }
    EXPECT_EQ(mixed, 0) << "of " << rounds << " rounds";
    EXPECT_EQ(failed, 0);
    EXPECT_EQ(leftovers(dir), std::vector<std::string>{});
    fs::remove_all(dir);
}

// ============================================================================================
// A signal in the middle of a write
// ============================================================================================

TEST(CliOutputs, ASignalDuringAWriteLeavesNoTemporaryAndTheOldFiles) {
    const fs::path dir = freshDir("signal");
    const std::string in = (dir / "big.node").string();
    ASSERT_EQ(runDtlab("gen uniform 1048576 --seed 5 -o " + in).status, 0);
    const std::string base = (dir / "out").string();
    for (const char* e : {".node", ".ele", ".neigh"}) put(base + e, std::string("old") + e);
    for (const int sig : {SIGTERM, SIGINT, SIGHUP, SIGPIPE}) {
        const pid_t pid = spawnDtlab({"triangulate", in, "-o", base, "--svg", base + ".svg"});
        ASSERT_GT(pid, 0);
        // Wait for the first temporary (the write has begun), then stop it.
        bool seen = false;
        const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(120);
        while (!seen && std::chrono::steady_clock::now() < until) {
            seen = hasTemporary(dir);
            if (!seen) std::this_thread::sleep_for(std::chrono::milliseconds(1));
            int st = 0;
            if (!seen && ::waitpid(pid, &st, WNOHANG) == pid) break;  // finished first
        }
        ASSERT_TRUE(seen) << "the write was never caught in the middle (signal " << sig << ")";
        ::kill(pid, sig);
        const int status = waitStatus(pid);
        EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << sig << ": " << status;
        EXPECT_EQ(leftovers(dir), std::vector<std::string>{}) << "signal " << sig;
        for (const char* e : {".node", ".ele", ".neigh"})
            EXPECT_EQ(slurpFile(base + e), std::string("old") + e) << "signal " << sig;
        EXPECT_FALSE(fs::exists(base + ".svg"));
    }
    fs::remove_all(dir);
}
