#include "bake/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>

namespace stipple::bake {

namespace {

// The temp file being written, for remove_pending_temp_file (a signal handler): the name
// lives in a static buffer, and g_pending is set only while the file exists.
char g_temp_path[4096];
volatile sig_atomic_t g_pending = 0;

// Blocks SIGINT/SIGTERM while alive, so the handler never sees a half-updated g_pending.
class SignalBlock {
  public:
    SignalBlock() {
        sigset_t set;
        sigemptyset(&set);
        sigaddset(&set, SIGINT);
        sigaddset(&set, SIGTERM);
        pthread_sigmask(SIG_BLOCK, &set, &previous_);
    }
    ~SignalBlock() { pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }
    SignalBlock(const SignalBlock&) = delete;
    SignalBlock& operator=(const SignalBlock&) = delete;

  private:
    sigset_t previous_;
};

BakeError io_error(const std::string& what, const std::string& path, int error) {
    return bake_error(BakeErrorCode::io, what + " '" + path + "': " + std::strerror(error));
}

bool write_all(int fd, const uint8_t* data, size_t size) {
    while (size > 0) {
        const ssize_t n = ::write(fd, data, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        data += n;
        size -= size_t(n);
    }
    return true;
}

std::string folder_of(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    if (slash == std::string::npos) return ".";
    return slash == 0 ? "/" : path.substr(0, slash);
}

// Creates the temp file; on success g_temp_path names it and g_pending is set.
BakeError create_temp(const std::string& path, int* fd) {
    const std::string pattern = path + ".XXXXXX";
    if (pattern.size() >= sizeof(g_temp_path))
        return bake_error(BakeErrorCode::io, "output path too long: '" + path + "'");
    SignalBlock block;
    std::memcpy(g_temp_path, pattern.c_str(), pattern.size() + 1);
    *fd = ::mkostemp(g_temp_path, O_CLOEXEC);
    if (*fd < 0) return io_error("cannot open a temporary file for", path, errno);
    g_pending = 1;
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(*fd, 0666 & ~mask);
    return BakeError();
}

void discard_temp(int fd) {
    SignalBlock block;
    if (fd >= 0) ::close(fd);
    if (g_pending) ::unlink(g_temp_path);
    g_pending = 0;
}

}  // namespace

void remove_pending_temp_file() noexcept {
    if (g_pending) ::unlink(g_temp_path);
    g_pending = 0;
}

BakeError write_file_atomically(const std::string& path, const std::vector<uint8_t>& bytes) {
    int fd = -1;
    BakeError error = create_temp(path, &fd);
    if (!error.ok()) return error;
    const std::string temp = g_temp_path;
    if (!write_all(fd, bytes.data(), bytes.size())) {
        error = io_error("cannot write", temp, errno);
    } else if (::fsync(fd) != 0) {
        error = io_error("cannot flush", temp, errno);
    }
    if (!error.ok()) {
        discard_temp(fd);
        return error;
    }
    const int closed = ::close(fd);
    if (closed != 0) {
        error = io_error("cannot write", temp, errno);
        discard_temp(-1);
        return error;
    }
    {
        SignalBlock block;
        if (::rename(temp.c_str(), path.c_str()) != 0) {
            error = io_error("cannot rename the temporary file to", path, errno);
            ::unlink(temp.c_str());
        }
        g_pending = 0;
    }
    if (!error.ok()) return error;
    // The rename is durable only once the folder's entry is on disk.
    const int dir = ::open(folder_of(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir >= 0) {
        ::fsync(dir);
        ::close(dir);
    }
    return BakeError();
}

}  // namespace stipple::bake
