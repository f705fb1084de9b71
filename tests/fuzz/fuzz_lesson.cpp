// Fuzz target: lesson files (TOML), from parseLesson through planLesson, answer checking and the
// findings of lesson check.
//
// The bytes are the lesson's text, read as if it were lessons/fuzz.toml in an empty folder (so a
// points_file can only fail, cleanly). Either outcome is checked: a LessonError is one line that
// names the file and, when it names a line, a line of the input; a lesson that loads is planned
// to its end (small point sets only, to keep runs fast), and every computed answer is accepted
// when typed back as displayed.
#include "tests/fuzz/fuzz_common.h"

#include "core/teaching/lesson.h"

#include <unistd.h>
#include <algorithm>
#include <filesystem>
#include <string>

namespace {

using namespace dlab;
using dlab::fuzz::fail;
using dlab::fuzz::require;

// Planning runs the whole insertion with every stop's breakpoint: a few hundred points keep one
// input in the milliseconds; bigger point sets are still parsed and checked.
constexpr std::size_t kMaxPlannedPoints = 200;

const std::string& lessonPath() {
    static const std::string path = [] {
        const auto dir = std::filesystem::temp_directory_path() /
                         ("dlab_fuzz_lesson_" + std::to_string(getpid()));
        std::filesystem::create_directories(dir);
        return (dir / "fuzz.toml").string();
    }();
    return path;
}

bool oneLine(const std::string& s) {
    return std::none_of(s.begin(), s.end(), [](char c) { return c == '\n' || c == '\r'; });
}

void checkError(const LessonError& e, std::string_view text, const std::string& path) {
    const std::string what = e.what();
    require(oneLine(what), "a lesson error is one line", what);
    require(e.file() == path && what.rfind(path, 0) == 0, "a lesson error names the file", what);
    const auto lines = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
    require(e.line() >= 0 && e.line() <= lines, "a lesson error blames a line of the input", what);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text = dlab::fuzz::asText(data, size);
    const std::string& path = lessonPath();
    Lesson lesson;
    try {
        lesson = parseLesson(text, path);
    } catch (const LessonError& e) {
        checkError(e, text, path);
        return 0;
    }
    require(lesson.points.size() <= kMaxLessonPoints,
            "a lesson holds at most kMaxLessonPoints points");
    require(lesson.stops.size() <= kMaxLessonStops, "a lesson holds at most kMaxLessonStops stops");
    for (const LessonStop& stop : lesson.stops) {
        std::string why;
        require(stop.text.empty() || parseLessonText(stop.text, &why).has_value(),
                "a loaded stop's text parses", why);
    }
    if (lesson.points.size() > kMaxPlannedPoints) return 0;
    LessonPlan plan;
    try {
        plan = planLesson(lesson);
    } catch (const LessonError& e) {
        checkError(e, text, path);
        require(e.stop() >= 1 && e.stop() <= static_cast<int>(lesson.stops.size()),
                "a planning error names a stop of the lesson", e.what());
        return 0;
    } catch (const std::exception& e) {
        fail("planning a loaded lesson throws nothing but LessonError", e.what());
    }
    require(plan.stops.size() == lesson.stops.size(), "the plan has one state per stop");
    std::size_t previous = 0;
    for (const StopState& s : plan.stops) {
        require(s.position >= previous && s.position <= plan.totalOps + plan.editOps,
                "stops are reached in order within the run");
        previous = s.position;
        if (s.answer) {
            require(acceptsAnswer(*s.answer, s.answer->display()),
                    "an answer typed as displayed is accepted", s.answer->display());
        }
    }
    // lesson check's own findings (undrawable characters, answers given away) name file, line and
    // a stop of the lesson too.
    for (const LessonError& e : lessonProblems(lesson, plan)) {
        checkError(e, text, path);
        require(e.stop() >= 0 && e.stop() <= static_cast<int>(lesson.stops.size()),
                "a check finding names a stop of the lesson", e.what());
    }
    return 0;
}
