// Files as pixels: F12's PNG of the window, the animated GIF as rendered, and the notice a bad
// file shows (the logic of files and sessions: logic/test_files.cpp).
#include "core/engine/generators.h"
#include "core/engine/io_read.h"
#include "tests/full_disk.h"
#include "tests/ui/ui_harness.h"
#include "ui/files/files.h"
#include "ui/files/gif_export.h"
#include "ui/files/session.h"
#include "ui/panels/panels.h"
#include "ui/platform/keys.h"

#include <gif_lib.h>
#include <gtest/gtest.h>
#include <imgui.h>
#include <stb_image.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

using dlab::Vec2;
using dlab::test::sameBits;
using dlab::test::TempDir;
using dlab::test::UiHarness;
namespace fs = std::filesystem;
namespace key = dlab::ui::key;

namespace {

constexpr std::array<int, 3> kNoticeRgb = {191, 20,
                                           26};  // the notice's background (0.75, 0.08, 0.10)

}  // namespace

// ============================================================================================
// Captures
// ============================================================================================

TEST(Files, F12WritesAPngOfTheWindow) {
    TempDir dir("png");
    UiHarness h(1000, 700);
    auto& st = h.state();
    st.files.screenshotFolder = dir.path.string();
    st.engine.seek(30);
    h.frames(2);
    h.press(key::kF12);
    ASSERT_TRUE(st.files.screenshotRequested);
    dlab::ui::serviceCaptures(h.gui());
    EXPECT_FALSE(st.files.screenshotRequested);
    std::vector<fs::path> pngs;
    for (const auto& e : fs::directory_iterator(dir.path)) pngs.push_back(e.path());
    ASSERT_EQ(pngs.size(), 1u);
    EXPECT_EQ(pngs[0].extension(), ".png");
    int w = 0, hgt = 0, n = 0;
    unsigned char* data = stbi_load(pngs[0].string().c_str(), &w, &hgt, &n, 4);
    ASSERT_NE(data, nullptr);
    int fw = 0, fh = 0;
    const auto& frame = h.gui().lastFrame(fw, fh);
    ASSERT_EQ(w, fw);
    ASSERT_EQ(hgt, fh);
    std::size_t diff = 0;
    for (std::size_t i = 0; i < static_cast<std::size_t>(w) * hgt * 4; ++i)
        diff += (i % 4 != 3) && data[i] != frame[i];
    stbi_image_free(data);
    EXPECT_EQ(diff, 0u);
}

TEST(Files, AnimatedGifHasOneFramePerStepAsRendered) {
    TempDir dir("gif");
    UiHarness h(1000, 700);
    auto& st = h.state();
    st.engine.seek(5);
    h.frames(2);
    dlab::ui::GifRequest req;
    req.path = dir / "steps.gif";
    req.from = 10;
    req.to = 40;
    req.every = 10;
    req.delayMs = 300;
    st.files.gif = req;
    dlab::ui::serviceCaptures(h.gui());
    EXPECT_FALSE(st.files.gif.has_value());
    EXPECT_EQ(st.engine.position(), 5u);  // back where it was
    int err = 0;
    GifFileType* gif = DGifOpenFileName(req.path.c_str(), &err);
    ASSERT_NE(gif, nullptr) << GifErrorString(err);
    ASSERT_EQ(DGifSlurp(gif), GIF_OK);
    ASSERT_EQ(gif->ImageCount, 4);
    const auto canvas = h.rect("canvas");
    EXPECT_EQ(gif->SWidth, static_cast<int>(std::lround(canvas[2] - canvas[0])));
    EXPECT_EQ(gif->SHeight, static_cast<int>(std::lround(canvas[3] - canvas[1])));
    GraphicsControlBlock gcb;
    ASSERT_EQ(DGifSavedExtensionToGCB(gif, 0, &gcb), GIF_OK);
    EXPECT_EQ(gcb.DelayTime, 30);
    // Frame k is the canvas at step 10 + 10 k: compare with a fresh rendering (the palette
    // quantization costs a little precision, nothing more).
    for (int k = 0; k < 4; ++k) {
        st.engine.seek(10 + 10 * k);
        h.frames(2);
        int w = 0, hh = 0;
        const auto px = dlab::ui::CaptureRegion(h.gui(), false, w, hh);
        ASSERT_EQ(w, gif->SWidth);
        const SavedImage& img = gif->SavedImages[k];
        const ColorMapObject* map =
            img.ImageDesc.ColorMap ? img.ImageDesc.ColorMap : gif->SColorMap;
        ASSERT_NE(map, nullptr);
        // 256 colours cannot hold every antialiased shade: most pixels come back exact, nearly
        // all close.
        int exact = 0, close = 0;
        for (int i = 0; i < w * hh; ++i) {
            const GifColorType c = map->Colors[img.RasterBits[i]];
            const int d = std::max({std::abs(c.Red - px[4 * i]), std::abs(c.Green - px[4 * i + 1]),
                                    std::abs(c.Blue - px[4 * i + 2])});
            exact += d == 0;
            close += d <= 24;
        }
        std::printf("[ info ] GIF frame %d: %.1f%% of pixels exact, %.2f%% within 24\n", k,
                    100.0 * exact / (w * hh), 100.0 * close / (w * hh));
        EXPECT_GT(exact, 0.9 * w * hh) << "frame " << k;
        EXPECT_GT(close, 0.99 * w * hh) << "frame " << k;
    }
    DGifCloseFile(gif, &err);
    // A request beyond the frame limit is refused with one line naming the file.
    req.to = 100000;
    req.every = 1;
    st.files.gif = req;
    dlab::ui::serviceCaptures(h.gui());
    EXPECT_NE(st.files.notice.find("steps.gif"), std::string::npos) << st.files.notice;
}

TEST(Files, ACaptureThatCannotBeWrittenKeepsTheOldFileAndSaysWhy) {
    UiHarness h(800, 600);
    auto& st = h.state();
    st.engine.seek(10);
    h.frames(2);
    const std::string noSpace = std::strerror(ENOSPC);
    auto gif = [&](const std::string& path) {
        dlab::ui::GifRequest req;
        req.path = path;
        req.from = 2;
        req.to = 6;
        req.every = 2;
        st.files.gif = req;
        st.files.notice.clear();
        dlab::ui::serviceCaptures(h.gui());
    };
    // A device that takes nothing: the reason, never "wrote".
    EXPECT_FALSE(dlab::ui::saveScreenshotFile(h.gui(), "/dev/full"));
    EXPECT_NE(st.files.notice.find("/dev/full: " + noSpace), std::string::npos) << st.files.notice;
    gif("/dev/full");
    EXPECT_NE(st.files.notice.find("/dev/full: " + noSpace), std::string::npos) << st.files.notice;
    // A full disk: the old files stay whole, no temporary is left.
    const dlab::testutil::SmallDisk disk("gui");
    if (!disk.ok()) GTEST_SKIP() << disk.why();
    const fs::path d = disk.dir();
    std::ofstream(d / "old.png") << "old png";
    std::ofstream(d / "old.gif") << "old gif";
    disk.fill();
    EXPECT_FALSE(dlab::ui::saveScreenshotFile(h.gui(), (d / "old.png").string()));
    EXPECT_NE(st.files.notice.find("old.png: " + noSpace), std::string::npos) << st.files.notice;
    st.files.screenshotFolder = d.string();  // F12: a new name in that folder
    st.files.screenshotRequested = true;
    st.files.notice.clear();
    dlab::ui::serviceCaptures(h.gui());
    EXPECT_NE(st.files.notice.find(noSpace), std::string::npos) << st.files.notice;
    gif((d / "old.gif").string());
    EXPECT_NE(st.files.notice.find("old.gif: " + noSpace), std::string::npos) << st.files.notice;
    EXPECT_EQ(dlab::testutil::slurpFile(d / "old.png"), "old png");
    EXPECT_EQ(dlab::testutil::slurpFile(d / "old.gif"), "old gif");
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(d)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"filler", "old.gif", "old.png"}));
}

TEST(Files, ABadFileChangesNothingAndShowsOneLineNamingFileAndLine) {
    TempDir dir("bad");
    UiHarness h;
    auto& st = h.state();
    st.engine.seek(33);
    st.select(4);
    h.frames(2);
    const auto points = st.engine.points();
    const auto view = st.view;
    const auto options = st.engine.options();
    const std::string good = dlab::ui::sessionText(st);
    auto lineOf = [&](const std::string& text, const std::string& needle) {
        const auto at = text.find(needle);
        return 1 + static_cast<int>(std::count(
                       text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
    };
    struct Case {
        std::string name, text, expect;
    };
    std::string badPoint = good;
    const std::string third = "\n    [";
    std::size_t at = 0;
    for (int k = 0; k < 4; ++k) at = badPoint.find(third, at + 1);
    badPoint.insert(at + third.size(), "\"x\", ");  // point 3 becomes ["x", x, y]
    std::string badVersion =
        std::regex_replace(good, std::regex("\"version\": 1"), "\"version\": 9");
    std::string badLocator =
        std::regex_replace(good, std::regex("\"locator\": \"walk\""), "\"locator\": \"teleport\"");
    std::string syntax = good;
    syntax.insert(syntax.find("\"view\""), "oops ");
    const std::vector<Case> cases = {
        {"point.json", badPoint,
         ":" + std::to_string(lineOf(badPoint, "\"x\", ")) + ": points[3]: expected [x, y]"},
        {"version.json", badVersion,
         ":" + std::to_string(lineOf(badVersion, "\"version\"")) +
             ": version: session version 9 is newer"},
        {"locator.json", badLocator,
         ":" + std::to_string(lineOf(badLocator, "teleport")) +
             ": options.locator: unknown locator"},
        {"syntax.json", syntax, ":" + std::to_string(lineOf(syntax, "oops")) + ": not valid JSON"},
        {"other.json", "{\"hello\": 1}\n", ": not a Delaunay Lab session"},
        {"points.csv", "1,2\n3,4\n5,inf\n", ":3:"},
    };
    for (const Case& c : cases) {
        const std::string path = dir / c.name;
        std::ofstream(path) << c.text;
        st.files.notice.clear();
        const std::size_t before = st.messages.size();
        EXPECT_FALSE(dlab::ui::openFile(st, path)) << c.name;
        EXPECT_TRUE(sameBits(st.engine.points(), points)) << c.name;
        EXPECT_EQ(st.engine.position(), 33u) << c.name;
        EXPECT_EQ(st.engine.options().locator, options.locator) << c.name;
        EXPECT_EQ(st.view.center, view.center) << c.name;
        EXPECT_EQ(st.selection.corner, 4) << c.name;
        ASSERT_GT(st.messages.size(), before);
        const std::string& msg = st.messages.back().text;
        EXPECT_EQ(st.messages.back().level, dlab::ui::Message::Level::Error);
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        EXPECT_EQ(msg.rfind(path, 0), 0u) << "does not start with the file: " << msg;
        EXPECT_NE(msg.find(c.expect), std::string::npos) << c.name << ": " << msg;
        EXPECT_FALSE(st.files.notice.empty());
        // The notice is on the screen, red, over the canvas.
        st.itemRects.erase("file-notice");
        h.frames(2);
        ASSERT_TRUE(st.itemRects.count("file-notice")) << c.name;
        EXPECT_GT(h.countColour(h.rect("file-notice"), kNoticeRgb), 500) << c.name;
    }
    h.clickItem("notice-dismiss");
    EXPECT_TRUE(st.files.notice.empty());
}
