// dtlab end to end: outputs of triangulate/trace/bench/gen, and one-line errors with a non-zero
// exit for bad input.
#include "core/engine/io_read.h"
#include "core/engine/mesh.h"
#include "tests/exact_check.h"
#include "tests/run_dtlab.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

using Result = dlab::testutil::DtlabResult;

Result dtlab(const std::string& args) { return dlab::testutil::runDtlab(args); }

fs::path tempDir() {
    const fs::path dir = fs::temp_directory_path() / ("dlab_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir;
}

std::string writeFile(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
}

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Reads BASE.node/.ele/.neigh back into a corner table (ids shifted to 0-based).
dlab::Mesh readTriangleOutput(const std::string& base) {
    dlab::Mesh m;
    const auto pts = dlab::readPointsFile(base + ".node");
    m.G = pts.points;
    std::istringstream ele(slurp(base + ".ele")), neigh(slurp(base + ".neigh"));
    int nt = 0, three = 0, attrs = 0;
    ele >> nt >> three >> attrs;
    int nt2 = 0, three2 = 0;
    neigh >> nt2 >> three2;
    EXPECT_EQ(nt, nt2);
    m.V.resize(3 * nt);
    std::vector<int> nb(3 * nt);
    for (int t = 0; t < nt; ++t) {
        int id = 0, id2 = 0;
        ele >> id >> m.V[3 * t] >> m.V[3 * t + 1] >> m.V[3 * t + 2];
        neigh >> id2 >> nb[3 * t] >> nb[3 * t + 1] >> nb[3 * t + 2];
        EXPECT_EQ(id, t + pts.indexBase);
        for (int k = 0; k < 3; ++k) {
            m.V[3 * t + k] -= pts.indexBase;
            if (nb[3 * t + k] != -1) nb[3 * t + k] -= pts.indexBase;
        }
    }
    // .neigh gives the triangle opposite each corner; find the matching corner there.
    m.O.assign(3 * nt, dlab::kNone);
    for (int c = 0; c < 3 * nt; ++c) {
        const int u = nb[c];
        if (u < 0) continue;
        for (int k = 0; k < 3; ++k) {
            if (nb[3 * u + k] == c / 3) m.O[c] = 3 * u + k;
        }
    }
    return m;
}

// Runs dtlab with these arguments (no shell, output discarded); returns its peak resident set
// in KiB, or -1 when it did not exit with status 0.
long peakKibOfDtlab(std::vector<std::string> args) {
    args.insert(args.begin(), DLAB_DTLAB_PATH);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
        if (!freopen("/dev/null", "w", stdout)) _exit(126);
        execv(argv[0], argv.data());
        _exit(127);
    }
    int status = 0;
    rusage usage{};
    if (pid < 0 || wait4(pid, &status, 0, &usage) != pid) return -1;
    return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? usage.ru_maxrss : -1;
}

}  // namespace

TEST(Cli, TriangulatePeaksNearTheCornerTableFloor) {
    // G, V and O take ~64 bytes a point, the points permuted for the batch 16 more. The GL
    // libraries (OSMesa's LLVM: ~50 MB resident from the start) stay out of this process.
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "AddressSanitizer's shadow memory and redzones are part of the peak here";
#endif
    // On a lattice, glibc's default would keep what the halves free on its heap: 135 MiB at 2^20.
    const fs::path dir = tempDir();
    constexpr long kPoints = 1 << 20;
    for (const char* kind : {"uniform", "grid"}) {
        const std::string in = (dir / (std::string(kind) + ".node")).string();
        ASSERT_EQ(
            dtlab("gen " + std::string(kind) + " " + std::to_string(kPoints) + " -o " + in).status,
            0);
        for (const char* threads : {"1", "2"}) {
            const long kib = peakKibOfDtlab(
                {"triangulate", in, "-o", (dir / "peak_out").string(), "--threads", threads});
            ASSERT_GT(kib, 0) << kind << ", threads " << threads;
            EXPECT_LT(kib * 1024, kPoints * 100 + (16l << 20))
                << kib << " KiB, " << kind << ", threads " << threads;
        }
    }
}

TEST(Cli, RenderedFramesDoNotGrowTheMemory) {
    // Headless, each frame's orphaned vertex buffers are let go once the frame is flushed: 120
    // more frames must not cost more memory (unflushed they cost ~0.6 MB a frame here).
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "AddressSanitizer's quarantine keeps freed memory on purpose";
#endif
    const fs::path dir = tempDir();
    const std::string in = (dir / "frames.node").string();
    ASSERT_EQ(dtlab("gen uniform 2000 --seed 3 -o " + in).status, 0);
    auto peak = [&](const char* frames) {
        return peakKibOfDtlab({"render", in, "--to-end", "--bench-frames", frames, "--size",
                               "800x500", "-o", (dir / "frames.png").string()});
    };
    const long few = peak("4"), many = peak("24");  // each --bench-frames N draws 6 N frames
    ASSERT_GT(few, 0);
    ASSERT_GT(many, 0);
    EXPECT_LT(many - few, 16 * 1024) << few << " KiB after 24 frames, " << many << " after 144";
}

TEST(Cli, TwoHalvesJoinedGiveTheTrianglesOfOneRun) {
    // Uniform points (no four cocircular): one Delaunay triangulation, whichever path makes it.
    const fs::path dir = tempDir();
    const std::string in = (dir / "h.node").string();
    ASSERT_EQ(dtlab("gen uniform 9000 --seed 4 -o " + in).status, 0);
    const std::string two = (dir / "two").string(), one = (dir / "one").string();
    const Result r2 = dtlab("triangulate " + in + " -o " + two + " --check");
    ASSERT_EQ(r2.status, 0) << r2.out;
    EXPECT_NE(r2.out.find("two halves on two threads, joined"), std::string::npos) << r2.out;
    const Result r1 = dtlab("triangulate " + in + " -o " + one + " --check --threads 1");
    ASSERT_EQ(r1.status, 0) << r1.out;
    EXPECT_EQ(r1.out.find("two halves"), std::string::npos) << r1.out;
    auto triangles = [](const dlab::Mesh& m) {
        std::set<std::array<std::int32_t, 3>> out;
        for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
            std::array<std::int32_t, 3> v{m.V[3 * t], m.V[3 * t + 1], m.V[3 * t + 2]};
            std::rotate(v.begin(), std::min_element(v.begin(), v.end()), v.end());
            out.insert(v);
        }
        return out;
    };
    const dlab::Mesh a = readTriangleOutput(two), b = readTriangleOutput(one);
    EXPECT_EQ(checkDelaunayExact(a), "");
    EXPECT_EQ(a.numTriangles(), b.numTriangles());
    EXPECT_EQ(triangles(a), triangles(b));
}

TEST(Cli, TriangulateShowsItsProgressOnATerminalOnly) {
    const fs::path dir = tempDir();
    const std::string in = (dir / "progress_in.node").string();
    ASSERT_EQ(dtlab("gen uniform 40000 --seed 6 -o " + in).status, 0);
    const std::string args = "triangulate " + in + " -o " + (dir / "progress_out").string() +
                             " --threads 1 --order input";
    const Result piped = dtlab(args);
    ASSERT_EQ(piped.status, 0) << piped.out;
    EXPECT_EQ(piped.out.find("triangulate: "), std::string::npos) << piped.out;
    // script(1) gives the command a terminal: the line is drawn there, then erased.
    const Result tty = dlab::testutil::runDtlab(args + "' /dev/null", "script -qec '");
    ASSERT_EQ(tty.status, 0) << tty.out;
    EXPECT_NE(tty.out.find("triangulate: 41% (16384 points)"), std::string::npos) << tty.out;
    EXPECT_NE(tty.out.find("\r\033[K"), std::string::npos) << tty.out;
}

TEST(Cli, CommandsThatNeedGlRunInDtlabGl) {
    const fs::path dir = tempDir();
    const std::string in = (dir / "gl.node").string();
    ASSERT_EQ(dtlab("gen uniform 500 --seed 2 -o " + in).status, 0);
    const std::string base = (dir / "gl_out").string();
    const Result r = dtlab("triangulate " + in + " -o " + base + " --locate=idbuffer-gl-batched");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("locate idbuffer-gl-batched"), std::string::npos) << r.out;
    EXPECT_EQ(checkDelaunayExact(readTriangleOutput(base)), "");
    // render's own help (its options), under the name the user typed.
    const Result help = dtlab("render --help");
    EXPECT_EQ(help.status, 0) << help.out;
    EXPECT_NE(help.out.find("--steps"), std::string::npos) << help.out;
    EXPECT_EQ(help.out.find("dtlab-gl"), std::string::npos) << help.out;
    // Bad options reach dtlab-gl's parser and fail there as they would anywhere.
    EXPECT_NE(dtlab("render --no-such-option -o x.png").status, 0);
}

TEST(Cli, TriangulateWritesAValidDelaunayTriangulationForEveryLocator) {
    const fs::path dir = tempDir();
    const std::string in = (dir / "pts.node").string();
    ASSERT_EQ(dtlab("gen clusters 3000 --seed 4 -o " + in).status, 0);
    for (const char* loc : {"naive", "walk", "grid", "idbuffer-cpu"}) {
        SCOPED_TRACE(loc);
        const std::string base = (dir / (std::string("out_") + loc)).string();
        const Result r =
            dtlab("triangulate " + in + " -o " + base + " --locate " + loc + " --order random");
        ASSERT_EQ(r.status, 0) << r.out;
        const dlab::Mesh m = readTriangleOutput(base);
        EXPECT_GT(m.numTriangles(), 5000);
        EXPECT_EQ(checkDelaunayExact(m), "");
    }
}

TEST(Cli, OneBasedInputGivesOneBasedOutput) {
    const fs::path dir = tempDir();
    const std::string in = writeFile(dir / "one.node", "4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n");
    const std::string base = (dir / "one_out").string();
    ASSERT_EQ(dtlab("triangulate " + in + " -o " + base).status, 0);
    const std::string ele = slurp(base + ".ele");
    EXPECT_EQ(ele.find(" 0 "), std::string::npos) << ele;  // no 0-based vertex id
    const dlab::Mesh m = readTriangleOutput(base);
    EXPECT_EQ(m.numTriangles(), 2);
    EXPECT_EQ(checkDelaunayExact(m), "");
}

TEST(Cli, TraceWritesOneJsonObjectPerOperation) {
    const fs::path dir = tempDir();
    const std::string in = writeFile(dir / "t.csv", "x,y\n0,0\n4,0\n0,4\n1,1\n3,3\n2,0\n");
    const std::string out = (dir / "t.jsonl").string();
    const Result r = dtlab("trace " + in + " -o " + out + " --order input");
    ASSERT_EQ(r.status, 0) << r.out;
    std::istringstream lines(slurp(out));
    std::string line;
    int count = 0, flips = 0, tests = 0;
    std::string last;
    while (std::getline(lines, line)) {
        const auto j = nlohmann::json::parse(line);
        EXPECT_EQ(j.at("i").get<int>(), count);
        last = j.at("op").get<std::string>();
        flips += last == "Flip";
        tests += last == "InCircleTest";
        ++count;
    }
    EXPECT_EQ(last, "Finalize");
    EXPECT_GT(tests, 0);
    const Result limited = dtlab("trace " + in + " -o " + out + " --limit 3");
    ASSERT_EQ(limited.status, 0);
    const std::string limitedText = slurp(out);
    EXPECT_EQ(std::count(limitedText.begin(), limitedText.end(), '\n'), 3);
}

TEST(Cli, BenchJsonHasTheAdvertisedFields) {
    const fs::path dir = tempDir();
    const std::string in = (dir / "b.node").string();
    ASSERT_EQ(dtlab("gen uniform 2000 -o " + in).status, 0);
    const Result r = dtlab("bench --input " + in + " --repeat 2 --json");
    ASSERT_EQ(r.status, 0) << r.out;
    const auto j = nlohmann::json::parse(r.out);
    for (const char* key :
         {"median_ms", "n", "ns_per_point", "flips_per_point", "walk_steps_per_point"}) {
        EXPECT_TRUE(j.contains(key)) << key;
    }
    EXPECT_EQ(j.at("n").get<int>(), 2000);
    EXPECT_GT(j.at("flips_per_point").get<double>(), 1.0);
}

TEST(Cli, TwoThreadsRunOneInserterWhereTheSplitWouldCostMore) {
    // Points on a parabola: the pilot finds the join a fifth of the work; the run says why it
    // kept to one core, and bench reports the one thread it used.
    const fs::path dir = tempDir();
    const std::string in = (dir / "p.node").string();
    ASSERT_EQ(dtlab("gen parabola 20000 --seed 2 -o " + in).status, 0);
    const Result r = dtlab("triangulate " + in + " -o " + (dir / "out").string() + " --check");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(r.out.find("two halves on two threads"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("one core: a pilot on 4095 sampled points"), std::string::npos) << r.out;
    const Result b = dtlab("bench --input " + in + " --repeat 1 --json");
    ASSERT_EQ(b.status, 0) << b.out;
    const auto j = nlohmann::json::parse(b.out);
    EXPECT_EQ(j.at("threads").get<int>(), 1);
    EXPECT_NE(j.at("one_core_because").get<std::string>().find("the join alone"),
              std::string::npos);
}

TEST(Cli, BenchJsonSaysWhichStageDecidedThePredicates) {
    const fs::path dir = tempDir();
    const std::string in = (dir / "g.node").string();
    ASSERT_EQ(dtlab("gen grid 16384 -o " + in).status, 0);
    std::int64_t zeroTail[2] = {};
    for (const int threads : {1, 2}) {
        const Result r = dtlab("bench --input " + in + " --repeat 2 --json --threads " +
                               std::to_string(threads));
        ASSERT_EQ(r.status, 0) << r.out;
        const auto j = nlohmann::json::parse(r.out);
        EXPECT_EQ(j.at("threads").get<int>(), threads);
        EXPECT_GT(j.at("locator_hit_rate").get<double>(), 0.0) << threads;  // both halves' walks
        const auto stages = j.at("predicates_past_filter");
        // A lattice: every quadrilateral cocircular, every difference exact, so the calls the
        // filter leaves are all decided by the zero-tail stage, none by expansions.
        zeroTail[threads - 1] = stages.at("incircle").at("zero-tail").get<std::int64_t>();
        EXPECT_GT(zeroTail[threads - 1], 4000) << threads;
        EXPECT_EQ(stages.at("incircle").at("expansion").get<std::int64_t>(), 0);
        EXPECT_EQ(stages.at("incircle").at("big-integer").get<std::int64_t>(), 0);
        EXPECT_TRUE(stages.at("orient2d").contains("stage-b"));
    }
    // Two threads count the second one's calls too: about as many as one thread makes.
    EXPECT_GT(zeroTail[1], zeroTail[0] * 8 / 10);
    EXPECT_LT(zeroTail[1], zeroTail[0] * 12 / 10);
}

TEST(Cli, BadInputGivesOneLineNamingTheFileAndLine) {
    const fs::path dir = tempDir();
    struct Case {
        std::string name, text, expect;
    };
    const std::vector<Case> cases = {
        {"nan.csv", "1,2\n3,nan\n", "nan.csv:2"},
        {"inf.xy", "1 2\n3 4\ninf 5\n", "inf.xy:3"},
        {"junk.csv", "1,2\n3,4x\n", "junk.csv:2"},
        {"short.node", "3 2 0 0\n0 0 0\n1 1 0\n", "short.node"},
        {"absurd.node", "999999999999 2 0 0\n0 0 0\n", "absurd.node:1"},
        {"empty.csv", "", "empty.csv"},
        {"binary.xy",
         std::string("\x7f"
                     "ELF\0\0\x01\x02\x03",
                     9),
         "binary.xy"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const std::string in = writeFile(dir / c.name, c.text);
        const Result r = dtlab("triangulate " + in + " -o " + (dir / "never").string());
        EXPECT_NE(r.status, 0);
        EXPECT_NE(r.out.find(c.expect), std::string::npos) << r.out;
        EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
        EXPECT_NE(r.out.find("dtlab: error: "), std::string::npos) << r.out;
    }
    const Result missing =
        dtlab("triangulate " + (dir / "nope.node").string() + " -o " + (dir / "x").string());
    EXPECT_NE(missing.status, 0);
    EXPECT_NE(missing.out.find("nope.node"), std::string::npos) << missing.out;
    EXPECT_FALSE(fs::exists(dir / "never.ele"));
}

TEST(Cli, DegenerateInputsAreNotErrors) {
    const fs::path dir = tempDir();
    const std::string in = writeFile(dir / "line.csv", "0,0\n1,1\n2,2\n2,2\n");
    const std::string base = (dir / "line_out").string();
    const Result r = dtlab("triangulate " + in + " -o " + base);
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("duplicate"), std::string::npos) << r.out;
    EXPECT_EQ(slurp(base + ".ele").substr(0, 2), "0 ");
}

// ============================================================================================
// Hard cases: tiny inputs on GL, files that are not regular, outputs over inputs, messages
// ============================================================================================

namespace {

// dtlab with a deadline: a command that blocks (a FIFO without a writer) fails the test with
// status 124 instead of hanging it.
Result dtlabWithin(int seconds, const std::string& args) {
    return dlab::testutil::runDtlab(args, "timeout " + std::to_string(seconds) + " ");
}

int lineCount(const std::string& s) {
    return static_cast<int>(std::count(s.begin(), s.end(), '\n'));
}

}  // namespace

TEST(Cli, GlLocatorsExitCleanlyOnTinyAndDegenerateInputs) {
    const fs::path dir = tempDir();
    const std::vector<std::pair<std::string, std::string>> inputs = {
        {"one.csv", "0,0\n"},
        {"three.csv", "0,0\n1,0\n0,1\n"},
        {"line.csv", "0,0\n1,1\n2,2\n3,3\n"},
        {"same.csv", "5,5\n5,5\n5,5\n"},
    };
    for (const auto& [name, text] : inputs) {
        const std::string in = writeFile(dir / name, text);
        for (const char* loc : {"idbuffer-gl", "idbuffer-gl-batched"}) {
            SCOPED_TRACE(name + " " + loc);
            const Result r =
                dtlab("triangulate " + in + " -o " + (dir / "tiny").string() + " --locate " + loc);
            EXPECT_EQ(r.status, 0) << r.out;
            EXPECT_NE(r.out.find("triangles in"), std::string::npos) << r.out;  // the summary
        }
    }
    const Result table = dtlab("table1 --sizes 3 --repeat 1");
    EXPECT_EQ(table.status, 0) << table.out;
}

TEST(Cli, FilesThatAreNotRegularAreRefusedInOneLineWithoutBlocking) {
    const fs::path dir = tempDir();
    const std::string fifo = (dir / "pipe.node").string();
    fs::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::string zero = (dir / "zero.node").string();
    fs::remove(zero);
    fs::create_symlink("/dev/zero", zero);
    const std::string folder = (dir / "folder.jsonl").string();
    fs::create_directories(folder);
    const std::string lesson =
        std::string(DLAB_SOURCE_DIR) + "/lessons/10_assignment_insertion.toml";
    struct Case {
        std::string args, expect;
    };
    const std::vector<Case> cases = {
        {"triangulate " + fifo + " -o " + (dir / "o").string(), "named pipe (FIFO)"},
        {"triangulate " + zero + " -o " + (dir / "o").string(), "a device"},
        {"diff-trace " + lesson + " " + folder, "a directory"},
        {"lesson show " + fifo, "named pipe (FIFO)"},
        {"lesson show " + folder, "a directory"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.args);
        const Result r = dtlabWithin(20, c.args);
        EXPECT_NE(r.status, 124) << "blocked";
        EXPECT_NE(r.status, 0);
        EXPECT_NE(r.out.find(c.expect), std::string::npos) << r.out;
        EXPECT_EQ(lineCount(r.out), 1) << r.out;
    }
    const Result check = dtlabWithin(20, "lesson check " + fifo);
    EXPECT_NE(check.status, 0);
    EXPECT_NE(check.out.find("named pipe (FIFO)"), std::string::npos) << check.out;
}

TEST(Cli, OutputsThatAreTheInputOrEachOtherAreRefusedBeforeWriting) {
    const fs::path dir = tempDir();
    const std::string text = "3 2 1 1\n0 0 0 7.5 1 # a comment\n1 1 0 2.5 0\n2 0 1 1.5 1\n";
    const std::string in = writeFile(dir / "keep.node", text);
    const Result same = dtlab("triangulate " + in + " -o " + (dir / "keep").string());
    EXPECT_EQ(same.status, 2) << same.out;
    EXPECT_NE(same.out.find("the input file"), std::string::npos) << same.out;
    EXPECT_EQ(slurp(in), text);
    EXPECT_FALSE(fs::exists(dir / "keep.ele"));
    const Result twice = dtlab("triangulate " + in + " -o " + (dir / "x").string() + " --off " +
                               (dir / "x.node").string());
    EXPECT_EQ(twice.status, 2) << twice.out;
    EXPECT_FALSE(fs::exists(dir / "x.ele"));
    const Result trace = dtlab("trace " + in + " -o " + in);
    EXPECT_EQ(trace.status, 2) << trace.out;
    EXPECT_EQ(slurp(in), text);
    const Result empty = dtlab("triangulate " + in + " -o \"\"");
    EXPECT_EQ(empty.status, 2) << empty.out;
    EXPECT_FALSE(fs::exists(dir / ".node"));
}

TEST(Cli, OutputsFollowLinksKeepTheUsersTmpFilesAndAreAllOrNone) {
    const fs::path dir = tempDir();
    const std::string in = writeFile(dir / "pts.csv", "0,0\n1,0\n0,1\n1,1\n");
    // A link is followed: its target gets the mesh, the link stays a link.
    fs::remove(dir / "linked.node");
    fs::create_symlink(dir / "real.node", dir / "linked.node");
    const std::string tmp = writeFile(dir / "linked.ele.tmp", "mine");
    ASSERT_EQ(dtlab("triangulate " + in + " -o " + (dir / "linked").string()).status, 0);
    EXPECT_TRUE(fs::is_symlink(dir / "linked.node"));
    EXPECT_EQ(slurp(dir / "real.node").substr(0, 8), "4 2 0 0\n");
    EXPECT_EQ(slurp(tmp), "mine");
    // A pipe is not replaced by a file (nobody reads it: refused).
    const std::string fifo = (dir / "out.off").string();
    fs::remove(fifo);
    for (const char* ext : {".node", ".ele", ".neigh"}) fs::remove(dir / ("p" + std::string(ext)));
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const Result r =
        dtlabWithin(20, "triangulate " + in + " -o " + (dir / "p").string() + " --off " + fifo);
    EXPECT_NE(r.status, 0) << r.out;
    EXPECT_NE(r.status, 124) << "blocked";
    EXPECT_TRUE(fs::is_fifo(fifo));
    EXPECT_FALSE(fs::exists(dir / "p.node"));  // none of the outputs, not some
    // One output that cannot be written: the old .node/.ele/.neigh stay together.
    const std::string base = (dir / "old").string();
    for (const char* ext : {".node", ".ele", ".neigh"}) writeFile(base + ext, "old");
    const Result fails = dtlab("triangulate " + in + " -o " + base + " --obj " +
                               (dir / "no_such_dir" / "m.obj").string());
    EXPECT_NE(fails.status, 0) << fails.out;
    for (const char* ext : {".node", ".ele", ".neigh"}) EXPECT_EQ(slurp(base + ext), "old") << ext;
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
}

TEST(Cli, RenderRunsInTheOrderItsHelpStates) {
    const fs::path dir = tempDir();
    const std::string in = (dir / "r.node").string();
    ASSERT_EQ(dtlab("gen uniform 3000 --seed 3 -o " + in).status, 0);
    const std::string png = (dir / "r.png").string();
    auto ops = [&](const std::string& extra) {
        const Result r = dtlab("render " + in + " --to-end --size 640x400 -o " + png + extra);
        EXPECT_EQ(r.status, 0) << r.out;
        return r.out.substr(r.out.find("operation"));
    };
    EXPECT_NE(dtlab("render --help").out.find("brio"), std::string::npos);
    EXPECT_EQ(ops(""), ops(" --order brio"));
    EXPECT_NE(ops(""), ops(" --order input"));
}

TEST(Cli, UsageErrorsExitWithTwoAndSayWhatIsWrong) {
    const fs::path dir = tempDir();
    const std::string in = writeFile(dir / "u.csv", "0,0\n1,0\n0,1\n");
    const std::string none = writeFile(dir / "none.node", "0 2 0 0\n");
    const std::string huge = writeFile(dir / "huge.csv",
                                       "-1.7e308,-1.7e308\n1.7e308,-1.7e308\n"
                                       "0,1.7e308\n");
    struct Case {
        std::string args, expect;
    };
    const std::vector<Case> cases = {
        {"gen uniform -1 -o " + (dir / "g.node").string(), "n"},
        {"gen uniform 0 -o " + (dir / "g.csv").string(), "n"},
        {"table1 --sweep 0", "--sweep"},
        {"trace " + in + " -o " + (dir / "t.jsonl").string() + " --limit -5", "--limit"},
        {"render " + in + " -o " + (dir / "s.png").string() + " --to-end --select 4294967299",
         "--select"},
        {"bench " + none, "no points"},
        {"triangulate " + huge + " -o " + (dir / "h").string() + " --boundary super", "super mode"},
        // Out of range, not clamped or wrapped; negative steps refused.
        {"triangulate " + in + " -o " + (dir / "s").string() + " --seed 18446744073709551616",
         "--seed must be a whole number from 0 to 18446744073709551615"},
        {"triangulate " + in + " -o " + (dir / "s").string() + " --seed -1", "--seed must be"},
        {"render " + in + " -o " + (dir / "s.png").string() + " --steps -5",
         "--steps must be 0 or more, not -5"},
        {"render " + in + " -o " + (dir / "s.png").string() + " --bench-frames 100000",
         "--bench-frames"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.args);
        const Result r = dtlab(c.args);
        EXPECT_EQ(r.status, 2) << r.out;
        EXPECT_NE(r.out.find(c.expect), std::string::npos) << r.out;
    }
    EXPECT_FALSE(fs::exists(dir / "g.csv"));
    EXPECT_FALSE(fs::exists(dir / "s.node"));
    // The largest seed itself is taken.
    EXPECT_EQ(dtlab("triangulate " + in + " -o " + (dir / "s").string() +
                    " --seed 18446744073709551615 --order random")
                  .status,
              0);
}

TEST(Cli, SuccessLinesEscapeControlCharactersOfFileNames) {
    const fs::path dir = tempDir();
    const std::string in = writeFile(dir / "p.csv", "0,0\n1,0\n0,1\n1,1\n");
    const std::string base = (dir / "a\tb\x1b[31m").string();
    const Result r = dtlab("triangulate " + in + " -o '" + base + "'");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(r.out.find('\t'), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find('\x1b'), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("a\\tb\\x1b[31m.node/.ele/.neigh"), std::string::npos) << r.out;
    const Result t = dtlab("trace " + in + " -o '" + base + ".jsonl'");
    ASSERT_EQ(t.status, 0) << t.out;
    EXPECT_NE(t.out.find("a\\tb\\x1b[31m.jsonl"), std::string::npos) << t.out;
}

TEST(Cli, NumbersWithAGluedHashAndUnguessableFilesAreExplained) {
    const fs::path dir = tempDir();
    const std::string inf = writeFile(dir / "inf.csv", "0,0\n1,0\n1.#INF,1\n");
    const Result r = dtlab("triangulate " + inf + " -o " + (dir / "i").string());
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find("inf.csv:3"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("1.#INF"), std::string::npos) << r.out;
    // No extension, taken for a .node by its shape, then broken: the guess is named.
    const std::string guess = writeFile(dir / "points", "3 2\n0 0 0\n1 1 0\nx y\n");
    const Result g = dtlab("triangulate " + guess + " -o " + (dir / "g").string());
    EXPECT_EQ(g.status, 2) << g.out;
    EXPECT_NE(g.out.find("no extension: read as Triangle .node"), std::string::npos) << g.out;
    EXPECT_EQ(lineCount(g.out), 1) << g.out;
}

TEST(Cli, LessonShowAndCheckEscapeControlCharacters) {
    const fs::path dir = tempDir();
    const std::string lesson = writeFile(dir / "esc.toml",
                                         "title = \"Bell \\u0007 and \\u001b[2J\"\n"
                                         "summary = \"s\"\n"
                                         "points = [[0, 0], [1, 0], [0, 1]]\n"
                                         "[[stop]]\n"
                                         "text = \"\\u001b]0;pwned\\u0007 line\\nnext\"\n");
    for (const char* cmd : {"lesson show ", "lesson check "}) {
        const Result r = dtlab(cmd + lesson);
        // show prints the lesson; check refuses it (the GUI's font cannot draw control
        // characters) and names them escaped.
        EXPECT_EQ(r.status, std::string(cmd) == "lesson show " ? 0 : 1) << r.out;
        EXPECT_EQ(r.out.find('\x1b'), std::string::npos) << r.out;
        EXPECT_EQ(r.out.find('\x07'), std::string::npos) << r.out;
        EXPECT_NE(r.out.find("\\x1b"), std::string::npos) << r.out;
    }
}

TEST(Cli, ALatticeLessonOfTheLargestSizeOpensWithinTheHistoryBudget) {
    // 100,000 lattice points in input order: the walks are long (tens of millions of steps),
    // and the history stops at its budget instead of taking gigabytes.
    const fs::path dir = tempDir();
    std::string text = "title = \"lattice\"\nsummary = \"s\"\npoints = [";  // input order
    for (int i = 0; i < 100000; ++i) {  // each row from both ends in turn: long walks
        const int k = i % 316, x = k % 2 ? 315 - k / 2 : k / 2;
        text += (i ? "," : "") + std::string("[") + std::to_string(x) + "," +
                std::to_string(i / 316) + "]";
    }
    text += "]\n[[stop]]\nrun_to = \"op:10\"\ntext = \"t\"\n";
    const std::string lesson = writeFile(dir / "lattice.toml", text);
    const long kib = peakKibOfDtlab({"lesson", "check", lesson});
    ASSERT_GT(kib, 0) << "lesson check failed";
    // About 820 MiB here in a release build. AddressSanitizer adds its redzones and keeps the
    // history's freed buffers (each vector doubles) in its quarantine: about 1350 MiB.
#if defined(__SANITIZE_ADDRESS__)
    constexpr long kLimitMib = 1600;
#else
    constexpr long kLimitMib = 1300;
#endif
    EXPECT_LT(kib, kLimitMib * 1024) << kib << " KiB";
}
