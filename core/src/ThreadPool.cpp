#include "ThreadPool.h"

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

void ThreadPool::runTasks() {
  while (!cancelled_.load(std::memory_order_relaxed)) {
    const std::size_t i = next_.fetch_add(1, std::memory_order_relaxed);
    if (i >= count_) return;
    task_(i);
    done_.fetch_add(1, std::memory_order_relaxed);
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
                     FunctionRef<bool(std::size_t)> afterCallerTask) {
  if (count == 0) return true;
  {
    std::lock_guard lock(mutex_);
    count_ = count;
    task_ = task;
    next_.store(0);
    done_.store(0);
    cancelled_.store(false);
    open_ = true;
    ++generation_;
  }
  // One task is the caller's: no worker to wake (a wake-up costs a system call, and a worker
  // that another program's threads keep waiting would hold up the return).
  if (count > 1) wake_.notify_all();

  while (!cancelled_.load(std::memory_order_relaxed)) {
    const std::size_t i = next_.fetch_add(1, std::memory_order_relaxed);
    if (i >= count_) break;
    task(i);
    const std::size_t finished = done_.fetch_add(1, std::memory_order_relaxed) + 1;
    if (afterCallerTask && !afterCallerTask(finished)) cancelled_.store(true);
  }

  // Wait only for the workers that joined: on a busy machine a worker may not run for a
  // scheduler time slice (milliseconds) after it is woken, long after the caller took the
  // remaining tasks; it then finds the job closed and goes back to sleep.
  std::unique_lock lock(mutex_);
  open_ = false;
  finished_.wait(lock, [&] { return busyWorkers_ == 0; });
  return !cancelled_.load();
}

}  // namespace facet::detail
