// Lessons: every lesson in lessons/ runs to its end; bad lesson files fail with file, line and
// stop; points files cannot escape the lesson's folder; answers are computed from the live
// state and checked tolerantly; Markdown-light text.
#include "core/teaching/lesson.h"

#include "core/engine/generators.h"
#include "core/engine/predicates.h"
#include "core/engine/triangulation_check.h"
#include "core/teaching/breakpoint.h"

#include "tests/run_dtlab.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

using namespace dlab;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> lessonFiles() {
    std::vector<std::string> out;
    const fs::path dir = fs::path(DLAB_SOURCE_DIR) / "lessons";
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        // A track (lecture.toml) plays stops of these lessons: its own tests are below.
        if (e.path().extension() == ".toml" && !isTrackFile(e.path().string()))
            out.push_back(e.path().string());
    }
    std::sort(out.begin(), out.end());
    return out;
}

fs::path scratchDir() {
    const fs::path d = fs::temp_directory_path() / ("dlab_lesson_" + std::to_string(::getpid()));
    fs::create_directories(d / "lessons");
    return d;
}

std::string write(const fs::path& p, const std::string& text) {
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
}

const std::string kHead = "title = \"t\"\npoints = [[0, 0], [6, 0], [5, 4], [1, 3], [3, 1]]\n";

// The error a lesson text raises when loaded and planned (as `dtlab lesson check` does).
LessonError errorOf(const std::string& text, const std::string& name = "x.toml") {
    const fs::path p = scratchDir() / "lessons" / name;
    write(p, text);
    try {
        planLesson(loadLesson(p.string()));
    } catch (const LessonError& e) {
        EXPECT_EQ(e.file(), p.string());
        EXPECT_EQ(std::string(e.what()).rfind(p.string() + ":", 0), 0u) << e.what();
        return e;
    }
    ADD_FAILURE() << "no error for:\n" << text;
    return LessonError("", 0, 0, "");
}

// A lesson text, and the error it must raise: its line, its stop (0: none) and words it says.
struct ErrorCase {
    std::string text;
    int line, stop;
    const char* says;
};

template <std::size_t N>
void expectErrors(const ErrorCase (&cases)[N]) {
    for (const ErrorCase& c : cases) {
        const LessonError e = errorOf(c.text);
        EXPECT_EQ(e.line(), c.line) << e.what();
        EXPECT_EQ(e.stop(), c.stop) << e.what();
        EXPECT_NE(e.message().find(c.says), std::string::npos)
            << e.what() << "\n  wanted: " << c.says;
    }
}

struct LiveRun {
    std::unique_ptr<Inserter> ins;
    std::unique_ptr<Journal> journal;
};
LiveRun start(const std::vector<Vec2>& pts, InsertOptions opt = {}) {
    LiveRun r;
    r.ins = std::make_unique<Inserter>(pts, opt);
    r.journal = std::make_unique<Journal>(*r.ins);
    return r;
}

Answer answer(LiveRun& r, const std::string& spec, std::int32_t selected = kNone) {
    std::string why;
    const std::size_t before = r.journal->position();
    auto a = computeAnswer(spec, *r.ins, *r.journal, selected, &why);
    EXPECT_EQ(r.journal->position(), before) << spec << " moved the journal";
    EXPECT_TRUE(a) << spec << ": " << why;
    return a.value_or(Answer{});
}

std::string unavailable(LiveRun& r, const std::string& spec, std::int32_t selected = kNone) {
    std::string why;
    EXPECT_FALSE(computeAnswer(spec, *r.ins, *r.journal, selected, &why)) << spec;
    return why;
}

using Result = dlab::testutil::DtlabResult;
Result dtlab(const std::string& args) { return dlab::testutil::runDtlab(args); }

}  // namespace

// ---- Every lesson in lessons/ runs to its end (one test each) -----------------------------------

class EveryLesson : public testing::TestWithParam<std::string> {};

TEST_P(EveryLesson, RunsToItsEndWithEveryAnswerComputed) {
    const Lesson lesson = loadLesson(GetParam());
    const LessonPlan plan = planLesson(lesson);
    ASSERT_EQ(plan.stops.size(), lesson.stops.size());
    EXPECT_FALSE(lesson.summary.empty()) << "every lesson says what it is about";
    std::size_t previous = 0;
    for (std::size_t k = 0; k < plan.stops.size(); ++k) {
        EXPECT_GE(plan.stops[k].position, previous) << "stop " << k + 1;
        previous = plan.stops[k].position;
        EXPECT_EQ(plan.stops[k].answer.has_value(), !lesson.stops[k].question.empty())
            << "stop " << k + 1;
        if (plan.stops[k].answer) {
            // The student who types the engine's answer is right.
            EXPECT_TRUE(acceptsAnswer(*plan.stops[k].answer, plan.stops[k].answer->display()))
                << "stop " << k + 1;
        }
    }
    EXPECT_LE(previous, plan.totalOps + plan.editOps);
    // The text may not contradict the engine, give answers away, or hold undrawable characters.
    for (const LessonError& e : lessonProblems(lesson, plan)) ADD_FAILURE() << e.what();
}

INSTANTIATE_TEST_SUITE_P(Lessons, EveryLesson, testing::ValuesIn(lessonFiles()),
                         [](const testing::TestParamInfo<std::string>& info) {
                             std::string name = fs::path(info.param).stem().string();
                             for (char& ch : name) {
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             }
                             return name;
                         });

TEST(Lessons, ShippedLessonsLoadAndAskQuestions) {
    const auto files = lessonFiles();
    EXPECT_GE(files.size(), 9u);
    std::size_t withQuestions = 0;
    for (const std::string& f : files) {
        const Lesson l = loadLesson(f);
        withQuestions += std::any_of(l.stops.begin(), l.stops.end(),
                                     [](const LessonStop& s) { return !s.question.empty(); });
    }
    EXPECT_GE(withQuestions, 9u);
}

TEST(Lessons, DtlabLessonCheckPassesOnTheLessonsAndFailsOnABrokenOne) {
    std::string all;
    for (const std::string& f : lessonFiles()) all += " " + f;
    const Result ok = dtlab("lesson check" + all);
    EXPECT_EQ(ok.status, 0) << ok.out;
    EXPECT_EQ(static_cast<std::size_t>(std::count(ok.out.begin(), ok.out.end(), '\n')),
              lessonFiles().size())
        << ok.out;
    const std::string bad =
        write(scratchDir() / "lessons" / "bad.toml",
              kHead +
                  "[[stop]]\nrun_to = \"flip\"\ntext = \"a\"\n\n[[stop]]\nrun_to = "
                  "\"inserted:99\"\ntext = \"b\"\n");
    const Result r = dtlab("lesson check " + lessonFiles().front() + " " + bad);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.out.find(bad + ":7: stop 2: run_to \"inserted:99\""), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(lessonFiles().front() + ": ok"), std::string::npos) << r.out;
    const Result show = dtlab("lesson show --tables " + lessonFiles().front());
    EXPECT_EQ(show.status, 0) << show.out;
    EXPECT_NE(show.out.find("## stop 1"), std::string::npos);
}

// ---- Loading errors name file, line and stop ----------------------------------------------------

TEST(LessonErrors, BadTomlNamesTheLine) {
    const LessonError e = errorOf("title = \"t\"\n\npoints = [[0, 0]\n");
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(e.message().find("not valid TOML"), std::string::npos) << e.what();
}

TEST(LessonErrors, StructureAndNames) {
    const std::string stop = "[[stop]]\ntext = \"x\"\n";
    const ErrorCase cases[] = {
        {"points = [[0,0]]\n" + stop, 1, 0, "needs a \"title\""},
        {"title = \"t\"\n" + stop, 1, 0, "needs \"points\""},
        {kHead, 1, 0, "at least one [[stop]]"},
        {kHead + "colour = 3\n" + stop, 3, 0, "unknown key \"colour\" at the top level"},
        {kHead + "[options]\nboundary = \"round\"\n" + stop, 4, 0, "boundary must be"},
        {kHead + "[options]\nseed = -1\n" + stop, 4, 0, "\"seed\" must be between"},
        {kHead + "[options]\nlocator = \"gpu\"\n" + stop, 4, 0, "locator must be"},
        {"title = \"t\"\npoints = [[0, 0], [1, 2, 3]]\n" + stop, 2, 0, "point 1 must be [x, y]"},
        {"title = \"t\"\npoints = [[0, 0], [\"a\", 2]]\n" + stop, 2, 0,
         "coordinates must be numbers"},
        {"title = \"t\"\npoints = [[0, 0], [nan, 2]]\n" + stop, 2, 0, "must be finite"},
        {kHead + "points_file = \"p.csv\"\n" + stop, 2, 0, "either \"points\" or \"points_file\""},
        {kHead + stop + "[[stop]]\ntext = \"y\"\npanels = [\"canvas\", \"tables\"]\n", 7, 2,
         "unknown panel \"tables\""},
        {kHead + stop + "[[stop]]\ntext = \"y\"\noverlays = [\"sparkles\"]\n", 7, 2,
         "unknown overlay \"sparkles\""},
        {kHead + "[[stop]]\nrun_to = \"flop\"\ntext = \"y\"\n", 4, 1,
         "unknown breakpoint \"flop\""},
        {kHead + "[[stop]]\nrun_to = \"op:3\"\ncount = 2\ntext = \"y\"\n", 5, 1,
         "\"count\" makes no sense"},
        {kHead + "[[stop]]\ncount = 2\ntext = \"y\"\n", 4, 1, "\"count\" needs a \"run_to\""},
        {kHead + "[[stop]]\nrun_to = \"flip\"\n", 3, 1, "needs a \"text\" or a \"question\""},
        {kHead + "[[stop]]\nquestion = \"How many?\"\n", 3, 1, "has no \"answer\""},
        {kHead + "[[stop]]\ntext = \"y\"\nanswer = \"triangles\"\n", 5, 1, "needs a \"question\""},
        {kHead + "[[stop]]\nquestion = \"q\"\nanswer = \"V[[c]\"\n", 5, 1, "neither a quantity"},
        {kHead + "[[stop]]\nquestion = \"q\"\nanswer = \"triangels\"\n", 5, 1,
         "neither a quantity (triangles,"},
        {kHead + "[[stop]]\nquestion = \"q\"\nanswer = \"x.n\"\n", 5, 1, "unknown name 'x'"},
        {kHead + "[[stop]]\ntext = \"y\"\nselect = \"d.o\"\n", 5, 1, "unknown name 'd'"},
        {kHead + "[[stop]]\ntext = \"y\"\nselect = \"c.q\"\n", 5, 1, "unknown operator 'q'"},
        {kHead + "[[stop]]\ntext = \"\"\"\nfine\n**not closed\n\"\"\"\n", 4, 1,
         "line 2 of the text: unclosed **"},
        {kHead + "[[stop]]\ntext = \"a `b\"\n", 4, 1, "unclosed `"},
        // A rect with inf is named for its value, not taken for a wrong order of corners.
        {kHead + "[[stop]]\ntext = \"y\"\nview = { rect = [0, 0, inf, 1] }\n", 5, 1,
         "view: rect's x1 is not a finite number"},
        {kHead + "[[stop]]\ntext = \"y\"\nview = { rect = [0, nan, 1, 1] }\n", 5, 1,
         "view: rect's y0 is not a finite number"},
        {kHead + "[[stop]]\ntext = \"y\"\nview = { rect = [1, 0, 0, 1] }\n", 5, 1,
         "x0 < x1 and y0 < y1"},
        {kHead + "kind = \"quiz\"\n" + stop, 3, 0, "kind must be"},
        {kHead + "stop = 3\n", 3, 0, "[[stop]] tables"},
    };
    expectErrors(cases);
}

TEST(LessonErrors, StopsThatCannotBeReachedOrAnswered) {
    const ErrorCase cases[] = {
        {kHead + "[[stop]]\nrun_to = \"inserted:99\"\ntext = \"y\"\n", 3, 1,
         "\"inserted:99\" (vertex 99 is in) is not reached"},
        {kHead + "[[stop]]\nrun_to = \"flip\"\ncount = 50\ntext = \"y\"\n", 3, 1,
         "not reached 50 times (only"},
        {kHead + "[[stop]]\nrun_to = \"op:9\"\ntext = \"y\"\n[[stop]]\nrun_to = \"op:4\"\ntext = "
                 "\"z\"\n",
         6, 2, "op:4 is before the previous stop (op 9)"},
        {kHead + "[[stop]]\nrun_to = \"op:100000\"\ntext = \"y\"\n", 3, 1,
         "past the end of the run"},
        {kHead + "[[stop]]\nrun_to = \"end\"\nselect = \"99\"\ntext = \"y\"\n", 3, 1,
         "not a corner of the mesh (0..11)"},
        {kHead + "[[stop]]\nrun_to = \"end\"\nselect = \"V[0]\"\ntext = \"y\"\n", 3, 1,
         "not a corner"},
        // Before Start the table is empty: no range "(0..-1)" to offer.
        {kHead + "[[stop]]\nrun_to = \"op:0\"\nselect = \"0\"\ntext = \"y\"\n", 3, 1,
         "is 0, not a corner of the mesh (it has no triangles at this stop)"},
        {kHead + "[[stop]]\nrun_to = \"end\"\nquestion = \"q\"\nanswer = \"O[c]\"\n", 6, 1,
         "no corner is selected"},
        {kHead + "[[stop]]\nrun_to = \"op:1\"\nquestion = \"q\"\nanswer = \"flipped_edge\"\n", 6, 1,
         "flipped_edge is not available here: no flip yet"},
        {kHead + "[[stop]]\nrun_to = \"end\"\nquestion = \"q\"\nanswer = \"next_op\"\n", 6, 1,
         "the run is finished"},
        {kHead + "[[stop]]\nrun_to = \"end\"\nquestion = \"q\"\nanswer = \"pixel\"\n", 6, 1,
         "needs locator = \"idbuffer-cpu\""},
    };
    expectErrors(cases);
    // An unbuildable run (super mode cannot enclose these coordinates) is an error, not a crash.
    const LessonError huge = errorOf(
        "title = \"t\"\npoints = [[-1.7e308, 0], [1.7e308, 0], [0, 1.7e308]]\n[options]\nboundary "
        "= \"super\"\n"
        "[[stop]]\ntext = \"y\"\n");
    EXPECT_NE(huge.message().find("cannot start the run"), std::string::npos) << huge.what();
}

// ---- Points files stay inside the lesson's folder -----------------------------------------------

TEST(LessonPointsFile, ReadsAFileBesideTheLessonAndRefusesEscapes) {
    const fs::path root = scratchDir() / "pf";
    fs::create_directories(root / "lessons" / "sets");
    write(root / "lessons" / "sets" / "four.csv", "x,y\n0,0\n6,0\n5,4\n1,3\n");
    write(root / "secret.csv", "0,0\n1,0\n0,1\n");
    const std::string stop =
        "[[stop]]\nrun_to = \"end\"\nquestion = \"q\"\nanswer = \"triangles\"\n";
    const fs::path lessonPath = root / "lessons" / "l.toml";
    auto load = [&](const std::string& file) {
        write(lessonPath, "title = \"t\"\npoints_file = \"" + file + "\"\n" + stop);
        return loadLesson(lessonPath.string());
    };
    const Lesson ok = load("sets/four.csv");
    EXPECT_EQ(ok.points.size(), 4u);
    EXPECT_EQ(planLesson(ok).stops[0].answer->a, 2);

    auto refused = [&](const std::string& file, const char* says) {
        try {
            load(file);
            ADD_FAILURE() << file << " was accepted";
        } catch (const LessonError& e) {
            EXPECT_EQ(e.line(), 2) << e.what();
            EXPECT_NE(e.message().find(says), std::string::npos) << file << ": " << e.what();
        }
    };
    refused("../secret.csv", "no \"..\"");
    refused("sets/../../secret.csv", "no \"..\"");
    refused("./sets/../sets/four.csv", "no \"..\"");  // even when it would come back inside
    refused((root / "secret.csv").string(), "not absolute");
    refused("/etc/passwd", "not absolute");
    refused("missing.csv", "not found");
    refused("sets", "not a regular file");
    refused("", "empty");
    fs::create_symlink(root / "secret.csv", root / "lessons" / "link.csv");
    refused("link.csv", "leads outside the lesson's folder");
    fs::create_directory_symlink(root, root / "lessons" / "up");
    refused("up/secret.csv", "leads outside the lesson's folder");
    // A sibling folder whose name starts like the lesson folder's is still outside.
    fs::create_directories(root / "lessons-evil");
    write(root / "lessons-evil" / "p.csv", "0,0\n1,0\n0,1\n");
    fs::create_symlink(root / "lessons-evil" / "p.csv", root / "lessons" / "sneaky.csv");
    refused("sneaky.csv", "leads outside");
    // A symlink that stays inside is fine.
    fs::create_symlink(root / "lessons" / "sets" / "four.csv", root / "lessons" / "alias.csv");
    EXPECT_EQ(load("alias.csv").points.size(), 4u);
    // A bad points file reports its own file and line inside the lesson's error.
    write(root / "lessons" / "sets" / "bad.csv", "0,0\n1,zero\n");
    try {
        load("sets/bad.csv");
        ADD_FAILURE();
    } catch (const LessonError& e) {
        EXPECT_NE(std::string(e.what()).find("bad.csv:2:"), std::string::npos) << e.what();
    }
}

// ---- A start triangulation: the run is Lawson's flip algorithm -------------------------------

// Ten points in convex position, triangulated as a fan from vertex 0: long thin triangles that
// take many flips to become Delaunay.
const std::string kFanPoints =
    "points = [[0, 7], [5, 3], [7, 2], [12, 0], [16, 2], [21, 6], [19, 9], [14, 12], [7, 12], "
    "[3, 10]]\n";
const std::string kFanTriangles =
    "triangles = [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5], [0, 5, 6], [0, 6, 7], [0, 7, 8], "
    "[0, 8, 9]]\n";

TEST(LessonStartMesh, TrianglesPlanTheFlipAlgorithmToTheDelaunayTriangulation) {
    const fs::path p = scratchDir() / "lessons" / "fan.toml";
    write(p, "title = \"fan\"\n" + kFanPoints + kFanTriangles +
                 "[[stop]]\nrun_to = \"op:1\"\nquestion = \"q\"\nanswer = \"delaunay_violations\"\n"
                 "[[stop]]\nrun_to = \"end\"\nquestion = \"q\"\nanswer = \"flips\"\n");
    const Lesson lesson = loadLesson(p.string());
    ASSERT_TRUE(lesson.start);
    EXPECT_EQ(lesson.start->V.size(), 24u);
    const LessonPlan plan = planLesson(lesson);
    ASSERT_EQ(plan.stops.size(), 2u);
    // After Start the fan is in the table, unrepaired: some of its edges are not Delaunay.
    EXPECT_GT(plan.stops[0].answer->a, 0);
    EXPECT_NE(plan.stops[0].banner.find("Start"), std::string::npos) << plan.stops[0].banner;

    // The same mesh repaired by the checker's own flip algorithm: as many flips.
    Mesh fan;
    fan.G = lesson.points;
    fan.V = lesson.start->V;
    fan.O.assign(fan.V.size(), kNone);  // checkMesh computes it
    const RepairResult repaired = repairByFlips(fan, checkMesh(fan));
    const std::int64_t flips = plan.stops[1].answer->a;
    EXPECT_EQ(flips, static_cast<std::int64_t>(repaired.flips.size()));
    EXPECT_GT(flips, 7);  // more flips than the fan has interior edges

    auto ins = makeInserter(lesson);
    EXPECT_TRUE(ins->repairs());
    ins->run();
    EXPECT_EQ(ins->stats().flips, flips);
    // As many in-circle tests as the checker's repair (an edge that comes off the stack on the
    // hull is tested by neither).
    EXPECT_EQ(ins->stats().inCircleTests, repaired.incircleTests);
    // Start, every edge off the stack, every flip, Finalize: no point is located or inserted.
    EXPECT_EQ(ins->stats().inserted, 0);
    EXPECT_GE(plan.totalOps, static_cast<std::size_t>(2 + flips + ins->stats().inCircleTests));
    Mesh result = ins->mesh();
    const CheckReport report = checkMesh(result);
    EXPECT_TRUE(report.isDelaunay()) << report.summary();
    EXPECT_EQ(result.numTriangles(), 8);
}

TEST(LessonStartMesh, TestsAndFlipsReadAsTheFlipAlgorithmsNotAnInsertions) {
    const fs::path p = scratchDir() / "lessons" / "fan_words.toml";
    write(p, "title = \"fan\"\n" + kFanPoints + kFanTriangles +
                 "[[stop]]\nrun_to = \"incircle\"\ntext = \"t\"\n[[stop]]\nrun_to = \"flip\"\n"
                 "text = \"t\"\n[[stop]]\nrun_to = \"end\"\ntext = \"t\"\n");
    const LessonPlan plan = planLesson(loadLesson(p.string()));
    ASSERT_EQ(plan.stops.size(), 3u);
    const std::string& test = plan.stops[0].banner;
    EXPECT_NE(test.find("InCircleTest"), std::string::npos) << test;
    EXPECT_EQ(test.find("vertex -"), std::string::npos) << test;  // no point being inserted
    EXPECT_NE(test.find("is vertex "), std::string::npos) << test;
    EXPECT_NE(plan.stops[1].banner.find("Flip: flip edge "), std::string::npos)
        << plan.stops[1].banner;
    EXPECT_NE(plan.stops[2].banner.find("every edge is locally Delaunay"), std::string::npos)
        << plan.stops[2].banner;
    EXPECT_EQ(plan.stops[2].banner.find("ghost"), std::string::npos) << plan.stops[2].banner;
}

TEST(LessonErrors, TrianglesThatAreNoTriangulationNameFileAndLine) {
    const std::string stop = "[[stop]]\nrun_to = \"end\"\ntext = \"t\"\n";
    // kHead's five points: four around the fifth, (3, 1).
    const ErrorCase cases[] = {
        {kHead + "triangles = [[0, 4, 1], [1, 2, 4], [2, 3, 4], [3, 0, 4]]\n" + stop, 3, 0,
         "\"triangles\" refused: not a valid triangulation of 5 points (4 triangles): 1 "
         "clockwise triangle (first: triangle 0 (0, 4, 1) is clockwise"},
        {kHead + "triangles = [[0, 1, 4], [1, 2, 4]]\n" + stop, 3, 0,
         "\"triangles\" refused: not a valid triangulation"},
        {kHead + "triangles = [\n  [0, 1, 4],\n  [1, 2, 9],\n]\n" + stop, 5, 0,
         "triangle 1 names vertex 9, but the points are numbered from 0 to 4"},
        {kHead + "triangles = [[0, 1]]\n" + stop, 3, 0, "triangle 0 must be [a, b, c]"},
        {kHead + "triangles = []\n" + stop, 3, 0, "must be a list of [a, b, c]"},
        {kHead +
             "triangles = [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]\n[options]\n"
             "order = \"random\"\n" +
             stop,
         4, 0, "[options] (boundary, locator, order) does not apply"},
    };
    expectErrors(cases);
    // The same four triangles counter-clockwise are a triangulation: the lesson plans.
    const fs::path p = scratchDir() / "lessons" / "ok.toml";
    write(p, kHead + "triangles = [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]\n" + stop);
    EXPECT_NO_THROW(planLesson(loadLesson(p.string())));
}

// ---- Answers ------------------------------------------------------------------------------------

TEST(LessonAnswers, QuantitiesFollowTheRecordedOps) {
    InsertOptions opt;
    opt.order = OrderKind::Input;
    LiveRun r = start(demoPoints(), opt);
    Journal& j = *r.journal;
    EXPECT_NE(unavailable(r, "op").find("nothing has happened"), std::string::npos);
    // Stop just before the first flip: next_flip is the edge that flip removes.
    std::size_t firstFlip = 0;
    {
        LiveRun probe = start(demoPoints(), opt);
        while (const Op* op = probe.journal->forward()) {
            if (op->type == OpType::Flip) {
                firstFlip = probe.journal->position();
                break;
            }
        }
    }
    ASSERT_GT(firstFlip, 1u);
    j.seek(firstFlip - 1);
    EXPECT_EQ(answer(r, "op").text, "InCircleTest");
    EXPECT_EQ(answer(r, "test_result").a, 1);
    EXPECT_EQ(answer(r, "next_op").text, "Flip");
    const Answer next = answer(r, "next_flip");
    ASSERT_EQ(next.kind, Answer::Kind::Edge);
    const Answer tested = answer(r, "test_edge");
    EXPECT_EQ(tested.a, next.a);  // the positive test names the edge that flips
    EXPECT_EQ(tested.b, next.b);
    j.forward();
    EXPECT_EQ(answer(r, "flipped_edge").display(), next.display());
    const Answer made = answer(r, "new_edge");
    const Op& flip = *j.current();
    const std::int32_t P = r.ins->mesh().V[flip.a], D = r.ins->mesh().V[flip.b];
    EXPECT_EQ(made.display(),
              std::to_string(std::min(P, D)) + "-" + std::to_string(std::max(P, D)));
    EXPECT_EQ(answer(r, "flips").a, 1);
    EXPECT_EQ(answer(r, "insertion_flips").a, 1);
    EXPECT_EQ(answer(r, "vertex").a, flip.vertex);
    EXPECT_EQ(answer(r, "position").a, static_cast<std::int64_t>(firstFlip));
    // At the end: counts agree with the mesh and the stats.
    j.seek(1u << 30);
    EXPECT_EQ(answer(r, "triangles").a, r.ins->mesh().numTriangles());
    EXPECT_EQ(answer(r, "all_triangles").a, r.ins->mesh().numTriangles());
    EXPECT_EQ(answer(r, "vertices").a, 11);  // 12 points, one duplicate
    EXPECT_EQ(answer(r, "duplicates").a, 1);
    EXPECT_EQ(answer(r, "edge_splits").a, r.ins->stats().edgeSplits);
    EXPECT_TRUE(answer(r, "convex").truth);
    EXPECT_EQ(answer(r, "delaunay_violations").a, 0);
    EXPECT_EQ(answer(r, "op").text, "Finalize");
    EXPECT_NE(unavailable(r, "next_flip").find("the run is finished"), std::string::npos);
}

// previous_flipped_edge and previous_new_edge name the flip before the latest: at each flip
// they are what flipped_edge and new_edge said at the flip before.
TEST(LessonAnswers, PreviousFlipIsTheOneBeforeTheLatest) {
    InsertOptions opt;
    opt.order = OrderKind::Input;
    LiveRun r = start(demoPoints(), opt);
    Journal& j = *r.journal;
    std::optional<Answer> removed, made;
    int checked = 0;
    while (const Op* op = j.forward()) {
        if (op->type != OpType::Flip) continue;
        if (removed) {
            EXPECT_EQ(answer(r, "previous_flipped_edge").display(), removed->display());
            EXPECT_EQ(answer(r, "previous_new_edge").display(), made->display());
            ++checked;
        } else {
            EXPECT_NE(unavailable(r, "previous_new_edge").find("first"), std::string::npos);
        }
        removed = answer(r, "flipped_edge");
        made = answer(r, "new_edge");
    }
    EXPECT_GT(checked, 3);
}

// most_flips is the most any insertion took (insertion_flips read as each one ends), and
// most_flips_vertex the first point to take that many.
TEST(LessonAnswers, MostFlipsIsTheLongestCascadeSoFar) {
    InsertOptions opt;
    opt.order = OrderKind::Input;
    LiveRun r = start(demoPoints(), opt);
    Journal& j = *r.journal;
    EXPECT_FALSE(unavailable(r, "most_flips").empty());
    std::int64_t most = -1, vertex = -1;
    int insertions = 0;
    while (const Op* op = j.forward()) {
        if (op->type != OpType::Inserted) continue;
        ++insertions;
        const std::int64_t f = answer(r, "insertion_flips").a;
        if (f > most) {
            most = f;
            vertex = op->vertex;
        }
        EXPECT_EQ(answer(r, "most_flips").a, most);
        EXPECT_EQ(answer(r, "most_flips_vertex").a, vertex);
    }
    EXPECT_GT(insertions, 5);
    EXPECT_GT(most, 1);  // the demo has a cascade: the check is not of zeros
}

// previous_test_edge names the test before the latest one of the same insertion: at each test
// it is what test_edge said at the test before, and the first test of an insertion has none.
TEST(LessonAnswers, PreviousTestIsTheOneBeforeTheLatestOfItsInsertion) {
    InsertOptions opt;
    opt.order = OrderKind::Input;
    LiveRun r = start(demoPoints(), opt);
    Journal& j = *r.journal;
    std::optional<Answer> before;  // the test before, in this insertion
    std::optional<std::int64_t> beforeSign;
    int checked = 0, firsts = 0;
    while (const Op* op = j.forward()) {
        if (endsInsertion(op->type)) before.reset();
        if (op->type != OpType::InCircleTest) continue;
        if (before) {
            EXPECT_EQ(answer(r, "previous_test_edge").display(), before->display());
            EXPECT_EQ(answer(r, "previous_test_result").a, *beforeSign);
            ++checked;
        } else {
            EXPECT_NE(unavailable(r, "previous_test_edge").find("first of its insertion"),
                      std::string::npos);
            ++firsts;
        }
        before = answer(r, "test_edge");
        beforeSign = answer(r, "test_result").a;
    }
    EXPECT_GT(checked, 3);
    EXPECT_GT(firsts, 3);
}

TEST(LessonAnswers, LocateHintStepsAndWhere) {
    InsertOptions opt;
    opt.order = OrderKind::Input;
    LiveRun r = start(demoPoints(), opt);
    Journal& j = *r.journal;
    // The first locate that takes steps.
    std::size_t located = 0, first = 0;
    std::int64_t steps = 0;
    while (const Op* op = j.forward()) {
        if (op->type == OpType::LocateStep && !first) first = j.position() - 1;
        if (op->type == OpType::LocateStep) ++steps;
        if (op->type == OpType::Located && first) {
            located = j.position() - 1;
            break;
        }
        if (op->type == OpType::Located) steps = 0;
    }
    ASSERT_GT(located, first);
    EXPECT_EQ(answer(r, "hint").a, j.ops()[first].a);
    EXPECT_EQ(answer(r, "locate_steps").a, steps);
    EXPECT_EQ(answer(r, "located").a, j.ops()[located].a);
    EXPECT_EQ(answer(r, "where").text, toString(j.ops()[located].where));
    EXPECT_EQ(answer(r, "next_vertex").a, j.ops()[located].vertex);
}

TEST(LessonAnswers, DegreePixelAndConvexity) {
    // Degree: the fan around the centre of a hexagon has 6 triangles.
    std::vector<Vec2> hex{{0, 0}};
    for (int k = 0; k < 6; ++k)
        hex.push_back(
            {10 * std::cos(k * 1.0471975511965976), 10 * std::sin(k * 1.0471975511965976)});
    LiveRun h = start(hex);
    h.journal->seek(1u << 30);
    std::int32_t atCentre = kNone;
    for (std::int32_t c = 0; c < h.ins->mesh().numCorners(); ++c) {
        if (h.ins->mesh().V[c] == 0) atCentre = c;
    }
    ASSERT_NE(atCentre, kNone);
    EXPECT_EQ(answer(h, "degree", atCentre).a, 6);
    EXPECT_NE(unavailable(h, "degree").find("needs a selected corner"), std::string::npos);
    // A hull vertex has an open fan: counted both ways.
    std::int32_t atHull = kNone;
    for (std::int32_t c = 0; c < h.ins->mesh().numCorners(); ++c) {
        if (h.ins->mesh().V[c] == 1) atHull = c;
    }
    EXPECT_EQ(answer(h, "degree", atHull).a, 2);

    // Pixel: with the CPU ID buffer, the id under the next point.
    InsertOptions idb;
    idb.locator = LocatorKind::IdBufferCpu;
    idb.order = OrderKind::Input;
    idb.locatorOptions.idBufferWidth = idb.locatorOptions.idBufferHeight = 32;
    LiveRun p = start(generatePoints(Generator::Uniform, 40, 3), idb);
    p.journal->seek(40);
    while (p.journal->current()->type != OpType::Inserted) p.journal->forward();
    const Answer px = answer(p, "pixel");
    const auto* buffer = dynamic_cast<IdBufferCpu*>(p.ins->locator());
    ASSERT_NE(buffer, nullptr);
    EXPECT_EQ(px.a, buffer->pixelAt(p.ins->mesh().G[p.ins->currentVertex()]));

    // The paper's super-triangle flaw (tests/test_inserter.cpp): not convex in super mode.
    const std::vector<Vec2> flaw{{0, 0}, {50, 0.001}, {100, 0}, {50, 50}};
    InsertOptions super;
    super.boundary = Boundary::Super;
    LiveRun s = start(flaw, super), e = start(flaw);
    s.journal->seek(1u << 30);
    e.journal->seek(1u << 30);
    EXPECT_FALSE(answer(s, "convex").truth);
    EXPECT_EQ(answer(s, "triangles").a, 2);
    EXPECT_TRUE(answer(e, "convex").truth);
    EXPECT_EQ(answer(e, "triangles").a, 3);
    EXPECT_EQ(answer(e, "hull_edges").a, 3);
}

TEST(LessonAnswers, CornerExpressionsUseTheSelection) {
    LiveRun r = start({{0, 0}, {6, 0}, {5, 4}, {1, 3}});
    r.journal->seek(1u << 30);
    const Mesh& m = r.ins->mesh();
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        const Answer o = answer(r, "O[c]", c);
        EXPECT_EQ(o.a, m.O[c]);
        EXPECT_TRUE(o.corner);
        EXPECT_EQ(answer(r, "c.n.v", c).a, m.V[next(c)]);
        EXPECT_TRUE(answer(r, "n(n(n(c))) == c", c).truth);
    }
    const Answer g = answer(r, "G[V[0]]");
    EXPECT_EQ(g.kind, Answer::Kind::Point);
    std::int32_t hull = 0;
    while (m.O[hull] != kNone) ++hull;
    EXPECT_NE(unavailable(r, "o(c).n", hull).find("cannot apply n"), std::string::npos);
}

TEST(LessonAnswers, StudentsTypeAnswersTheirWay) {
    Answer n;
    n.kind = Answer::Kind::Integer;
    n.a = 17;
    EXPECT_TRUE(acceptsAnswer(n, "17"));
    EXPECT_TRUE(acceptsAnswer(n, " +17 "));
    EXPECT_FALSE(acceptsAnswer(n, "18"));
    EXPECT_FALSE(acceptsAnswer(n, "17x"));
    EXPECT_FALSE(acceptsAnswer(n, ""));
    Answer none = n;
    none.a = -1;
    none.corner = true;
    EXPECT_TRUE(acceptsAnswer(none, "-1"));
    EXPECT_TRUE(acceptsAnswer(none, "None"));
    EXPECT_TRUE(acceptsAnswer(none, "boundary"));
    n.a = -1;
    EXPECT_FALSE(acceptsAnswer(n, "none")) << "none only stands for a missing corner";
    Answer e;
    e.kind = Answer::Kind::Edge;
    e.a = 4;
    e.b = 9;
    for (const char* s : {"4-9", "9-4", "4 9", "(9, 4)", "edge 4-9", "4–9", "vertices 4 and 9",
                          "edge from vertex 4 to vertex 9"})
        EXPECT_TRUE(acceptsAnswer(e, s)) << s;
    for (const char* s : {"4", "4-9-1", "4-8", "49"}) EXPECT_FALSE(acceptsAnswer(e, s)) << s;
    Answer t;
    t.kind = Answer::Kind::Text;
    t.text = "SplitEdge";
    for (const char* s : {"SplitEdge", "split edge", "split-edge", " SPLIT_EDGE "})
        EXPECT_TRUE(acceptsAnswer(t, s)) << s;
    EXPECT_FALSE(acceptsAnswer(t, "split"));
    Answer y;
    y.kind = Answer::Kind::Truth;
    y.truth = false;
    EXPECT_TRUE(acceptsAnswer(y, "No"));
    EXPECT_TRUE(acceptsAnswer(y, "false"));
    EXPECT_FALSE(acceptsAnswer(y, "yes"));
    Answer p;
    p.kind = Answer::Kind::Point;
    p.point = {1.5, -2};
    EXPECT_TRUE(acceptsAnswer(p, "(1.5, -2)"));
    EXPECT_TRUE(acceptsAnswer(p, "1.5 -2.0"));
    EXPECT_FALSE(acceptsAnswer(p, "(1.5, 2)"));
    EXPECT_EQ(p.display(), "(1.5, -2)");
    EXPECT_EQ(e.display(), "4-9");
    EXPECT_EQ(y.display(), "no");
}

// A count of in-circle tests may carry the question's own words as its unit.
TEST(LessonAnswers, ACountOfInCircleTestsTakesItsUnitAsTheQuestionWritesIt) {
    const fs::path p = scratchDir() / "lessons" / "tests_unit.toml";
    write(p,
          "title = \"t\"\npoints = [[0, 0], [4, 0], [0, 4], [3, 3], [1, 1]]\n"
          "[[stop]]\nrun_to = \"end\"\n"
          "question = \"How many in-circle tests did the run make?\"\nanswer = \"tests\"\n");
    const LessonPlan plan = planLesson(loadLesson(p.string()));
    const Answer& a = *plan.stops[0].answer;
    ASSERT_GT(a.a, 0);
    const std::string n = std::to_string(a.a);
    for (const std::string& typed :
         {n, n + " tests", n + " in-circle tests", n + " incircle tests", n + " times"})
        EXPECT_TRUE(acceptsAnswer(a, typed)) << typed;
    for (const std::string& typed : {n + " flips", std::to_string(a.a + 1) + " in-circle tests"})
        EXPECT_FALSE(acceptsAnswer(a, typed)) << typed;
}

TEST(LessonAnswers, LabelsAndPhrasesAsPeopleWriteThem) {
    Answer s0;  // a super-triangle vertex: the canvas says s0
    s0.kind = Answer::Kind::Integer;
    s0.a = 21;
    s0.labelA = "s0";
    for (const char* typed : {"s0", "S0", " s 0 ", "21"})
        EXPECT_TRUE(acceptsAnswer(s0, typed)) << typed;
    EXPECT_FALSE(acceptsAnswer(s0, "s1"));
    EXPECT_EQ(s0.display(), "s0");
    Answer e;  // the edge 1-s0
    e.kind = Answer::Kind::Edge;
    e.a = 1;
    e.b = 21;
    e.labelB = "s0";
    for (const char* typed : {"1-s0", "s0-1", "edge 1-s0", "1 - 21", "from 1 to s0"})
        EXPECT_TRUE(acceptsAnswer(e, typed)) << typed;
    for (const char* typed : {"1-s1", "1", "1-s0-2"})
        EXPECT_FALSE(acceptsAnswer(e, typed)) << typed;
    EXPECT_EQ(e.display(), "1-s0");
    Answer g = s0;  // the ghost vertex
    g.labelA = "g";
    EXPECT_TRUE(acceptsAnswer(g, "g"));
    EXPECT_TRUE(acceptsAnswer(g, "G"));
    Answer where;
    where.kind = Answer::Kind::Text;
    where.text = "edge";
    for (const char* typed : {"edge", "on an edge", "On the edge", "it is on an edge"})
        EXPECT_TRUE(acceptsAnswer(where, typed)) << typed;
    EXPECT_FALSE(acceptsAnswer(where, "inside"));
    where.text = "outside-hull";
    for (const char* typed : {"outside", "outside the hull", "outside hull", "beyond the hull"})
        EXPECT_TRUE(acceptsAnswer(where, typed)) << typed;
    where.text = "inside";
    EXPECT_TRUE(acceptsAnswer(where, "inside a triangle"));
    EXPECT_FALSE(acceptsAnswer(where, "on a vertex"));
    Answer t;  // a triangle: the canvas says t25
    t.kind = Answer::Kind::Integer;
    t.a = 25;
    t.triangle = true;
    for (const char* typed : {"25", "t25", "T 25", "triangle 25"})
        EXPECT_TRUE(acceptsAnswer(t, typed)) << typed;
    Answer three;
    three.kind = Answer::Kind::Integer;
    three.a = 3;
    EXPECT_TRUE(acceptsAnswer(three, "three"));
    EXPECT_FALSE(acceptsAnswer(three, "four"));
    Answer yes;
    yes.kind = Answer::Kind::Truth;
    yes.truth = true;
    EXPECT_TRUE(acceptsAnswer(yes, "yes, it flips"));
    EXPECT_FALSE(acceptsAnswer(yes, "no"));
}

TEST(LessonAnswers, UnitsNumberWordsPunctuationAndSpellings) {
    LiveRun r = start({{0, 0}, {10, 0}, {5, 8}, {5, -2}, {3, 3}});
    while (!r.ins->done()) r.journal->forward();
    Answer angle = answer(r, "min_angle");
    ASSERT_EQ(angle.kind, Answer::Kind::Integer);
    const std::string a = std::to_string(angle.a);
    for (const std::string& typed : {a, a + "\u00b0", a + " \u00b0", a + " degrees", a + " degree",
                                     a + "deg", a + " degrees.", " " + a + "! "})
        EXPECT_TRUE(acceptsAnswer(angle, typed)) << typed;
    const std::string off = std::to_string(angle.a + 1);
    for (const std::string& typed : {off + "\u00b0", off + " degrees", a + " steps",
                                     a + " triangles", a + "x", a + " degrees 5"})
        EXPECT_FALSE(acceptsAnswer(angle, typed)) << typed;

    Answer steps = answer(r, "walk_steps");
    const std::string n = std::to_string(steps.a);
    EXPECT_TRUE(acceptsAnswer(steps, n + " steps"));
    EXPECT_TRUE(acceptsAnswer(steps, n + " step."));
    EXPECT_FALSE(acceptsAnswer(steps, n + " corners"));
    EXPECT_FALSE(acceptsAnswer(steps, std::to_string(steps.a + 1) + " steps"));

    Answer corners = answer(r, "corners");
    EXPECT_TRUE(acceptsAnswer(corners, std::to_string(corners.a) + " corners"));
    EXPECT_TRUE(acceptsAnswer(corners, std::to_string(corners.a) + " rows"));
    EXPECT_FALSE(acceptsAnswer(corners, std::to_string(corners.a) + " degrees"));

    Answer six;  // a count with its unit as the quantity gives it, and number words to twenty
    six.kind = Answer::Kind::Integer;
    six.a = 6;
    six.units = {"times", "time"};
    for (const char* typed : {"6 times", "Six.", "six times", "SIX", "\"6\"", "6!"})
        EXPECT_TRUE(acceptsAnswer(six, typed)) << typed;
    for (const char* typed : {"Seven.", "6 steps", "times", "66 times", "6 timesx", ".6"})
        EXPECT_FALSE(acceptsAnswer(six, typed)) << typed;
    Answer twenty = six;
    twenty.a = 20;
    EXPECT_TRUE(acceptsAnswer(twenty, "twenty"));
    EXPECT_TRUE(acceptsAnswer(twenty, "Twenty times."));
    EXPECT_FALSE(acceptsAnswer(twenty, "nineteen"));

    Answer where;  // the hints' own words for a point on a hull edge, or beyond the hull
    where.kind = Answer::Kind::Text;
    where.text = "edge";
    for (const char* typed :
         {"on the boundary", "On the hull edge.", "boundary", "on the boundary of the mesh"})
        EXPECT_TRUE(acceptsAnswer(where, typed)) << typed;
    for (const char* typed : {"in a ghost triangle", "inside", "on a vertex", "outside the hull"})
        EXPECT_FALSE(acceptsAnswer(where, typed)) << typed;
    where.text = "outside-hull";
    for (const char* typed : {"in a ghost triangle", "ghost triangle", "Outside the hull."})
        EXPECT_TRUE(acceptsAnswer(where, typed)) << typed;
    EXPECT_FALSE(acceptsAnswer(where, "on the boundary"));

    Answer pixel;  // the ID-buffer's three cases, in the panel's words too
    pixel.kind = Answer::Kind::Text;
    pixel.text = "empty";
    for (const char* typed : {"empty", "empty pixel", "an empty pixel.", "Unpainted"})
        EXPECT_TRUE(acceptsAnswer(pixel, typed)) << typed;
    for (const char* typed : {"miss", "missed", "hit"})
        EXPECT_FALSE(acceptsAnswer(pixel, typed)) << typed;
    pixel.text = "miss";
    for (const char* typed : {"miss", "missed", "a miss"})
        EXPECT_TRUE(acceptsAnswer(pixel, typed)) << typed;
    EXPECT_FALSE(acceptsAnswer(pixel, "empty pixel"));

    Answer op;  // British spellings of the tool's names
    op.kind = Answer::Kind::Text;
    op.text = "Finalize";
    for (const char* typed : {"Finalize", "Finalise", "finalise.", "FINALISE"})
        EXPECT_TRUE(acceptsAnswer(op, typed)) << typed;
    for (const char* typed : {"Final", "Finish", "Flip"})
        EXPECT_FALSE(acceptsAnswer(op, typed)) << typed;
}

TEST(LessonAnswers, TheQuestionsNounIsAUnitOfItsAnswer) {
    const fs::path p = write(scratchDir() / "lessons" / "units.toml", kHead + R"(
[[stop]]
run_to = "end"
question = "How many Voronoi vertices will the diagram have?"
answer = "triangles"

[[stop]]
question = "How many times must you press S?"
answer = "corners"
)");
    const LessonPlan plan = planLesson(loadLesson(p.string()));
    const Answer& t = *plan.stops[0].answer;
    const std::string n = std::to_string(t.a);
    for (const std::string& typed : {n + " voronoi vertices", n + " vertices", n + " triangles"})
        EXPECT_TRUE(acceptsAnswer(t, typed)) << typed;
    EXPECT_FALSE(acceptsAnswer(t, n + " steps"));
    const Answer& c = *plan.stops[1].answer;
    EXPECT_TRUE(acceptsAnswer(c, std::to_string(c.a) + " times"));
    EXPECT_FALSE(acceptsAnswer(c, std::to_string(c.a) + " degrees"));
}

TEST(LessonAnswers, LiveAnswersCarryTheCanvasLabels) {
    // Super mode: the first in-circle tests involve super vertices, named s0..s2 as on canvas.
    InsertOptions super;
    super.boundary = Boundary::Super;
    super.order = OrderKind::Input;
    LiveRun r = start({{0, 0}, {6, 0}, {5, 4}, {1, 3}}, super);
    while (const Op* op = r.journal->forward()) {
        if (op->type == OpType::InCircleTest && op->b != kNone) break;
    }
    const Answer tested = answer(r, "test_edge");
    const bool touchesSuper = tested.b >= 4;
    ASSERT_TRUE(touchesSuper) << tested.display();
    EXPECT_EQ(tested.labelB, "s" + std::to_string(tested.b - 4));
    EXPECT_TRUE(acceptsAnswer(tested, tested.display()));
    EXPECT_TRUE(acceptsAnswer(tested, std::to_string(tested.a) + "-" + std::to_string(tested.b)));
}

TEST(LessonAnswers, ForwardLookingQuantitiesMatchWhatHappensNext) {
    InsertOptions opt;
    opt.order = OrderKind::Input;
    LiveRun r = start(demoPoints(), opt);
    Journal& j = *r.journal;
    int tests = 0, locates = 0;
    while (!j.atEnd()) {
        std::string why;
        const auto nextEdge = computeAnswer("next_test_edge", *r.ins, j, kNone, &why);
        const auto willFlip = computeAnswer("will_flip", *r.ins, j, kNone, &why);
        const auto nextWhere = computeAnswer("next_where", *r.ins, j, kNone, &why);
        const auto nextTri = computeAnswer("next_located", *r.ins, j, kNone, &why);
        const Op* op = j.forward();
        if (op->type == OpType::InCircleTest && nextEdge) {
            ++tests;
            EXPECT_EQ(nextEdge->display(), answer(r, "test_edge").display());
            EXPECT_EQ(willFlip->truth, op->sign > 0);
        }
        if (op->type == OpType::Located && nextWhere) {
            ++locates;
            EXPECT_EQ(nextWhere->text, toString(op->where));
            EXPECT_EQ(nextTri->a, op->a);
        }
    }
    EXPECT_GT(tests, 10);
    EXPECT_GT(locates, 5);
    j.seek(0);
    j.forward();  // Start: the next locate is in this insertion, the next test too
    EXPECT_TRUE(answer(r, "next_where").kind == Answer::Kind::Text);
}

TEST(LessonAnswers, TrianglesAroundAndEdgesAroundDifferOnTheHull) {
    LiveRun r = start({{0, 0}, {6, 0}, {5, 4}, {1, 3}, {3, 1.5}});
    r.journal->seek(1u << 30);
    const Mesh& m = r.ins->mesh();
    std::int32_t atHull = kNone, atCentre = kNone;
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        if (m.V[c] == 0) atHull = c;
        if (m.V[c] == 4) atCentre = c;
    }
    EXPECT_EQ(answer(r, "triangles_around", atCentre).a, 4);
    EXPECT_EQ(answer(r, "edges_around", atCentre).a, 4);
    // Vertex 0 on the hull: its edges go to 1, 3 and the centre, between two triangles.
    EXPECT_EQ(answer(r, "triangles_around", atHull).a, 2);
    EXPECT_EQ(answer(r, "edges_around", atHull).a, 3);
}

TEST(LessonAnswers, ChangedCornersOfAFlip) {
    InsertOptions opt;
    opt.order = OrderKind::Input;
    LiveRun r = start(demoPoints(), opt);
    while (const Op* op = r.journal->forward()) {
        if (op->type == OpType::Flip) break;
    }
    ASSERT_EQ(r.journal->current()->type, OpType::Flip);
    // The paper's Figure 6: the flip rewrites all six corners of its two triangles (V at two, O
    // at four), and the O of the outer neighbours that now face back at them.
    const Op& flip = *r.journal->current();
    std::set<std::int32_t> vCells, all;
    for (std::uint32_t i = 0; i < flip.numChanges; ++i) {
        const CellChange& ch = r.journal->changes()[flip.firstChange + i];
        all.insert(ch.corner());
        if (!ch.isO()) vCells.insert(ch.corner());
    }
    EXPECT_EQ(vCells.size(), 2u);
    for (std::int32_t c : {flip.a, next(flip.a), prev(flip.a), flip.b, next(flip.b), prev(flip.b)})
        EXPECT_TRUE(all.count(c)) << "corner " << c;
    EXPECT_EQ(answer(r, "changed_corners").a, static_cast<std::int64_t>(all.size()));
    EXPECT_GE(all.size(), 6u);
    EXPECT_LE(all.size(), 8u);
}

// ---- Engine values in the text, expectations, and what lesson check refuses --------------------

TEST(LessonValues, TextEmbedsTheEngineValuesAtTheStop) {
    const fs::path p = scratchDir() / "lessons" / "values.toml";
    write(p, kHead +
                 "[[stop]]\nrun_to = \"split\"\ntext = \"\"\"\n{{queue}} edges wait; "
                 "vertex {{vertex}}\nat corner 0: {{ V[0] }}\"\"\"\nquestion = \"Which "
                 "edge is tested first?\"\nanswer = \"next_test_edge\"\nhint = \"One of "
                 "{{queue}}\"\n");
    const Lesson lesson = loadLesson(p.string());
    EXPECT_EQ(lesson.stops[0].textLine, 6);
    const LessonPlan plan = planLesson(lesson);
    LiveRun r = start(lesson.points, lesson.options);
    r.journal->seek(plan.stops[0].position);
    EXPECT_EQ(plan.stops[0].text, std::to_string(answer(r, "queue").a) + " edges wait; vertex " +
                                      std::to_string(answer(r, "vertex").a) +
                                      "\nat corner 0: " + std::to_string(r.ins->mesh().V[0]));
    EXPECT_EQ(plan.stops[0].hint, "One of 3");
    EXPECT_NE(plan.stops[0].banner.find("Split: split triangle"), std::string::npos)
        << plan.stops[0].banner;
}

TEST(LessonValues, UnknownOrUnclosedValuesNameFileLineAndStop) {
    const std::string stop = "[[stop]]\ntext = \"x\"\n";
    const ErrorCase cases[] = {
        {kHead + stop + "[[stop]]\ntext = \"\"\"\nfine\n{{walk_stepz}} steps\"\"\"\n", 8, 2,
         "unknown value {{walk_stepz}} in the text"},
        {kHead + "[[stop]]\ntext = \"{{queue\"\n", 4, 1, "unclosed {{"},
        {kHead + "[[stop]]\ntext = \"{{ }}\"\n", 4, 1, "empty {{}}"},
        {kHead + "[[stop]]\nquestion = \"Is {{x.n}} right?\"\nanswer = \"queue\"\n", 4, 1,
         "in the question: neither a quantity"},
        {kHead + "[[stop]]\ntext = \"t\"\nexpect = { walk_stepz = 0 }\n", 5, 1,
         "expect \"walk_stepz\": neither a quantity"},
        {kHead + "[[stop]]\ntext = \"t\"\nexpect = 3\n", 5, 1, "must be a table"},
        {kHead + "[[stop]]\ntext = \"t\"\nexpect = { queue = [1] }\n", 5, 1,
         "a string, a number or true/false"},
        {kHead + "[[stop]]\ntext = \"{{next_flip}}\"\nrun_to = \"end\"\n", 4, 1,
         "the run is finished"},
    };
    expectErrors(cases);
}

TEST(LessonExpectations, CheckFailsWhereTheTextContradictsTheEngine) {
    const std::string head =
        "title = \"t\"\npoints = [[0, 0], [6, 0], [5, 4], [1, 3], [3, 1]]\n"
        "[options]\nlocator = \"naive\"\n";
    LiveRun r = start({{0, 0}, {6, 0}, {5, 4}, {1, 3}, {3, 1}}, [] {
        InsertOptions o;
        o.order = OrderKind::Input;
        o.locator = LocatorKind::Naive;
        return o;
    }());
    const std::vector<Breakpoint> located{*parseBreakpoint("located")};
    for (int i = 0; i < 2; ++i) runUntil(*r.journal, *r.ins, located, 1u << 30);
    const std::int64_t steps = answer(r, "locate_steps").a;
    // The text claims a longer walk than the engine's, on an edge: check names file, line, stop.
    const std::string claim = std::to_string(steps + 3);
    const std::string wrong = head +
                              "[[stop]]\nrun_to = \"located\"\ncount = 2\ntext = \"A long "
                              "walk.\"\nexpect = { locate_steps = " +
                              claim + " }\n";
    const LessonError e = errorOf(wrong);
    EXPECT_EQ(e.line(), 9) << e.what();
    EXPECT_EQ(e.stop(), 1);
    EXPECT_NE(e.message().find("the lesson expects locate_steps = " + claim +
                               ", but the engine says " + std::to_string(steps)),
              std::string::npos)
        << e.what();
    const LessonError where = errorOf(head +
                                      "[[stop]]\nrun_to = \"located\"\ncount = 2\ntext = \"On "
                                      "it.\"\nexpect = { where = \"on an edge\" }\n");
    EXPECT_NE(where.message().find("expects where = on an edge, but the engine says inside"),
              std::string::npos)
        << where.what();
    const Result cli = dtlab("lesson check " + scratchDir().string() + "/lessons/x.toml");
    EXPECT_EQ(cli.status, 1);
    EXPECT_NE(cli.out.find("x.toml:9: stop 1: the lesson expects where = on an edge"),
              std::string::npos)
        << cli.out;
    // What the engine says passes, in any spelling a student would use.
    const fs::path ok = scratchDir() / "lessons" / "ok.toml";
    write(ok, head +
                  "[[stop]]\nrun_to = \"located\"\ncount = 2\ntext = \"Found.\"\nexpect = { "
                  "locate_steps = " +
                  std::to_string(steps) +
                  ", where = \"inside a triangle\", convex = true, \"V[0]\" = " +
                  std::to_string(r.ins->mesh().V[0]) + " }\n");
    EXPECT_NO_THROW(planLesson(loadLesson(ok.string())));
}

TEST(LessonCheck, RefusesCharactersTheGuiCannotDraw) {
    EXPECT_FALSE(firstUndrawable("plain - text, 2\u00b75, \u2192, \u2212 1, \u2264"));
    const auto bad = firstUndrawable("a \u221e b");  // infinity: not in the font's ranges
    ASSERT_TRUE(bad);
    EXPECT_EQ(bad->first, 2u);
    EXPECT_EQ(bad->second, U'\u221e');
    EXPECT_TRUE(firstUndrawable("broken \xff byte"));
    const fs::path p = scratchDir() / "lessons" / "font.toml";
    write(p, kHead + "[[stop]]\ntext = \"\"\"\nfine\nto \u221e and back\"\"\"\n");
    const Lesson lesson = loadLesson(p.string());
    const auto problems = lessonProblems(lesson, planLesson(lesson));
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].line(), 6);
    EXPECT_EQ(problems[0].stop(), 1);
    EXPECT_NE(problems[0].message().find("U+221E"), std::string::npos) << problems[0].what();
    const Result cli = dtlab("lesson check " + p.string());
    EXPECT_EQ(cli.status, 1);
    EXPECT_NE(cli.out.find("font.toml:6: stop 1: the text has"), std::string::npos) << cli.out;
}

TEST(LessonCheck, RefusesAnswersGivenAwayByTheTextOrTheBanner) {
    Answer n;
    n.kind = Answer::Kind::Integer;
    n.a = 3;
    EXPECT_TRUE(answerAppearsIn(n, "the three edges"));
    EXPECT_TRUE(answerAppearsIn(n, "split into 3"));
    EXPECT_TRUE(answerAppearsIn(n, "triangle t3"));
    EXPECT_FALSE(answerAppearsIn(n, "vertex 13 and 0.3"));
    n.a = -1;
    EXPECT_TRUE(answerAppearsIn(n, "says so with `-1`"));
    EXPECT_FALSE(answerAppearsIn(n, "edge 0-1"));
    Answer e;
    e.kind = Answer::Kind::Edge;
    e.a = 0;
    e.b = 2;
    EXPECT_TRUE(answerAppearsIn(e, "the diagonal 2-0 stays"));
    EXPECT_TRUE(answerAppearsIn(e, "the diagonal 0\u20132 stays"));
    EXPECT_FALSE(answerAppearsIn(e, "vertices 0, 1 and 2"));
    Answer w;
    w.kind = Answer::Kind::Text;
    w.text = "SkipDuplicate";
    EXPECT_TRUE(answerAppearsIn(w, "[40] SkipDuplicate: vertex 6 ..."));
    EXPECT_TRUE(answerAppearsIn(w, "we skip duplicate points"));
    w.text = "edge";
    EXPECT_TRUE(answerAppearsIn(w, "it lies on the edge"));
    EXPECT_FALSE(answerAppearsIn(w, "it lies on the diagonal"));
    EXPECT_FALSE(answerAppearsIn(w, "every edge around it is Delaunay"));

    // In a lesson: the text says the answer; the banner says the other one.
    const fs::path p = scratchDir() / "lessons" / "giveaway.toml";
    write(p, kHead +
                 "[[stop]]\nrun_to = \"op:1\"\ntext = \"Four triangles.\"\n"
                 "question = \"How many triangles?\"\nanswer = \"all_triangles\"\n"
                 "[[stop]]\nrun_to = \"flip\"\ntext = \"A flip.\"\n"
                 "question = \"Which edge did it make?\"\nanswer = \"new_edge\"\n");
    const Lesson lesson = loadLesson(p.string());
    const auto problems = lessonProblems(lesson, planLesson(lesson));
    ASSERT_EQ(problems.size(), 2u);
    EXPECT_EQ(problems[0].stop(), 1);
    EXPECT_EQ(problems[0].line(), 5);
    EXPECT_NE(problems[0].message().find("the answer (4) already appears in the stop's text"),
              std::string::npos)
        << problems[0].what();
    EXPECT_EQ(problems[1].stop(), 2);
    EXPECT_EQ(problems[1].line(), 8);
    EXPECT_NE(problems[1].message().find("appears in the operation banner"), std::string::npos)
        << problems[1].what();
    EXPECT_EQ(dtlab("lesson check " + p.string()).status, 1);
}

// The flip queue numbered in test order shows the edge tested next as 1: a stop asking for it
// must number the queue in push order (the reader applies the stack's rule) or not at all.
TEST(LessonCheck, RefusesTheQueueInTestOrderWhereTheNextTestIsAsked) {
    const auto problemsWith = [](const std::string& overlays) {
        const fs::path p = scratchDir() / "lessons" / "queueorder.toml";
        write(p, kHead + "[[stop]]\nrun_to = \"split\"\n" + overlays +
                     "text = \"A split.\"\nquestion = \"Which edge is tested first?\"\n"
                     "answer = \"next_test_edge\"\n");
        const Lesson lesson = loadLesson(p.string());
        std::vector<std::string> out;
        for (const LessonError& e : lessonProblems(lesson, planLesson(lesson)))
            if (e.message().find("flip-queue-order") != std::string::npos) out.push_back(e.what());
        return out;
    };
    const auto ordered = problemsWith("overlays = [\"flip-queue\", \"flip-queue-order\"]\n");
    ASSERT_EQ(ordered.size(), 1u);
    EXPECT_NE(ordered[0].find("queueorder.toml:3: stop 1"), std::string::npos) << ordered[0];
    EXPECT_EQ(problemsWith("").size(), 1u) << "no overlays named: the defaults number the queue";
    EXPECT_TRUE(problemsWith("overlays = [\"flip-queue\", \"flip-queue-pushed\"]\n").empty());
    EXPECT_TRUE(problemsWith("overlays = [\"flip-queue-order\"]\n").empty()) << "no queue drawn";
}

TEST(LessonCheck, AnswerOnTheRenderedSlideInAnyPhrasingItTakes) {
    Answer corners;
    corners.kind = Answer::Kind::Integer;
    corners.a = 6;
    corners.units = {"corners", "corner"};
    const std::string q = "How many corners does the table have (that is, how many rows)?";
    EXPECT_EQ(answerOnSlide(corners, {"Go to corner | 6 corners   l(c) = o(n(c))"}, q).value_or(""),
              "Go to corner | 6 corners   l(c) = o(n(c))");
    EXPECT_TRUE(answerOnSlide(corners, {"corners | 6"}, q)) << "a statistics row: unit first";
    EXPECT_TRUE(answerOnSlide(corners, {"six corners"}, q));
    // Ids are everywhere on a slide: a bare number, or another count, gives nothing away.
    EXPECT_FALSE(answerOnSlide(corners, {"6", "1 | 0 | 6 | -1", "vertex 6", "7 corners"}, q));
    EXPECT_FALSE(answerOnSlide(corners, {"How many corners does the table have"}, q))
        << "the question itself is on the slide";
    Answer angle;
    angle.kind = Answer::Kind::Integer;
    angle.a = 32;
    angle.units = {"degrees", "degree", "\u00b0"};
    EXPECT_TRUE(answerOnSlide(angle, {"smallest angle 32\u00b0"}, ""));
    EXPECT_FALSE(answerOnSlide(angle, {"smallest angle 22\u00b0"}, ""));
    Answer outcome;
    outcome.kind = Answer::Kind::Text;
    outcome.text = "hit";
    EXPECT_TRUE(answerOnSlide(outcome, {"Last locate (v15): HIT - the pixel's triangle t3"}, ""));
    outcome.text = "empty";
    EXPECT_TRUE(answerOnSlide(outcome, {"Last locate (v4): empty pixel - nothing painted"}, ""));
    EXPECT_FALSE(answerOnSlide(outcome, {"Last locate (v4): miss - walked 2 steps"}, ""));
    Answer steps;
    steps.kind = Answer::Kind::Integer;
    steps.a = 2;
    steps.units = {"steps", "step"};
    EXPECT_TRUE(answerOnSlide(steps, {"Last locate (v16): miss - walked 2 steps from t5"}, ""));
    Answer e;
    e.kind = Answer::Kind::Edge;
    e.a = 0;
    e.b = 2;
    EXPECT_TRUE(answerOnSlide(e, {"[12] Flip: flip edge 1-3 to 0-2"}, ""));
    Answer yes;
    yes.kind = Answer::Kind::Truth;
    yes.truth = true;
    EXPECT_FALSE(answerOnSlide(yes, {"yes"}, "")) << "a truth value is never said";
}

TEST(LessonCheck, FailsWhereTheRenderedSlideShowsTheAnswer) {
    // Planted: the answer in the statistics (a table of counts) and in a corner-table cell.
    const std::string stats = write(scratchDir() / "lessons" / "on_stats.toml", kHead + R"(
[[stop]]
run_to = "end"
tab = "statistics"
text = "Every point is in."
question = "How many in-circle tests did the run make?"
answer = "tests"
)");
    Result r = dtlab("lesson check " + stats);
    EXPECT_EQ(r.status, 1) << r.out;
    EXPECT_NE(r.out.find(stats + ":4: stop 1: the answer ("), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("is on the rendered slide"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("in-circle tests |"), std::string::npos) << r.out;

    const std::string cell = write(scratchDir() / "lessons" / "in_cell.toml", kHead + R"(
[[stop]]
run_to = "end"
tab = "vertex-table"
text = "Every point is in."

[[stop]]
select = "1"
tab = "corner-table"
text = "Corner 1 is selected."
question = "What is O[c] for the selected corner?"
answer = "O[c]"
)");
    r = dtlab("lesson check " + cell);
    EXPECT_EQ(r.status, 1) << r.out;
    EXPECT_NE(r.out.find(cell + ":9: stop 2: the answer ("), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("row 1 of the corner table"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("stop 1:"), std::string::npos) << r.out;

    // The same questions on slides that do not show the answer pass.
    const std::string fine = write(scratchDir() / "lessons" / "fine.toml", kHead + R"(
[[stop]]
run_to = "end"
tab = "vertex-table"
text = "Every point is in."
question = "How many in-circle tests did the run make?"
answer = "tests"

[[stop]]
select = "1"
text = "Corner 1 is selected."
question = "What is O[c] for the selected corner?"
answer = "O[c]"
)");
    r = dtlab("lesson check " + fine);
    EXPECT_EQ(r.status, 0) << r.out;
    // Without GL the slides are not read.
    EXPECT_EQ(dtlab("lesson check --no-slides " + stats).status, 0);
}

TEST(LessonHandout, WritesTextAndQuestionsWithoutAnswers) {
    const std::string lesson = std::string(DLAB_SOURCE_DIR) + "/lessons/01_corner_table.toml";
    const fs::path out = scratchDir() / "handout.md";
    const Result r = dtlab("lesson handout " + lesson + " -o " + out.string());
    ASSERT_EQ(r.status, 0) << r.out;
    std::ifstream in(out);
    const std::string md((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const Lesson l = loadLesson(lesson);
    const LessonPlan plan = planLesson(l);
    EXPECT_EQ(md.rfind("# " + l.title, 0), 0u);
    std::size_t questions = 0;
    for (std::size_t k = 0; k < l.stops.size(); ++k) {
        if (l.stops[k].question.empty()) continue;
        ++questions;
        EXPECT_NE(md.find(plan.stops[k].question), std::string::npos) << "stop " << k + 1;
    }
    std::size_t blanks = 0;
    for (auto at = md.find("Your answer:"); at != std::string::npos;
         at = md.find("Your answer:", at + 1))
        ++blanks;
    EXPECT_EQ(blanks, questions);
    EXPECT_EQ(md.find("A: "), std::string::npos);
    EXPECT_EQ(md.find("{{"), std::string::npos) << "values are rendered";
    // Each stop's picture in the folder beside it, as the HTML handout has; the objectives first;
    // hints fold away.
    for (std::size_t k = 1; k <= l.stops.size(); ++k) {
        char png[48];
        std::snprintf(png, sizeof png, "handout_files/%02zu.png", k);
        EXPECT_NE(md.find(std::string("](") + png + ")"), std::string::npos) << png;
        EXPECT_TRUE(fs::is_regular_file(out.parent_path() / png)) << png;
    }
    EXPECT_LT(md.find(l.objectives.at(0)), md.find("Question 1."));
    EXPECT_NE(md.find("<details><summary>Hint</summary>"), std::string::npos);
    // The answer key stays in `lesson show`.
    const Result show = dtlab("lesson show " + lesson);
    EXPECT_NE(show.out.find("A: "), std::string::npos);
    EXPECT_NE(dtlab("lesson handout " + lesson).status, 0) << "-o is required";
}

// An assignment has no stops: its handout is its own text, with the objectives and the minutes
// the file states, in Markdown and in HTML.
TEST(LessonHandout, AnAssignmentsHandoutHoldsItsTextObjectivesAndMinutes) {
    const std::string lesson =
        std::string(DLAB_SOURCE_DIR) + "/lessons/10_assignment_insertion.toml";
    const Lesson l = loadLesson(lesson);
    ASSERT_TRUE(l.assignment);
    ASSERT_TRUE(l.stops.empty());
    ASSERT_FALSE(l.text.empty());
    ASSERT_FALSE(l.objectives.empty());
    const fs::path dir = scratchDir() / "assignment";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const auto read = [](const fs::path& f) {
        std::ifstream in(f);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    const Result r = dtlab("lesson handout " + lesson + " -o " + (dir / "a.md").string());
    ASSERT_EQ(r.status, 0) << r.out;
    const std::string md = read(dir / "a.md");
    for (const std::string& o : l.objectives) EXPECT_NE(md.find(o), std::string::npos) << o;
    EXPECT_NE(md.find(std::to_string(l.minutes) + " minutes"), std::string::npos);
    // Every line of the text, as the file has it (Markdown-light is Markdown).
    std::istringstream lines(l.text);
    int seen = 0;
    for (std::string line; std::getline(lines, line);) {
        if (line.find_first_not_of(' ') == std::string::npos) continue;
        EXPECT_NE(md.find(line), std::string::npos) << line;
        ++seen;
    }
    EXPECT_GT(seen, 10);
    const Result h = dtlab("lesson handout " + lesson + " -o " + (dir / "a.html").string());
    ASSERT_EQ(h.status, 0) << h.out;
    const std::string html = read(dir / "a.html");
    for (const std::string& o : l.objectives) EXPECT_NE(html.find(o), std::string::npos) << o;
    EXPECT_NE(html.find("<code>dtlab diff-trace"), std::string::npos);
}

TEST(LessonHandout, HtmlShowsEachStopsSlideAndNoAnswers) {
    const std::string lesson = std::string(DLAB_SOURCE_DIR) + "/lessons/07_super_triangle.toml";
    const fs::path dir = scratchDir() / "html";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path out = dir / "super.html";
    const Result r = dtlab("lesson handout " + lesson + " -o " + out.string());
    ASSERT_EQ(r.status, 0) << r.out;
    std::ifstream in(out);
    const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const Lesson l = loadLesson(lesson);
    const LessonPlan plan = planLesson(l);
    EXPECT_NE(html.find("<h1>" + l.title + "</h1>"), std::string::npos);
    std::size_t questions = 0;
    for (std::size_t k = 0; k < l.stops.size(); ++k) {
        char name[48];
        std::snprintf(name, sizeof name, "super_files/%02zu.png", k + 1);
        EXPECT_NE(html.find(std::string("<img src=\"") + name + "\""), std::string::npos)
            << "stop " << k + 1;
        // A PNG of the 1280x720 slide: the signature, then IHDR's width and height.
        std::ifstream png(dir / name, std::ios::binary);
        char head[24] = {};
        png.read(head, sizeof head);
        ASSERT_TRUE(png) << name << " is missing or short";
        EXPECT_EQ(std::string(head + 1, 3), "PNG") << name;
        const auto be32 = [&](int at) {
            return (unsigned(static_cast<unsigned char>(head[at])) << 24) |
                   (unsigned(static_cast<unsigned char>(head[at + 1])) << 16) |
                   (unsigned(static_cast<unsigned char>(head[at + 2])) << 8) |
                   unsigned(static_cast<unsigned char>(head[at + 3]));
        };
        EXPECT_EQ(be32(16), 1280u) << name;
        EXPECT_EQ(be32(20), 720u) << name;
        if (l.stops[k].question.empty()) continue;
        ++questions;
        EXPECT_NE(html.find(plan.stops[k].question), std::string::npos) << "stop " << k + 1;
    }
    // Bold and code of the text are HTML, its quotes escaped.
    EXPECT_NE(html.find("<strong>super-triangle</strong>"), std::string::npos);
    EXPECT_NE(html.find("<code>boundary = &quot;exact&quot;</code>"), std::string::npos);
    std::size_t blanks = 0;
    for (auto at = html.find("Your answer:"); at != std::string::npos;
         at = html.find("Your answer:", at + 1))
        ++blanks;
    EXPECT_EQ(blanks, questions);
    EXPECT_EQ(html.find("A: "), std::string::npos);
    EXPECT_EQ(html.find("{{"), std::string::npos) << "values are rendered";
    EXPECT_EQ(html.find('*'), std::string::npos) << "Markdown left literal";
}

// ---- Markdown-light -----------------------------------------------------------------------------

TEST(LessonText, ParagraphsListsBoldAndCode) {
    std::string why;
    const auto blocks = parseLessonText(
        "A **corner** is `3t + i`.\nSecond line joins.\n\n- first item\n- second **bold** item\n  "
        "continues\n\n"
        "1. one\n2. two `n(c)`\n",
        &why);
    ASSERT_TRUE(blocks) << why;
    ASSERT_EQ(blocks->size(), 5u);
    const TextBlock& p = (*blocks)[0];
    EXPECT_EQ(p.kind, TextBlock::Kind::Paragraph);
    ASSERT_EQ(p.spans.size(), 5u);
    EXPECT_EQ(p.spans[1].style, TextSpan::Style::Bold);
    EXPECT_EQ(p.spans[1].text, "corner");
    EXPECT_EQ(p.spans[3].style, TextSpan::Style::Code);
    EXPECT_EQ(p.spans[3].text, "3t + i");
    EXPECT_EQ(p.spans[4].text, ". Second line joins.");
    EXPECT_EQ((*blocks)[1].kind, TextBlock::Kind::Bullet);
    EXPECT_EQ((*blocks)[2].spans.back().text, " item continues");
    EXPECT_EQ((*blocks)[3].kind, TextBlock::Kind::Numbered);
    EXPECT_EQ((*blocks)[4].number, 2);
    EXPECT_EQ((*blocks)[4].spans.back().style, TextSpan::Style::Code);
    EXPECT_FALSE(parseLessonText("ok\n\nthen **open", &why));
    EXPECT_EQ(why, "line 3 of the text: unclosed ** (bold)");
    EXPECT_TRUE(parseLessonText("", &why)->empty());
}

// ---- Facts the lessons state in their text (kept true by these checks) --------------------------

TEST(LessonFacts, LocatingLessonWalkLocatorTakesElevenSteps) {
    Lesson lesson = loadLesson(std::string(DLAB_SOURCE_DIR) + "/lessons/03_locating.toml");
    ASSERT_EQ(lesson.options.locator, LocatorKind::Naive);
    Inserter naive(lesson.points, lesson.options);
    naive.run();
    EXPECT_EQ(naive.stats().walkSteps, 153);
    lesson.options.locator = LocatorKind::Walk;
    Inserter walk(lesson.points, lesson.options);
    walk.run();
    EXPECT_EQ(walk.stats().walkSteps, 11);
}

// Lesson 12 contrasts its BRIO walk with random order: the same points in random order walk
// over five times as many steps, and flip about as often (both below 3 per point).
TEST(LessonFacts, WhyFastLessonRandomOrderWalksOverFiveTimesAsFarAsBrio) {
    Lesson lesson = loadLesson(std::string(DLAB_SOURCE_DIR) + "/lessons/12_why_fast.toml");
    ASSERT_EQ(lesson.options.order, OrderKind::Brio);
    ASSERT_EQ(lesson.options.locator, LocatorKind::Walk);
    Inserter brio(lesson.points, lesson.options);
    brio.run();
    lesson.options.order = OrderKind::Random;
    Inserter random(lesson.points, lesson.options);
    random.run();
    EXPECT_GT(random.stats().walkSteps, 5 * brio.stats().walkSteps);
    const auto n = static_cast<std::int64_t>(lesson.points.size());
    EXPECT_LT(brio.stats().flips, 3 * n);
    EXPECT_LT(random.stats().flips, 3 * n);
}

TEST(LessonFacts, SuperTriangleLessonExactModeGivesThreeTrianglesAndAConvexHull) {
    Lesson lesson = loadLesson(std::string(DLAB_SOURCE_DIR) + "/lessons/07_super_triangle.toml");
    ASSERT_EQ(lesson.options.boundary, Boundary::Super);
    lesson.options.boundary = Boundary::Exact;
    LiveRun e = start(lesson.points, lesson.options);
    e.journal->seek(1u << 30);
    EXPECT_EQ(answer(e, "triangles").a, 3);
    EXPECT_TRUE(answer(e, "convex").truth);
}

// Lesson 7's sliver (0, 1, 2) along the top: Delaunay among the input points, yet its circle
// holds the top super vertex, and only that one.
TEST(LessonFacts, SuperTriangleLessonSliverCircleHoldsOnlyTheTopSuperVertex) {
    const Lesson lesson =
        loadLesson(std::string(DLAB_SOURCE_DIR) + "/lessons/07_super_triangle.toml");
    ASSERT_EQ(lesson.points.size(), 4u);
    const Inserter ins(lesson.points, lesson.options);
    const auto& G = ins.mesh().G;
    ASSERT_EQ(G.size(), 7u);  // the input and s0, s1, s2
    const Vec2 a = G[0], b = G[1], c = G[2];
    ASSERT_GT(orient2d(a, b, c), 0);
    EXPECT_LT(incircle(a, b, c, G[3]), 0) << "the sliver is Delaunay among the input points";
    std::int32_t top = 4;
    for (std::int32_t s = 4; s < 7; ++s) {
        if (G[s].y > G[top].y) top = s;
    }
    for (std::int32_t s = 4; s < 7; ++s)
        EXPECT_EQ(incircle(a, b, c, G[s]) > 0, s == top) << "super vertex s" << s - 4;
    EXPECT_GT(G[top].y, G[0].y) << "s" << top - 4 << " is above the points";
}

TEST(LessonFacts, SplitLessonOldTriangleChangesOnlyV2O0AndO1) {
    const Lesson lesson = loadLesson(std::string(DLAB_SOURCE_DIR) + "/lessons/04_split.toml");
    LiveRun r = start(lesson.points, lesson.options);
    while (const Op* op = r.journal->forward()) {
        if (op->type == OpType::Split) break;
    }
    const Op& split = *r.journal->current();
    ASSERT_EQ(split.type, OpType::Split);
    ASSERT_EQ(split.a, 0);
    std::set<std::int32_t> cells;  // slot = 2 * corner + (O ? 1 : 0)
    for (std::uint32_t i = 0; i < split.numChanges; ++i) {
        const CellChange& ch = r.journal->changes()[split.firstChange + i];
        if (ch.corner() < 3) cells.insert(ch.slot);
    }
    EXPECT_EQ(cells, (std::set<std::int32_t>{2 * 2, 2 * 0 + 1, 2 * 1 + 1}));
}

TEST(LessonFacts, FlipsLessonTestsAreThreePlusTwoPerFlip) {
    const Lesson lesson = loadLesson(std::string(DLAB_SOURCE_DIR) + "/lessons/05_flips.toml");
    const LessonPlan plan = planLesson(lesson);
    std::int64_t flips = -1, tests = -1;
    for (std::size_t k = 0; k < lesson.stops.size(); ++k) {
        if (lesson.stops[k].answer == "insertion_flips") flips = plan.stops[k].answer->a;
        if (lesson.stops[k].answer == "insertion_tests") tests = plan.stops[k].answer->a;
    }
    ASSERT_GT(flips, 0);
    EXPECT_EQ(tests, 3 + 2 * flips);
}

TEST(LessonSlides, RenderWritesOneSlidePerStopWithoutAnOutputFile) {
    const std::string lesson = std::string(DLAB_SOURCE_DIR) + "/lessons/01_corner_table.toml";
    const fs::path dir = scratchDir() / "slides";
    fs::remove_all(dir);
    const Result r =
        dtlab("render --lesson " + lesson + " --slides " + dir.string() + " --size 640x400");
    ASSERT_EQ(r.status, 0) << r.out;
    const std::size_t stops = loadLesson(lesson).stops.size();
    for (std::size_t k = 1; k <= stops; ++k) {
        char name[16];
        std::snprintf(name, sizeof name, "%02zu.png", k);
        EXPECT_GT(fs::file_size(dir / name), 0u) << name;
    }
    EXPECT_FALSE(fs::exists(dir / "00.png"));
    const Result none = dtlab("render --lesson " + lesson);
    EXPECT_EQ(none.status, 2) << none.out;
    EXPECT_NE(none.out.find("needs -o FILE.png"), std::string::npos) << none.out;
}

TEST(LessonFigure, LiftingMapDrawsTheInCircleTestAtTheStop) {
    const Lesson lesson =
        loadLesson(std::string(DLAB_SOURCE_DIR) + "/lessons/04b_delaunay_foundations.toml");
    const LessonPlan plan = planLesson(lesson);
    std::size_t figures = 0;
    for (std::size_t k = 0; k < lesson.stops.size(); ++k) {
        if (lesson.stops[k].figure != "lifting-map") continue;
        ++figures;
        LiveRun r = start(lesson.points, lesson.options);
        r.journal->seek(plan.stops[k].position);
        const auto f = liftingMapAt(*r.ins, r.journal->current());
        ASSERT_TRUE(f) << "stop " << k + 1;
        // The figure's sign is the exact test's, and the lifted point is below the plane through
        // the lifted triangle exactly when the test says inside.
        EXPECT_EQ(f->sign, answer(r, "test_result").a);
        EXPECT_EQ(f->vertex, answer(r, "vertex").a);
        const Answer tested = answer(r, "test_edge");
        const std::set<std::int32_t> tri(std::begin(f->vertices), std::end(f->vertices));
        EXPECT_TRUE(tri.count(static_cast<std::int32_t>(tested.a)) &&
                    tri.count(static_cast<std::int32_t>(tested.b)));
    }
    EXPECT_EQ(figures, 1u);
    // An unknown figure, and a figure where no in-circle test is at hand, name line and stop.
    const LessonError unknown = errorOf(kHead + "[[stop]]\ntext = \"t\"\nfigure = \"torus\"\n");
    EXPECT_EQ(unknown.line(), 5);
    EXPECT_NE(unknown.message().find("unknown figure \"torus\""), std::string::npos);
    const LessonError none =
        errorOf(kHead + "[[stop]]\nrun_to = \"end\"\ntext = \"t\"\nfigure = \"lifting-map\"\n");
    EXPECT_EQ(none.stop(), 1);
    EXPECT_NE(none.message().find("needs an in-circle test"), std::string::npos) << none.what();
}

// ---- Objectives, minutes and tracks -------------------------------------------------------------

TEST(LessonObjectives, AreReadAndShownAboveTheFirstStop) {
    const fs::path p = scratchDir() / "lessons" / "obj.toml";
    write(p, kHead +
                 "objectives = [\"name a corner\", \"say what O is\"]\nminutes = 7\n"
                 "[[stop]]\ntext = \"First.\"\n[[stop]]\ntext = \"Second.\"\n");
    const Lesson l = loadLesson(p.string());
    EXPECT_EQ(l.objectives, (std::vector<std::string>{"name a corner", "say what O is"}));
    EXPECT_EQ(l.minutes, 7);
    const LessonPlan plan = planLesson(l);
    EXPECT_EQ(plan.stops[0].text, objectivesText(l.objectives) + "First.");
    EXPECT_NE(plan.stops[0].text.find("name a corner; say what O is"), std::string::npos);
    EXPECT_EQ(plan.stops[1].text, "Second.");
}

TEST(LessonObjectives, BadValuesNameTheLine) {
    const std::string stop = "[[stop]]\ntext = \"x\"\n";
    const ErrorCase cases[] = {
        {kHead + "objectives = \"one\"\n" + stop, 3, 0, "list of 1 to 8"},
        {kHead + "objectives = []\n" + stop, 3, 0, "list of 1 to 8"},
        {kHead + "objectives = [\n  \"fine\",\n  3,\n]\n" + stop, 5, 0, "sentences"},
        {kHead + "objectives = [\"**open\"]\n" + stop, 3, 0, "**"},
        {kHead + "minutes = 0\n" + stop, 3, 0, "between 1 and 300"},
        {kHead + "minutes = \"ten\"\n" + stop, 3, 0, "whole number"},
    };
    expectErrors(cases);
}

namespace {

// A track beside two small lessons, in a folder of its own; returns the track's path.
std::string plantTrack(const std::string& name, const std::string& track) {
    const fs::path dir = scratchDir() / ("track_" + name);
    const std::string lesson = kHead +
                               "objectives = [\"a\"]\nminutes = 5\n"
                               "[[stop]]\ntext = \"One.\"\n[[stop]]\nrun_to = \"end\"\n"
                               "text = \"Two.\"\n[[stop]]\ntext = \"Three.\"\n";
    write(dir / "a.toml", lesson);
    write(dir / "bare.toml", kHead + "[[stop]]\ntext = \"No objectives.\"\n");
    return write(dir / "track.toml", track);
}

const std::string kTrackHead =
    "title = \"T\"\nkind = \"track\"\nobjectives = [\"learn\"]\nminutes = 50\n";

LessonError trackError(const std::string& name, const std::string& text) {
    const std::string path = plantTrack(name, text);
    try {
        loadTrack(path);
    } catch (const LessonError& e) {
        EXPECT_EQ(e.file(), path);
        EXPECT_EQ(std::string(e.what()).rfind(path + ":", 0), 0u) << e.what();
        return e;
    }
    ADD_FAILURE() << "no error for:\n" << text;
    return LessonError("", 0, 0, "");
}

}  // namespace

TEST(LessonTrack, ReadsItsItemsInOrder) {
    const std::string path =
        plantTrack("ok", kTrackHead +
                             "[[item]]\nlesson = \"a.toml\"\nstops = [1, 3]\nminutes = 20\n"
                             "[[item]]\nlesson = \"a.toml\"\nstops = [2]\nminutes = 30\n");
    EXPECT_TRUE(isTrackFile(path));
    const Track t = loadTrack(path);
    ASSERT_EQ(t.items.size(), 2u);
    EXPECT_EQ(t.slides(), 3u);
    EXPECT_EQ(t.items[0].stops, (std::vector<std::size_t>{0, 2}));
    EXPECT_EQ(t.items[1].minutes, 30);
    EXPECT_EQ(t.items[1].line, 9);
    const auto slides = trackSlides(t);
    EXPECT_EQ(slides, (std::vector<std::pair<std::size_t, std::size_t>>{{0, 0}, {0, 2}, {1, 1}}));
    // A lesson is no track, and loadLesson on a track says what it is.
    EXPECT_FALSE(isTrackFile(std::string(DLAB_SOURCE_DIR) + "/lessons/01_corner_table.toml"));
    try {
        loadLesson(path);
        ADD_FAILURE() << "a track loaded as a lesson";
    } catch (const LessonError& e) {
        EXPECT_NE(e.message().find("this is a track"), std::string::npos) << e.what();
    }
}

TEST(LessonTrack, PlantedErrorsNameFileAndLine) {
    const std::string item = "[[item]]\nlesson = \"a.toml\"\nstops = [1]\nminutes = 10\n";
    struct Case {
        std::string name, text;
        int line;
        const char* says;
    } cases[] = {
        {"nostop", kTrackHead + "[[item]]\nlesson = \"a.toml\"\nstops = [1, 4]\nminutes = 5\n", 7,
         "has stops 1 to 3: no stop 4"},
        {"backwards", kTrackHead + "[[item]]\nlesson = \"a.toml\"\nstops = [2, 1]\nminutes = 5\n",
         7, "go forward"},
        {"over", kTrackHead + item + item + item + item + item + item, 25,
         "add up to 60 here, more than the track's 50"},
        {"nominutes", kTrackHead + "[[item]]\nlesson = \"a.toml\"\nstops = [1]\n", 5,
         "needs \"minutes\""},
        {"noobjectives", "title = \"T\"\nkind = \"track\"\nminutes = 50\n" + item, 1,
         "needs \"objectives\""},
        {"bare", kTrackHead + "[[item]]\nlesson = \"bare.toml\"\nstops = [1]\nminutes = 5\n", 5,
         "states no objectives or minutes"},
        {"missing", kTrackHead + "[[item]]\nlesson = \"gone.toml\"\nstops = [1]\nminutes = 5\n", 6,
         "gone.toml"},
        {"outside", kTrackHead + "[[item]]\nlesson = \"../a.toml\"\nstops = [1]\nminutes = 5\n", 6,
         ".."},
        {"empty", kTrackHead, 1, "[[item]]"},
        {"key", kTrackHead + "[[item]]\nlesson = \"a.toml\"\nstop = [1]\nminutes = 5\n", 7,
         "unknown key \"stop\""},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const LessonError e = trackError(c.name, c.text);
        EXPECT_EQ(e.line(), c.line) << e.what();
        EXPECT_NE(e.message().find(c.says), std::string::npos) << e.what();
    }
}

TEST(LessonTrack, TheLectureFitsFiftyMinutesAndChecks) {
    const std::string path = std::string(DLAB_SOURCE_DIR) + "/lessons/lecture.toml";
    const Track t = loadTrack(path);
    int minutes = 0;
    for (const TrackItem& i : t.items) {
        EXPECT_GT(i.minutes, 0) << i.written;
        minutes += i.minutes;
        const Lesson l = loadLesson(i.lesson);
        EXPECT_FALSE(l.objectives.empty()) << i.written;
        EXPECT_GT(l.minutes, 0) << i.written;
    }
    EXPECT_LE(minutes, 50);
    EXPECT_LE(t.minutes, 50);
    EXPECT_LE(t.slides(), 25u);
    EXPECT_FALSE(t.objectives.empty());
    const Result r = dtlab("lesson check --no-slides " + path);
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("ok: track"), std::string::npos) << r.out;
    // A planted error in a track fails `lesson check` with the track's file and line.
    const std::string bad = plantTrack(
        "check", kTrackHead + "[[item]]\nlesson = \"a.toml\"\nstops = [9]\nminutes = 5\n");
    const Result f = dtlab("lesson check --no-slides " + bad);
    EXPECT_NE(f.status, 0);
    EXPECT_NE(f.out.find(bad + ":7:"), std::string::npos) << f.out;
}

TEST(LessonHandout, TrackHandoutHasEverySlideFoldedHintsAndNoAnswers) {
    const std::string path = std::string(DLAB_SOURCE_DIR) + "/lessons/lecture.toml";
    const Track t = loadTrack(path);
    const fs::path dir = scratchDir() / "trackhandout";
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (const char* name : {"lecture.md", "lecture.html"}) {
        SCOPED_TRACE(name);
        const fs::path out = dir / name;
        const Result r = dtlab("lesson handout " + path + " -o " + out.string());
        ASSERT_EQ(r.status, 0) << r.out;
        std::ifstream in(out);
        const std::string doc((std::istreambuf_iterator<char>(in)),
                              std::istreambuf_iterator<char>());
        for (std::size_t k = 1; k <= t.slides(); ++k) {
            char png[48];
            std::snprintf(png, sizeof png, "lecture_files/%02zu.png", k);
            EXPECT_NE(doc.find(png), std::string::npos) << png;
            EXPECT_TRUE(fs::is_regular_file(dir / png)) << png;
        }
        char past[48];
        std::snprintf(past, sizeof past, "lecture_files/%02zu.png", t.slides() + 1);
        EXPECT_FALSE(fs::exists(dir / past)) << "one picture a slide, no more";
        EXPECT_NE(doc.find(t.objectives[0]), std::string::npos) << "objectives first";
        EXPECT_NE(doc.find("<details><summary>Hint</summary>"), std::string::npos);
        EXPECT_EQ(doc.find("{{"), std::string::npos);
        EXPECT_EQ(doc.find("A: "), std::string::npos);
        if (out.extension() == ".html") {
            EXPECT_EQ(doc.find('*'), std::string::npos) << "Markdown left literal in the HTML";
        }
        fs::remove_all(dir / "lecture_files");  // the next one writes its own
    }
}

// ---- Lessons with edits: stops inside the removals and constraints after the run ----------------

namespace {

// The finished exact-mode run of the points, in input order, and its editor with `edits` added.
struct EditedRun {
    std::unique_ptr<Inserter> ins;
    std::unique_ptr<Editor> editor;
};
EditedRun editedRun(const std::vector<Vec2>& pts, const std::vector<std::string>& edits) {
    InsertOptions o;
    o.order = OrderKind::Input;
    EditedRun r;
    r.ins = std::make_unique<Inserter>(pts, o);
    r.ins->run();
    r.editor = std::make_unique<Editor>(r.ins->mesh());
    for (const std::string& e : edits) {
        std::string message;
        EXPECT_TRUE(r.editor->add(*parseEdit(e), message)) << e << ": " << message;
    }
    r.editor->seek(0);
    return r;
}

const std::vector<Vec2> kEditPoints = {{0, 0}, {6, 0}, {5, 4}, {1, 3}, {3, 1}};

// Edges of the finished mesh that the open segment p-q crosses at a point inside both.
int properCrossings(const Mesh& m, Vec2 p, Vec2 q) {
    int n = 0;
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        const std::int32_t o = m.O[c];
        if (o != kNone && o < c) continue;
        const Vec2 a = m.G[m.V[next(c)]], b = m.G[m.V[prev(c)]];
        if (orient2d(p, q, a) * orient2d(p, q, b) < 0 && orient2d(a, b, p) * orient2d(a, b, q) < 0)
            ++n;
    }
    return n;
}

}  // namespace

TEST(LessonEdits, StopsInsideARemovalReadTheEditorsRecords) {
    const std::string text = kHead +
                             "edits = [\"remove vertex 4\"]\n"
                             "[[stop]]\nrun_to = \"edit:0\"\ntext = \"a\"\nquestion = \"q\"\n"
                             "answer = \"removal_degree\"\n"
                             "[[stop]]\nrun_to = \"ear-test\"\ntext = \"b\"\n"
                             "[[stop]]\nrun_to = \"ear-flip\"\ntext = \"c\"\nquestion = \"q\"\n"
                             "answer = \"degree_left\"\n"
                             "[[stop]]\nrun_to = \"merge\"\ntext = \"d\"\n"
                             "[[stop]]\nrun_to = \"edit:1\"\ntext = \"e\"\nquestion = \"q\"\n"
                             "answer = \"ear_flips\"\n";
    const fs::path p = scratchDir() / "lessons" / "removal.toml";
    write(p, text);
    const Lesson lesson = loadLesson(p.string());
    ASSERT_EQ(lesson.edits.size(), 1u);
    const LessonPlan plan = planLesson(lesson);
    EditedRun r = editedRun(kEditPoints, {"remove vertex 4"});
    const Editor& ed = *r.editor;
    const auto& V = ed.mesh().V;
    const auto degree = std::count(V.begin(), V.end(), 4);
    const auto& ops = ed.edits()[0].removal.ops;
    const auto flips = std::count_if(
        ops.begin(), ops.end(), [](const RemoveOp& o) { return o.type == RemoveOpType::Flip; });
    // The degree goes down by one per ear flip, and the last three triangles merge.
    EXPECT_EQ(degree, flips + 3);
    EXPECT_EQ(plan.stops[0].answer->a, degree);
    EXPECT_EQ(plan.stops[0].position, plan.totalOps);
    EXPECT_EQ(plan.stops[2].answer->a, degree - 1);
    EXPECT_EQ(plan.stops[4].answer->a, flips);
    EXPECT_EQ(plan.stops[4].position, plan.totalOps + ops.size());
    EXPECT_EQ(plan.editOps, ops.size());
    // Each stop sits right after an op of its kind.
    const auto firstOf = [&](RemoveOpType t) {
        return std::find_if(ops.begin(), ops.end(),
                            [&](const RemoveOp& o) { return o.type == t; }) -
               ops.begin() + 1;
    };
    EXPECT_EQ(plan.stops[1].position, plan.totalOps + firstOf(RemoveOpType::EarTest));
    EXPECT_EQ(plan.stops[3].position, plan.totalOps + firstOf(RemoveOpType::Merge));
    EXPECT_NE(plan.stops[1].caption.find("remove vertex 4"), std::string::npos);
    // A wrong number planted as an expectation fails with the file, the line and the stop.
    write(p, text + "expect = { ear_flips = " + std::to_string(flips + 1) + " }\n");
    const LessonError e =
        errorOf(text + "expect = { ear_flips = " + std::to_string(flips + 1) + " }\n");
    EXPECT_EQ(e.stop(), 5);
    EXPECT_NE(e.message().find("expects ear_flips = " + std::to_string(flips + 1) +
                               ", but the engine says " + std::to_string(flips)),
              std::string::npos)
        << e.what();
    const Result cli = dtlab("lesson check --no-slides " + p.string());
    EXPECT_EQ(cli.status, 1) << cli.out;
    EXPECT_NE(cli.out.find("stop 5: the lesson expects ear_flips"), std::string::npos) << cli.out;
}

TEST(LessonEdits, StopsInsideAConstraintCountItsCrossingsFlipsAndRepair) {
    const std::string edit = "constrain 0-2";
    EditedRun r = editedRun(kEditPoints, {edit});
    const int crossings = properCrossings(r.ins->mesh(), kEditPoints[0], kEditPoints[2]);
    ASSERT_GT(crossings, 0) << "the segment must cross an edge for this test";
    const auto& ops = r.editor->edits()[0].constraint.ops;
    const auto count = [&](ConstrainOpType t) {
        return std::count_if(ops.begin(), ops.end(),
                             [&](const ConstrainOp& o) { return o.type == t; });
    };
    const std::string text = kHead + "edits = [\"" + edit +
                             "\"]\n"
                             "[[stop]]\nrun_to = \"edit:0\"\ntext = \"a\"\nquestion = \"q\"\n"
                             "answer = \"crossed_edges\"\n"
                             "[[stop]]\nrun_to = \"segment-walk\"\ntext = \"b\"\n"
                             "[[stop]]\nrun_to = \"constrain-mark\"\ntext = \"c\"\nquestion = "
                             "\"q\"\nanswer = \"sloan_flips\"\n"
                             "[[stop]]\nrun_to = \"edit:1\"\ntext = \"d\"\nquestion = \"q\"\n"
                             "answer = \"repair_tests\"\nexpect = { repair_flips = " +
                             std::to_string(count(ConstrainOpType::Flip)) + " }\n";
    const fs::path p = scratchDir() / "lessons" / "constrain.toml";
    write(p, text);
    const LessonPlan plan = planLesson(loadLesson(p.string()));
    EXPECT_EQ(plan.stops[0].answer->a, crossings);
    EXPECT_EQ(plan.stops[1].position, plan.totalOps + 1);  // the walk is the first op
    EXPECT_EQ(plan.stops[2].answer->a, count(ConstrainOpType::SloanFlip));
    EXPECT_GE(plan.stops[2].answer->a, crossings);  // each crossing edge flips at least once
    EXPECT_EQ(plan.stops[3].answer->a, count(ConstrainOpType::InCircleTest));
    // The segment is an edge after the mark: the corner expressions read the edited mesh.
    EXPECT_EQ(computeEditAnswer("triangles", *r.editor)->a,
              static_cast<std::int64_t>(r.ins->mesh().numTriangles()));
}

// The paper's super-triangle: the edits work on the mesh with the super-triangle still in (its
// vertices are real points), as the removal's degree counts them.
TEST(LessonEdits, ASuperTriangleLessonEditsTheMeshWithTheSuperTriangleIn) {
    const std::string text = kHead +
                             "edits = [\"remove vertex 4\", \"move vertex 2 to 1.5, 0.5\"]\n"
                             "[options]\nboundary = \"super\"\n"
                             "[[stop]]\nrun_to = \"edit:0\"\ntext = \"a\"\nquestion = \"q\"\n"
                             "answer = \"removal_degree\"\n"
                             "[[stop]]\nrun_to = \"edit:2\"\ntext = \"b\"\n";
    const fs::path p = scratchDir() / "lessons" / "removal_super.toml";
    write(p, text);
    const Lesson lesson = loadLesson(p.string());
    ASSERT_EQ(lesson.edits.size(), 2u);
    const LessonPlan plan = planLesson(lesson);
    auto ins = makeInserter(lesson);
    Journal journal(*ins);
    std::unique_ptr<Editor> ed = startEdits(lesson, journal, *ins);
    EXPECT_EQ(ed->boundary(), Boundary::Super);
    const auto& V = ed->mesh().V;
    EXPECT_EQ(plan.stops[0].answer->a, std::count(V.begin(), V.end(), 4));
    EXPECT_GT(plan.editOps, 0u);
    EXPECT_EQ(plan.stops[1].position, plan.totalOps + plan.editOps);
    ed->seek(ed->total());
    EXPECT_EQ(std::count(ed->mesh().V.begin(), ed->mesh().V.end(), 4), 0);
    EXPECT_EQ(ed->mesh().G[2], (Vec2{1.5, 0.5}));
    for (std::int32_t s = ed->firstVirtual(); s < ed->firstVirtual() + 3; ++s)
        EXPECT_GT(std::count(ed->mesh().V.begin(), ed->mesh().V.end(), s), 0)
            << "the super-triangle's vertex " << s << " is still in";
}

TEST(LessonEdits, TargetsAndEditsThatDoNotFitNameFileLineAndStop) {
    const ErrorCase cases[] = {
        {kHead + "[[stop]]\nrun_to = \"ear-test\"\ntext = \"a\"\n", 3, 1,
         "the lesson has no edits"},
        {kHead + "edits = [\"remove vertex 4\"]\n[[stop]]\nrun_to = \"ear-flip\"\ntext = "
                 "\"a\"\n[[stop]]\nrun_to = \"flip\"\ntext = \"b\"\n",
         7, 2, "run_to is an edit target"},
        {kHead + "edits = [\"remove vertex 4\"]\n[[stop]]\nrun_to = \"sloan-flip\"\ntext = \"a\"\n",
         4, 1, "is not reached in the edits"},
        {kHead + "edits = [\"remove vertex 4\"]\n[[stop]]\nrun_to = \"edit:2\"\ntext = \"a\"\n", 4,
         1, "the lesson has 1 edits"},
        {kHead + "edits = [\"remove vertex 4\"]\n[[stop]]\nrun_to = \"edit:1\"\ntext = "
                 "\"a\"\nquestion = \"q\"\nanswer = \"crossed_edges\"\n",
         8, 1, "this edit constrains no segment"},
        {kHead + "[[stop]]\ntext = \"a\"\nquestion = \"q\"\nanswer = \"ear_flips\"\n", 6, 1,
         "a stop inside the lesson's edits"},
        {kHead + "edits = [\"remove vertex 9\"]\n[[stop]]\ntext = \"a\"\n", 3, 0,
         "the lesson has points 0 to 4"},
        {kHead + "edits = [\"delete 4\"]\n[[stop]]\ntext = \"a\"\n", 3, 0, "an edit is"},
        {kHead + "edits = [\"constrain 0-2\", \"remove vertex 0\"]\n[[stop]]\ntext = \"a\"\n", 3, 0,
         "edit \"remove vertex 0\" is refused"},
    };
    expectErrors(cases);
}
