#pragma once

// Persistent worker threads for the render phases. Work is a count of independent tasks;
// which thread runs which task does not matter for the result (every task writes its own
// outputs), so any thread count gives the same bytes.

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "FunctionRef.h"

namespace facet::detail {

// Work a job's tasks need done first (ThreadPool::run), without a wake-up of the workers of its
// own: a thread that finds only the later tasks left waits for the first stage's running ones.
struct FirstStage {
  std::size_t count = 0;
  FunctionRef<void(std::size_t)> task;
};

class ThreadPool {
 public:
  /// `threads` counts the calling thread too: ThreadPool(1) starts no worker.
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int threadCount() const { return static_cast<int>(workers_.size()) + 1; }
  /// The hardware's threads (at least 1): the count a thread count of 0 asks for.
  static int hardwareThreads();

  /// Runs task(i) for every i in [0, count) on all threads, the caller included, and
  /// returns when all have finished. After each task the *caller* runs, it calls
  /// afterCallerTask(tasksFinishedSoFar); when that returns false no further task starts and
  /// run() returns false once the running ones finish. A task that throws cancels the job
  /// (or an afterCallerTask that throws) the same way, and run() rethrows its exception once every
  /// thread has left the job (a worker's would otherwise end the program, and the caller's would
  /// leave workers running a task whose captures are gone). Allocates nothing unless a task throws.
  ///
  /// `first`: tasks that all finish before any of `task`'s starts, on whichever thread, in
  /// the same job (FirstStage). afterCallerTask counts only `task`'s.
  bool run(std::size_t count, FunctionRef<void(std::size_t)> task,
           FunctionRef<bool(std::size_t)> afterCallerTask = {}, FirstStage first = {});

 private:
  void workerLoop();
  void runTasks();
  bool succeeds(FunctionRef<void()> work);
  enum class Took { FirstStageTask, Task, Stop };
  Took runNextTask();
  bool runFirstStageTask(std::size_t i);
  bool awaitFirstStage();

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable finished_;
  std::size_t generation_ = 0;  // guarded by mutex_
  int busyWorkers_ = 0;         // guarded by mutex_: workers inside the current job
  bool open_ = false;           // guarded by mutex_: workers may still join the current job
  bool stopping_ = false;       // guarded by mutex_
  std::exception_ptr failure_;  // guarded by mutex_: the current job's first exception

  // The current job; written by run() before the generation is published under mutex_.
  std::size_t count_ = 0;
  FunctionRef<void(std::size_t)> task_;
  FirstStage first_;                       // task indices [0, first_.count) are its
  std::atomic<std::size_t> firstDone_{0};  // its tasks finished (release: their writes seen)
  std::atomic<std::size_t> next_{0};
  std::atomic<std::size_t> done_{0};
  std::atomic<bool> cancelled_{false};
};

}  // namespace facet::detail
