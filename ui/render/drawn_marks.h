// What the canvas drew, in the roles it drew it in (the test edge, queued and flipped edges, the
// test's circle, points and their labels), recorded only while `lesson check` reads a slide: the
// record is null otherwise, and each call costs one test of a pointer.
#pragma once

#include "core/teaching/slide_check.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace dlab::ui {

// The list marks go to; null (the normal GUI): nothing is recorded.
inline std::vector<SlideMark>* g_markRecord = nullptr;
inline bool recordingMarks() { return g_markRecord != nullptr; }

// Records one mark drawn in box [x0, x1] x [y0, y1] (screen pixels) while a record is open.
inline void recordMark(SlideMarkRole role, std::int32_t a, std::int32_t b, float x0, float y0,
                       float x1, float y1) {
    if (std::vector<SlideMark>* r = g_markRecord)
        r->push_back(
            {role, a, b, {std::min(x0, x1), std::min(y0, y1), std::max(x0, x1), std::max(y0, y1)}});
}

// Opens a record for the frames drawn while it lives (one slide), and closes it.
class MarkRecording {
public:
    explicit MarkRecording(std::vector<SlideMark>& into) { g_markRecord = &into; }
    ~MarkRecording() { g_markRecord = nullptr; }
    MarkRecording(const MarkRecording&) = delete;
    MarkRecording& operator=(const MarkRecording&) = delete;
};

}  // namespace dlab::ui
