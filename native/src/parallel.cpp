// The thread pool behind parallel_chunks (parallel.h).
#include "parallel.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>

#if defined(__x86_64__) || defined(_M_X64) || defined(__i386__) || defined(_M_IX86)
#include <immintrin.h>
#endif
#ifdef _WIN32
#include <windows.h>
#else
#include <unistd.h>
#endif

namespace geofair {
namespace {

// Before it sleeps, a thread that waits (a worker for the next loop, the caller for the
// workers' chunks) checks for this long: the loops of a solve follow each other closely,
// and waking a sleeping thread costs more than a short spin (docs/DESIGN_NOTES.md,
// "Threads").
constexpr auto kSpin = std::chrono::microseconds(200);

void cpu_relax() {
#if defined(__x86_64__) || defined(_M_X64) || defined(__i386__) || defined(_M_IX86)
  _mm_pause();
#elif defined(__aarch64__) && (defined(__GNUC__) || defined(__clang__))
  __asm__ __volatile__("yield");
#else
  std::this_thread::yield();
#endif
}

// Calls cpu_relax until done() or kSpin has passed, and yields the core now and then to
// another thread that may be waiting for it (the one being waited for, where threads
// outnumber the cores).
template <class Done>
void spin_until(Done&& done) {
  const auto end = std::chrono::steady_clock::now() + kSpin;
  for (int k = 1; !done(); ++k) {
    if (k % 64 == 0) {
      if (std::chrono::steady_clock::now() > end) return;
      std::this_thread::yield();
    }
    cpu_relax();
  }
}

// Workers wait for a loop, run their chunk and report back; the calling thread runs chunk 0.
// A pool lives as long as the process (never destroyed: joining threads while a library
// unloads can deadlock), its workers detached. What a loop is (chunk_, n_, threads_) is
// written and read under mutex_; generation_ and pending_ are atomic besides, so that a
// waiting thread can check them without the mutex while it spins.
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
    pending_.store(threads - 1);
    error_ = nullptr;
    generation_.fetch_add(1);
    lock.unlock();
    start_.notify_all();
    std::exception_ptr own;
    try {
      chunk(0, 0, bound(1));
    } catch (...) {
      own = std::current_exception();
    }
    spin_until([this] { return pending_.load() == 0; });
    lock.lock();
    done_.wait(lock, [this] { return pending_.load() == 0; });
    chunk_ = nullptr;
    if (own) std::rethrow_exception(own);
    if (error_) std::rethrow_exception(error_);
    return true;
  }

 private:
  int bound(int t) const { return int(std::int64_t(n_) * t / threads_); }

  void work(int id) {
    std::uint64_t seen = 0;
    bool spin = true;  // false after a loop that used fewer threads: sleep at once
    for (;;) {
      if (spin) spin_until([&] { return generation_.load() != seen; });
      std::unique_lock<std::mutex> lock(mutex_);
      start_.wait(lock, [&] { return generation_.load() != seen; });
      seen = generation_.load();
      spin = id < threads_;
      if (!spin) continue;  // this loop uses fewer threads
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
      if (pending_.fetch_sub(1) == 1) done_.notify_one();
    }
  }

  std::mutex busy_;   // held by the loop that has the pool
  std::mutex mutex_;  // guards the fields below
  std::condition_variable start_, done_;
  int workers_ = 0;
  const std::function<void(int, int, int)>* chunk_ = nullptr;
  int n_ = 0, threads_ = 1;
  std::atomic<int> pending_{0};
  std::atomic<std::uint64_t> generation_{0};
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
