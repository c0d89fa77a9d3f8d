#include "common/thread_team.h"

#include <algorithm>

namespace tvf {

ThreadTeam& ThreadTeam::shared() {
  static ThreadTeam team(kHelpers);
  return team;
}

int ThreadTeam::usefulParts() {
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  return std::clamp(cores, 1, kHelpers + 1);
}

ThreadTeam::ThreadTeam(int helpers) {
  helpers_.reserve(helpers);
  for (int h = 0; h < helpers; ++h) helpers_.emplace_back([this, h] { serve(h); });
}

ThreadTeam::~ThreadTeam() {
  {
    std::lock_guard<std::mutex> lock(m_);
    quit_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : helpers_) t.join();
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
