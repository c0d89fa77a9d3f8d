#include "common/thread_team.h"

#include <algorithm>

#if defined(__EMSCRIPTEN_PTHREADS__)
#include <emscripten.h>
#endif

namespace tvf {

int ThreadTeam::helpers() {
#if defined(__EMSCRIPTEN_PTHREADS__)
  // The workers the pool started with (wasm/node-pre.js); a pthread beyond them would never start.
  static const int started = EM_ASM_INT({ return typeof tvfThreadHelpers == 'number' ? tvfThreadHelpers : 0; });
  return std::clamp(started, 0, kHelpers);
#else
  return kHelpers;
#endif
}

ThreadTeam& ThreadTeam::shared() {
  static ThreadTeam team(helpers());
  return team;
}

int ThreadTeam::usefulParts() {
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  return std::clamp(cores, 1, maxParts());
}

ThreadTeam::ThreadTeam(int helpers) {
  helpers_.reserve(helpers);
  try {
    for (int h = 0; h < helpers; ++h) helpers_.emplace_back([this, h] { serve(h); });
  } catch (...) {  // a thread that cannot start: the ones that did are stopped, the caller told
    stop();
    throw;
  }
}

void ThreadTeam::stop() {
  {
    std::lock_guard<std::mutex> lock(m_);
    quit_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : helpers_) t.join();
  helpers_.clear();
}

ThreadTeam::~ThreadTeam() {
  stop();
}

// Helper h runs task h + 1 of every generation that has that many parts.
void ThreadTeam::serve(int helper) {
  unsigned seen = 0;
  std::unique_lock<std::mutex> lock(m_);
  for (;;) {
    wake_.wait(lock, [&] { return quit_ || generation_ != seen; });
    if (quit_) return;
    seen = generation_;
    if (helper + 1 >= parts_) continue;
    const std::function<void(int)>& task = *task_;
    lock.unlock();
    task(helper + 1);
    lock.lock();
    if (--pending_ == 0) done_.notify_one();
  }
}

void ThreadTeam::run(int parts, const std::function<void(int)>& task) {
  const int helped = std::min(parts - 1, static_cast<int>(helpers_.size()));
  std::unique_lock<std::mutex> busy(busy_, std::try_to_lock);
  if (helped <= 0 || !busy.owns_lock()) {
    for (int k = 0; k < parts; ++k) task(k);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(m_);
    task_ = &task;
    parts_ = helped + 1;
    pending_ = helped;
    ++generation_;
  }
  wake_.notify_all();
  task(0);
  for (int k = helped + 1; k < parts; ++k) task(k);
  std::unique_lock<std::mutex> lock(m_);
  done_.wait(lock, [&] { return pending_ == 0; });
  task_ = nullptr;
}

}  // namespace tvf
