// Settings and lesson progress on disk: progress written as it is made (a SIGTERM loses nothing),
// two instances that both make progress both keep it, and a damaged settings file kept aside.
#include "tests/ui/ui_harness.h"
#include "ui/files/settings.h"
#include "ui/lesson_player.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

using dlab::test::TempDir;
using dlab::test::UiHarness;
namespace fs = std::filesystem;

namespace {

std::string lessonPath(const char* name) {
    return std::string(DLAB_SOURCE_DIR) + "/lessons/" + name;
}

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// The progress the settings file holds for a lesson (null JSON when none).
nlohmann::json progressOnDisk(const std::string& settings, const std::string& lesson) {
    const auto j = nlohmann::json::parse(slurp(settings), nullptr, false);
    if (!j.is_object() || !j.contains("lessons") || !j["lessons"].contains(lesson)) return {};
    return j["lessons"][lesson];
}

// The stops of the open lesson that ask a question.
std::vector<std::size_t> questionStops(const dlab::ui::AppState& st) {
    std::vector<std::size_t> out;
    const auto& stops = st.lessonPlayer.plan.stops;
    for (std::size_t k = 0; k < stops.size(); ++k) {
        if (stops[k].answer) out.push_back(k);
    }
    return out;
}

// An instance that reads the settings at start and saves progress as it is made.
void startInstance(dlab::ui::AppState& st, const std::string& settings) {
    dlab::ui::WindowOptions window;
    std::string warning;
    dlab::ui::loadSettings(settings, st, window, warning);
    ASSERT_TRUE(warning.empty()) << warning;
    st.lessonPlayer.settingsPath = settings;
}

// Answers the question at stop k (wrongly: a try counts as answered, 1).
void tryAnswer(dlab::ui::AppState& st, std::size_t k) {
    dlab::ui::goToStop(st, k);
    st.lessonPlayer.typed = "not the answer";
    dlab::ui::checkAnswer(st);
}

}  // namespace

TEST(Settings, TwoInstancesMakingProgressBothKeepIt) {
    TempDir dir("settings_two");
    const std::string settings = dir / "settings.json";
    const std::string flips = lessonPath("05_flips.toml"), walking = lessonPath("02_walking.toml");
    dlab::ui::AppState first, second;
    startInstance(first, settings);
    startInstance(second, settings);

    // The first goes far into the flips lesson and tries its first question.
    ASSERT_TRUE(dlab::ui::openLesson(first, flips));
    const auto questions = questionStops(first);
    ASSERT_GE(questions.size(), 2u) << "the flips lesson asks fewer than two questions";
    tryAnswer(first, questions[0]);
    dlab::ui::goToStop(first, 6);
    dlab::ui::saveLessonProgressIfChanged(first);  // what every frame does
    // The second, started before, opens the same lesson (its own progress in it: none), tries
    // another question, then a second lesson, and exits first.
    ASSERT_TRUE(dlab::ui::openLesson(second, flips));
    EXPECT_EQ(second.lessonPlayer.progress.furthest, 0u);
    tryAnswer(second, questions[1]);
    ASSERT_TRUE(dlab::ui::openLesson(second, walking));
    dlab::ui::goToStop(second, 4);
    dlab::ui::saveLessonProgressIfChanged(second);
    std::string error;
    ASSERT_TRUE(dlab::ui::saveSettings(settings, second, {}, error)) << error;
    // The first exits last, its settings whole.
    dlab::ui::closeLesson(first);
    ASSERT_TRUE(dlab::ui::saveSettings(settings, first, {}, error)) << error;

    const auto f = progressOnDisk(settings, flips);
    ASSERT_TRUE(f.is_object()) << slurp(settings);
    EXPECT_EQ(f["furthest"], 6);
    ASSERT_TRUE(f["answers"].is_array());
    EXPECT_EQ(f["answers"][questions[0]], 1) << f.dump();
    EXPECT_EQ(f["answers"][questions[1]], 1) << f.dump();
    const auto w = progressOnDisk(settings, walking);
    ASSERT_TRUE(w.is_object()) << slurp(settings);
    EXPECT_EQ(w["furthest"], 4);
    // A third instance starting now reopens the flips lesson where the first left it.
    dlab::ui::AppState third;
    startInstance(third, settings);
    ASSERT_TRUE(dlab::ui::openLesson(third, flips));
    EXPECT_EQ(third.lessonPlayer.progress.furthest, 6u);
    EXPECT_EQ(third.lessonPlayer.progress.stop, 6u);
}

TEST(Settings, MergedProgressKeepsTheFurthestStopAndEveryAnswer) {
    dlab::LessonProgress a{"l.toml", "T", 2, 5, {0, 2, 1, 0}};
    const dlab::LessonProgress b{"l.toml", "T", 7, 7, {1, 1, 0, 0, 2, 0, 0, 0}};
    dlab::ui::mergeProgress(a, b);
    EXPECT_EQ(a.stop, 2u);  // the writer's own stop on show
    EXPECT_EQ(a.furthest, 7u);
    EXPECT_EQ(a.answers, (std::vector<std::uint8_t>{1, 2, 1, 0, 2, 0, 0, 0}));
    // Another lesson at the same path: nothing of it is mixed in.
    dlab::LessonProgress c{"l.toml", "Other", 0, 1, {0}};
    dlab::ui::mergeProgress(c, b);
    EXPECT_EQ(c.furthest, 1u);
    EXPECT_EQ(c.answers, (std::vector<std::uint8_t>{0}));
}

TEST(Settings, ADamagedSettingsFileIsKeptAsideAndSaid) {
    TempDir dir("settings_bad");
    const std::string settings = dir / "settings.json";
    const std::string damaged = R"({"presentation": tru, "lessons": {"x.toml": {"furthest": 3}}})";
    std::ofstream(settings) << damaged;
    UiHarness h;
    auto& st = h.state();
    dlab::ui::WindowOptions window;
    std::string warning;
    dlab::ui::loadSettings(settings, st, window, warning);
    EXPECT_NE(warning.find(settings + ": damaged settings file"), std::string::npos) << warning;
    EXPECT_NE(warning.find("kept as " + settings + ".bad-"), std::string::npos) << warning;
    std::vector<fs::path> aside;
    for (const auto& e : fs::directory_iterator(dir.path)) {
        if (e.path().filename().string().rfind("settings.json.bad-", 0) == 0)
            aside.push_back(e.path());
    }
    ASSERT_EQ(aside.size(), 1u);
    EXPECT_EQ(slurp(aside[0].string()), damaged);
    // Progress made now goes into a fresh file; the damaged one stays as it was.
    st.lessonPlayer.settingsPath = settings;
    ASSERT_TRUE(dlab::ui::openLesson(st, lessonPath("05_flips.toml")));
    dlab::ui::goToStop(st, 2);
    h.frames(1);
    EXPECT_EQ(progressOnDisk(settings, lessonPath("05_flips.toml"))["furthest"], 2);
    EXPECT_EQ(slurp(aside[0].string()), damaged);

    // Damaged while the GUI runs (another program wrote it): kept aside too, said in the
    // messages, and the progress written again.
    std::ofstream(settings, std::ios::trunc) << "{\"lessons\": ";
    st.messages.clear();
    dlab::ui::goToStop(st, 3);
    h.frames(1);
    ASSERT_FALSE(st.messages.empty());
    EXPECT_NE(st.messages.back().text.find("damaged settings file"), std::string::npos)
        << st.messages.back().text;
    EXPECT_EQ(progressOnDisk(settings, lessonPath("05_flips.toml"))["furthest"], 3);
}

// The child of Settings.ProgressSurvivesSigterm: makes progress in a lesson, one stop a frame,
// saying each stop reached in a file, until it is killed.
TEST(Settings, DISABLED_ProgressChildUntilKilled) {
    const char* dir = std::getenv("DLAB_SETTINGS_DIR");
    ASSERT_NE(dir, nullptr);
    UiHarness h;
    auto& st = h.state();
    startInstance(st, std::string(dir) + "/settings.json");
    ASSERT_TRUE(dlab::ui::openLesson(st, lessonPath("05_flips.toml")));
    std::ofstream reached(std::string(dir) + "/reached.txt");
    for (std::size_t k = 1; k < 6; ++k) {
        dlab::ui::goToStop(st, k);
        h.frames(1);
        reached << k << "\n" << std::flush;
    }
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));  // wait for the signal
}

TEST(Settings, ProgressSurvivesSigterm) {
    TempDir dir("settings_sigterm");
    ::setenv("DLAB_SETTINGS_DIR", dir.path.c_str(), 1);
    const pid_t child = ::fork();
    if (child == 0) {
        ::execl("/proc/self/exe", "dlab_ui_logic_tests", "--gtest_also_run_disabled_tests",
                "--gtest_filter=Settings.DISABLED_ProgressChildUntilKilled",
                static_cast<char*>(nullptr));
        ::_exit(127);
    }
    ::unsetenv("DLAB_SETTINGS_DIR");
    ASSERT_GT(child, 0);
    const std::string reached = dir / "reached.txt";
    for (int i = 0; i < 1200 && slurp(reached) != "1\n2\n3\n4\n5\n"; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_EQ(::kill(child, SIGTERM), 0);
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the child ended by itself (status " << status << ")";
    ASSERT_EQ(slurp(reached), "1\n2\n3\n4\n5\n") << "the child did not reach stop 5";
    const auto p = progressOnDisk(dir / "settings.json", lessonPath("05_flips.toml"));
    ASSERT_TRUE(p.is_object()) << slurp(dir / "settings.json");
    EXPECT_EQ(p["furthest"], 5);
    EXPECT_EQ(p["stop"], 5);
}
