// The Check tab on a mesh made elsewhere: opened from a file, its problems listed as the exact
// check names them and picked (the view goes there), the flip algorithm stepped by the engine
// to an exactly Delaunay end and back to the mesh as opened, and a broken mesh shown, not
// repaired.
#include "core/engine/generators.h"
#include "core/engine/inserter.h"
#include "core/engine/io_write.h"
#include "core/engine/predicates.h"
#include "tests/exact_check.h"
#include "tests/scrambled_mesh.h"
#include "tests/ui/ui_harness.h"
#include "ui/files/files.h"
#include "ui/panels/panels.h"
#include "ui/render/drawn_text.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <fstream>
#include <string>
#include <vector>

using dlab::test::TempDir;
using dlab::test::UiHarness;
using namespace dlab;

namespace {

// A valid triangulation of 80 points that is far from Delaunay: legal random flips of ours.
Mesh scrambledMesh() {
    Inserter ins(generatePoints(Generator::Uniform, 80, 3));
    ins.run();
    Mesh m = ins.mesh();
    dlab::test::scrambleByLegalFlips(m, 9, 200);
    return m;
}

void writeMesh(const TempDir& dir, const std::string& base, const Mesh& m) {
    std::ofstream node(dir / (base + ".node")), ele(dir / (base + ".ele"));
    writeNode(node, m.G);
    writeEle(ele, m);
}

std::string drawnText() {
    std::string all;
    for (const std::string& line : ui::drawnLines(ui::drawnText(ImGui::GetDrawData())))
        all += line + "\n";
    return all;
}

}  // namespace

TEST(CheckPanel, AnOpenedMeshIsCheckedPickedAndRepairedStepByStep) {
    TempDir dir("check_panel");
    const Mesh m = scrambledMesh();
    writeMesh(dir, "m", m);
    UiHarness h(1600, 1000);
    ui::AppState& st = h.state();
    ASSERT_TRUE(ui::openFile(st, dir / "m.ele")) << st.messages.back().text;
    h.frames(3);
    const ui::Engine& e = st.engine;
    ASSERT_TRUE(e.repairs());
    EXPECT_EQ(e.position(), 1u);  // Start done: the mesh as opened
    EXPECT_EQ(e.mesh().V, m.V);
    ASSERT_TRUE(st.meshCheck.open);
    const std::size_t bad = st.meshCheck.report.count(MeshProblem::Kind::NotDelaunay);
    ASSERT_GT(bad, 0u);
    const std::string text = drawnText();
    EXPECT_NE(text.find(std::to_string(bad) + " edges not Delaunay"), std::string::npos) << text;
    EXPECT_NE(text.find("not-delaunay: "), std::string::npos) << text;

    // Picking a problem moves the view onto it.
    const ui::View before = st.view;
    h.clickItem("check-first-problem");
    h.frames(2);
    EXPECT_EQ(st.meshCheck.picked, 0);
    EXPECT_GT(st.view.scale, before.scale);

    // The flip algorithm to its end: exactly Delaunay, and the panel says so.
    st.engine.toEnd(10000000);
    h.frames(3);
    ASSERT_TRUE(e.atEnd());
    EXPECT_GT(e.inserter().stats().flips, 0);
    EXPECT_EQ(checkDelaunayExact(e.mesh()), "");
    EXPECT_TRUE(st.meshCheck.now.isDelaunay());
    EXPECT_NE(drawnText().find("valid Delaunay triangulation"), std::string::npos);

    // And back to the mesh as opened, bit for bit.
    st.engine.seek(1);
    h.frames(2);
    EXPECT_EQ(e.mesh().V, m.V);
    EXPECT_EQ(st.meshCheck.now.count(MeshProblem::Kind::NotDelaunay), bad);
}

TEST(CheckPanel, AMeshThatIsNoTriangulationIsShownNotRepaired) {
    TempDir dir("check_panel_bad");
    Mesh m = scrambledMesh();
    std::swap(m.V[0], m.V[1]);  // one triangle clockwise
    writeMesh(dir, "bad", m);
    UiHarness h(1280, 720);
    ui::AppState& st = h.state();
    ASSERT_TRUE(ui::openFile(st, dir / "bad.ele"));
    h.frames(3);
    EXPECT_FALSE(st.meshCheck.report.isTriangulation());
    EXPECT_GE(st.meshCheck.report.count(MeshProblem::Kind::ClockwiseTriangle), 1u);
    EXPECT_EQ(st.engine.mesh().V, m.V);  // shown as it is
    st.engine.toEnd(1000);
    EXPECT_EQ(st.engine.inserter().stats().inCircleTests, 0);  // nothing tested, nothing flipped
    EXPECT_EQ(st.engine.mesh().V, m.V);
    h.frames(2);
    const std::string text = drawnText();
    EXPECT_NE(text.find("not a valid triangulation"), std::string::npos) << text;
    EXPECT_NE(text.find("clockwise"), std::string::npos) << text;
}

TEST(CheckPanel, TrianglesNamingMissingVerticesAreListedAndTheOthersShown) {
    TempDir dir("check_panel_missing");
    Mesh m = scrambledMesh();
    const std::int32_t missing = m.numVertices() + 7;
    m.V[3 * 5 + 1] = missing;  // triangles 5 and 9 name a vertex that does not exist
    m.V[3 * 9 + 2] = missing;
    writeMesh(dir, "x", m);
    UiHarness h(1280, 720);
    ui::AppState& st = h.state();
    ASSERT_TRUE(ui::openFile(st, dir / "x.ele"));
    h.frames(3);
    EXPECT_EQ(st.meshCheck.report.count(MeshProblem::Kind::VertexRange), 2u);
    std::vector<std::int32_t> others;
    for (std::int32_t t = 0; t < m.numTriangles(); ++t)
        if (t != 5 && t != 9)
            others.insert(others.end(), m.V.begin() + 3 * t, m.V.begin() + 3 * t + 3);
    EXPECT_EQ(st.engine.mesh().V, others);  // the others, in the file's order
    for (std::int32_t c = 0; c < st.engine.mesh().numCorners(); ++c) {
        const std::int32_t o = st.engine.mesh().O[c];
        if (o != kNone) {
            EXPECT_EQ(st.engine.mesh().O[o], c);
        }
    }
    st.engine.toEnd(1000);
    EXPECT_EQ(st.engine.mesh().V, others);  // shown, never repaired
    h.frames(2);
    const std::string text = drawnText();
    EXPECT_NE(text.find(std::to_string(missing)), std::string::npos) << text;
    bool warned = false;
    for (const auto& msg : st.messages)
        warned =
            warned || msg.text.find(
                          "2 triangles name a vertex that does not exist (listed "
                          "in the Check tab, not drawn); the other " +
                          std::to_string(m.numTriangles() - 2) + " are shown") != std::string::npos;
    EXPECT_TRUE(warned);
}

TEST(CheckPanel, AnUnreadableMeshChangesNothing) {
    TempDir dir("check_panel_unreadable");
    UiHarness h(1280, 720);
    ui::AppState& st = h.state();
    const std::vector<Vec2> points = st.engine.points();
    std::ofstream(dir / "y.off") << "OFF\nthis is not a mesh\n";
    EXPECT_FALSE(ui::openFile(st, dir / "y.off"));
    EXPECT_NE(st.files.notice.find("y.off"), std::string::npos) << st.files.notice;
    EXPECT_TRUE(dlab::test::sameBits(st.engine.points(), points));
}
