// AppState's actions: loading and editing points, options, selection moves, the message log.
#include "ui/app_state.h"

#include "core/engine/generators.h"
#include "ui/files/files.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace dlab::ui {

void View::fit(Vec2 lo, Vec2 hi) {
    const double w = hi.x - lo.x, h = hi.y - lo.y;
    center = {lo.x / 2 + hi.x / 2, lo.y / 2 + hi.y / 2};
    const double extent = std::max(w, h);
    if (!(extent > 0) || !std::isfinite(extent)) {
        // One point (or none): a unit box around it, or around the paper's box centre.
        scale = std::min(size.x, size.y) / std::max(2.0, std::abs(center.x) * 1e-12 + 2.0);
        return;
    }
    const double sx = size.x / (w > 0 ? w : extent), sy = size.y / (h > 0 ? h : extent);
    scale = 0.9 * std::min(sx, sy);
}

void View::zoomAt(glm::dvec2 screen, double factor) {
    const Vec2 before = toWorld(screen);
    scale = std::clamp(scale * factor, 1e-300, 1e300);
    const Vec2 after = toWorld(screen);
    center.x += before.x - after.x;
    center.y += before.y - after.y;
}

InsertOptions demoOptions() {
    InsertOptions o;
    o.order = OrderKind::Input;  // vertex k is the k-th point: easier to follow in class
    return o;
}

void loadDemo(AppState& state) {
    state.setOptions(demoOptions());
    state.loadPoints(demoPoints(), "built-in demo");
}

bool openStartupInput(AppState& state, const std::string& input) {
    if (input.empty()) {
        loadDemo(state);
        return true;
    }
    if (openFile(state, input)) return true;
    loadDemo(state);  // in the demo's own order, whatever the failed file had set
    return false;
}

void AppState::log(Message::Level level, std::string text) {
    messages.push_back({level, std::move(text)});
    if (messages.size() > 5000) messages.erase(messages.begin(), messages.begin() + 1000);
}

bool AppState::loadPoints(std::vector<Vec2> points, std::string sourceName) {
    return loadPointsWith(std::move(points), std::move(sourceName), engine.options());
}

bool AppState::loadUserPoints(std::vector<Vec2> points, std::string sourceName) {
    return loadPointsWith(std::move(points), std::move(sourceName), userOptions);
}

bool AppState::loadPointsWith(std::vector<Vec2> points, std::string sourceName,
                              const InsertOptions& options) {
    std::string error;
    const std::size_t n = points.size();
    std::vector<Vec2> previous = engine.points();
    const bool newOptions = !sameRun(options, engine.options());
    if (!engine.reset(std::move(points), options, error)) {
        log(Message::Level::Error, sourceName + ": " + error + " (nothing was changed)");
        return false;
    }
    if (!previous.empty()) {
        undoPoints.push_back(std::move(previous));
        redoPoints.clear();
    }
    source = std::move(sourceName);
    selection = {};
    run.running = false;
    fitPending = true;
    log(Message::Level::Info, source + ": " + std::to_string(n) + " points" +
                                  (newOptions ? std::string(", ") + optionsText(options) : ""));
    if (engine.batch()) log(Message::Level::Warning, engine.batchReason());
    checkHistory();
    return true;
}

namespace {

// The edits after the run, made again on a run of new points. Only where no point was removed:
// a removal renumbers the points after it, and the edits name points by number.
void redoEditsOnNewRun(AppState& st, const std::vector<std::string>& edits, bool idsKept,
                       std::size_t position) {
    if (edits.empty()) return;
    if (!idsKept) {
        st.log(Message::Level::Warning,
               std::to_string(edits.size()) +
                   " edit(s) after the run dropped: a point removed renumbers the points after it");
        return;
    }
    for (const std::string& text : edits) {
        const auto edit = parseEdit(text);
        std::string message;
        if (!edit || !st.engine.edit(*edit, message))
            st.log(Message::Level::Warning, text + " no longer applies: " + message);
    }
    st.engine.seek(position);
}

// A run of new points at the same step, with the edits after the run made again.
bool resetKeepingEdits(AppState& st, std::vector<Vec2> points, std::string& error) {
    Engine& e = st.engine;
    const std::vector<std::string> edits = editTexts(e);
    const bool idsKept = points.size() >= e.points().size();
    const std::size_t position = e.position();
    if (!e.resetAt(std::move(points), e.options(), position, error)) return false;
    redoEditsOnNewRun(st, edits, idsKept, position);
    return true;
}

}  // namespace

bool AppState::editPoints(std::vector<Vec2> points) {
    std::string error;
    std::vector<Vec2> previous = engine.points();
    if (!resetKeepingEdits(*this, std::move(points), error)) {
        log(Message::Level::Error, "edit refused: " + error);
        return false;
    }
    undoPoints.push_back(std::move(previous));
    redoPoints.clear();
    if (selection.corner >= engine.mesh().numCorners()) selection = {};
    return true;
}

namespace {

// Undo and redo: the points on top of `from` come back; the points now go onto `to`.
bool swapPoints(AppState& st, std::vector<std::vector<Vec2>>& from,
                std::vector<std::vector<Vec2>>& to) {
    if (from.empty()) return false;
    std::string error;
    std::vector<Vec2> now = st.engine.points();
    if (!resetKeepingEdits(st, from.back(), error)) return false;
    from.pop_back();
    to.push_back(std::move(now));
    return true;
}

// What an edit of the points did, in a message's words: "point 7 removed (12 -> 11 points)",
// "point 3 moved", "2 points added (10 -> 12 points)".
std::string editText(const std::vector<Vec2>& before, const std::vector<Vec2>& after) {
    const std::size_t n = std::min(before.size(), after.size());
    std::size_t changed = 0, first = n;
    for (std::size_t i = 0; i < n; ++i) {
        if (before[i].x != after[i].x || before[i].y != after[i].y) {
            ++changed;
            first = std::min(first, i);
        }
    }
    const std::string counts =
        " (" + std::to_string(before.size()) + " -> " + std::to_string(after.size()) + " points)";
    if (after.size() != before.size()) {
        const bool added = after.size() > before.size();
        const std::size_t k = added ? after.size() - before.size() : before.size() - after.size();
        const std::string verb = added ? " added" : " removed";
        // One point at the end, or one whose place the rest moved up into.
        if (k == 1) return "point " + std::to_string(first < n ? first : n) + verb + counts;
        return std::to_string(k) + " points" + verb + counts;
    }
    if (changed == 1) return "point " + std::to_string(first) + " moved";
    return std::to_string(changed) + " points changed";
}

}  // namespace

bool AppState::undoEdit() {
    // The edits after the run are newer than any edit of the points (which restarts the run).
    if (const Editor* ed = engine.editor(); ed && !ed->edits().empty()) {
        std::string message;
        const bool ok = engine.undoEdit(message);
        log(Message::Level::Info, message);
        return ok;
    }
    if (undoPoints.empty()) {
        log(Message::Level::Info, "nothing to undo: no edit of the points");
        return false;
    }
    const std::string what = editText(undoPoints.back(), engine.points());
    if (!swapPoints(*this, undoPoints, redoPoints)) return false;
    selection = {};
    log(Message::Level::Info, "undone: " + what);
    return true;
}

bool AppState::redoEdit() {
    std::string message;
    if (engine.redoEdit(message)) {
        log(Message::Level::Info, message);
        return true;
    }
    if (redoPoints.empty()) {
        log(Message::Level::Info, "nothing to redo: no edit of the points");
        return false;
    }
    const std::string what = editText(engine.points(), redoPoints.back());
    if (!swapPoints(*this, redoPoints, undoPoints)) return false;
    selection = {};
    log(Message::Level::Info, "redone: " + what);
    return true;
}

bool AppState::setOptions(const InsertOptions& options) {
    std::string error;
    if (!engine.reset(engine.points(), options, error)) {
        log(Message::Level::Error, std::string("options refused: ") + error);
        return false;
    }
    selection = {};
    run.running = false;
    log(Message::Level::Info, "restarted: " + optionsText(options));
    checkHistory();
    return true;
}

bool AppState::setUserOptions(const InsertOptions& options) {
    if (!setOptions(options)) return false;
    if (!lessonPlayer.lesson) userOptions = options;
    return true;
}

std::string groupedCount(std::size_t n) {
    std::string digits = std::to_string(n), out;
    for (std::size_t k = 0; k < digits.size(); ++k) {
        if (k > 0 && (digits.size() - k) % 3 == 0) out += ',';
        out += digits[k];
    }
    return out;
}

std::string approximateCount(std::size_t n) {
    if (n >= 1000000) {
        const double m = static_cast<double>(n) / 1e6;
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.*f million", m < 10 ? 1 : 0, m);
        return buf;
    }
    std::size_t unit = 1;  // two significant digits
    while (n / unit >= 100) unit *= 10;
    return groupedCount((n + unit / 2) / unit * unit);
}

std::string historyOfferText(const AppState& st) {
    const Engine& e = st.engine;
    std::string s = groupedCount(e.points().size()) + " points in " + toString(e.options().order) +
                    " order make about " + approximateCount(e.estimatedOps()) +
                    " operations, more than the history holds (" + approximateCount(e.opLimit()) +
                    "): stepping would stop there and the rest run in one batch.";
    if (st.historyOffer.brioOps > 0)
        s += " In BRIO order they make about " + approximateCount(st.historyOffer.brioOps) + ".";
    return s;
}

void AppState::checkHistory() {
    HistoryOffer& h = historyOffer;
    if (!engine.historyWillOverflow()) {
        h = {};
        return;
    }
    if (h.open && h.run == engine.run()) return;
    h.open = true;
    h.run = engine.run();
    h.brioOps = 0;
    if (engine.options().order != OrderKind::Brio) {
        InsertOptions brio = engine.options();
        brio.order = OrderKind::Brio;
        const std::size_t ops = estimateRunOps(engine.points(), brio);
        if (ops > 0 && ops <= engine.opLimit()) h.brioOps = ops;
    }
    log(Message::Level::Warning, historyOfferText(*this));
}

std::string optionsText(const InsertOptions& o) {
    return std::string("boundary ") + toString(o.boundary) + ", locate " + toString(o.locator) +
           ", order " + toString(o.order);
}

void AppState::select(std::int32_t corner) {
    const Mesh& m = engine.mesh();
    selection.corner = corner >= 0 && corner < m.numCorners() ? corner : kNone;
    selection.lastMove = {};
}

bool AppState::moveSelection(char op) {
    const Mesh& m = engine.mesh();
    const std::int32_t c = selection.corner;
    if (c < 0 || c >= m.numCorners()) {
        log(Message::Level::Info,
            "select a corner first (click near one, or a row of the corner table)");
        return false;
    }
    std::int32_t to = kNone;
    switch (op) {
        case 'n': to = m.n(c); break;
        case 'p': to = m.p(c); break;
        case 'o': to = m.o(c); break;
        case 'l': to = m.l(c); break;
        case 'r': to = m.r(c); break;
        case 's': to = m.s(c); break;
        case 'u': to = m.u(c); break;
        default: return false;
    }
    if (to == kNone) {
        log(Message::Level::Info,
            std::string("c.") + op + " of corner " + std::to_string(c) +
                " crosses the boundary (no neighbour there): the selection stays");
        return false;
    }
    selection.corner = to;
    selection.lastMove = {c, op, to, engine.version()};
    selection.jumpToCorner = to;
    return true;
}

const CornerMove* AppState::currentMove() const {
    const CornerMove& mv = selection.lastMove;
    return mv.op && mv.version == engine.version() ? &mv : nullptr;
}

}  // namespace dlab::ui
