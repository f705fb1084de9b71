// Lesson player: open (load + plan), go to a stop (seek, select, panels, overlays), answers.
#include "ui/lesson_player.h"

#include "ui/app_state.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

namespace dlab::ui {

namespace {

// The stop's view for the canvas' next frame; a stop without one shows all the points, so that a
// slide looks the same whichever stop came before it.
void applyView(AppState& st, const LessonStop& stop) {
    LessonState& L = st.lessonPlayer;
    L.pendingView.reset();
    if (stop.view.empty()) {
        st.fitPending = true;
        return;
    }
    if (stop.view.rect) {
        L.pendingView = *stop.view.rect;
    } else {
        const auto& G = st.engine.mesh().G;
        double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL;
        for (std::int32_t v : stop.view.fit) {
            // The super-triangle's vertices are gone after Finalize: fit what is there.
            if (v < 0 || static_cast<std::size_t>(v) >= G.size()) continue;
            if (st.engine.options().boundary == Boundary::Exact &&
                v == static_cast<std::int32_t>(st.engine.points().size()))
                continue;  // the ghost vertex has no position
            x0 = std::min(x0, G[v].x);
            y0 = std::min(y0, G[v].y);
            x1 = std::max(x1, G[v].x);
            y1 = std::max(y1, G[v].y);
        }
        if (!(x0 <= x1)) {
            st.fitPending = true;
            return;
        }
        L.pendingView = std::array<double, 4>{x0, y0, x1, y1};
    }
    st.fitPending = false;
}

// Stop k's overlays, the same however it is reached (paged to, resumed, jumped to): exactly
// those the last stop up to k names (a stop without a list keeps the one before it), or the
// user's from before the lesson when no stop so far names any.
void applyStopOverlays(AppState& st, std::size_t k) {
    const LessonState& L = st.lessonPlayer;
    std::size_t named = k + 1;
    while (named > 0 && L.lesson->stops[named - 1].overlays.empty()) --named;
    if (named == 0) {
        if (L.userOverlays) st.overlays = *L.userOverlays;
        return;
    }
    Overlays& o = st.overlays;
    for (const OverlaySwitch& s : kOverlaySwitches)
        if (s.perStop) o.*s.flag = false;
    for (const std::string& name : L.lesson->stops[named - 1].overlays) {
        if (bool* b = overlaySwitch(o, name)) *b = true;
    }
}

// The lesson's edits after its run's end, in order (the plan checked that each is taken).
bool applyLessonEdits(AppState& st, const Lesson& lesson) {
    for (const Edit& e : lesson.edits) {
        std::string message;
        if (!st.engine.edit(e, message)) {
            st.log(Message::Level::Error,
                   lesson.title + ": edit \"" + describe(e) + "\": " + message);
            return false;
        }
    }
    return true;
}

// The lesson's run in the engine: its points inserted with its options, or Lawson's flip
// algorithm from its start triangulation (`triangles`); then its edits.
bool loadLessonRun(AppState& st, const Lesson& lesson) {
    if (!st.setOptions(lesson.options)) return false;
    if (!lesson.start)
        return st.loadPoints(lesson.points, lesson.title) && applyLessonEdits(st, lesson);
    std::string error;
    std::vector<Vec2> previous = st.engine.points();
    if (!st.engine.resetRepair(lesson.points, *lesson.start, true, error)) {
        st.log(Message::Level::Error, lesson.title + ": " + error + " (nothing was changed)");
        return false;
    }
    if (!previous.empty()) {
        st.undoPoints.push_back(std::move(previous));
        st.redoPoints.clear();
    }
    st.source = lesson.title;
    st.selection = {};
    st.run.running = false;
    st.fitPending = true;
    st.log(Message::Level::Info, lesson.title + ": " + std::to_string(lesson.points.size()) +
                                     " points, " + std::to_string(lesson.start->V.size() / 3) +
                                     " triangles given: Lawson's flip algorithm from them");
    return true;
}

void saveProgress(AppState& st) {
    LessonState& L = st.lessonPlayer;
    if (!L.lesson) return;
    LessonProgress& kept = L.saved[L.progress.lesson];
    if (kept == L.progress) return;
    kept = L.progress;
    ++L.changes;
}

bool openLessonFile(AppState& st, const std::string& path);

// A track's slide k: its item's lesson opened when another one is, the stop shown; the track's
// objectives above the first slide's text, the lesson's own left out (they are the track's).
bool showTrackSlide(AppState& st, std::size_t k) {
    LessonState& L = st.lessonPlayer;
    const auto track = L.track;
    const auto slides = trackSlides(*track);
    k = std::min(k, slides.size() - 1);
    const TrackItem& item = track->items[slides[k].first];
    if (!L.lesson || L.progress.lesson != item.lesson) {
        if (!openLessonFile(st, item.lesson)) return false;
        L.track = track;  // openLessonFile keeps it; a failure above leaves the track as it was
        const std::string own = objectivesText(L.lesson->objectives);
        std::string& first = L.plan.stops[0].text;
        if (!own.empty() && first.rfind(own, 0) == 0) first.erase(0, own.size());
    }
    const std::size_t stop = slides[k].second;
    std::string& text = L.plan.stops[stop].text;
    const std::string mine = objectivesText(track->objectives);
    if (k == 0 && text.rfind(mine, 0) != 0) text = mine + text;
    L.trackSlide = k;
    goToStop(st, stop);
    return true;
}

}  // namespace

bool openLesson(AppState& st, const std::string& path) {
    if (isTrackFile(path)) {
        std::shared_ptr<const Track> track;
        try {
            track = std::make_shared<const Track>(loadTrack(path));
        } catch (const LessonError& e) {
            st.log(Message::Level::Error, std::string(e.what()) + " (the track was not opened)");
            return false;
        }
        const auto before = st.lessonPlayer.track;
        saveProgress(st);
        st.lessonPlayer.track = track;
        st.lessonPlayer.lesson.reset();  // the first item's lesson opens afresh
        if (showTrackSlide(st, 0)) {
            st.log(Message::Level::Info, "track: " + track->title + " (" +
                                             std::to_string(track->slides()) + " slides, " +
                                             std::to_string(track->minutes) + " minutes)");
            return true;
        }
        st.lessonPlayer.track = before;
        return false;
    }
    if (!openLessonFile(st, path)) return false;
    st.lessonPlayer.track.reset();
    return true;
}

std::size_t slideCount(const AppState& st) {
    const LessonState& L = st.lessonPlayer;
    if (L.track) return L.track->slides();
    return L.lesson ? L.lesson->stops.size() : 0;
}

std::size_t slideIndex(const AppState& st) {
    const LessonState& L = st.lessonPlayer;
    return L.track ? L.trackSlide : L.progress.stop;
}

void goToSlide(AppState& st, std::size_t k) {
    if (st.lessonPlayer.track) {
        showTrackSlide(st, k);
    } else {
        goToStop(st, k);
    }
}

namespace {

bool openLessonFile(AppState& st, const std::string& path) {
    std::shared_ptr<Lesson> lesson;
    LessonPlan plan;
    try {
        lesson = std::make_shared<Lesson>(loadLesson(path));
        plan = planLesson(*lesson);
    } catch (const LessonError& e) {
        st.log(Message::Level::Error, std::string(e.what()) + " (the lesson was not opened)");
        return false;
    } catch (const std::exception& e) {
        st.log(Message::Level::Error, path + ": " + e.what() + " (the lesson was not opened)");
        return false;
    }
    saveProgress(st);
    const InsertOptions before = st.engine.options();
    if (!loadLessonRun(st, *lesson)) return false;
    LessonState& L = st.lessonPlayer;
    if (!L.userOverlays) {  // a lesson opened over another keeps the user's from before both
        L.userOverlays = std::make_shared<const Overlays>(st.overlays);
        L.optionsBefore = before;
    }
    L.lesson = lesson;
    L.plan = std::move(plan);
    L.progress = {};
    if (const auto it = L.saved.find(path);
        it != L.saved.end() && it->second.title == lesson->title)
        L.progress = it->second;
    L.progress.lesson = path;
    L.progress.title = lesson->title;
    L.progress.answers.resize(lesson->stops.size(), 0);
    st.log(Message::Level::Info,
           "lesson: " + lesson->title + " (" + std::to_string(lesson->stops.size()) + " stops)");
    if (lesson->stops.empty()) {
        st.engine.seek(0);
    } else {
        goToStop(st, std::min(L.progress.stop, lesson->stops.size() - 1));
    }
    return true;
}

}  // namespace

void closeLesson(AppState& st) {
    saveProgress(st);
    LessonState& L = st.lessonPlayer;
    L.lesson.reset();
    L.track.reset();
    L.plan = {};
    L.pendingView.reset();
    if (L.userOverlays) st.overlays = *L.userOverlays;
    L.userOverlays.reset();
    st.fitPending = true;  // a stop's zoom is the lesson's too
    // The lesson's options were the lesson's: the user's from before it come back (on its
    // points; Ctrl+Z brings the user's points back).
    const std::optional<InsertOptions> before = std::exchange(L.optionsBefore, std::nullopt);
    if (before && !sameRun(st.engine.options(), *before) && st.setOptions(*before))
        st.log(Message::Level::Info,
               "lesson closed: your options are back (" + optionsText(*before) + ")");
}

const Overlays& userOverlays(const AppState& st) {
    return st.lessonPlayer.userOverlays ? *st.lessonPlayer.userOverlays : st.overlays;
}

bool slideMode(const AppState& st) {
    const LessonState& L = st.lessonPlayer;
    return st.presentation && L.lesson && !L.lesson->stops.empty();
}

bool lessonStateChanged(const AppState& st) {
    const LessonState& L = st.lessonPlayer;
    if (!L.lesson) return false;
    std::vector<std::string> edits;
    for (const Edit& e : L.lesson->edits) edits.push_back(describe(e));
    return !sameRun(st.engine.options(), L.lesson->options) ||
           st.engine.points() != L.lesson->points ||
           st.engine.repairs() != L.lesson->start.has_value() || editTexts(st.engine) != edits;
}

void goToStop(AppState& st, std::size_t k) {
    LessonState& L = st.lessonPlayer;
    if (!L.lesson || L.lesson->stops.empty()) return;
    k = std::min(k, L.lesson->stops.size() - 1);
    // The stops are operations of the lesson's own run: after the user changed the points or
    // the options, going to a stop brings the lesson's back (their own stay on the undo stack).
    if (lessonStateChanged(st)) {
        if (!loadLessonRun(st, *L.lesson)) return;
        st.log(Message::Level::Info,
               "lesson: its points and options are back (Ctrl+Z brings your points back)");
    }
    const LessonStop& stop = L.lesson->stops[k];
    const StopState& at = L.plan.stops[k];
    st.run.running = false;
    st.engine.seek(at.position);
    st.select(at.selected);
    if (at.selected != kNone) st.selection.jumpToCorner = at.selected;
    applyStopOverlays(st, k);
    applyView(st, stop);
    L.progress.stop = k;
    L.progress.furthest = std::max(L.progress.furthest, k);
    L.typed.clear();
    L.feedback = LessonState::Feedback::None;
    L.showHint = false;
    L.paneHeightStop = static_cast<std::size_t>(-1);  // the pane measures the new stop afresh
    // The stop's tab in front, or else the first panel it names.
    L.pendingTabSelect = stop.tab.empty();
    st.pendingTab = stop.tab == "none" ? std::string() : stop.tab;
    saveProgress(st);
}

bool checkAnswer(AppState& st) {
    LessonState& L = st.lessonPlayer;
    if (!L.lesson) return false;
    const std::size_t k = L.progress.stop;
    if (k >= L.plan.stops.size() || !L.plan.stops[k].answer) return false;
    const bool right = acceptsAnswer(*L.plan.stops[k].answer, L.typed);
    L.feedback = right ? LessonState::Feedback::Right : LessonState::Feedback::Wrong;
    if (k < L.progress.answers.size())
        L.progress.answers[k] = std::max<std::uint8_t>(L.progress.answers[k], right ? 2 : 1);
    saveProgress(st);
    return right;
}

bool lessonWantsPanel(const AppState& st, const char* panel) {
    const LessonState& L = st.lessonPlayer;
    if (!L.lesson || L.lesson->stops.empty()) return true;
    const auto& panels =
        L.lesson->stops[std::min(L.progress.stop, L.lesson->stops.size() - 1)].panels;
    if (panels.empty()) return true;
    return std::any_of(panels.begin(), panels.end(),
                       [&](const std::string& p) { return p == panel; });
}

}  // namespace dlab::ui
