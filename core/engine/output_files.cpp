// Output sets: temporaries removed on a fatal signal, checked writes, and the commit that puts a
// whole set in place or none of it.
//
// [SECTION] Temporaries removed on a signal
// [SECTION] A stream that keeps the reason of a failed write
// [SECTION] Checks
// [SECTION] Temporaries and bodies
// [SECTION] The commit
// [SECTION] writeTextFiles
//
// How a set is committed (all new or all old):
//   1. Every output is written whole to a temporary beside its file, each write, flush, fsync
//      and close checked. Nothing the user sees has changed yet.
//   2. The signals that end a process are held in this thread, and each folder of the set is
//      locked (flock, in one order): a second writer of the same files waits here, so two
//      commits never interleave.
//   3. Pre-flight: each old file is kept under a hidden name, as a hard link (the file itself)
//      or, where it cannot be linked, a copy. An old file that the folder will not let us
//      replace (a sticky folder and someone else's file) refuses the set here, unchanged.
//   4. The temporaries are renamed over their files, those most likely to fail first. When one
//      rename fails, the ones already done are undone from what step 3 kept, in reverse order,
//      and the set is all old again. An old file that could be neither linked nor copied
//      is renamed last, so it never needs undoing; two such files refuse the set.
//   5. The kept old files are removed, the folders synced, the locks released.
// A temporary is registered while it lives and removed by the handler of SIGINT, SIGTERM,
// SIGHUP and SIGPIPE (when the program has no handler of its own). SIGKILL leaves it.
#include "core/engine/output_files.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <ostream>
#include <random>
#include <stdexcept>
#include <streambuf>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <pthread.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#if defined(__linux__) && !defined(__EMSCRIPTEN__)
#include <sys/syscall.h>
#endif

namespace dlab {

namespace fs = std::filesystem;

//-----------------------------------------------------------------------------------------------
// [SECTION] Temporaries removed on a signal
//-----------------------------------------------------------------------------------------------

namespace {

// Live temporaries, one path per slot ("f/path": a file, "d/path": a folder), written by the
// threads that write and read by a signal handler: atomic pointers, no lock. A path belongs to
// whoever takes it out of its slot (exchange): the writer frees it; a handler leaves it, the
// process is ending.
constexpr std::size_t kSlots = 1024;
std::atomic<char*> g_slots[kSlots];

constexpr int kFatalSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE};

// A temporary folder's files (it holds files only), then the folder: system calls only.
void removeFolderNow(const char* path) {
#if defined(__linux__) && !defined(__EMSCRIPTEN__)
    for (int pass = 0; pass < 4; ++pass) {
        const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        if (fd < 0) break;
        alignas(8) char buf[4096];
        bool removed = false;
        long n = 0;
        while ((n = ::syscall(SYS_getdents64, fd, buf, sizeof buf)) > 0) {
            // struct linux_dirent64: d_ino (8 bytes), d_off (8), d_reclen (2), d_type (1), d_name
            for (long off = 0; off < n;) {
                unsigned short reclen = 0;
                std::memcpy(&reclen, buf + off + 16, sizeof reclen);
                const char* name = buf + off + 19;
                if (std::strcmp(name, ".") != 0 && std::strcmp(name, "..") != 0)
                    removed = ::unlinkat(fd, name, 0) == 0 || removed;
                off += reclen;
            }
        }
        ::close(fd);
        if (!removed) break;
    }
#endif
    ::rmdir(path);
}

void onFatalSignal(int sig) {
    removeOutputTemporaries();
    std::signal(sig, SIG_DFL);  // then end as the signal would have ended us
    std::raise(sig);            // delivered when the handler returns (sig is blocked in it)
}

// Handles the signals that end a process, where the program neither handles nor ignores them.
void installHandlers() {
    static std::once_flag once;
    std::call_once(once, [] {
        for (const int sig : kFatalSignals) {
            struct sigaction now {};
            if (::sigaction(sig, nullptr, &now) != 0) continue;
            if ((now.sa_flags & SA_SIGINFO) != 0 || now.sa_handler != SIG_DFL) continue;
            struct sigaction ours {};
            ours.sa_handler = onFatalSignal;
            sigemptyset(&ours.sa_mask);
            for (const int s : kFatalSignals) sigaddset(&ours.sa_mask, s);
            ::sigaction(sig, &ours, nullptr);
        }
    });
}

// Registers a temporary for removal on a signal; returns its slot (kSlots: none was free, the
// temporary is then only removed by the normal paths).
std::size_t track(const std::string& path, bool folder) {
    installHandlers();
    const std::string entry = (folder ? "d/" : "f/") + path;
    char* copy = static_cast<char*>(std::malloc(entry.size() + 1));
    if (!copy) return kSlots;
    std::memcpy(copy, entry.c_str(), entry.size() + 1);
    for (std::size_t k = 0; k < kSlots; ++k) {
        char* expected = nullptr;
        if (g_slots[k].compare_exchange_strong(expected, copy)) return k;
    }
    std::free(copy);
    return kSlots;
}

void untrack(std::size_t& slot) {
    if (slot < kSlots) std::free(g_slots[slot].exchange(nullptr));
    slot = kSlots;
}

// Holds the ending signals in this thread while a set is committed: a commit is never cut in
// the middle by them (they are delivered when it is done, and the temporaries then removed).
class SignalsHeld {
public:
    SignalsHeld() {
        sigset_t set;
        sigemptyset(&set);
        for (const int s : kFatalSignals) sigaddset(&set, s);
        m_held = ::pthread_sigmask(SIG_BLOCK, &set, &m_old) == 0;
    }
    ~SignalsHeld() {
        if (m_held) ::pthread_sigmask(SIG_SETMASK, &m_old, nullptr);
    }
    SignalsHeld(const SignalsHeld&) = delete;
    SignalsHeld& operator=(const SignalsHeld&) = delete;

private:
    sigset_t m_old{};
    bool m_held = false;
};

}  // namespace

void removeOutputTemporaries() {
    for (std::atomic<char*>& slot : g_slots) {
        const char* p = slot.exchange(nullptr);
        if (!p) continue;
        if (p[0] == 'd')
            removeFolderNow(p + 2);
        else
            ::unlink(p + 2);
    }
}

//-----------------------------------------------------------------------------------------------
// [SECTION] A stream that keeps the reason of a failed write
//-----------------------------------------------------------------------------------------------

namespace {

// Writes to a file descriptor and keeps the errno of the first failed write (an ofstream keeps
// only "bad", and errno is long gone by the time anyone looks): a full disk then reads "No
// space left on device". After a failure nothing more is written.
class FdBuf : public std::streambuf {
public:
    explicit FdBuf(int fd) : m_fd(fd), m_buf(std::size_t{1} << 16) { reset(); }
    int error() const { return m_error; }

protected:
    int_type overflow(int_type c) override {
        if (!drain()) return traits_type::eof();
        if (!traits_type::eq_int_type(c, traits_type::eof())) {
            *pptr() = traits_type::to_char_type(c);
            pbump(1);
        }
        return traits_type::not_eof(c);
    }
    std::streamsize xsputn(const char* s, std::streamsize n) override {
        if (static_cast<std::size_t>(n) < m_buf.size()) return std::streambuf::xsputn(s, n);
        if (!drain() || !writeAll(s, static_cast<std::size_t>(n))) return 0;
        return n;
    }
    int sync() override { return drain() ? 0 : -1; }

private:
    void reset() { setp(m_buf.data(), m_buf.data() + m_buf.size()); }
    bool drain() {
        const bool ok = writeAll(pbase(), static_cast<std::size_t>(pptr() - pbase()));
        reset();
        return ok;
    }
    bool writeAll(const char* p, std::size_t n) {
        while (m_error == 0 && n > 0) {
            const ssize_t w = ::write(m_fd, p, std::min(n, std::size_t{1} << 30));
            if (w < 0 && errno == EINTR) continue;
            if (w <= 0) {
                m_error = w < 0 ? errno : EIO;
                break;
            }
            p += w;
            n -= static_cast<std::size_t>(w);
        }
        return m_error == 0;
    }

    int m_fd;
    int m_error = 0;
    std::vector<char> m_buf;
};

}  // namespace

//-----------------------------------------------------------------------------------------------
// [SECTION] Checks
//-----------------------------------------------------------------------------------------------

namespace {

[[noreturn]] void cannotWrite(const std::string& path, const std::string& why) {
    throw std::runtime_error("cannot write " + path + ": " + why);
}

std::string errnoText(int e) { return std::generic_category().message(e); }

// Where the bytes of an output go: the file a symbolic link points to (followed link by link,
// so a dangling link names the file it will create), not the link. A device, pipe or socket
// reached through links (/dev/stdout, /proc/self/fd/1: links to "pipe:[...]", which is no
// path) is the path itself, opened as it is.
fs::path targetOf(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode)) return path;
    fs::path p = path;
    std::error_code ec;
    for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
        const fs::path to = fs::read_symlink(p, ec);
        if (ec) break;
        p = to.is_absolute() ? to : p.parent_path() / to;
    }
    return p;
}

// The identity of an existing file (device and inode, so hard links match too), or of the
// path it would have.
struct FileId {
    bool exists = false;
    dev_t dev = 0;
    ino_t ino = 0;
    std::string name;  // weakly canonical path, for files that do not exist yet
    bool operator==(const FileId& o) const {
        return exists == o.exists && (exists ? dev == o.dev && ino == o.ino : name == o.name);
    }
};

FileId fileId(const std::string& path) {
    FileId id;
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) {
        id.exists = true;
        id.dev = st.st_dev;
        id.ino = st.st_ino;
    } else {
        std::error_code ec;
        const fs::path c = fs::weakly_canonical(fs::absolute(path, ec), ec);
        id.name = (ec ? fs::path(path) : c).lexically_normal().string();
    }
    return id;
}

}  // namespace

void checkOutputFiles(const std::vector<OutputFile>& outputs,
                      const std::vector<std::string>& inputs) {
    std::vector<FileId> ids;
    for (const OutputFile& o : outputs) {
        if (o.path.empty() || fs::path(o.path).filename().empty())
            cannotWrite("\"" + o.path + "\"", "an output needs a file name");
        const FileId id = fileId(o.path);
        for (const std::string& in : inputs) {
            if (fileId(in) == id)
                cannotWrite(o.path, "it is the input file " + in + " (choose another output)");
        }
        for (std::size_t k = 0; k < ids.size(); ++k) {
            if (ids[k] == id) cannotWrite(o.path, "it is also the output " + outputs[k].path);
        }
        ids.push_back(id);
    }
}

//-----------------------------------------------------------------------------------------------
// [SECTION] Temporaries and bodies
//-----------------------------------------------------------------------------------------------

namespace {

// One output on its way: written to a unique temporary beside its target, renamed at the end;
// or, for a device or pipe, written straight through.
struct Pending {
    const OutputFile* out = nullptr;
    fs::path target;
    std::string temp;  // empty: written through
    std::size_t slot = kSlots;
    bool folder() const { return static_cast<bool>(out->fill); }
};

fs::path folderOf(const fs::path& target) {
    const fs::path dir = target.parent_path();
    return dir.empty() ? fs::path(".") : dir;
}

// A hidden name beside `target` for what it holds: ".NAME.<what>.XXXXXX" (a pattern for mkstemp
// and mkdtemp).
std::string hiddenPattern(const fs::path& target, const char* what) {
    return (folderOf(target) / ("." + target.filename().string() + "." + what + ".XXXXXX"))
        .string();
}

// The mode a new file gets (0666 less the umask; 0777 for a folder), or the mode of the one it
// replaces; the owner can always read and write what they asked to write (Emscripten's umask
// reads as 0777).
mode_t modeFor(const struct stat* existing, bool folder) {
    if (existing) return existing->st_mode & 07777;
    const mode_t mask = ::umask(0);
    ::umask(mask);
    return folder ? (0777 & ~mask) | 0700 : (0666 & ~mask) | 0600;
}

void removeTemp(Pending& p) {
    if (p.temp.empty()) return;
    std::error_code ec;
    if (p.folder())
        fs::remove_all(p.temp, ec);
    else
        ::unlink(p.temp.c_str());
    p.temp.clear();
    untrack(p.slot);
}

void prepareFolder(Pending& p, const struct stat* existing) {
    if (existing && !S_ISDIR(existing->st_mode)) cannotWrite(p.out->path, "it is not a folder");
    std::string pattern = hiddenPattern(p.target, "tmp");
    {
        const SignalsHeld held;  // no signal between creating it and registering it
        if (!::mkdtemp(pattern.data())) cannotWrite(p.out->path, errnoText(errno));
        p.temp = pattern;
        p.slot = track(p.temp, true);
    }
    if (::chmod(p.temp.c_str(), modeFor(existing, true)) != 0)
        cannotWrite(p.out->path, errnoText(errno));
}

void prepare(Pending& p) {
    const std::string& path = p.out->path;
    struct stat st {};
    const bool exists = ::stat(p.target.c_str(), &st) == 0;
    if (p.folder()) return prepareFolder(p, exists ? &st : nullptr);
    if (exists && S_ISDIR(st.st_mode)) cannotWrite(path, "it is a directory");
    if (exists && !S_ISREG(st.st_mode)) {
        // A device or pipe is written through; a pipe without a reader is refused, not waited on.
        const int fd = ::open(p.target.c_str(), O_WRONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
        if (fd < 0 && errno == ENXIO) cannotWrite(path, "it is a named pipe that nobody reads");
        if (fd < 0) cannotWrite(path, errnoText(errno));
        ::close(fd);
        return;
    }
    std::string pattern = hiddenPattern(p.target, "tmp");
    int fd = -1;
    {
        const SignalsHeld held;  // no signal between creating it and registering it
        fd = ::mkstemp(pattern.data());
        if (fd < 0) cannotWrite(path, errnoText(errno));
        p.temp = pattern;
        p.slot = track(p.temp, false);
    }
    const bool modeSet = ::fchmod(fd, modeFor(exists ? &st : nullptr, false)) == 0;
    const int e = errno;
    ::close(fd);
    if (!modeSet) cannotWrite(path, errnoText(e));
}

// Writes an output's body to its temporary (or through to its device), every step checked; a
// temporary is on the disk (fsync) before anything is renamed over the old file.
void writeBody(const Pending& p) {
    const std::string& shown = p.out->path;
    const bool through = p.temp.empty();
    const std::string file = through ? p.target.string() : p.temp;
    int fd = -1;
    do {
        fd = ::open(file.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
    } while (fd < 0 && errno == EINTR);
    if (fd < 0) cannotWrite(shown, errnoText(errno));
    FdBuf buf(fd);
    std::ostream os(&buf);
    try {
        p.out->body(os);
    } catch (...) {
        ::close(fd);
        throw;
    }
    os.flush();
    int e = buf.error();
    if (e == 0 && !os) e = EIO;
    // fsync: EINVAL where a file system cannot sync (nothing to wait for then).
    if (e == 0 && !through && ::fsync(fd) != 0 && errno != EINVAL) e = errno;
    if (::close(fd) != 0 && e == 0 && errno != EINTR) e = errno;
    if (e != 0) cannotWrite(shown, errnoText(e));
}

}  // namespace

//-----------------------------------------------------------------------------------------------
// [SECTION] The commit
//-----------------------------------------------------------------------------------------------

namespace {

// How an output's old file is kept until its set is in place.
enum class Keep {
    Nothing,  // there is none: undoing removes the new file
    Link,     // a hard link to it (the file itself, under a second name)
    Copy,     // a copy (it could not be linked)
    Folder,   // the old folder, swapped out by the rename
    None,     // it could be neither linked nor copied: renamed last, never undone
};

struct Step {
    Pending* p = nullptr;
    Keep keep = Keep::Nothing;
    std::string kept = {};  // where the old file (or folder) is kept
    bool done = false;
};

// Locks on the folders of a set's outputs, taken in one order (device, inode) so that two
// writers never wait on each other crosswise; released when the descriptors close. flock is
// advisory: it orders the writers that take it (this code) and costs readers nothing. A folder
// that cannot be opened for reading is renamed into unlocked.
class FolderLocks {
public:
    explicit FolderLocks(const std::vector<Step>& steps) {
        struct Folder {
            std::pair<dev_t, ino_t> id;
            int fd;
            const std::string* shown;  // an output in it, to name in a message
            bool operator<(const Folder& o) const { return id < o.id; }
        };
        std::vector<Folder> folders;
        for (const Step& s : steps) {
            const int fd =
                ::open(folderOf(s.p->target).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
            if (fd < 0) continue;
            struct stat st {};
            const bool known =
                ::fstat(fd, &st) != 0 || std::any_of(folders.begin(), folders.end(), [&](auto& f) {
                    return f.id == std::make_pair(st.st_dev, st.st_ino);
                });
            if (known) {
                ::close(fd);
                continue;
            }
            folders.push_back({{st.st_dev, st.st_ino}, fd, &s.p->out->path});
            m_fds.push_back(fd);
        }
        std::sort(folders.begin(), folders.end());
        for (const Folder& f : folders) {
            if (!lock(f.fd)) {
                for (const int fd : m_fds) ::close(fd);
                cannotWrite(*f.shown, "its folder stays locked by another program");
            }
        }
    }
    ~FolderLocks() {
        for (const int fd : m_fds) ::close(fd);
    }
    FolderLocks(const FolderLocks&) = delete;
    FolderLocks& operator=(const FolderLocks&) = delete;
    // The renames on the disk (a folder's fsync), before the old files are let go.
    void sync() const {
        for (const int fd : m_fds) ::fsync(fd);
    }

private:
    // A commit holds its lock for milliseconds: waiting a minute means that another program
    // holds it (a lock on a folder is rare), and a write never waits for ever. False then; a
    // folder that cannot be locked at all (no flock there) is renamed into unlocked.
    static bool lock(int fd) {
        const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        while (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
            if (errno != EWOULDBLOCK && errno != EINTR) return true;
            if (std::chrono::steady_clock::now() > until) return false;
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        return true;
    }

    std::vector<int> m_fds;
};

// A copy of the old file at `target` under a hidden name beside it, with its mode; false when
// it cannot be read or the copy cannot be written.
bool copyOld(const fs::path& target, const struct stat& st, std::string& kept) {
    const int in = ::open(target.c_str(), O_RDONLY | O_CLOEXEC);
    if (in < 0) return false;
    std::string name = hiddenPattern(target, "old");
    const int out = ::mkstemp(name.data());
    bool ok = out >= 0 && ::fchmod(out, st.st_mode & 07777) == 0;
    std::vector<char> buf(std::size_t{1} << 16);
    while (ok) {
        const ssize_t n = ::read(in, buf.data(), buf.size());
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            ok = n == 0;
            break;
        }
        for (ssize_t done = 0; ok && done < n;) {
            const ssize_t w = ::write(out, buf.data() + done, static_cast<std::size_t>(n - done));
            ok = w > 0 || (w < 0 && errno == EINTR);
            done += std::max<ssize_t>(w, 0);
        }
    }
    ::close(in);
    if (out >= 0 && ::close(out) != 0) ok = false;
    if (!ok && out >= 0) ::unlink(name.c_str());
    if (ok) kept = name;
    return ok;
}

// A hard link to the old file under a hidden name beside it; false when it cannot be made.
bool linkOld(const fs::path& target, std::string& kept) {
    std::mt19937_64 random(std::random_device{}());
    static const char kChars[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
    for (int attempt = 0; attempt < 100; ++attempt) {
        std::string name = hiddenPattern(target, "old");
        for (std::size_t k = name.size() - 6; k < name.size(); ++k)
            name[k] = kChars[random() % (sizeof kChars - 1)];
        if (::link(target.c_str(), name.c_str()) == 0) {
            kept = name;
            return true;
        }
        if (errno != EEXIST) return false;
    }
    return false;
}

// Whether a sticky folder keeps us from replacing (renaming over) the file: it lets only the
// file's owner, the folder's owner and root do that. Asked before anything changes, so a set
// with such a file is refused whole.
bool stickyRefuses(const fs::path& target, const struct stat& file) {
    struct stat dir {};
    if (::geteuid() == 0 || ::stat(folderOf(target).c_str(), &dir) != 0) return false;
    return (dir.st_mode & S_ISVTX) != 0 && file.st_uid != ::geteuid() && dir.st_uid != ::geteuid();
}

// Pre-flight for one output: keeps its old file (step 3 of the commit).
void keepOld(Step& s) {
    const Pending& p = *s.p;
    struct stat st {};
    if (::lstat(p.target.c_str(), &st) != 0) return;  // Keep::Nothing
    if (p.folder()) {
        s.keep = Keep::Folder;
        return;
    }
    if (stickyRefuses(p.target, st))
        cannotWrite(p.out->path, errnoText(EPERM) +
                                     " (it belongs to another user, in a sticky "
                                     "folder: only its owner may replace it)");
    if (linkOld(p.target, s.kept))
        s.keep = Keep::Link;
    else if (copyOld(p.target, st, s.kept))
        s.keep = Keep::Copy;
    else
        s.keep = Keep::None;
}

// Puts a folder in place of the old one: one atomic swap where the system has it (the old one
// then sits under the temporary's name), else the old one renamed aside first.
int swapFolder(Step& s) {
    Pending& p = *s.p;
#if defined(__linux__) && !defined(__EMSCRIPTEN__) && defined(RENAME_EXCHANGE)
    if (::renameat2(AT_FDCWD, p.temp.c_str(), AT_FDCWD, p.target.c_str(), RENAME_EXCHANGE) == 0) {
        s.kept = p.temp;
        return 0;
    }
    if (errno != EINVAL && errno != ENOSYS) return errno;
#endif
    std::string aside = hiddenPattern(p.target, "old");
    if (!::mkdtemp(aside.data())) return errno;
    if (::rename(p.target.c_str(), aside.c_str()) != 0) {
        const int e = errno;
        ::rmdir(aside.c_str());
        return e;
    }
    if (::rename(p.temp.c_str(), p.target.c_str()) != 0) {
        const int e = errno;
        ::rename(aside.c_str(), p.target.c_str());
        return e;
    }
    s.kept = aside;
    return 0;
}

// Step 4 for one output: 0, or the errno of the failed rename.
int renameIn(Step& s) {
    Pending& p = *s.p;
    if (s.keep == Keep::Folder) return swapFolder(s);
    return ::rename(p.temp.c_str(), p.target.c_str()) == 0 ? 0 : errno;
}

// Undoes a done rename; false when the old file could not be put back (it stays in s.kept).
bool undo(Step& s) {
    Pending& p = *s.p;
    switch (s.keep) {
        case Keep::Nothing:
            if (p.folder()) {
                std::error_code ec;
                return fs::remove_all(p.target, ec) != static_cast<std::uintmax_t>(-1);
            }
            return ::unlink(p.target.c_str()) == 0;
        case Keep::Link:
        case Keep::Copy: return ::rename(s.kept.c_str(), p.target.c_str()) == 0;
        case Keep::Folder: {
            // The new folder back under the temporary's name (removed with it), the old in place.
            std::string back = hiddenPattern(p.target, "tmp");
            if (!::mkdtemp(back.data()) || ::rename(p.target.c_str(), back.c_str()) != 0)
                return false;
            if (::rename(s.kept.c_str(), p.target.c_str()) != 0) return false;
            if (s.kept == p.temp) p.temp = back;  // after a swap: the temporary's name moved
            std::error_code ec;
            fs::remove_all(back, ec);
            return true;
        }
        case Keep::None: return false;
    }
    return false;
}

// The order of step 4: copies first (a file that could not be linked is likely not ours, the
// rename most likely to fail: nothing is undone then), the unkept one last.
int renameRank(Keep k) {
    switch (k) {
        case Keep::Copy: return 0;
        case Keep::None: return 2;
        default: return 1;
    }
}

// Removes what step 3 kept: the old files (after success), or those of a refused set.
void dropKept(std::vector<Step>& steps) {
    for (Step& s : steps) {
        if (s.kept.empty()) continue;
        std::error_code ec;
        if (s.keep == Keep::Folder)
            fs::remove_all(s.kept, ec);
        else
            ::unlink(s.kept.c_str());
        if (s.kept == s.p->temp) s.p->temp.clear();
        s.kept.clear();
    }
}

// Undoes the done renames after `failed`'s, newest first, and throws the failure; the message
// names any old file that could not be put back and where it is.
[[noreturn]] void rollBack(std::vector<Step>& steps, const Step& failed, int error) {
    std::string lost;
    for (auto it = steps.rbegin(); it != steps.rend(); ++it) {
        if (!it->done) continue;
        if (undo(*it)) {
            it->done = false;
            it->kept.clear();  // back in place
            continue;
        }
        lost +=
            "; " + it->p->out->path + " could not be put back: its old content is in " + it->kept;
        it->kept.clear();  // kept for the user
    }
    dropKept(steps);
    cannotWrite(failed.p->out->path, errnoText(error) + lost);
}

void commit(std::vector<Pending>& pending) {
    std::vector<Step> steps;
    for (Pending& p : pending) {
        if (!p.temp.empty()) steps.push_back(Step{&p});
    }
    if (steps.empty()) return;
    const FolderLocks locks(steps);  // waiting for another writer, Ctrl-C still works
    const SignalsHeld held;
    try {
        for (Step& s : steps) keepOld(s);
        const auto unkept = std::count_if(steps.begin(), steps.end(),
                                          [](const Step& s) { return s.keep == Keep::None; });
        if (unkept > 1) {
            const auto it = std::find_if(steps.rbegin(), steps.rend(),
                                         [](const Step& s) { return s.keep == Keep::None; });
            cannotWrite(it->p->out->path,
                        "its old file can be neither linked nor copied aside, so it could not be "
                        "put back if another file of the set failed");
        }
    } catch (...) {
        dropKept(steps);
        throw;
    }
    std::stable_sort(steps.begin(), steps.end(), [](const Step& a, const Step& b) {
        return renameRank(a.keep) < renameRank(b.keep);
    });
    for (Step& s : steps) {
        if (const int e = renameIn(s); e != 0) rollBack(steps, s, e);
        s.done = true;
        if (s.kept != s.p->temp) {
            s.p->temp.clear();  // now the file itself
        }
        untrack(s.p->slot);
    }
    locks.sync();
    dropKept(steps);
}

}  // namespace

//-----------------------------------------------------------------------------------------------
// [SECTION] writeTextFiles
//-----------------------------------------------------------------------------------------------

void writeTextFiles(const std::vector<OutputFile>& outputs,
                    const std::vector<std::string>& inputs) {
    checkOutputFiles(outputs, inputs);
    std::vector<Pending> pending(outputs.size());
    try {
        for (std::size_t k = 0; k < outputs.size(); ++k) {
            pending[k].out = &outputs[k];
            pending[k].target = targetOf(outputs[k].path);
            prepare(pending[k]);
        }
        for (Pending& p : pending) {
            if (p.folder())
                p.out->fill(p.temp);
            else
                writeBody(p);
        }
        commit(pending);
    } catch (...) {
        for (Pending& p : pending) removeTemp(p);
        throw;
    }
    for (Pending& p : pending) removeTemp(p);
}

void writeTextFile(const std::string& path, const std::function<void(std::ostream&)>& body) {
    writeTextFiles({OutputFile{path, body, {}}});
}

}  // namespace dlab
