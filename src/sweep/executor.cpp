#include "sweep/executor.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <thread>

extern char** environ;  // NOLINT: POSIX

namespace snapjump::sweep {

namespace fs = std::filesystem;

namespace {

// The last lines of a log that say what went wrong.
std::string tail_of(const fs::path& log, std::size_t lines) {
  std::ifstream f(log);
  std::vector<std::string> all;
  for (std::string l; std::getline(f, l);) {
    if (!l.empty()) all.push_back(l);
  }
  std::string out;
  for (std::size_t i = all.size() > lines ? all.size() - lines : 0; i < all.size(); ++i) {
    out += all[i];
    out += '\n';
  }
  return out;
}

// Starts `snapjump run ...` for one run with its output in the run's log. Returns the pid.
pid_t spawn_run(const ExecOptions& o, const std::vector<std::string>& args, const fs::path& log) {
  std::vector<std::string> env_text;
  for (char** e = environ; *e != nullptr; ++e) {
    if (std::strncmp(*e, "OMP_NUM_THREADS=", 16) != 0 &&
        std::strncmp(*e, "SNAPJUMP_SWEEP_PARENT=", 22) != 0) {
      env_text.emplace_back(*e);
    }
  }
  env_text.push_back(fmt::format("OMP_NUM_THREADS={}", o.threads));
  // A sweep fills the machine (jobs x threads = cores): threads that spin while they wait then
  // make a run many times slower (docs/performance.md, "Threads under load"), so its runs wait
  // passively unless the user chose a policy.
  if (std::getenv("OMP_WAIT_POLICY") == nullptr) env_text.emplace_back("OMP_WAIT_POLICY=passive");
  // The child ties its life to this process (app/run.cpp): a sweep killed with -9 leaves no
  // runs going on that a restarted sweep would start a second time.
  env_text.push_back(fmt::format("SNAPJUMP_SWEEP_PARENT={}", ::getpid()));
  std::vector<char*> envp;
  for (auto& s : env_text) envp.push_back(s.data());
  envp.push_back(nullptr);

  std::vector<std::string> argv_text = {o.executable.string()};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& s : argv_text) argv.push_back(s.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  const std::string log_path = log.string();
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_path.c_str(),
                                   O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    throw std::runtime_error(
        fmt::format("cannot start {}: {}", o.executable.string(), std::strerror(rc)));
  }
  return pid;
}

std::string duration(double s) {
  if (s < 90) return fmt::format("{:.0f} s", s);
  if (s < 5400) return fmt::format("{:.1f} min", s / 60);
  return fmt::format("{:.1f} h", s / 3600);
}

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point a) {
  return std::chrono::duration<double>(Clock::now() - a).count();
}

// A run's process going on, by its pid.
struct Running {
  std::size_t run;
  Clock::time_point start;
};
using RunningRuns = std::map<pid_t, Running>;

// Starts the run the work source names next (resumed from its checkpoint, or from nothing);
// false when the source has none left.
bool start_next(const Spec& spec, const std::vector<std::size_t>& todo, const WorkSource& next,
                const ExecOptions& o, std::ostream& log, RunningRuns& running) {
  const auto k = next();
  if (!k) return false;
  if (*k >= todo.size()) return false;
  const std::size_t i = todo[*k];
  const auto& run = spec.runs[i];
  const auto p = paths_of(spec, run);
  auto state = state_of(p);
  std::vector<std::string> args;
  if (state == RunState::Failed && resumes_after_kill(p)) {
    // Killed from outside after a checkpoint: go on from it.
    fs::remove(p.failed);
    state = RunState::Resumable;
  }
  if (state == RunState::Failed || state == RunState::Interrupted) {
    // Start again from nothing: the run's folder is the sweep's own.
    fs::remove_all(p.dir);
    fs::remove(p.failed);
    state = RunState::New;
  }
  if (state == RunState::Done) return true;  // finished meanwhile (another process)
  if (state == RunState::Resumable) {
    args = {"run", "--resume", p.dir.string(), "--quiet"};
  } else {
    args = {"run", p.case_file.string(), "--output", p.dir.string(), "--quiet"};
  }
  {
    std::ofstream l(p.log, std::ios::app);
    l << fmt::format("== {} {}\n", state == RunState::Resumable ? "resuming" : "starting",
                     run.name);
  }
  const pid_t pid = spawn_run(o, args, p.log);
  running[pid] = {i, Clock::now()};
  std::string what;
  for (const auto& s : run.settings) what += fmt::format(" {}={}", s.key, s.text);
  log << fmt::format("{}{} {}{}\n", o.label, run.name,
                     state == RunState::Resumable ? "resumed" : "started", what)
      << std::flush;
  return true;
}

// How a run whose process ended stands (finished, interrupted by a stop, or failed: then its
// failed file says why), counted in the report and logged.
void record_end(const Spec& spec, std::size_t i, double took, int status, bool stopping,
                const ExecOptions& o, std::ostream& log, ExecReport& report) {
  const auto& run = spec.runs[i];
  const auto p = paths_of(spec, run);
  const auto state = state_of(p);
  std::string how;
  if (WIFEXITED(status)) {
    how = fmt::format("exit status {}", WEXITSTATUS(status));
  } else if (WIFSIGNALED(status)) {
    how = fmt::format("killed by signal {} ({})", WTERMSIG(status), strsignal(WTERMSIG(status)));
  }
  if (state == RunState::Done) {
    ++report.finished;
    log << fmt::format("{}{} finished in {}\n", o.label, run.name, duration(took));
  } else if (stopping && (state == RunState::Resumable || state == RunState::Interrupted)) {
    ++report.interrupted;
    log << fmt::format(
        "{}{} interrupted after {} ({})\n", o.label, run.name, duration(took),
        state == RunState::Resumable ? "it resumes from its checkpoint" : "it starts again");
  } else {
    ++report.failed;
    const std::string why = fmt::format("{}; log {}:\n{}", how, p.log.string(), tail_of(p.log, 4));
    std::ofstream f(p.failed);
    f << why;
    log << fmt::format("{}{} FAILED after {} ({}); see {}\n", o.label, run.name, duration(took),
                       how, p.log.string());
  }
}

// The progress line after a run ended; one process that sees the whole sweep (no label) also
// estimates what is left from the mean run-seconds `busy` of those done here.
void log_progress(const ExecReport& report, std::size_t todo, std::size_t running, double busy,
                  double elapsed, const ExecOptions& o, std::ostream& log) {
  const int done_here = report.finished + report.failed + report.interrupted;
  std::string eta;
  if (o.label.empty()) {
    const double mean = busy / done_here;
    const auto left = static_cast<double>(todo - static_cast<std::size_t>(done_here));
    eta = fmt::format(" of {}, about {} to go", todo, duration(mean * left / std::max(1, o.jobs)));
  }
  log << fmt::format("{}{} run(s) done{}, {} running, {} elapsed\n", o.label, done_here, eta,
                     running, duration(elapsed))
      << std::flush;
}

}  // namespace

fs::path self_executable() { return fs::read_symlink("/proc/self/exe"); }

std::vector<std::size_t> runs_to_do(const Spec& spec, bool retry_failed) {
  std::vector<std::size_t> todo;
  for (std::size_t i = 0; i < spec.runs.size(); ++i) {
    const auto s = state_of(paths_of(spec, spec.runs[i]));
    if (s == RunState::Done || (s == RunState::Failed && !retry_failed)) continue;
    todo.push_back(i);
  }
  return todo;
}

ExecReport execute(const Spec& spec, const std::vector<std::size_t>& todo, const WorkSource& next,
                   const ExecOptions& o, std::ostream& log, const std::function<void()>& idle) {
  const auto t0 = Clock::now();
  RunningRuns running;
  ExecReport report;
  double busy = 0.0;  // run-seconds finished here
  bool exhausted = false;
  std::optional<Clock::time_point> stop_at;
  bool forwarded = false;
  while (true) {
    if (!stop_at && o.stop_requested && o.stop_requested()) {
      stop_at = Clock::now();
      report.stopped = true;
      exhausted = true;
      log << fmt::format("{}stopping: no run is started; waiting for the {} running\n", o.label,
                         running.size())
          << std::flush;
    }
    if (stop_at && !forwarded && seconds_since(*stop_at) > kForwardAfter) {
      for (const auto& [pid, r] : running) ::kill(pid, SIGINT);
      forwarded = true;
    }
    while (!exhausted && static_cast<int>(running.size()) < o.jobs) {
      if (!start_next(spec, todo, next, o, log, running)) exhausted = true;
    }
    if (running.empty()) break;
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid == 0) {
      if (idle) idle();
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      continue;
    }
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(fmt::format("waiting for runs: {}", std::strerror(errno)));
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const auto [i, start] = it->second;
    running.erase(it);
    const double took = seconds_since(start);
    busy += took;
    record_end(spec, i, took, status, stop_at.has_value(), o, log, report);
    log_progress(report, todo.size(), running.size(), busy, seconds_since(t0), o, log);
  }
  return report;
}

}  // namespace snapjump::sweep
