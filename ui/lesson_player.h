// The lesson player: a loaded lesson, its plan (every stop's position, selection and answer,
// computed headlessly by core/lesson), the stop on show, and the student's answers. Going to a
// stop seeks the run, selects the stop's corner and shows the stop's panels, overlays, view and
// side tab. The lesson's overlays are the lesson's: the user's come back when it closes.
#pragma once

#include "core/teaching/lesson.h"

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>

namespace dlab::ui {

struct AppState;
using ::dlab::Overlays;  // core/teaching/overlays.h

struct LessonState {
    std::shared_ptr<const Lesson> lesson;  // null: no lesson open
    // A track open: its items' lessons are opened in turn as its slides are paged through.
    std::shared_ptr<const Track> track;
    std::size_t trackSlide = 0;  // the track's slide on show (0-based)
    LessonPlan plan;
    LessonProgress progress;
    std::string typed;  // the answer field
    enum class Feedback : std::uint8_t { None, Right, Wrong, Shown } feedback = Feedback::None;
    bool showHint = false;
    bool pendingTabSelect = false;  // the side column shows the stop's panel once
    // The box (x0, y0, x1, y1) the canvas fits at its next frame: the stop's view.
    std::optional<std::array<double, 4>> pendingView;
    // The user's overlays from before the lesson opened: back when it closes (and what the
    // settings save while a lesson is open).
    std::shared_ptr<const Overlays> userOverlays;
    // The run's options from before the lesson opened: back when it closes.
    std::optional<InsertOptions> optionsBefore;
    float slideQuestionHeight = 0;  // the slide's question block, as laid out last frame
    float slideTextHeight = 0;      // and the height the stop's text needed
    // The windowed lesson pane's whole content at this stop: the most it took in any frame since
    // the stop was shown (a scrollbar that comes and goes changes the wrapping: never shrinking
    // keeps the layout still).
    float paneHeightWanted = 0;
    std::size_t paneHeightStop = static_cast<std::size_t>(-1);
    // Progress of every lesson opened, by path (persisted with the settings).
    std::map<std::string, LessonProgress> saved;
    // Where the progress is written as it changes (saveLessonProgressIfChanged); empty: only
    // with the settings at exit, if at all.
    std::string settingsPath;
    std::uint64_t changes = 0, changesSaved = 0;  // of `saved`: counted, and as last written
};

// Loads, checks and plans the lesson, then shows its first stop (or where the student was).
// On a bad lesson: logs "FILE:LINE: stop K: what", changes nothing, returns false. A track file
// (kind = "track") opens as a track, at its first slide.
bool openLesson(AppState& state, const std::string& path);
// The slides the clickers page through: the track's when one is open, else the lesson's stops.
std::size_t slideCount(const AppState& state);
std::size_t slideIndex(const AppState& state);
// Shows slide k (clamped): a stop of the open lesson, or of a track (opening its lesson).
void goToSlide(AppState& state, std::size_t k);
void closeLesson(AppState& state);
// Shows stop k (0-based, clamped); brings the lesson's points and options back first when the
// user changed them (the stops are operations of the lesson's own run).
void goToStop(AppState& state, std::size_t k);
// Whether the engine's points or options differ from the open lesson's.
bool lessonStateChanged(const AppState& state);
// Checks the typed answer against the engine's; records it in the progress.
bool checkAnswer(AppState& state);
// The side-column tab and the visibility of the inspector/messages a stop asks for.
bool lessonWantsPanel(const AppState& state, const char* panelName);
// The slide layout: presentation mode with a lesson (that has stops) open.
bool slideMode(const AppState& state);
// The overlays the settings keep: the user's, also while a lesson shows its own.
const Overlays& userOverlays(const AppState& state);

}  // namespace dlab::ui
