// Fuzz target: readPointsFile, i.e. file loading, dispatch on the extension and format sniffing.
//
// The first byte picks the extension (known ones, upper case, none, unknown), the rest is the
// file's content. Either outcome is checked: an InputError follows the one-line rules; a
// successful read of a sniffed file equals what the guessed format's parser reads directly.
#include "tests/fuzz/fuzz_common.h"

#include <unistd.h>
#include <cstdio>
#include <filesystem>
#include <string>

namespace {

constexpr const char* kExtensions[] = {".node", ".pts", ".csv", ".xy", ".txt",     ".dat",
                                       ".NODE", ".Csv", "",     ".in", ".node.bak"};

std::string scratchPath(const char* extension) {
    static const std::string dir = [] {
        auto d = std::filesystem::temp_directory_path() /
                 ("dlab_fuzz_read_file_" + std::to_string(getpid()));
        std::filesystem::create_directories(d);
        return d.string();
    }();
    return dir + "/input" + extension;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace dlab;
    using namespace dlab::fuzz;
    if (size == 0) return 0;
    constexpr std::size_t kCount = sizeof kExtensions / sizeof kExtensions[0];
    const char* extension = kExtensions[data[0] % kCount];
    const std::string_view text = asText(data + 1, size - 1);
    const std::string path = scratchPath(extension);
    {
        std::FILE* f = std::fopen(path.c_str(), "wb");
        require(f != nullptr, "can create the scratch file", path);
        require(std::fwrite(text.data(), 1, text.size(), f) == text.size(),
                "can write the scratch file", path);
        std::fclose(f);
    }
    PointSet ps;
    try {
        ps = readPointsFile(path);
    } catch (const InputError& e) {
        checkInputError(e, text, path);
        std::remove(path.c_str());
        return 0;
    }
    std::remove(path.c_str());
    require(ps.path == path, "PointSet::path is the file's path", ps.path);

    // A sniffed file says what it was read as; reading it with that parser gives the same.
    // The sniff's own warning comes first and has a fixed shape; a parser's warning may quote the
    // file's text, which can say anything (": read as " included).
    const std::string first = ps.warnings.empty() ? std::string() : ps.warnings.front();
    const bool sniffed =
        (first.starts_with("no extension: read as ") || first.starts_with("unknown extension '")) &&
        first.ends_with(" by its content");
    const std::string ext = std::filesystem::path(path).extension().string();
    const bool known = ext == ".node" || ext == ".pts" || ext == ".csv" || ext == ".xy" ||
                       ext == ".NODE" || ext == ".Csv" || ext == ".txt" || ext == ".dat";
    require(sniffed != known, "exactly the files with an unknown extension are sniffed", path);
    Reparse parser = &parseXY;
    std::string_view format = "xy";
    if (sniffed) {
        const std::string& w = ps.warnings.front();
        if (w.find("Triangle .node") != std::string::npos) {
            parser = &parseNode;
            format = "node";
        } else if (w.find("Rossignac .pts") != std::string::npos) {
            parser = &parsePts;
            format = "pts";
        }
        const PointSet direct =
            mustRead(parser, text, path, "the sniffed format's parser reads the file");
        requireSamePoints(direct, ps, "a sniffed read equals the guessed parser's read");
    } else if (ext == ".node" || ext == ".NODE") {
        parser = &parseNode;
        format = "node";
    } else if (ext == ".pts") {
        parser = &parsePts;
        format = "pts";
    }
    checkPointSet(ps, path, parser, format);
    return 0;
}
