#include "ThreadPool.h"

#include <utility>

namespace facet::detail {

ThreadPool::ThreadPool(int threads) {
  for (int i = 1; i < threads; ++i)
    workers_.emplace_back([this] { workerLoop(); });
}

int ThreadPool::hardwareThreads() {
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : static_cast<int>(n);
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (std::thread& worker : workers_)
    worker.join();
}

// Runs work; if it throws, keeps the job's first exception for run() and cancels the job.
bool ThreadPool::succeeds(FunctionRef<void()> work) {
  try {
    work();
    return true;
  } catch (...) {
    std::lock_guard lock(mutex_);
    if (!failure_) failure_ = std::current_exception();
    cancelled_.store(true);
    return false;
  }
}

// The first stage's task i; false if it threw (the job is cancelled).
bool ThreadPool::runFirstStageTask(std::size_t i) {
  auto runTask = [&] { first_.task(i); };
  if (!succeeds(runTask)) return false;
  firstDone_.fetch_add(1, std::memory_order_release);
  return true;
}

// Waits until every task of the first stage has finished (all were taken: a thread asks only
// after taking a later index), yielding the core to them; false if the job was cancelled.
bool ThreadPool::awaitFirstStage() {
  while (firstDone_.load(std::memory_order_acquire) < first_.count) {
    if (cancelled_.load(std::memory_order_relaxed)) return false;
    std::this_thread::yield();
  }
  return true;
}

// Takes the job's next index and runs its task: a first-stage one, or one of task_ once the
// whole first stage has finished. Stop: the job is over for this thread (no task left, the job
// cancelled, or the task threw).
ThreadPool::Took ThreadPool::runNextTask() {
  const std::size_t i = next_.fetch_add(1, std::memory_order_relaxed);
  if (i < first_.count) return runFirstStageTask(i) ? Took::FirstStageTask : Took::Stop;
  if (i - first_.count >= count_ || !awaitFirstStage()) return Took::Stop;
  auto runTask = [&] { task_(i - first_.count); };
  return succeeds(runTask) ? Took::Task : Took::Stop;
}

void ThreadPool::runTasks() {
  while (!cancelled_.load(std::memory_order_relaxed)) {
    const Took took = runNextTask();
    if (took == Took::Stop) return;
    if (took == Took::Task) done_.fetch_add(1, std::memory_order_relaxed);
  }
}

void ThreadPool::workerLoop() {
  std::size_t seen = 0;
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
      if (stopping_) return;
      seen = generation_;
      if (!open_) continue;  // woke after the others finished the job: nothing to join
      ++busyWorkers_;
    }
    runTasks();
    {
      std::lock_guard lock(mutex_);
      if (--busyWorkers_ == 0) finished_.notify_one();
    }
  }
}

bool ThreadPool::run(std::size_t count, FunctionRef<void(std::size_t)> task,
                     FunctionRef<bool(std::size_t)> afterCallerTask, FirstStage first) {
  if (count == 0 && first.count == 0) return true;
  {
    std::lock_guard lock(mutex_);
    count_ = count;
    task_ = task;
    first_ = first;
    firstDone_.store(0);
    next_.store(0);
    done_.store(0);
    cancelled_.store(false);
    failure_ = nullptr;
    open_ = true;
    ++generation_;
  }
  // One task is the caller's: no worker to wake (a wake-up costs a system call, and a worker
  // that another program's threads keep waiting would hold up the return).
  if (first.count + count > 1) wake_.notify_all();

  while (!cancelled_.load(std::memory_order_relaxed)) {
    const Took took = runNextTask();
    if (took == Took::Stop) break;
    if (took == Took::FirstStageTask) continue;
    const std::size_t finished = done_.fetch_add(1, std::memory_order_relaxed) + 1;
    bool goOn = true;
    auto askCaller = [&] { goOn = afterCallerTask(finished); };
    if (afterCallerTask && !succeeds(askCaller)) break;
    if (!goOn) cancelled_.store(true);
  }

  // Wait only for the workers that joined: on a busy machine a worker may not run for a
  // scheduler time slice (milliseconds) after it is woken, long after the caller took the
  // remaining tasks; it then finds the job closed and goes back to sleep.
  std::unique_lock lock(mutex_);
  open_ = false;
  finished_.wait(lock, [&] { return busyWorkers_ == 0; });
  if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
  return !cancelled_.load();
}

}  // namespace facet::detail
