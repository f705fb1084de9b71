// The whole UI on the null platform: no GL context, nothing drawn, every frame's drawing counted.
#include "core/engine/generators.h"
#include "tests/ui/ui_harness.h"
#include "ui/gui.h"
#include "ui/platform/keys.h"

#include <gtest/gtest.h>

#include <string>

using dlab::test::UiHarness;

namespace {

// A Gui on the null platform that counts into `counts`.
struct CountedGui {
    explicit CountedGui(dlab::ui::NullRendererCounts& counts)
        : platform(dlab::ui::makeNullPlatform(1200, 800, &counts)), gui(*platform, state) {
        state.setOptions(dlab::ui::demoOptions());
        state.loadPoints(dlab::demoPoints(), "built-in demo");
    }
    dlab::ui::AppState state;
    std::unique_ptr<dlab::ui::Platform> platform;
    dlab::ui::Gui gui;
};

}  // namespace

TEST(NullRenderer, EveryFrameDrawsTheMeshInTwoPassesAndNoPixels) {
    dlab::ui::NullRendererCounts counts;
    CountedGui g(counts);
    for (int i = 0; i < 5; ++i) g.gui.frame();
    EXPECT_EQ(g.gui.platform().name(), std::string("null"));
    EXPECT_EQ(counts.frames, 5);
    EXPECT_EQ(counts.meshUpdates, 5);
    EXPECT_EQ(counts.meshPasses, 10);  // the fill under the highlights, the edges above
    int w = -1, h = -1;
    EXPECT_TRUE(g.gui.lastFrame(w, h).empty());
    EXPECT_FALSE(g.state.engine.hasGl());
}

TEST(NullRenderer, KeysAndButtonsStepTheRun) {
    UiHarness h;
    auto& e = h.state().engine;
    e.seek(10);
    h.press(dlab::ui::key::kRight);
    EXPECT_EQ(e.position(), 11u);
    h.press(dlab::ui::key::kLeft);
    EXPECT_EQ(e.position(), 10u);
    h.clickItem(">");
    EXPECT_EQ(e.position(), 11u);
}

TEST(NullRenderer, GlLocatorsAreRefusedWithAReason) {
    UiHarness h;
    dlab::InsertOptions o = h.state().engine.options();
    o.locator = dlab::LocatorKind::IdBufferGl;
    EXPECT_FALSE(h.state().setOptions(o));
    ASSERT_FALSE(h.state().messages.empty());
    EXPECT_NE(h.state().messages.back().text.find("needs a GL context"), std::string::npos)
        << h.state().messages.back().text;
    EXPECT_EQ(h.state().engine.idBufferGl(), nullptr);
}

TEST(NullRenderer, TheIdBufferViewHandsItsImageToTheRenderer) {
    dlab::ui::NullRendererCounts counts;
    CountedGui g(counts);
    dlab::InsertOptions o = g.state.engine.options();
    o.locator = dlab::LocatorKind::IdBufferCpu;
    ASSERT_TRUE(g.state.setOptions(o));
    g.state.pendingTab = "idbuffer";
    g.state.engine.seek(40);
    for (int i = 0; i < 4; ++i) g.gui.frame();
    EXPECT_GE(counts.imageUploads, 1);
    const long long uploads = counts.imageUploads;
    g.state.engine.seek(80);
    for (int i = 0; i < 3; ++i) g.gui.frame();
    EXPECT_GT(counts.imageUploads, uploads);  // the run moved: the image was made again
}
