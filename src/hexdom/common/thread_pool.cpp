#include "hexdom/common/thread_pool.h"

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

namespace hexdom {

namespace {

class Pool {
 public:
  ~Pool() {
    {
      const std::lock_guard<std::mutex> lock(mu_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

  void run(int helpers, const std::function<void()>& work) {
    Job job{&work, helpers};
    {
      const std::lock_guard<std::mutex> lock(mu_);
      while (static_cast<int>(threads_.size()) < helpers) threads_.emplace_back([this] { serve(); });
      jobs_.push_back(&job);
    }
    wake_.notify_all();
    work();
    std::unique_lock<std::mutex> lock(mu_);
    const auto it = std::find(jobs_.begin(), jobs_.end(), &job);  // no helper joins from now on
    if (it != jobs_.end()) jobs_.erase(it);
    job.done.wait(lock, [&] { return job.running == 0; });
  }

 private:
  struct Job {
    const std::function<void()>* work;
    int wanted;       // helpers that may still join
    int running = 0;  // helpers in work() now
    std::condition_variable done;
  };

  void serve() {
    std::unique_lock<std::mutex> lock(mu_);
    for (;;) {
      wake_.wait(lock, [&] { return stop_ || !jobs_.empty(); });
      if (stop_) return;
      Job* job = jobs_.front();
      if (--job->wanted == 0) jobs_.pop_front();
      ++job->running;
      lock.unlock();
      (*job->work)();
      lock.lock();
      if (--job->running == 0) job->done.notify_all();
    }
  }

  std::mutex mu_;
  std::condition_variable wake_;
  std::deque<Job*> jobs_;  // loops that still take helpers, oldest first
  std::vector<std::thread> threads_;
  bool stop_ = false;
};

Pool& pool() {
  static Pool p;
  return p;
}

}  // namespace

void run_on_pool(int helpers, const std::function<void()>& work) {
  if (helpers <= 0) {
    work();
    return;
  }
  pool().run(helpers, work);
}

}  // namespace hexdom
