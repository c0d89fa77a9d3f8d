#pragma once
// A few helper threads that live as long as the process and run one task each on request: the backward
// substitution's independent subtrees (solver/backward_substitution.h) after every edit.
//
// A thread per solve would cost its creation each time, and in wasm a pthread started while the caller then
// blocks runs only if a pre-started worker is free (emscripten's PTHREAD_POOL_SIZE); otherwise the page would
// hang. So the helpers are started once, as many as the build provides (helpers()), and shared: a caller that
// finds them busy with another caller's tasks runs its own tasks itself, one after another.
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace tvf {

// Item `begin` of part k of `parts` over `count` items (part k covers [partBegin(k), partBegin(k + 1))).
inline int32_t partBegin(int32_t count, int part, int parts) {
  return static_cast<int32_t>(static_cast<int64_t>(count) * part / parts);
}

class ThreadTeam {
 public:
  // The most helpers a build can have: natively 15 (sixteen parts); a wasm build with pthreads the most
  // workers its pool may start with (TVF_THREAD_HELPERS); without pthreads none.
#if defined(TVF_THREAD_HELPERS)
  static constexpr int kHelpers = TVF_THREAD_HELPERS;
#elif defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
  static constexpr int kHelpers = 0;
#else
  static constexpr int kHelpers = 15;
#endif

  // The helpers this process has: natively kHelpers; in wasm as many as the module's pool started
  // (wasm/node-pre.js: one fewer than the cores, at most kHelpers, or what the page asked for).
  static int helpers();
  // The most parts run() runs at once: helpers() + 1.
  static int maxParts() { return helpers() + 1; }
  // The process's team, its helpers started on the first call (std::system_error when one cannot start; the
  // next call tries again).
  static ThreadTeam& shared();
  // How many parts a solve should be cut into here: the cores there are, at most maxParts().
  static int usefulParts();

  ~ThreadTeam();
  ThreadTeam(const ThreadTeam&) = delete;
  ThreadTeam& operator=(const ThreadTeam&) = delete;

  // Runs task(k) for k = 0 .. parts - 1 and returns when all have returned: task(0) on the calling thread,
  // the others on helpers (or on the calling thread, in turn, when there are too few free helpers). Tasks
  // must not throw. Everything the caller wrote before is visible to the tasks, and everything the tasks
  // wrote is visible to the caller after.
  void run(int parts, const std::function<void(int)>& task);

 private:
  explicit ThreadTeam(int helpers);
  void serve(int helper);
  void stop();

  std::mutex busy_;  // held by the caller whose tasks the helpers run
  std::mutex m_;
  std::condition_variable wake_, done_;
  const std::function<void(int)>* task_ = nullptr;
  int parts_ = 0, pending_ = 0;
  unsigned generation_ = 0;
  bool quit_ = false;
  std::vector<std::thread> helpers_;
};

}  // namespace tvf
