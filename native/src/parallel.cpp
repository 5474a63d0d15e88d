// The thread pool behind parallel_chunks (parallel.h).
#include "parallel.h"

#include <condition_variable>
#include <cstdlib>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>

#ifdef _WIN32
#include <windows.h>
#else
#include <unistd.h>
#endif

namespace geofair {
namespace {

// Workers wait for a loop, run their chunk and report back; the calling thread runs chunk 0.
// A pool lives as long as the process (never destroyed: joining threads while a library
// unloads can deadlock), its workers detached.
class Pool {
 public:
  // Runs the loop on `threads` threads; false (nothing run) while another loop has the pool.
  bool run(int threads, int n, const std::function<void(int, int, int)>& chunk) {
    std::unique_lock<std::mutex> owner(busy_, std::try_to_lock);
    if (!owner.owns_lock()) return false;
    std::unique_lock<std::mutex> lock(mutex_);
    while (workers_ < threads - 1) {
      const int id = workers_ + 1;
      std::thread([this, id] { work(id); }).detach();
      ++workers_;
    }
    chunk_ = &chunk;
    n_ = n;
    threads_ = threads;
    pending_ = threads - 1;
    error_ = nullptr;
    ++generation_;
    lock.unlock();
    start_.notify_all();
    std::exception_ptr own;
    try {
      chunk(0, 0, bound(1));
    } catch (...) {
      own = std::current_exception();
    }
    lock.lock();
    done_.wait(lock, [this] { return pending_ == 0; });
    chunk_ = nullptr;
    if (own) std::rethrow_exception(own);
    if (error_) std::rethrow_exception(error_);
    return true;
  }

 private:
  int bound(int t) const { return int(std::int64_t(n_) * t / threads_); }

  void work(int id) {
    std::uint64_t seen = 0;
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      start_.wait(lock, [&] { return generation_ != seen; });
      seen = generation_;
      if (id >= threads_) continue;  // this loop uses fewer threads
      const auto* chunk = chunk_;
      const int begin = bound(id), end = bound(id + 1);
      lock.unlock();
      std::exception_ptr error;
      try {
        (*chunk)(id, begin, end);
      } catch (...) {
        error = std::current_exception();
      }
      lock.lock();
      if (error && !error_) error_ = error;
      if (--pending_ == 0) done_.notify_one();
    }
  }

  std::mutex busy_;   // held by the loop that has the pool
  std::mutex mutex_;  // guards the fields below
  std::condition_variable start_, done_;
  int workers_ = 0;
  const std::function<void(int, int, int)>* chunk_ = nullptr;
  int n_ = 0, threads_ = 1, pending_ = 0;
  std::uint64_t generation_ = 0;
  std::exception_ptr error_;
};

long process_id() {
#ifdef _WIN32
  return long(GetCurrentProcessId());
#else
  return long(getpid());
#endif
}

// The process's pool; a child forked after loops ran starts one of its own (the parent's
// workers do not exist in it).
Pool& pool() {
  static std::mutex mutex;
  static Pool* instance = nullptr;
  static long owner = 0;
  const std::lock_guard<std::mutex> lock(mutex);
  const long pid = process_id();
  if (!instance || owner != pid) {
    instance = new Pool;  // the one of a parent is left as it is
    owner = pid;
  }
  return *instance;
}

thread_local int requested_threads = 0;  // 0: the machine's cores

}  // namespace

int machine_cores() {
  static const int cores = std::max(1, int(std::thread::hardware_concurrency()));
  return cores;
}

namespace {
int environment_threads(const char* name) {
  const char* value = std::getenv(name);
  return value ? std::max(0, std::atoi(value)) : 0;
}
}  // namespace

int requested_threads_from_environment() {
  // Read once per process; at most 4 threads a core (a typo of 1000 would start a thousand).
  static const int threads = std::min(environment_threads("GEOFAIR_NUM_THREADS"), 4 * machine_cores());
  return threads;
}

int max_threads() {
  static const int threads = [] {
    if (const int n = requested_threads_from_environment(); n > 0) return n;
    if (const int n = environment_threads("OMP_NUM_THREADS"); n > 0) return n;
    return machine_cores();
  }();
  return threads;
}

int loop_threads() { return requested_threads > 0 ? requested_threads : max_threads(); }

void set_loop_threads(int threads) { requested_threads = std::max(1, threads); }

void parallel_chunks(int n, bool parallel, const std::function<void(int, int, int)>& chunk) {
  const int threads = parallel ? std::min(loop_threads(), n) : 1;
  if (threads > 1 && pool().run(threads, n, chunk)) return;
  chunk(0, 0, n);
}

}  // namespace geofair
