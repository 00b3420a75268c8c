// Baselines run as child processes: own address space (a crash or a timeout loses one case,
// not the run) and their own peak RSS from wait4.
#include <fcntl.h>
#include <poll.h>
#include <sched.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>

#include "bench.h"
#include "gdr/error.h"
#include "process_settings.h"

namespace gdr_bench {

ProcessResult run_process(const std::vector<std::string>& argv, double timeout_seconds,
                          const std::string& cwd) {
  int fds[2];
  if (pipe(fds) != 0) throw gdr::Error(gdr::Status::InternalError, "pipe failed");
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);

  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) throw gdr::Error(gdr::Status::InternalError, "fork failed");
  if (pid == 0) {
    // An OpenMP runtime with thread binding pins our main thread, and children inherit the
    // mask: give the baseline every CPU again so multi-threaded ones (TBB) see them all.
    cpu_set_t all;
    CPU_ZERO(&all);
    const long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    for (long i = 0; i < cpus && i < CPU_SETSIZE; ++i) CPU_SET(i, &all);
    sched_setaffinity(0, sizeof all, &all);
    dup2(fds[1], STDOUT_FILENO);
    close(fds[0]);
    close(fds[1]);
    if (!cwd.empty() && chdir(cwd.c_str()) != 0) {
      std::fprintf(stderr, "cannot enter %s: %s\n", cwd.c_str(), std::strerror(errno));
      _exit(127);
    }
    gdr::cli::restore_user_tunables();
    execv(args[0], args.data());
    std::fprintf(stderr, "cannot run %s: %s\n", args[0], std::strerror(errno));
    _exit(127);
  }
  close(fds[1]);

  ProcessResult r;
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  char buffer[4096];
  for (;;) {
    const double left = timeout_seconds - elapsed();
    if (left <= 0) {
      kill(pid, SIGKILL);
      r.timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = poll(&p, 1, static_cast<int>(std::min(left, 1.0) * 1000) + 1);
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n <= 0) break;  // child closed stdout (exited)
    r.out.append(buffer, static_cast<std::size_t>(n));
  }
  close(fds[0]);
  int status = 0;
  rusage usage{};
  while (wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  r.seconds = elapsed();
  r.max_rss_mb = usage.ru_maxrss / 1024.0;  // Linux reports kilobytes
  r.exit_code = r.timed_out ? -1 : (WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status));
  return r;
}

std::map<std::string, std::string> parse_json_line(const std::string& line) {
  std::map<std::string, std::string> out;
  std::size_t i = line.find('{');
  if (i == std::string::npos) return out;
  ++i;
  auto skip = [&] {
    while (i < line.size() && (line[i] == ' ' || line[i] == ',' || line[i] == '\t')) ++i;
  };
  auto quoted = [&] {
    std::string s;
    for (++i; i < line.size() && line[i] != '"'; ++i) {
      if (line[i] == '\\' && i + 1 < line.size()) ++i;
      s += line[i];
    }
    ++i;
    return s;
  };
  for (skip(); i < line.size() && line[i] == '"'; skip()) {
    const std::string key = quoted();
    while (i < line.size() && (line[i] == ' ' || line[i] == ':')) ++i;
    if (i < line.size() && line[i] == '"') {
      out[key] = quoted();
    } else {
      const std::size_t end = line.find_first_of(",}", i);
      out[key] = line.substr(i, end - i);
      i = end == std::string::npos ? line.size() : end;
    }
  }
  return out;
}

}  // namespace gdr_bench
