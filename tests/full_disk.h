// Small file systems for tests of writes that fail: a tmpfs filled to the last page (a full
// disk) or remounted read-only. Mounting needs root: `why()` says why a test must skip.
#pragma once

#include <sys/mount.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace dlab::testutil {

class SmallDisk {
public:
    // Mounts a tmpfs of `bytes` on a new folder.
    explicit SmallDisk(const std::string& name, std::size_t bytes = std::size_t{1} << 20) {
        m_dir = std::filesystem::temp_directory_path() /
                ("dlab_disk_" + name + "_" + std::to_string(::getpid()));
        std::error_code ec;
        std::filesystem::create_directories(m_dir, ec);
        if (::geteuid() != 0) {
            m_why = "mounting a small tmpfs needs root";
            return;
        }
        const std::string options = "size=" + std::to_string(bytes);
        if (::mount("tmpfs", m_dir.c_str(), "tmpfs", 0, options.c_str()) != 0) {
            m_why = std::string("cannot mount a tmpfs here: ") + std::strerror(errno);
            return;
        }
        m_mounted = true;
    }
    ~SmallDisk() {
        if (m_mounted) ::umount2(m_dir.c_str(), MNT_DETACH);
        std::error_code ec;
        std::filesystem::remove_all(m_dir, ec);
    }
    SmallDisk(const SmallDisk&) = delete;
    SmallDisk& operator=(const SmallDisk&) = delete;

    bool ok() const { return m_mounted; }
    const std::string& why() const { return m_why; }
    const std::filesystem::path& dir() const { return m_dir; }

    // Takes every page left (call after the old files are in place): any new write then fails
    // with ENOSPC.
    void fill() const {
        std::ofstream filler(m_dir / "filler", std::ios::binary);
        const std::string chunk(4096, 'x');
        for (int k = 0; k < (1 << 20) && filler.write(chunk.data(), 4096); ++k) {}
    }
    // Makes it read-only (writes then fail with EROFS).
    bool readOnly() const {
        return ::mount(nullptr, m_dir.c_str(), nullptr, MS_REMOUNT | MS_RDONLY, nullptr) == 0;
    }

private:
    std::filesystem::path m_dir;
    std::string m_why;
    bool m_mounted = false;
};

// What a write leaves behind when it does not clean up: hidden temporaries and kept old files.
inline std::vector<std::string> leftovers(const std::filesystem::path& dir) {
    std::vector<std::string> found;
    std::error_code ec;
    for (auto it = std::filesystem::recursive_directory_iterator(dir, ec);
         it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.find(".tmp.") != std::string::npos || name.find(".old.") != std::string::npos)
            found.push_back(it->path().string());
    }
    return found;
}

inline std::string slurpFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

inline int countLines(const std::string& s) {
    int n = 0;
    for (const char c : s) n += c == '\n';
    return n + (!s.empty() && s.back() != '\n');
}

}  // namespace dlab::testutil
