// The check of a slide as rendered: what a stop's text names (vertices, panels, a count of queued
// edges), read against the text runs and canvas marks of its slide, as pure functions on planted
// slides; and `dtlab lesson check` failing with file, line and stop on planted lessons.
#include "core/teaching/slide_check.h"

#include "tests/run_dtlab.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>

using namespace dlab;
namespace fs = std::filesystem;

namespace {

fs::path scratch() {
    const fs::path d = fs::temp_directory_path() / ("dlab_slide_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

std::string write(const std::string& name, const std::string& text) {
    const fs::path p = scratch() / name;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
}

const std::string kHead = "title = \"t\"\npoints = [[0, 0], [6, 0], [5, 4], [1, 3], [3, 1]]\n";

SlideMark mark(SlideMarkRole role, std::int32_t a, std::int32_t b, SlideBox box) {
    return {role, a, b, box};
}

// A canvas 0..600 x 0..400 with vertex 3's point at (100, 100) and its label "3" beside it.
RenderedSlide slideWithVertex3() {
    RenderedSlide s;
    s.marks.push_back(mark(SlideMarkRole::Canvas, -1, -1, {0, 0, 600, 400}));
    s.marks.push_back(mark(SlideMarkRole::Vertex, 3, -1, {95, 95, 105, 105}));
    s.marks.push_back(mark(SlideMarkRole::VertexLabel, 3, -1, {108, 80, 118, 96}));
    s.runs.push_back({"3", {108, 81, 118, 95}, 1});
    return s;
}

}  // namespace

TEST(SlideCheck, ReadsTheVerticesATextNames) {
    EXPECT_EQ(verticesNamedIn("Vertex 11 is next."), (std::vector<std::int32_t>{11}));
    EXPECT_EQ(verticesNamedIn("vertices 2, 3 and 5 span it"), (std::vector<std::int32_t>{2, 3, 5}));
    EXPECT_EQ(verticesNamedIn("edge 4-9 flips to 2\u20137"),
              (std::vector<std::int32_t>{4, 9, 2, 7}));
    // Corners, triangles, rows and operations are no vertices; nor is a bare count.
    EXPECT_TRUE(verticesNamedIn("corners 0-2 of triangle 0, rows 3-5, op 12, 6 corners").empty());
    EXPECT_TRUE(verticesNamedIn("tests = 3 + 2 x flips; a 1-based count").empty());
    EXPECT_TRUE(verticesNamedIn("the corners at the new vertex (2, 14 and 17)").empty());
}

TEST(SlideCheck, ReadsThePanelsATextRefersTo) {
    EXPECT_EQ(panelsNamedIn("The corner table marks the changed cells."),
              (std::vector<std::string>{"corner-table"}));
    EXPECT_EQ(
        panelsNamedIn("The statistics panel counts them; the ID buffer view shows the pixel."),
        (std::vector<std::string>{"idbuffer", "statistics"}));
    EXPECT_TRUE(panelsNamedIn("A corner table stores V and O.").empty())
        << "the idea, not the panel";
    const std::vector<std::string> table = {"c | t | V[c] | O[c] | n | p | l | r", "0 | 0 | 1 | 4"};
    EXPECT_TRUE(panelOnSlide("corner-table", table));
    EXPECT_FALSE(panelOnSlide("corner-table", {"v | x | y | state", "0 | 0 | 100 | vertex"}));
    EXPECT_TRUE(panelOnSlide("vertex-table", {"v | x | y | state"}));
    EXPECT_TRUE(panelOnSlide("statistics", {"Checks of the current mesh (exact)"}));
    EXPECT_TRUE(panelOnSlide("statistics", {"Counts of the run"}));
    EXPECT_FALSE(panelOnSlide("statistics", {"the statistics say"}));
}

TEST(SlideCheck, ReadsACountOfQueuedEdges) {
    EXPECT_EQ(queueCountIn("Each flip adds two: 4 edges wait now."), 4);
    EXPECT_EQ(queueCountIn("3 edges are waiting"), 3);
    EXPECT_EQ(queueCountIn("2 edges in the queue"), 2);
    EXPECT_EQ(queueCountIn("the queue holds 5"), 5);
    EXPECT_FALSE(queueCountIn("4 edges around vertex 2"));
}

TEST(SlideCheck, AVertexLabelMustBeDrawnInsideTheCanvasAndUncovered) {
    EXPECT_EQ(vertexLabelProblem(3, slideWithVertex3()), std::nullopt);
    RenderedSlide s = slideWithVertex3();
    EXPECT_NE(vertexLabelProblem(4, s).value_or("").find("vertex 4 is not on the canvas"),
              std::string::npos);
    s.marks.pop_back();  // the point without its label (vertex-ids off)
    EXPECT_NE(vertexLabelProblem(3, s).value_or("").find("drawn without its id"),
              std::string::npos);
    s = slideWithVertex3();
    s.runs.push_back({"6 (s2)", {104, 84, 150, 98}, 1});  // another label over it
    EXPECT_NE(vertexLabelProblem(3, s).value_or("").find("covered by \"6 (s2)\""),
              std::string::npos);
    s = slideWithVertex3();
    s.marks[2].box = {598, 80, 608, 96};  // past the canvas's right edge
    s.runs[0].box = {598, 81, 608, 95};
    EXPECT_NE(vertexLabelProblem(3, s).value_or("").find("cut off"), std::string::npos);
    s = slideWithVertex3();
    s.marks.push_back(mark(SlideMarkRole::Vertex, 0, -1, {97, 96, 107, 106}));  // 2 px away
    EXPECT_NE(vertexLabelProblem(3, s).value_or("").find("as one dot"), std::string::npos);
    const std::vector<Vec2> same = {{0, 0}, {1, 1}, {2, 2}, {0, 0}};
    EXPECT_EQ(vertexLabelProblem(3, s, same), std::nullopt) << "a duplicate point is one dot";
}

TEST(SlideCheck, TheCanvasLegendMustNotCoverANamedVertexOrItsLabel) {
    RenderedSlide s = slideWithVertex3();
    s.marks.push_back(mark(SlideMarkRole::Legend, -1, -1, {300, 200, 500, 300}));  // elsewhere
    EXPECT_EQ(vertexLabelProblem(3, s), std::nullopt);
    s.marks.back().box = {60, 60, 102, 110};  // over the point, not the label
    EXPECT_NE(vertexLabelProblem(3, s).value_or("").find("legend covers vertex 3"),
              std::string::npos);
    s.marks.back().box = {106, 60, 200, 90};  // over the label only
    EXPECT_NE(vertexLabelProblem(3, s).value_or("").find("legend covers vertex 3"),
              std::string::npos);
}

// A lesson planned here, its slide planted: the check compares the picture with the engine.
TEST(SlideCheck, TheEdgeDrawnUnderTestAndTheQueueCountMatchTheEngine) {
    const std::string path = write("test_edge.toml", kHead + R"(
[[stop]]
run_to = "incircle"
count = 3
text = "The test of edge {{test_edge}} answered {{test_result}}; {{queue}} edges wait."
)");
    const Lesson lesson = loadLesson(path);
    const LessonPlan plan = planLesson(lesson);
    ASSERT_EQ(plan.stops[0].text, "The test of edge 0-2 answered 1; 0 edges wait.");
    RenderedSlide s;
    s.marks.push_back(mark(SlideMarkRole::Canvas, -1, -1, {0, 0, 600, 400}));
    for (std::int32_t v : {0, 2}) {
        const float x = 100.0f * static_cast<float>(v + 1);
        s.marks.push_back(mark(SlideMarkRole::Vertex, v, -1, {x - 5, 95, x + 5, 105}));
        s.marks.push_back(mark(SlideMarkRole::VertexLabel, v, -1, {x + 8, 80, x + 18, 96}));
        s.runs.push_back({std::to_string(v), {x + 8, 81, x + 18, 95}, 1});
    }
    s.marks.push_back(mark(SlideMarkRole::TestEdge, 2, 0, {100, 100, 300, 100}));
    EXPECT_TRUE(renderedSlideProblems(lesson, plan, {s}).empty());

    RenderedSlide wrong = s;
    wrong.marks[5] = mark(SlideMarkRole::TestEdge, 1, 2, {100, 100, 300, 100});
    wrong.marks.push_back(mark(SlideMarkRole::QueuedEdge, 0, 1, {0, 0, 1, 1}));
    const auto problems = renderedSlideProblems(lesson, plan, {wrong});
    ASSERT_EQ(problems.size(), 2u);
    EXPECT_EQ(problems[0].line(), 4);
    EXPECT_EQ(problems[0].stop(), 1);
    EXPECT_NE(problems[0].message().find("draws 1-2 as the edge under test, but the engine tests "
                                         "0-2"),
              std::string::npos)
        << problems[0].what();
    EXPECT_EQ(problems[1].line(), 7);
    EXPECT_NE(problems[1].message().find("says 0 queued edges (the engine has 0), but the canvas "
                                         "draws 1"),
              std::string::npos)
        << problems[1].what();
}

TEST(SlideCheck, NeedsAreCheckedAsTheyLoad) {
    const std::string ok = write("needs.toml", kHead + R"(
[[stop]]
needs = ["vertex:4", "corner:2", "triangle:0", "panel:corner-table"]
text = "x"
)");
    EXPECT_EQ(loadLesson(ok).stops[0].needs.size(), 4u);
    EXPECT_EQ(loadLesson(ok).stops[0].needsLine, 5);
    const struct {
        const char* needs;
        const char* says;
    } bad[] = {
        {R"(["panel:table"])", "unknown panel \"table\""},
        {R"(["vertex:x"])", "vertex needs an id"},
        {R"(["edge:1"])", "write vertex:N, corner:N, triangle:N or panel:NAME"},
        {R"("vertex:4")", "\"needs\" must be a list"},
    };
    for (const auto& b : bad) {
        const std::string p =
            write("bad_needs.toml", kHead + "\n[[stop]]\nneeds = " + b.needs + "\ntext = \"x\"\n");
        try {
            loadLesson(p);
            ADD_FAILURE() << "no error for needs = " << b.needs;
        } catch (const LessonError& e) {
            EXPECT_EQ(e.line(), 5) << e.what();
            EXPECT_EQ(e.stop(), 1) << e.what();
            EXPECT_NE(std::string(e.what()).find(b.says), std::string::npos) << e.what();
        }
    }
}

// Each class planted in a lesson file fails `dtlab lesson check` (run in dtlab-gl: the slides are
// rendered) with the file, the line and the stop.
TEST(SlideCheck, LessonCheckFailsOnEachClassPlantedInALessonFile) {
    const std::string split = "\n[[stop]]\nrun_to = \"split\"\ncount = 2\n";
    const struct {
        std::string name, stop, says;
        int line;
    } planted[] = {
        {"count.toml",
         "overlays = [\"vertex-ids\", \"flip-queue\"]\ntext = \"Vertex 4 split a "
         "triangle: 4 edges wait for their test.\"\n",
         "the text says 4 queued edges (the engine has 3), but the canvas draws 3", 8},
        {"queue_off.toml", "overlays = [\"vertex-ids\"]\ntext = \"{{queue}} edges wait.\"\n",
         "the text says 3 queued edges (the engine has 3), but the canvas draws 0", 8},
        {"unlabelled.toml", "overlays = [\"flip-queue\"]\ntext = \"Vertex 4 split a triangle.\"\n",
         "vertex 4 is drawn without its id", 8},
        {"panel.toml", "tab = \"vertex-table\"\ntext = \"The corner table shows its new rows.\"\n",
         "the corner-table panel is not on the slide", 8},
        {"corner.toml", "overlays = [\"vertex-ids\"]\ntext = \"Corner 2 sits at a vertex.\"\n",
         "corner 2 has no label on the canvas", 8},
        {"needs.toml", "overlays = [\"fill\"]\nneeds = [\"vertex:2\"]\ntext = \"A split.\"\n",
         "vertex 2 is drawn without its id: turn the vertex-ids overlay on", 8},
        {"off_view.toml",
         "view = { rect = [100, 100, 110, 110] }\ntext = \"The last test: {{test_edge}}.\"\n",
         "the stop is about the in-circle test of edge 0-2, but the canvas does not draw it", 4},
    };
    for (const auto& p : planted) {
        std::string stop = split + p.stop;
        if (p.name == "off_view.toml")
            stop = "\n[[stop]]\nrun_to = \"incircle\"\ncount = 3\n" + p.stop;
        const std::string file = write(p.name, kHead + stop);
        const auto r = dlab::testutil::runDtlab("lesson check " + file);
        EXPECT_EQ(r.status, 1) << p.name << ": " << r.out;
        const std::string where = file + ":" + std::to_string(p.line) + ": stop 1: ";
        EXPECT_NE(r.out.find(where + p.says), std::string::npos)
            << p.name << ": wanted " << where << p.says << "\n"
            << r.out;
    }
    // The same stops with what they need on the slide pass.
    const std::string fine = write(
        "fine.toml", kHead + split +
                         "overlays = [\"vertex-ids\", \"flip-queue\"]\ntab = \"corner-table\"\n"
                         "needs = [\"vertex:2\"]\ntext = \"Vertex 4 split a triangle: {{queue}} "
                         "edges wait. The corner table has its new rows.\"\n");
    const auto r = dlab::testutil::runDtlab("lesson check " + fine);
    EXPECT_EQ(r.status, 0) << r.out;
}
