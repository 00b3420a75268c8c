// TetGen in a child process (see tetgen_process.h). The child runs tetrahedralize on the
// input it inherited by fork, writes a header and the result's arrays into a pipe and
// exits; the parent reads them as they come, watching the clock and the abort hook.
#define TETLIBRARY
#include <tetgen.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <new>
#include <thread>

#include "cdt3d/tetgen_process.h"
#include "gdr/error.h"

namespace gdr::cdt3d {
namespace {

// What the child sends first; the arrays follow in this order, those flagged absent left out.
struct Header {
  std::int32_t code;  // 0: done; else the int TetGen threw (its exit codes)
  std::int32_t points, tets, corners, subfaces;
  std::int32_t has_point_markers, has_neighbours, has_subface_markers, has_subface_tets;
};

// TetGen's exit codes (tetgen.h, terminatetetgen) as our errors.
[[noreturn]] void throw_tetgen_code(int code) {
  switch (code) {
    case 1: throw Error(Status::OutOfDeviceMemory, "TetGen ran out of memory");
    case 3: throw Error(Status::SelfIntersectingInput, "TetGen found a self-intersection (within its tolerance)");
    case 4: throw Error(Status::InvalidInput, "TetGen found a very small input feature (below its tolerance)");
    case 5: throw Error(Status::InvalidInput, "TetGen found two very close input facets");
    case 2: throw Error(Status::InternalError, "TetGen reported an internal error (code 2)");
    default: throw Error(Status::InvalidInput, "TetGen failed (code " + std::to_string(code) + ")");
  }
}

int tetrahedralize_code(const std::string& switches, tetgenio& in, tetgenio& out) {
  tetgenbehavior behavior;
  std::string buffer = switches;
  if (!behavior.parse_commandline(buffer.data()))
    throw Error(Status::InternalError, "TetGen rejected the switches '" + switches + "'");
  try {
    tetrahedralize(&behavior, &in, &out);
  } catch (int code) {
    return code;
  } catch (const std::bad_alloc&) {
    return 1;
  }
  return 0;
}

bool write_all(int fd, const void* data, std::size_t bytes) {
  const char* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t n = ::write(fd, p, bytes);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    bytes -= static_cast<std::size_t>(n);
  }
  return true;
}

[[noreturn]] void child(const std::string& switches, tetgenio& in, int fd) {
#ifdef __linux__
  prctl(PR_SET_PDEATHSIG, SIGKILL);  // a parent killed meanwhile takes TetGen with it
#endif
  // The parent's handlers (ParaView's logger prints a stack trace and "FATL" on SIGABRT)
  // are not for an assertion in TetGen here: the parent reports it and tries again.
  for (const int sig : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL}) std::signal(sig, SIG_DFL);
  tetgenio out;
  Header h{};
  h.code = tetrahedralize_code(switches, in, out);
  if (h.code == 0) {
    h.points = out.numberofpoints;
    h.tets = out.numberoftetrahedra;
    h.corners = out.numberofcorners;
    h.subfaces = out.numberoftrifaces;
    h.has_point_markers = out.pointmarkerlist != nullptr;
    h.has_neighbours = out.neighborlist != nullptr;
    h.has_subface_markers = out.trifacemarkerlist != nullptr;
    h.has_subface_tets = out.adjtetlist != nullptr;
  }
  const auto n = [](std::int32_t a, std::int32_t b) { return static_cast<std::size_t>(a) * b; };
  bool ok = write_all(fd, &h, sizeof h);
  if (ok && h.code == 0) {
    ok = write_all(fd, out.pointlist, n(h.points, 3) * sizeof(REAL)) &&
         (!h.has_point_markers || write_all(fd, out.pointmarkerlist, n(h.points, 1) * sizeof(int))) &&
         write_all(fd, out.tetrahedronlist, n(h.tets, h.corners) * sizeof(int)) &&
         (!h.has_neighbours || write_all(fd, out.neighborlist, n(h.tets, 4) * sizeof(int))) &&
         write_all(fd, out.trifacelist, n(h.subfaces, 3) * sizeof(int)) &&
         (!h.has_subface_markers || write_all(fd, out.trifacemarkerlist, n(h.subfaces, 1) * sizeof(int))) &&
         (!h.has_subface_tets || write_all(fd, out.adjtetlist, n(h.subfaces, 2) * sizeof(int)));
  }
  _exit(ok ? 0 : 1);  // no destructors, no atexit handlers: they belong to the parent
}

using Clock = std::chrono::steady_clock;

// Reads the child's bytes as they come: false on end of file or a read error (the child
// died), TimedOut past the deadline; `cancel` polled every 50 ms.
struct Reader {
  int fd;
  Clock::time_point deadline;
  const std::function<bool()>& cancel;
  bool timed_out = false, cancelled = false;

  bool read(void* data, std::size_t bytes) {
    char* p = static_cast<char*>(data);
    while (bytes > 0) {
      if (cancel && cancel()) return cancelled = true, false;
      if (Clock::now() > deadline) return timed_out = true, false;
      pollfd pfd{fd, POLLIN, 0};
      const int r = ::poll(&pfd, 1, 50);
      if (r < 0 && errno != EINTR) return false;
      if (r <= 0) continue;
      const ssize_t n = ::read(fd, p, bytes);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return false;
      p += n;
      bytes -= static_cast<std::size_t>(n);
    }
    return true;
  }
  template <class T>
  bool array(T*& into, std::size_t count) {
    into = new T[count > 0 ? count : 1];
    return read(into, count * sizeof(T));
  }
};

}  // namespace

TetGenOutcome run_tetgen_process(const std::string& switches, tetgenio& in, tetgenio& out,
                                 double seconds, const std::function<bool()>& cancel) {
  int fds[2];
  const bool piped = ::pipe(fds) == 0;
  const pid_t pid = piped ? ::fork() : -1;
  if (pid < 0) {  // no pipe or process to spare: TetGen here, unguarded
    if (piped) {
      ::close(fds[0]);
      ::close(fds[1]);
    }
    const int code = tetrahedralize_code(switches, in, out);
    if (code != 0) throw_tetgen_code(code);
    return {};
  }
  if (pid == 0) {
    ::close(fds[0]);
    child(switches, in, fds[1]);
  }
  ::close(fds[1]);
#ifdef F_SETPIPE_SZ
  ::fcntl(fds[0], F_SETPIPE_SZ, 1 << 20);  // fewer wake-ups for large results (best effort)
#endif
  Reader r{fds[0], Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds)),
           cancel};
  Header h{};
  bool ok = r.read(&h, sizeof h);
  if (ok && h.code == 0) {
    out.deinitialize();
    out.initialize();
    out.firstnumber = in.firstnumber;
    out.numberofpoints = h.points;
    out.numberoftetrahedra = h.tets;
    out.numberofcorners = h.corners;
    out.numberoftrifaces = h.subfaces;
    const auto n = [](std::int32_t a, std::int32_t b) { return static_cast<std::size_t>(a) * b; };
    ok = r.array(out.pointlist, n(h.points, 3)) &&
         (!h.has_point_markers || r.array(out.pointmarkerlist, n(h.points, 1))) &&
         r.array(out.tetrahedronlist, n(h.tets, h.corners)) &&
         (!h.has_neighbours || r.array(out.neighborlist, n(h.tets, 4))) &&
         r.array(out.trifacelist, n(h.subfaces, 3)) &&
         (!h.has_subface_markers || r.array(out.trifacemarkerlist, n(h.subfaces, 1))) &&
         (!h.has_subface_tets || r.array(out.adjtetlist, n(h.subfaces, 2)));
  }
  ::close(fds[0]);
  int status = 0;
  if (ok) {  // the child is exiting: its memory is freed while we go on (tens of ms)
    if (::waitpid(pid, &status, WNOHANG) == 0) std::thread([pid] { ::waitpid(pid, nullptr, 0); }).detach();
  } else {
    ::kill(pid, SIGKILL);
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
  }
  if (r.cancelled) throw Error(Status::Aborted, "aborted during TetGen's tetrahedralization");
  if (r.timed_out) return {TetGenOutcome::TimedOut, SIGKILL};
  if (!ok) {
    if (WIFSIGNALED(status)) return {TetGenOutcome::Crashed, WTERMSIG(status)};
    throw Error(Status::InternalError, "TetGen's process ended without a result (exit status " +
                                           std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
  }
  if (h.code != 0) throw_tetgen_code(h.code);
  return {};
}

}  // namespace gdr::cdt3d
