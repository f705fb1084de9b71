// Animated GIFs of a range of steps (giflib 5): each frame is the GUI rendered at one step (in
// the window, or headless through OSMesa), cropped to the canvas or whole, quantized to its own
// 256-colour palette, looping forever.
#pragma once

#include "ui/app_state.h"

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace dlab::ui {

class Gui;

class GifWriter {
public:
    GifWriter();
    ~GifWriter();
    GifWriter(const GifWriter&) = delete;
    GifWriter& operator=(const GifWriter&) = delete;

    // Starts a GIF of width x height frames on `os` (`path` names it in messages). False with a
    // one-line reason.
    bool open(std::ostream& os, const std::string& path, int width, int height, std::string& error);
    // One frame: RGBA rows, top row first, `width` pixels each; shown for delayMs.
    bool addFrame(const std::uint8_t* rgba, int delayMs, std::string& error);
    // Finishes the GIF. False when anything failed.
    bool close(std::string& error);
    int frames() const { return m_frames; }

private:
    struct File;
    std::unique_ptr<File> m_file;
    std::string m_path;
    int m_width = 0, m_height = 0, m_frames = 0;
};

// Renders operations request.from .. request.to (every request.every) through `gui` and writes
// them to request.path, whole or not at all (writeTextFile: a failure keeps the old file); the
// run goes back to where it was. Returns the number of frames, 0 with a one-line `error` on
// failure.
int exportStepsGif(Gui& gui, const GifRequest& request, std::string& error);

// The pixels of the last frame inside the canvas (or the whole frame), RGBA, top row first.
std::vector<std::uint8_t> CaptureRegion(Gui& gui, bool wholeWindow, int& width, int& height);

}  // namespace dlab::ui
