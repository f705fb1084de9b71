// A lesson stop's view (a zoom rectangle or "fit these vertices") and side tab: read from the
// file, bad ones named by file and line; an assignment's own text is kept and printed by
// dtlab lesson show.
#include "core/teaching/lesson.h"

#include "tests/run_dtlab.h"

#include <gtest/gtest.h>

#include <string>

using namespace dlab;

namespace {

const std::string kHead = "title = \"t\"\npoints = [[0, 0], [4, 0], [0, 3], [4, 3]]\n";

std::string lessonError(const std::string& stop) {
    try {
        parseLesson(kHead + "[[stop]]\ntext = \"x\"\n" + stop, "v.toml");
    } catch (const LessonError& e) {
        return e.what();
    }
    ADD_FAILURE() << "accepted: " << stop;
    return "";
}

}  // namespace

TEST(LessonView, ViewAndTabAreRead) {
    const Lesson l = parseLesson(kHead +
                                     "[[stop]]\ntext = \"a\"\nview = { fit = [1, 2, 6] }\n"
                                     "tab = \"idbuffer\"\n"
                                     "[[stop]]\ntext = \"b\"\nview = { rect = [-1, -2.5, 3, 4] }\n"
                                     "[[stop]]\ntext = \"c\"\n",
                                 "v.toml");
    ASSERT_EQ(l.stops.size(), 3u);
    EXPECT_EQ(l.stops[0].view.fit, (std::vector<std::int32_t>{1, 2, 6}));
    EXPECT_FALSE(l.stops[0].view.rect);
    EXPECT_EQ(l.stops[0].tab, "idbuffer");
    ASSERT_TRUE(l.stops[1].view.rect);
    EXPECT_EQ(*l.stops[1].view.rect, (std::array<double, 4>{-1, -2.5, 3, 4}));
    EXPECT_TRUE(l.stops[1].tab.empty());
    EXPECT_TRUE(l.stops[2].view.empty());
}

TEST(LessonView, BadViewsAndTabsNameTheLine) {
    EXPECT_NE(lessonError("view = 5\n").find("v.toml:5: stop 1: \"view\" must be view = { fit"),
              std::string::npos)
        << lessonError("view = 5\n");
    // Four points and the super-triangle's three: vertices 0 to 6.
    EXPECT_NE(lessonError("view = { fit = [1, 7] }\n").find("fit takes vertex numbers from 0 to 6"),
              std::string::npos);
    EXPECT_NE(lessonError("view = { fit = [] }\n").find("at least one vertex"), std::string::npos);
    EXPECT_NE(lessonError("view = { rect = [3, 0, 1, 2] }\n").find("x0 < x1 and y0 < y1"),
              std::string::npos);
    EXPECT_NE(lessonError("view = { rect = [0, 0, 1] }\n").find("rect is [x0, y0, x1, y1]"),
              std::string::npos);
    EXPECT_NE(lessonError("view = { fit = [1], rect = [0, 0, 1, 1] }\n").find("\"view\" must be"),
              std::string::npos);
    EXPECT_NE(lessonError("view = { zoom = 2 }\n").find("unknown key \"zoom\" in a view"),
              std::string::npos);
    EXPECT_NE(lessonError("tab = \"tables\"\n").find("v.toml:5: stop 1: unknown tab \"tables\""),
              std::string::npos)
        << lessonError("tab = \"tables\"\n");
}

TEST(AssignmentText, IsKeptAndShownByLessonShow) {
    const std::string path = std::string(DLAB_SOURCE_DIR) + "/lessons/10_assignment_insertion.toml";
    const Lesson l = loadLesson(path);
    EXPECT_TRUE(l.assignment);
    EXPECT_NE(l.text.find("--by-op --corners"), std::string::npos);
    const auto r = dlab::testutil::runDtlab("lesson show " + path);
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("Triangulate the 38 points"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("u becomes (D, B, P) in place"), std::string::npos);
}
