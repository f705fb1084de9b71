// dtlab lesson check | show | handout: runs lessons headlessly (every stop reached, every answer
// computed, every expectation met), prints a lesson's answer key, or writes a student handout.
#include "app/dtlab_common.h"

#include "core/engine/output_files.h"
#include "core/engine/text_util.h"
#include "core/teaching/lesson.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <set>
#include <sstream>

extern char** environ;

namespace dlab::cli {

namespace {

struct LessonArgs {
    std::vector<std::string> files;
    std::string file;
    std::string output;
    bool tables = false;
    bool noSlides = false;
};

// The corner table at a stop, one triangle per line: "t 3: V 4 2 5 | O 7 -1 12". Inside the
// lesson's edits (`edits`), the edited mesh: its ghost vertex reads "g".
void printTables(const Inserter& ins, const Editor* edits) {
    const Mesh& m = edits ? edits->mesh() : ins.mesh();
    const auto name = [&](std::int32_t v) {
        if (edits) return v >= edits->firstVirtual() ? std::string("g") : std::to_string(v);
        if (!ins.isVirtual(v) || ins.done()) return std::to_string(v);
        return ins.options().boundary == Boundary::Exact ? std::string("g")
                                                         : "s" + std::to_string(v - ins.numInput());
    };
    for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
        std::cout << "  t " << t << " (corners " << 3 * t << ".." << 3 * t + 2 << "): V";
        for (int k = 0; k < 3; ++k) std::cout << ' ' << name(m.V[3 * t + k]);
        std::cout << " | O";
        for (int k = 0; k < 3; ++k) std::cout << ' ' << m.O[3 * t + k];
        std::cout << "\n";
    }
}

std::size_t questions(const Lesson& lesson) {
    std::size_t n = 0;
    for (const LessonStop& s : lesson.stops) n += !s.question.empty();
    return n;
}

// Checks one lesson file as `lesson check` does; prints its line. False when it failed.
bool checkLessonFile(const std::string& path, bool noSlides) {
    try {
        const Lesson lesson = loadLesson(path);
        const LessonPlan plan = planLesson(lesson);
        std::vector<LessonError> problems = lessonProblems(lesson, plan);
        if (!noSlides && !lesson.stops.empty()) {
            const std::vector<RenderedSlide> slides = renderedSlides(path);
            std::vector<std::vector<std::string>> lines;
            for (const RenderedSlide& s : slides) lines.push_back(s.lines);
            for (LessonError& e : slideProblems(lesson, plan, lines))
                problems.push_back(std::move(e));
            for (LessonError& e : renderedSlideProblems(lesson, plan, slides))
                problems.push_back(std::move(e));
        }
        if (!problems.empty()) {
            for (const LessonError& e : problems)
                std::cerr << "dtlab: error: " << escapeControls(e.what()) << "\n";
            return false;
        }
        std::cout << escapeControls(path) << ": ok: \"" << escapeControls(lesson.title) << "\" ("
                  << (lesson.assignment ? "assignment, " : "") << lesson.points.size()
                  << " points, " << lesson.stops.size() << " stops, " << questions(lesson)
                  << " questions, " << plan.totalOps << " operations"
                  << (plan.editOps ? " + " + std::to_string(plan.editOps) + " of edits" : "")
                  << (lesson.minutes ? ", " + std::to_string(lesson.minutes) + " minutes" : "")
                  << ")\n";
        return true;
    } catch (const LessonError& e) {
        std::cerr << "dtlab: error: " << escapeControls(e.what()) << "\n";
        return false;
    }
}

std::string canonicalName(const std::string& path) {
    std::error_code ec;
    const auto c = std::filesystem::weakly_canonical(path, ec);
    return ec ? path : c.string();
}

// A track: its own keys and references (loadTrack), then every lesson it plays checked whole
// as `lesson check` checks a lesson (once, when the same run has not checked it already).
bool checkTrackFile(const std::string& path, bool noSlides, std::set<std::string>& checked) {
    Track track;
    try {
        track = loadTrack(path);
    } catch (const LessonError& e) {
        std::cerr << "dtlab: error: " << escapeControls(e.what()) << "\n";
        return false;
    }
    bool ok = true;
    std::size_t asked = 0;
    int minutes = 0;
    for (const TrackItem& item : track.items) {
        minutes += item.minutes;
        const Lesson lesson = loadLesson(item.lesson);  // loadTrack read it already
        for (std::size_t k : item.stops) asked += !lesson.stops[k].question.empty();
        if (checked.insert(canonicalName(item.lesson)).second)
            ok = checkLessonFile(item.lesson, noSlides) && ok;
    }
    if (!ok) {
        std::cerr << "dtlab: error: " << escapeControls(path)
                  << ": a lesson it plays fails its check\n";
        return false;
    }
    std::cout << escapeControls(path) << ": ok: track \"" << escapeControls(track.title) << "\" ("
              << track.items.size() << " items, " << track.slides() << " stops, " << asked
              << " questions, " << minutes << " of " << track.minutes << " minutes)\n";
    return true;
}

void runCheck(const LessonArgs& args) {
    if (!args.noSlides) needGl();  // the slides are rendered: dtlab-gl runs the check
    int failed = 0;
    std::set<std::string> checked;  // lessons checked by this run (a track's are not again)
    for (const std::string& path : args.files) {
        if (isTrackFile(path)) {
            failed += !checkTrackFile(path, args.noSlides, checked);
            continue;
        }
        const bool ok = checkLessonFile(path, args.noSlides);
        failed += !ok;
        if (ok) checked.insert(canonicalName(path));
    }
    std::cout.flush();
    if (failed)
        fail(std::to_string(failed) + " of " + std::to_string(args.files.size()) +
             " lessons failed");
}

// The answer key of a lesson: every stop, or those `only` lists (a track's item).
void showLesson(const std::string& path, bool tables, const std::vector<std::size_t>* only) {
    try {
        const Lesson lesson = loadLesson(path);
        const LessonPlan plan = planLesson(lesson);
        auto ins = makeInserter(lesson);
        Journal journal(*ins);
        std::unique_ptr<Editor> editor;  // the lesson's edits, made at the first stop inside them
        // Lesson files are untrusted: no control character reaches the terminal.
        const auto text = [](std::string_view s) { return escapeControlsKeepLines(s); };
        std::cout << "# " << escapeControls(lesson.title) << "\n"
                  << text(lesson.summary) << "\n"
                  << "options: boundary " << toString(lesson.options.boundary) << ", locator "
                  << toString(lesson.options.locator) << ", order "
                  << toString(lesson.options.order) << ", seed " << lesson.options.seed << "; "
                  << lesson.points.size() << " points"
                  << (lesson.pointsFile.empty() ? "" : " from " + escapeControls(lesson.pointsFile))
                  << "; " << plan.totalOps << " operations"
                  << (plan.editOps ? " + " + std::to_string(plan.editOps) + " of edits" : "")
                  << "\n";
        for (const Edit& e : lesson.edits) std::cout << "edit: " << describe(e) << "\n";
        if (!lesson.text.empty())
            std::cout << "\n"
                      << escapeControlsKeepLines(lesson.text)
                      << (lesson.text.back() == '\n' ? "" : "\n");
        for (std::size_t k = 0; k < lesson.stops.size(); ++k) {
            if (only && std::find(only->begin(), only->end(), k) == only->end()) continue;
            const LessonStop& s = lesson.stops[k];
            const StopState& st = plan.stops[k];
            std::cout << "\n## stop " << k + 1 << " (line " << s.line << "): "
                      << (s.runTo ? "run_to " + toString(*s.runTo) +
                                        (s.count > 1 ? " x" + std::to_string(s.count) : "")
                                  : std::string("stay"))
                      << " -> op " << st.position << "\n";
            if (!st.caption.empty()) std::cout << "caption: " << text(st.caption) << "\n";
            if (tables && st.position > plan.totalOps) {  // inside the edits
                if (!editor) editor = startEdits(lesson, journal, *ins);
                editor->seek(st.position - plan.totalOps);
                printTables(*ins, editor.get());
            } else if (tables) {
                journal.seek(st.position);
                printTables(*ins, nullptr);
            }
            if (st.selected != kNone) std::cout << "selected corner: " << st.selected << "\n";
            if (!st.text.empty())
                std::cout << text(st.text) << (st.text.back() == '\n' ? "" : "\n");
            if (!s.question.empty()) {
                std::cout << "Q: " << text(st.question) << "\nA: " << text(st.answer->display())
                          << "   (" << text(s.answer) << ")\n";
                if (!st.hint.empty()) std::cout << "hint: " << text(st.hint) << "\n";
            }
            for (const LessonExpect& e : s.expect)
                std::cout << "checked: " << text(e.spec) << " = " << text(e.value) << "\n";
        }
    } catch (const LessonError& e) {
        fail(e.what(), 2);  // bad input
    }
}

void runShow(const LessonArgs& args) {
    if (!isTrackFile(args.file)) return showLesson(args.file, args.tables, nullptr);
    Track track;
    try {
        track = loadTrack(args.file);
    } catch (const LessonError& e) {
        fail(e.what(), 2);  // bad input
    }
    std::cout << "# track: " << escapeControls(track.title) << " (" << track.slides() << " stops, "
              << track.minutes << " minutes)\n"
              << escapeControlsKeepLines(track.summary) << "\n";
    for (const std::string& o : track.objectives)
        std::cout << "objective: " << escapeControls(o) << "\n";
    for (std::size_t i = 0; i < track.items.size(); ++i) {
        const TrackItem& item = track.items[i];
        std::cout << "\n=== item " << i + 1 << " (line " << item.line
                  << "): " << escapeControls(item.written) << ", " << item.minutes
                  << " minutes\n\n";
        showLesson(item.lesson, args.tables, &item.stops);
    }
}

std::string htmlEscaped(std::string_view t) {
    std::string out;
    for (char c : t) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

// Lesson text (Markdown-light: paragraphs, lists, **bold**, `code`) as HTML.
std::string htmlText(const std::string& text) {
    const auto blocks = parseLessonText(text);
    if (!blocks) return "<p>" + htmlEscaped(text) + "</p>\n";  // the loader checked it
    std::string out;
    const char* list = nullptr;  // the list open: "ul", "ol" or none
    for (const TextBlock& b : *blocks) {
        const char* want = b.kind == TextBlock::Kind::Bullet     ? "ul"
                           : b.kind == TextBlock::Kind::Numbered ? "ol"
                                                                 : nullptr;
        if (list && want != list) out += std::string("</") + list + ">\n";
        if (want && want != list) out += std::string("<") + want + ">\n";
        list = want;
        out += list ? "<li>" : "<p>";
        for (const TextSpan& sp : b.spans) {
            const std::string t = htmlEscaped(sp.text);
            out += sp.style == TextSpan::Style::Bold   ? "<strong>" + t + "</strong>"
                   : sp.style == TextSpan::Style::Code ? "<code>" + t + "</code>"
                                                       : t;
        }
        out += list ? "</li>\n" : "</p>\n";
    }
    if (list) out += std::string("</") + list + ">\n";
    return out;
}

// What a child said on stderr: its last line, without its "dtlab: error: " (fail adds it).
std::string childMessage(int fd) {
    std::string said;
    char buf[4096];
    for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) != 0;) {
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) break;
        said.append(buf, static_cast<std::size_t>(n));
    }
    while (!said.empty() && said.back() == '\n') said.pop_back();
    said = said.substr(said.rfind('\n') + 1);
    const std::string prefix = "dtlab: error: ";
    return said.rfind(prefix, 0) == 0 ? said.substr(prefix.size()) : said;
}

// One slide per stop (DIR/01.png, ...) by `dtlab-gl render --slides`: GL runs in dtlab-gl, so
// that dtlab itself never loads it. DIR is a temporary folder that becomes `shownDir`: a
// message from dtlab-gl names shownDir.
void renderSlides(const std::string& lesson, const std::string& dir, const std::string& shownDir) {
    std::error_code ec;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
    const std::string gl = ((ec ? std::filesystem::path(".") : self.parent_path()) / "dtlab-gl");
    std::vector<std::string> args = {gl,  "render",    "--lesson", lesson,    "--slides",
                                     dir, "--handout", "--size",   "1280x720"};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::cout.flush();
    int err[2];
    if (::pipe2(err, O_CLOEXEC) != 0) fail("cannot start " + gl + ": " + std::strerror(errno));
    pid_t pid = 0;
    posix_spawn_file_actions_t quiet;  // its "wrote N slides" is not ours to print
    posix_spawn_file_actions_init(&quiet);
    posix_spawn_file_actions_addopen(&quiet, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&quiet, err[1], 2);
    const int spawned = posix_spawn(&pid, gl.c_str(), &quiet, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&quiet);
    ::close(err[1]);
    std::string said = spawned == 0 ? childMessage(err[0]) : std::string();
    ::close(err[0]);
    if (spawned != 0)
        fail("the handout's pictures need " + gl +
             ", which cannot be started: " + std::strerror(spawned));
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
    if (!WIFEXITED(status))
        fail("the handout's pictures could not be rendered (" + gl + " render crashed)");
    if (WEXITSTATUS(status) == 0) return;
    for (std::size_t at; (at = said.find(dir)) != std::string::npos;)
        said.replace(at, dir.size(), shownDir);
    fail(said.empty() ? gl + " render failed" : said, WEXITSTATUS(status));
}

// Lesson text inline (a question, a hint): its spans, no paragraph around them.
std::string htmlInline(const std::string& text) {
    std::string html = htmlText(text);
    for (const char* tag : {"<p>", "</p>\n", "<ul>\n", "</ul>\n", "<li>", "</li>\n"}) {
        for (std::size_t at; (at = html.find(tag)) != std::string::npos;)
            html.replace(at, std::strlen(tag), " ");
    }
    return trimmed(html);
}

// What a handout shows: the lessons it plays (one, or a track's) and its pages in order.
struct Handout {
    std::string title, summary;
    // A track's, or a lesson's without stops (a lesson's are in its first stop otherwise).
    std::vector<std::string> objectives;
    int minutes = 0;    // 0: not stated
    std::string intro;  // the lesson's own text (an assignment's instructions), before the pages
    std::vector<Lesson> lessons;
    std::vector<LessonPlan> plans;
    struct Page {
        std::size_t lesson, stop;
        int minutes = 0;  // a track item's first page: the item's minutes
    };
    std::vector<Page> pages;
    bool track = false;
    // The page's text: a track leaves a lesson's own objectives out (the track states its own).
    std::string text(const Page& p) const {
        std::string t = plans[p.lesson].stops[p.stop].text;
        const std::string own = objectivesText(lessons[p.lesson].objectives);
        if (track && !own.empty() && t.rfind(own, 0) == 0) t.erase(0, own.size());
        return t;
    }
};

Handout loadHandout(const std::string& path) {
    Handout h;
    if (!isTrackFile(path)) {
        h.lessons.push_back(loadLesson(path));
        h.plans.push_back(planLesson(h.lessons[0]));
        const Lesson& l = h.lessons[0];
        h.title = l.title;
        h.summary = l.summary;
        h.minutes = l.minutes;
        h.intro = l.text;
        if (l.stops.empty()) h.objectives = l.objectives;
        for (std::size_t k = 0; k < h.lessons[0].stops.size(); ++k) h.pages.push_back({0, k});
        return h;
    }
    const Track track = loadTrack(path);
    h.track = true;
    h.title = track.title;
    h.summary = track.summary;
    h.objectives = track.objectives;
    h.minutes = track.minutes;
    for (std::size_t i = 0; i < track.items.size(); ++i) {
        h.lessons.push_back(loadLesson(track.items[i].lesson));
        h.plans.push_back(planLesson(h.lessons.back()));
        for (std::size_t k : track.items[i].stops)
            h.pages.push_back({i, k, k == track.items[i].stops[0] ? track.items[i].minutes : 0});
    }
    return h;
}

std::string pageHeading(const Handout& h, std::size_t n) {
    const Handout::Page& p = h.pages[n];
    std::string out = (h.track ? "Slide " : "Stop ") + std::to_string(n + 1);
    if (h.track && p.minutes)
        out += ": " + h.lessons[p.lesson].title + " (" + std::to_string(p.minutes) + " min)";
    return out;
}

// The handout as HTML: each stop's slide (PNGs in FILE_files/ beside it), text and question;
// hints fold away.
std::string handoutHtml(const Handout& ho, const std::string& pictures) {
    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << htmlEscaped(ho.title)
      << "</title>\n<style>body{font-family:sans-serif;max-width:60em;margin:auto}"
         "img{max-width:100%;border:1px solid #ccc}.answer{border-bottom:1px solid #000;"
         "display:inline-block;width:20em}</style></head><body>\n<h1>"
      << htmlEscaped(ho.title) << "</h1>\n<p>" << htmlEscaped(ho.summary) << "</p>\n"
      << htmlText(objectivesText(ho.objectives));
    if (ho.minutes) h << "<p><em>" << ho.minutes << " minutes.</em></p>\n";
    h << htmlText(ho.intro);
    int asked = 0;
    for (std::size_t n = 0; n < ho.pages.size(); ++n) {
        const Handout::Page& p = ho.pages[n];
        const StopState& st = ho.plans[p.lesson].stops[p.stop];
        char png[32];
        std::snprintf(png, sizeof png, "/%02zu.png", n + 1);
        h << "<h2>" << htmlEscaped(pageHeading(ho, n)) << "</h2>\n<img src=\""
          << htmlEscaped(pictures + png) << "\" alt=\"slide " << n + 1 << "\">\n"
          << htmlText(ho.text(p));
        if (ho.lessons[p.lesson].stops[p.stop].question.empty()) continue;
        h << "<p><strong>Question " << ++asked << ".</strong> " << htmlInline(st.question)
          << "</p>\n";
        if (!st.hint.empty())
            h << "<details><summary>Hint</summary><p>" << htmlInline(st.hint) << "</p></details>\n";
        h << "<p>Your answer: <span class=\"answer\"></span></p>\n";
    }
    h << "</body></html>\n";
    return h.str();
}

// The same in Markdown, each slide's picture from FILE_files/; hints fold away (<details>).
std::string handoutMarkdown(const Handout& ho, const std::string& pictures) {
    std::ostringstream md;
    md << "# " << ho.title << "\n\n" << ho.summary << "\n";
    if (!ho.objectives.empty()) md << "\n" << trimmed(objectivesText(ho.objectives)) << "\n";
    if (ho.minutes) md << "\n*" << ho.minutes << " minutes.*\n";
    if (const std::string t = trimmed(ho.intro); !t.empty()) md << "\n" << t << "\n";
    int asked = 0;
    for (std::size_t n = 0; n < ho.pages.size(); ++n) {
        const Handout::Page& p = ho.pages[n];
        const StopState& st = ho.plans[p.lesson].stops[p.stop];
        char png[32];
        std::snprintf(png, sizeof png, "/%02zu.png", n + 1);
        md << "\n## " << pageHeading(ho, n) << "\n\n![slide " << n + 1 << "](" << pictures << png
           << ")\n\n";
        if (const std::string t = trimmed(ho.text(p)); !t.empty()) md << t << "\n";
        if (ho.lessons[p.lesson].stops[p.stop].question.empty()) continue;
        md << "\n**Question " << ++asked << ".** " << st.question << "\n";
        if (!st.hint.empty())
            md << "\n<details><summary>Hint</summary>\n\n" << st.hint << "\n\n</details>\n";
        md << "\nYour answer: ____________________\n";
    }
    return md.str();
}

// A handout for students: the lesson's (or track's) text and questions, no answers, each
// slide's picture in FILE_files/ beside it; Markdown, or HTML when FILE ends in .html. The
// handout and its folder of pictures are one set: both new, or both as they were.
void runHandout(const LessonArgs& args) {
    namespace fs = std::filesystem;
    const fs::path out(args.output);
    const bool html = out.extension() == ".html" || out.extension() == ".htm";
    const std::string pictures = out.stem().string() + "_files";
    const std::string folder = (out.parent_path() / pictures).string();
    std::string text;
    std::vector<OutputFile> files = {{args.output, [&](std::ostream& os) { os << text; }, {}}};
    try {
        const Handout h = loadHandout(args.file);
        text = html ? handoutHtml(h, pictures) : handoutMarkdown(h, pictures);
        files.push_back(
            {folder, {}, [&](const std::string& dir) { renderSlides(args.file, dir, folder); }});
    } catch (const LessonError& e) {
        fail(e.what());
    }
    writeTextFiles(files, {args.file});
    std::cout << "wrote " << escapeControls(args.output) << " (pictures in "
              << escapeControls(folder) << ")\n";
}

}  // namespace

void addLesson(CLI::App& app) {
    auto args = std::make_shared<LessonArgs>();
    CLI::App* cmd = app.add_subcommand("lesson", "Check lessons, or print a lesson's answer key");
    cmd->require_subcommand(1);
    CLI::App* check = cmd->add_subcommand("check",
                                          "Run every lesson to its end headlessly: each stop "
                                          "reached in order, each answer computable, each "
                                          "expectation met, every character drawable, no "
                                          "answer given away by the text, the banner or the "
                                          "rendered slide");
    check->add_option("lessons", args->files, "Lesson files (.toml)")->required();
    check->add_flag("--no-slides", args->noSlides,
                    "Do not render the slides (no GL): skip the check that the answer is not on "
                    "the slide as drawn");
    check->callback([args] { guarded([&] { runCheck(*args); }); });
    CLI::App* show = cmd->add_subcommand(
        "show", "Print a lesson (or a track) stop by stop with the engine's answers");
    show->add_option("lesson", args->file, "Lesson or track file (.toml)")->required();
    show->add_flag("--tables", args->tables,
                   "Also print the corner table (V and O per triangle) at each stop");
    show->callback([args] { guarded([&] { runShow(*args); }); });
    CLI::App* handout = cmd->add_subcommand(
        "handout",
        "Write a lesson (or a track) as a handout for students: text and questions, no answers, "
        "each stop's slide (canvas and text) in FILE_files/ beside it (PNGs drawn by dtlab-gl); "
        "Markdown, or HTML when FILE ends in .html");
    handout->add_option("lesson", args->file, "Lesson or track file (.toml)")->required();
    handout->add_option("-o,--output", args->output, "Markdown or .html file to write")->required();
    handout->callback([args] { guarded([&] { runHandout(*args); }); });
}

}  // namespace dlab::cli
