// The lesson panel: the stop's text (Markdown-light: bold, code, lists), its question with an
// answer field and immediate feedback, a hint, and the way between stops. Shown at the top of
// the side column while a lesson is open.
#include "core/engine/voronoi.h"
#include "core/teaching/describe.h"
#include "ui/gui.h"
#include "ui/lesson_player.h"
#include "ui/panels/panels.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

namespace dlab::ui {

namespace {

// Draws one span word by word, wrapping at the panel's right edge. `glued`: the span goes on the
// last one's word without a space ("`code`," or "**bold**.").
void WrappedSpan(const TextSpan& span, float right, bool glued, float& widest) {
    ImFont* font = span.style == TextSpan::Style::Bold   ? fonts().bold
                   : span.style == TextSpan::Style::Code ? fonts().mono
                                                         : fonts().ui;
    ImGui::PushFont(font);
    const float space = ImGui::CalcTextSize(" ").x;
    std::size_t i = 0;
    const std::string& t = span.text;
    while (i < t.size()) {
        std::size_t j = t.find(' ', i);
        if (j == std::string::npos) j = t.size();
        const std::string word = t.substr(i, j - i);
        if (word.empty()) {  // a span that starts with a space: the space is already there
            i = j + 1;
            continue;
        }
        if (glued && i == 0) ImGui::SameLine(0, 0);
        const ImVec2 size = ImGui::CalcTextSize(word.c_str());
        const float x = ImGui::GetCursorScreenPos().x;
        if (x + size.x > right &&
            x > ImGui::GetWindowPos().x + ImGui::GetStyle().WindowPadding.x + 40)
            ImGui::NewLine();
        if (span.style == TextSpan::Style::Code) {
            const ImVec2 p = ImGui::GetCursorScreenPos();
            ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(p.x - 2, p.y),
                                                      ImVec2(p.x + size.x + 2, p.y + size.y),
                                                      IM_COL32(232, 234, 240, 255), 3);
        }
        ImGui::TextUnformatted(word.c_str());
        widest = std::max(widest, ImGui::GetItemRectMax().x);
        ImGui::SameLine(0, space);
        i = j + 1;
    }
    ImGui::PopFont();
}

// Returns the right edge of its widest line (screen x).
float RichText(const std::string& text) {
    float widest = ImGui::GetCursorScreenPos().x;
    std::string error;
    const auto blocks = parseLessonText(text, &error);
    if (!blocks) {
        ImGui::TextWrapped("%s", text.c_str());  // the loader checked it; never expected
        return ImGui::GetItemRectMax().x;
    }
    const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
    for (const TextBlock& b : *blocks) {
        if (b.kind == TextBlock::Kind::Bullet) {
            ImGui::Bullet();
            ImGui::SameLine();
        } else if (b.kind == TextBlock::Kind::Numbered) {
            ImGui::Text("%d.", b.number);
            ImGui::SameLine();
        }
        for (std::size_t i = 0; i < b.spans.size(); ++i) {
            const std::string& t = b.spans[i].text;
            const bool glued = i > 0 && !t.empty() && t.front() != ' ' &&
                               !b.spans[i - 1].text.empty() && b.spans[i - 1].text.back() != ' ';
            WrappedSpan(b.spans[i], right, glued, widest);
        }
        ImGui::NewLine();
        if (b.kind == TextBlock::Kind::Paragraph) ImGui::Spacing();
    }
    return widest;
}

// The stop's question, the answer field, Check, Hint and the feedback (wrapped: nothing runs
// past the column).
void Question(AppState& st, const LessonStop& stop, std::size_t k) {
    LessonState& L = st.lessonPlayer;
    if (stop.question.empty()) return;
    const StopState& shown = L.plan.stops[k];  // the words with their {{values}} filled in
    ImGui::Spacing();
    ImGui::PushFont(fonts().bold);
    ImGui::TextWrapped("%s", shown.question.c_str());
    ImGui::PopFont();
    ImGui::SetNextItemWidth(std::min(260.0f, ImGui::GetContentRegionAvail().x * 0.6f));
    const bool enter = ImGui::InputText("##answer", &L.typed, ImGuiInputTextFlags_EnterReturnsTrue);
    RecordItem(st, "lesson-answer");
    ImGui::SameLine();
    if (ImGui::Button("Check") || enter) checkAnswer(st);
    RecordItem(st, "lesson-check");
    if (!stop.hint.empty()) {
        ImGui::SameLine();
        if (ImGui::SmallButton("Hint")) L.showHint = !L.showHint;
        RecordItem(st, "lesson-hint");
    }
    auto coloured = [](ImVec4 colour, const std::string& text) {
        ImGui::PushStyleColor(ImGuiCol_Text, colour);
        ImGui::TextWrapped("%s", text.c_str());
        ImGui::PopStyleColor();
    };
    if (L.feedback == LessonState::Feedback::Right) {
        coloured(ImVec4(0.1f, 0.55f, 0.2f, 1), "Right: " + L.plan.stops[k].answer->display());
    } else if (L.feedback == LessonState::Feedback::Wrong) {
        coloured(ImVec4(0.8f, 0.2f, 0.1f, 1),
                 "Not quite. Look again at the canvas and the tables, and try again.");
        if (ImGui::SmallButton("Show the answer")) L.feedback = LessonState::Feedback::Shown;
    }
    if (L.feedback == LessonState::Feedback::Shown)
        ImGui::TextWrapped("The answer: %s", L.plan.stops[k].answer->display().c_str());
    if (L.showHint) ImGui::TextWrapped("Hint: %s", shown.hint.c_str());
}

// The side tab a slide shows: the `tab` of this stop or of the last stop before it that named
// one (the same whichever way the slides are visited); none when no stop named one or the last
// one named "none".
using PanelFn = void (*)(AppState&);
PanelFn SlideTab(const Lesson& lesson, std::size_t k) {
    static const std::pair<const char*, PanelFn> tabs[] = {
        {"corner-table", ShowCornerTable}, {"vertex-table", ShowVertexTable},
        {"expressions", ShowExpressions},  {"predicates", ShowPredicates},
        {"idbuffer", ShowIdBuffer},        {"statistics", ShowStatistics},
    };
    for (std::size_t i = k + 1; i-- > 0;) {
        const std::string& name = lesson.stops[i].tab;
        if (name.empty()) continue;
        for (const auto& [id, fn] : tabs) {
            if (name == id) return fn;
        }
        return nullptr;
    }
    return nullptr;
}

// The slide's top rows: the way between stops, the title, and the operation on show.
// A handout's picture (st.handoutSlides) has no buttons: the title and the banner.
void SlideHeader(AppState& st) {
    const Lesson& lesson = *st.lessonPlayer.lesson;
    const std::size_t k = slideIndex(st), n = slideCount(st);  // a track's slides, or the stops
    if (!st.handoutSlides) {
        if (ImGui::Button("<") && k > 0) goToSlide(st, k - 1);
        RecordItem(st, "lesson-previous");  // the same buttons as the panel's
        ImGui::SameLine();
        ImGui::Text("%zu / %zu", k + 1, n);
        ImGui::SameLine();
        if (ImGui::Button(">") && k + 1 < n) goToSlide(st, k + 1);
        RecordItem(st, "lesson-next");
        ImGui::SameLine();
        if (ImGui::Button("Close")) {
            closeLesson(st);
            return;
        }
        RecordItem(st, "lesson-close");
        ImGui::SameLine();
    }
    ImGui::PushFont(fonts().bold);
    ImGui::TextWrapped("%s", lesson.title.c_str());
    ImGui::PopFont();
    const Engine& e = st.engine;
    if (const Op* op = e.current()) {
        ImGui::TextWrapped("%s %s: %s", opLabel(e.position()).c_str(), toString(op->type),
                           describe(*op, e.inserter()).c_str());
    } else if (e.editing()) {
        ImGui::TextWrapped("%s %s", opLabel(e.position()).c_str(), editOpText(e).c_str());
    } else {
        ImGui::TextWrapped("%zu points, before the first operation", e.points().size());
    }
    RecordItem(st, "slide-banner");
}

// The lifting map of the in-circle test at the stop, in an oblique view: coordinates centred on
// the tested triangle's circumcenter and scaled by its radius, so that its circle lifts to the
// plane z = 1 and the new point is inside exactly when its lift is below that plane.
void LiftingFigure(const AppState& st) {
    const auto f = liftingMapAt(st.engine.inserter(), st.engine.current());
    if (!f) return;
    const Vec2 o = circumcenter(f->triangle[0], f->triangle[1], f->triangle[2]);
    const double r = std::hypot(f->triangle[0].x - o.x, f->triangle[0].y - o.y);
    if (!(r > 0) || !std::isfinite(r)) return;
    const float w = std::min(ImGui::GetContentRegionAvail().x, 360.0f), h = w * 0.7f;
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const float s = w / 5.0f;
    const ImVec2 base(p0.x + w * 0.5f, p0.y + h * 0.92f);
    const double zMax = 2.6;
    const auto screen = [&](double x, double y, double z) {
        return ImVec2(base.x + s * static_cast<float>(x + 0.45 * y),
                      base.y - s * static_cast<float>(0.25 * y + z * 1.1));
    };
    const auto ring = [&](double z, ImU32 col, float thick) {  // the paraboloid at height z
        const double rad = std::sqrt(z);
        ImVec2 prev = screen(rad, 0, z);
        for (int k = 1; k <= 48; ++k) {
            const double a = k * 2 * 3.14159265358979 / 48;
            const ImVec2 q = screen(rad * std::cos(a), rad * std::sin(a), z);
            dl->AddLine(prev, q, col, thick);
            prev = q;
        }
    };
    dl->AddRectFilled(p0, ImVec2(p0.x + w, p0.y + h), IM_COL32(250, 250, 252, 255), 4);
    for (double z : {0.25, 2.25}) ring(z, IM_COL32(190, 195, 210, 255), 1);
    for (double x : {-1.0, 1.0}) {  // the silhouette: z = x²
        ImVec2 prev = screen(0, 0, 0);
        for (int k = 1; k <= 24; ++k) {
            const double u = x * std::sqrt(zMax) * k / 24;
            const ImVec2 q = screen(u, 0, u * u);
            dl->AddLine(prev, q, IM_COL32(150, 155, 175, 255), 1.5f);
            prev = q;
        }
    }
    ring(1, IM_COL32(60, 110, 200, 255), 2);  // the lifted circle: the plane z = 1
    const auto lifted = [&](Vec2 p) {
        const double x = (p.x - o.x) / r, y = (p.y - o.y) / r;
        return std::array<double, 3>{x, y, x * x + y * y};
    };
    for (int k = 0; k < 3; ++k) {
        const auto q = lifted(f->triangle[k]);
        const ImVec2 at = screen(q[0], q[1], q[2]);
        dl->AddCircleFilled(at, 4, IM_COL32(60, 110, 200, 255));
        dl->AddText(ImVec2(at.x + 5, at.y - 16), IM_COL32(40, 60, 120, 255),
                    std::to_string(f->vertices[k]).c_str());
    }
    const auto d = lifted(f->point);
    const double z = std::min(d[2], zMax);
    const ImU32 red = IM_COL32(220, 60, 40, 255);
    dl->AddLine(screen(d[0], d[1], 0), screen(d[0], d[1], std::max(z, 1.0)),
                IM_COL32(120, 120, 120, 255), 1);
    dl->AddCircle(screen(d[0], d[1], 1), 4, IM_COL32(60, 110, 200, 255));
    dl->AddCircleFilled(screen(d[0], d[1], z), 5, red);
    dl->AddText(ImVec2(screen(d[0], d[1], z).x + 6, screen(d[0], d[1], z).y - 6), red,
                std::to_string(f->vertex).c_str());
    ImGui::Dummy(ImVec2(w, h));
    ImGui::TextWrapped(
        "Lifted onto z = x² + y² (scaled to the circle of %d %d %d): vertex %d's "
        "lift is %s the plane of the circle.",
        f->vertices[0], f->vertices[1], f->vertices[2], f->vertex,
        f->sign > 0    ? "below"
        : f->sign == 0 ? "on"
                       : "above");
}

}  // namespace

void ShowSlide(AppState& st) {
    LessonState& L = st.lessonPlayer;
    const std::size_t n = L.lesson->stops.size(), k = std::min(L.progress.stop, n - 1);
    SlideHeader(st);
    if (!L.lesson) return;  // closed
    const LessonStop& stop = L.lesson->stops[k];
    const ImGuiWindowFlags still =
        ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse;
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const float gap = ImGui::GetStyle().ItemSpacing.x;
    // A slide with a side tab gives the column more room.
    const PanelFn tab = st.handoutSlides ? nullptr : SlideTab(*L.lesson, k);
    const float sideW = std::clamp(avail.x * (tab ? 0.48f : 0.4f), std::min(300.0f, avail.x * 0.5f),
                                   avail.x * 0.6f);
    ImGui::BeginChild("##slidecanvas", ImVec2(avail.x - sideW - gap, avail.y), false, still);
    ShowCanvas(st);
    DrawDebugOverlays(st);
    ShowCanvasLegend(st);
    ShowCanvasNotice(st);
    if (!st.handoutSlides) ShowTimeline(st);  // a handout's picture: canvas and text
    ImGui::EndChild();
    ImGui::SameLine(0, gap);
    ImGui::BeginChild("##slideside", ImVec2(sideW, avail.y), false, still);
    // The question and the text's heights come from the last frame: the question is pinned to
    // the bottom, the text takes what it needs (at most 70 % with a tab), the tab the rest.
    const float rest = std::max(0.0f, avail.y - L.slideQuestionHeight);
    const float textH = tab ? std::clamp(L.slideTextHeight, rest * 0.3f, rest * 0.7f) : rest;
    // A scrollbar only when the text needs more than it gets (never one that stays from the
    // previous stop's layout: the bar narrows the text, which then needs it).
    ImGui::BeginChild("##slidetext", ImVec2(0, std::max(1.0f, textH)), false,
                      L.slideTextHeight <= textH + 0.5f ? still : 0);
    const ImVec2 textAt = ImGui::GetWindowPos();
    float textRight = RichText(L.plan.stops[k].text);  // with its {{values}} filled in
    if (stop.figure == "lifting-map") {
        LiftingFigure(st);
        textRight = std::max(textRight, ImGui::GetItemRectMax().x);
    }
    L.slideTextHeight = ImGui::GetCursorPosY() + ImGui::GetStyle().ItemSpacing.y;
    const float scrolls = ImGui::GetScrollMaxY();
    ImGui::EndChild();
    RecordItem(st, "slide-text");
    // What the text needs, not clipped: tests check that it fits in its box.
    st.itemRects["slide-text-content"] = {textAt.x, textAt.y, textRight,
                                          textAt.y + L.slideTextHeight + scrolls};
    if (tab) {
        ImGui::BeginChild("##slidetab", ImVec2(0, std::max(1.0f, rest - textH)), true);
        tab(st);
        ImGui::EndChild();
        RecordItem(st, "slide-tab");
    }
    const float y0 = ImGui::GetCursorScreenPos().y;
    const float x0 = ImGui::GetCursorScreenPos().x;
    if (!st.handoutSlides) Question(st, stop, k);  // a handout prints the question below
    // The cursor waits one item spacing below the last item (and the text child above keeps one).
    const float spacing = ImGui::GetStyle().ItemSpacing.y;
    const float y1 = ImGui::GetCursorScreenPos().y - spacing;
    const bool asked = !stop.question.empty() && !st.handoutSlides;
    L.slideQuestionHeight = asked ? y1 - y0 + 2 * spacing : 0.0f;
    // Not clipped (unlike RecordItem): tests check that the whole question is on the slide.
    if (asked) st.itemRects["slide-question"] = {x0, y0, x0 + sideW, y1};
    ImGui::EndChild();
}

namespace {

// A lesson without stops (an assignment): its summary, its text and the way to close it.
void AssignmentPanel(AppState& st) {
    const Lesson& lesson = *st.lessonPlayer.lesson;
    ImGui::TextWrapped("%s", lesson.summary.c_str());
    ImGui::TextDisabled(lesson.assignment
                            ? "An assignment: the points are loaded. Step through them, or compare "
                              "your own run with `dtlab diff-trace` (or the Trace compare panel)."
                            : "This lesson has no stops.");
    const bool close = ImGui::Button("Close lesson");
    RecordItem(st, "lesson-close");
    if (close) {
        closeLesson(st);  // frees the lesson: nothing of it is read after this
        return;
    }
    if (!lesson.text.empty()) {
        ImGui::Separator();
        ImGui::BeginChild("##assignmenttext", ImVec2(0, 0), false);
        RichText(lesson.text);
        ImGui::EndChild();
        RecordItem(st, "assignment-text");
    }
}

// Previous, Next, the way back to the stop, Close. False when the lesson was closed.
bool StopButtons(AppState& st, std::size_t k, std::size_t n) {
    const LessonState& L = st.lessonPlayer;
    const std::size_t i = slideIndex(st), slides = slideCount(st);  // a track's, or = k, n
    if (ImGui::Button("< Previous") && i > 0) goToSlide(st, i - 1);
    RecordItem(st, "lesson-previous");
    ImGui::SameLine();
    if (L.track) {
        ImGui::Text("Slide %zu of %zu (stop %zu of %zu)", i + 1, slides, k + 1, n);
    } else {
        ImGui::Text("Stop %zu of %zu", k + 1, n);
    }
    ImGui::SameLine();
    if (ImGui::Button("Next >") && i + 1 < slides) goToSlide(st, i + 1);
    RecordItem(st, "lesson-next");
    ImGui::SameLine();
    if (lessonStateChanged(st)) {
        if (ImGui::SmallButton("Back to the lesson")) goToStop(st, k);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(
                "You changed the points or the options: this brings the lesson's back (Ctrl+Z, "
                "yours)");
        ImGui::SameLine();
    } else if (st.engine.position() != L.plan.stops[k].position) {
        if (ImGui::SmallButton("Back to the stop")) goToStop(st, k);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("You stepped away from this stop's operation");
        ImGui::SameLine();
    }
    if (ImGui::SmallButton("Close")) {
        closeLesson(st);
        return false;
    }
    RecordItem(st, "lesson-close");
    return true;
}

// One box per stop: orange the current one, green answered right, amber tried, grey seen.
void ProgressBoxes(const LessonState& L, std::size_t k, std::size_t n) {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float w = ImGui::GetContentRegionAvail().x / static_cast<float>(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t a = i < L.progress.answers.size() ? L.progress.answers[i] : 0;
        const ImU32 col = i == k                     ? IM_COL32(240, 120, 0, 255)
                          : a == 2                   ? IM_COL32(60, 170, 80, 255)
                          : a == 1                   ? IM_COL32(235, 170, 60, 255)
                          : i <= L.progress.furthest ? IM_COL32(170, 175, 190, 255)
                                                     : IM_COL32(220, 222, 228, 255);
        dl->AddRectFilled(ImVec2(p.x + i * w + 1, p.y), ImVec2(p.x + (i + 1) * w - 1, p.y + 6), col,
                          2);
    }
    ImGui::Dummy(ImVec2(0, 10));
}

}  // namespace

void ShowLesson(AppState& st) {
    LessonState& L = st.lessonPlayer;
    if (!L.lesson) return;
    const Lesson& lesson = *L.lesson;
    ImGui::PushFont(fonts().caption);
    ImGui::TextWrapped("%s", lesson.title.c_str());
    ImGui::PopFont();
    const std::size_t n = lesson.stops.size();
    if (n == 0) {
        AssignmentPanel(st);
        return;
    }
    const std::size_t k = std::min(L.progress.stop, n - 1);
    if (!StopButtons(st, k, n)) return;  // closed: nothing of the lesson is read after this
    ProgressBoxes(L, k, n);
    ImGui::Separator();
    const float header = ImGui::GetCursorPosY();
    ImGui::BeginChild("##lessontext", ImVec2(0, 0), false);
    const LessonStop& stop = lesson.stops[k];
    // The stop's words with their {{values}} as the engine computed them at the stop.
    RichText(L.plan.stops[k].text);
    if (stop.figure == "lifting-map") LiftingFigure(st);
    Question(st, stop, k);
    // What the pane needs to show the text and the question whole (app.cpp sizes it).
    const float wanted = header + ImGui::GetCursorPosY() + 2 * ImGui::GetStyle().WindowPadding.y;
    L.paneHeightWanted = L.paneHeightStop == k ? std::max(L.paneHeightWanted, wanted) : wanted;
    L.paneHeightStop = k;
    ImGui::EndChild();
    RecordItem(st, "lesson-text");
}

}  // namespace dlab::ui
