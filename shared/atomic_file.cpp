#include "shared/atomic_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "shared/input_file.h"

namespace body {
namespace {

namespace fs = std::filesystem;

// The temporaries a signal handler may unlink: fixed storage, no allocation.
struct TempSlot {
    std::atomic<bool> used{false};
    std::atomic<bool> ready{false};
    char path[4096] = {};
};
std::array<TempSlot, 32> g_temps;

int register_temp(const std::string& path) {
    if (path.size() >= sizeof(TempSlot::path)) return -1;
    for (size_t i = 0; i < g_temps.size(); ++i) {
        bool expected = false;
        if (!g_temps[i].used.compare_exchange_strong(expected, true)) continue;
        std::memcpy(g_temps[i].path, path.c_str(), path.size() + 1);
        g_temps[i].ready = true;
        return int(i);
    }
    return -1;
}

void unregister_temp(int slot) {
    if (slot < 0) return;
    g_temps[size_t(slot)].ready = false;
    g_temps[size_t(slot)].used = false;
}

// Removes `name` under directory fd `parent`, a directory with everything in
// it: only system calls (getdents64, unlinkat, openat), so a signal handler
// may call it. Deeper than 16 levels is left (our staged trees have 2).
void remove_tree_at(int parent, const char* name, int depth) {
    if (::unlinkat(parent, name, 0) == 0 || errno != EISDIR || depth > 16) return;
    const int fd = ::openat(parent, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) return;
    alignas(8) char buf[2048];
    for (bool removed = true; removed;) {  // entries removed while listing may hide others: list again
        removed = false;
        ::lseek(fd, 0, SEEK_SET);
        for (ssize_t n; (n = ::getdents64(fd, buf, sizeof buf)) > 0;) {
            for (ssize_t off = 0; off < n;) {
                const auto* d = reinterpret_cast<const struct dirent64*>(buf + off);
                off += d->d_reclen;
                if (std::strcmp(d->d_name, ".") == 0 || std::strcmp(d->d_name, "..") == 0) continue;
                remove_tree_at(fd, d->d_name, depth + 1);
                removed = true;
            }
        }
        if (removed && ::unlinkat(parent, name, AT_REMOVEDIR) == 0) break;
    }
    ::close(fd);
    ::unlinkat(parent, name, AT_REMOVEDIR);
}

extern "C" void unlink_temporaries(int sig) {
    const int saved = errno;
    for (TempSlot& t : g_temps)
        if (t.ready) remove_tree_at(AT_FDCWD, t.path, 0);  // files and staged directories alike
    errno = saved;
    ::signal(sig, SIG_DFL);
    ::raise(sig);
}

// A registered temporary, unregistered (and removed unless kept) on scope exit.
class TempGuard {
public:
    explicit TempGuard(std::string path) : path_(std::move(path)), slot_(register_temp(path_)) {}
    ~TempGuard() {
        unregister_temp(slot_);
        if (!kept_) {
            std::error_code ignored;
            fs::remove_all(path_, ignored);
        }
    }
    void keep() { kept_ = true; }
    const std::string& path() const { return path_; }

private:
    std::string path_;
    int slot_;
    bool kept_ = false;
};

std::string temp_name(const std::string& path) { return path + ".tmp-" + std::to_string(::getpid()); }

}  // namespace

std::string renamed_in_message(std::string message, const std::string& from, const std::string& to) {
    if (from.empty()) return message;
    for (size_t at = message.find(from); at != std::string::npos; at = message.find(from, at + to.size()))
        message.replace(at, from.size(), to);
    return message;
}

ScratchPath::ScratchPath(const std::string& path) {
    sweep_stale_temporaries(path);
    path_ = temp_name(path);
    slot_ = register_temp(path_);
}

ScratchPath::~ScratchPath() {
    unregister_temp(slot_);
    std::error_code ignored;
    fs::remove_all(path_, ignored);
}

void remove_temporaries_on_signal() {
    struct sigaction sa {};
    sa.sa_handler = unlink_temporaries;
    sigemptyset(&sa.sa_mask);
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(sig, &sa, nullptr);
}

void sweep_stale_temporaries(const std::string& path) {
    fs::path p = fs::path(path).lexically_normal();
    if (p.filename().empty()) p = p.parent_path();
    const std::string prefix = p.filename().string() + ".tmp-";
    const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (!name.starts_with(prefix) || name.size() == prefix.size()) continue;
        const std::string digits = name.substr(prefix.size());
        if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) continue;
        const pid_t pid = pid_t(std::stol(digits));
        if (pid == ::getpid() || ::kill(pid, 0) == 0 || errno != ESRCH) continue;
        std::error_code ignored;
        fs::remove_all(it->path(), ignored);
    }
}

Status write_file_atomically(const std::string& path, const std::function<std::string(std::ostream&)>& write) {
    sweep_stale_temporaries(path);
    TempGuard temp(temp_name(path));
    std::string reason;
    {
        std::ofstream out(temp.path(), std::ios::binary | std::ios::trunc);
        if (!out) return runtime_error(path + ": cannot create file: " + std::strerror(errno));
        reason = write(out);
        out.close();  // checked: a file system may report a full disk only when the file is closed
        if (reason.empty() && !out) reason = "write failed (disk full?)";
    }
    if (reason.empty() && std::rename(temp.path().c_str(), path.c_str()) != 0)
        reason = std::string("cannot rename temporary file: ") + std::strerror(errno);
    if (!reason.empty()) return runtime_error(path + ": " + reason);
    temp.keep();  // renamed: nothing left to remove
    return ok_status();
}

Status write_file_atomically(const std::string& path, std::span<const uint8_t> bytes) {
    return write_file_atomically(path, [&](std::ostream& out) {
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        return std::string();
    });
}

Status write_directory_atomically(const std::string& dir, const std::function<Status(const std::string&)>& fill,
                                  const std::function<std::string(const std::string&)>& replaceable) {
    fs::path target = fs::path(dir).lexically_normal();
    if (target.filename().empty()) target = target.parent_path();
    std::error_code ec;
    const bool exists = fs::exists(target, ec);
    if (exists) {
        if (!fs::is_directory(target, ec)) return input_error(target.string() + ": exists and is not a directory");
        if (std::string why = replaceable(target.string()); !why.empty())
            return input_error(target.string() + ": " + why + "; not replacing it");
    }
    sweep_stale_temporaries(target.string());
    TempGuard staged(temp_name(target.string()));
    fs::remove_all(staged.path(), ec);
    fs::create_directories(staged.path(), ec);
    if (ec) return runtime_error(target.string() + ": cannot create the staging directory: " + ec.message());
    // The staged directory is gone once this returns: a failure names the output instead.
    if (Status st = fill(staged.path()); !st)
        return Error{renamed_in_message(st.error().message, staged.path(), target.string()), st.error().exit_code};
    fs::path old;
    if (exists) {
        old = target;
        old += ".old-" + std::to_string(::getpid());
        fs::rename(target, old, ec);
        if (ec) return runtime_error(target.string() + ": cannot move the old directory aside: " + ec.message());
    }
    fs::rename(staged.path(), target, ec);
    if (ec) {
        if (!old.empty()) fs::rename(old, target, ec);
        return runtime_error(target.string() + ": cannot rename the new directory into place: " + ec.message());
    }
    staged.keep();
    if (!old.empty()) fs::remove_all(old, ec);
    return ok_status();
}

Result<std::string> read_file(const std::string& path) {
    if (auto regular = check_regular_file(path); !regular) return regular.error();
    std::ifstream in(path, std::ios::binary);
    if (!in) return input_error(path + ": cannot open: " + std::strerror(errno));
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad()) return input_error(path + ": read failed");
    return buffer.str();
}

}  // namespace body
