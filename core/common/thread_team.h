#pragma once
// A few helper threads that live as long as the process and run one task each on request: the backward
// substitution's independent subtrees (solver/backward_substitution.h) after every edit.
//
// A thread per solve would cost its creation each time, and in wasm a pthread started while the caller then
// blocks runs only if a pre-started worker is free (emscripten's PTHREAD_POOL_SIZE); otherwise the page would
// hang. So the helpers are started once, as many as the build provides (kHelpers), and shared: a caller that
// finds them busy with another caller's tasks runs its own tasks itself, one after another.
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace tvf {

class ThreadTeam {
 public:
  // Natively up to four parts; a wasm build with pthreads as many as the workers it starts with (the
  // module's PTHREAD_POOL_SIZE, passed as TVF_THREAD_HELPERS); without pthreads one.
#if defined(TVF_THREAD_HELPERS)
  static constexpr int kHelpers = TVF_THREAD_HELPERS;
#elif defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
  static constexpr int kHelpers = 0;
#else
  static constexpr int kHelpers = 3;
#endif

  // The process's team, its helpers started on the first call.
  static ThreadTeam& shared();
  // How many parts a solve should be cut into here: the cores there are, at most kHelpers + 1.
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
