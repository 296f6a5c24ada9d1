#include "app/sweep_command.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <optional>
#include <thread>

#include "app/cli.hpp"
#include "app/run.hpp"
#include "io/folder_lock.hpp"
#include "sweep/executor.hpp"
#include "sweep/mpi_work.hpp"
#include "sweep/sweep.hpp"

namespace snapjump::app {

namespace fs = std::filesystem;

namespace {

int failed_runs(const sweep::Spec& spec) {
  int n = 0;
  for (const auto& r : spec.runs) {
    if (sweep::state_of(sweep::paths_of(spec, r)) == sweep::RunState::Failed) ++n;
  }
  return n;
}

}  // namespace

int run_here(const sweep::Spec& spec, sweep::ExecOptions options, int jobs, bool retry_failed,
             std::ostream& out) {
  const auto todo = sweep::runs_to_do(spec, retry_failed);
  const int cores = static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
  options.jobs = jobs > 0 ? jobs : std::max(1, cores / options.threads);
  fmt::print(out,
             "sweep {}: {} runs, {} to do ({} already finished or failed), {} at a time with {} "
             "thread(s) each; folder {}\n",
             spec.file.string(), spec.runs.size(), todo.size(), spec.runs.size() - todo.size(),
             options.jobs, options.threads, spec.output.string());
  std::size_t counter = 0;
  // Ctrl-C stops the sweep: no run started after it, the running ones stopped and waited for.
  const SigintStop stop;
  options.stop_requested = [&stop] { return stop.requested(); };
  const auto report = sweep::execute(
      spec, todo, [&] { return std::optional(counter++); }, options, out);
  const fs::path table = spec.output / "sweep.csv";
  const int with_result = sweep::write_table(spec, table);
  if (report.stopped) {
    fmt::print(out,
               "sweep stopped: {} of {} runs have a result, {} interrupted here; table {}; the "
               "same command again goes on (interrupted runs resume from their checkpoints)\n",
               with_result, spec.runs.size(), report.interrupted, table.string());
    return kExitInterrupted;
  }
  const int failed = failed_runs(spec);
  fmt::print(out, "sweep done: {} of {} runs have a result, {} failed ({} now); table {}\n",
             with_result, spec.runs.size(), failed, report.failed, table.string());
  return failed > 0 ? kExitFailure : kExitOk;
}

SweepCommand::SweepCommand(CLI::App& app) {
  cmd_ = app.add_subcommand(
      "sweep",
      "Run many poppers from a sweep file (a base case, values to vary): each run in its own "
      "folder, several at a time or over MPI processes (mpirun -n K snapjump sweep ...); "
      "finished runs are skipped when started again; one table (sweep.csv) at the end.");
  cmd_->add_option("sweep", file_, "sweep file (TOML; see docs/sweeps.md)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd_->add_option("--output", output_,
                   "the sweep's folder (default: the file's output key, or "
                   "runs/sweep-<file name>); running again into it resumes the sweep");
  cmd_->add_option("--jobs", jobs_,
                   "runs at the same time in this process (default: the cores divided by "
                   "--threads; 1 per process under MPI)")
      ->check(CLI::PositiveNumber);
  cmd_->add_option("--threads", threads_, "OpenMP threads per run (default 1)")
      ->check(CLI::PositiveNumber);
  cmd_->add_flag("--retry-failed", retry_failed_, "run again the runs that failed before");
  cmd_->add_flag("--dry-run", dry_run_, "list the runs and their states; run nothing");
  cmd_->add_flag("--table-only", table_only_, "only write sweep.csv from what has finished");
}

bool SweepCommand::parsed() const { return cmd_->parsed(); }

int SweepCommand::run(std::ostream& out, std::ostream& err) const {
  sweep::Spec spec;
  try {
    spec = sweep::load_spec(file_);
  } catch (const sweep::SweepError& e) {
    fmt::print(err, "error: {}\n", e.what());
    return kExitBadInput;
  }
  if (!output_.empty()) spec.output = output_;
  if (dry_run_) {
    list_runs(spec, out);
    return kExitOk;
  }
  sweep::ExecOptions options;
  options.executable = sweep::self_executable();
  options.threads = threads_;
  options.retry_failed = retry_failed_;
  if (sweep::launched_by_mpi()) return run_over_mpi(spec, options, out, err);
  return run_in_this_process(spec, options, out, err);
}

void SweepCommand::list_runs(const sweep::Spec& spec, std::ostream& out) const {
  fmt::print(out, "sweep {}: {} runs into {}\n", file_, spec.runs.size(), spec.output.string());
  for (const auto& r : spec.runs) {
    std::string what;
    for (const auto& s : r.settings) what += fmt::format("  {} = {}", s.key, s.text);
    fmt::print(out, "  {}  {:<11}{}\n", r.name,
               sweep::to_string(sweep::state_of(sweep::paths_of(spec, r))), what);
  }
}

int SweepCommand::run_over_mpi(const sweep::Spec& spec, sweep::ExecOptions options,
                               std::ostream& out, std::ostream& err) const {
  const fs::path table = spec.output / "sweep.csv";
  sweep::MpiWork mpi;
  const bool root = mpi.rank() == 0;
  bool ok = true;
  std::optional<io::FolderLock> lock;
  if (root) {
    try {
      if (!table_only_) {
        sweep::check_folder(spec);  // before the lock: a refused folder gets no lock file
        fs::create_directories(spec.output);
        lock.emplace(spec.output, "sweep.lock", "the sweep folder");
        sweep::prepare_folder(spec);
      }
    } catch (const std::exception& e) {
      fmt::print(err, "error: {}\n", error_text(e, "preparing the sweep"));
      ok = false;
    }
  }
  if (!mpi.all(ok)) return kExitBadInput;
  std::vector<std::size_t> todo;
  if (root && !table_only_) todo = sweep::runs_to_do(spec, retry_failed_);
  mpi.broadcast(todo);
  if (root) {
    fmt::print(out, "sweep {}: {} runs, {} to do, over {} MPI processes; folder {}\n", file_,
               spec.runs.size(), todo.size(), mpi.size(), spec.output.string());
  }
  options.jobs = jobs_ > 0 ? jobs_ : 1;
  options.label = fmt::format("rank {}: ", mpi.rank());
  sweep::ExecReport report;
  bool run_ok = true;
  try {
    report = sweep::execute(
        spec, todo, [&] { return std::optional(mpi.next()); }, options, out,
        [&] { mpi.progress(); });
  } catch (const std::exception& e) {
    fmt::print(err, "rank {}: error: {}\n", mpi.rank(), error_text(e, "running the sweep"));
    run_ok = false;
  }
  const long failed = mpi.sum(report.failed);
  run_ok = mpi.all(run_ok);
  if (root) {
    try {
      const int with_result = sweep::write_table(spec, table);
      const int all_failed = failed_runs(spec);
      fmt::print(out, "sweep done: {} of {} runs have a result, {} failed ({} now); table {}\n",
                 with_result, spec.runs.size(), all_failed, failed, table.string());
      if (all_failed > 0) run_ok = false;
    } catch (const std::exception& e) {
      fmt::print(err, "error: {}\n", error_text(e, "writing the sweep's table"));
      run_ok = false;
    }
  }
  return failed > 0 || !mpi.all(run_ok) ? kExitFailure : kExitOk;
}

int SweepCommand::run_in_this_process(const sweep::Spec& spec, const sweep::ExecOptions& options,
                                      std::ostream& out, std::ostream& err) const {
  try {
    if (!table_only_) {
      // One sweep per folder: a second one on the same folder is refused. The folder is checked
      // first, so a folder that is refused (one holding something else, "/", "..") gets no lock
      // file; prepare_folder checks it again under the lock.
      sweep::check_folder(spec);
      fs::create_directories(spec.output);
      const io::FolderLock lock(spec.output, "sweep.lock", "the sweep folder");
      sweep::prepare_folder(spec);
      return run_here(spec, options, jobs_, retry_failed_, out);
    }
    const fs::path table = spec.output / "sweep.csv";
    const int with_result = sweep::write_table(spec, table);
    fmt::print(out, "{} of {} runs have a result; table {}\n", with_result, spec.runs.size(),
               table.string());
    return kExitOk;
  } catch (const sweep::SweepError& e) {
    fmt::print(err, "error: {}\n", e.what());
    return kExitBadInput;
  } catch (const io::LockFileRefused& e) {
    fmt::print(err, "error: {}\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    fmt::print(err, "error: {}\n", error_text(e, "running the sweep"));
    return kExitFailure;
  }
}

}  // namespace snapjump::app
