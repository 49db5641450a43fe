// Results kept in memory under a Hash128 of everything that made them, so that a second call with
// the same inputs returns the first call's result. Safe from several threads.
#pragma once

#include <cstddef>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <utility>

#include "hexdom/common/hash128.h"

namespace hexdom {

/// Keeps values by key; when the values kept cost more than `budget` in all (`cost` of each, 1 by
/// default), the oldest are dropped, the newest always staying. A key kept already is not replaced.
template <class Value>
class KeptResults {
 public:
  explicit KeptResults(size_t budget, std::function<size_t(const Value&)> cost = [](const Value&) { return size_t(1); })
      : budget_(budget), cost_(std::move(cost)) {}

  /// Whether `k` is kept; its value into `out` when it is.
  bool find(const Hash128& k, Value* out) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = kept_.find(k);
    if (it == kept_.end()) return false;
    *out = it->second;
    return true;
  }

  void keep(const Hash128& k, Value v) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (kept_.count(k)) return;
    size_ += cost_(v);
    order_.push_back(k);
    kept_.emplace(k, std::move(v));
    while (size_ > budget_ && order_.size() > 1) {
      const auto old = kept_.find(order_.front());
      size_ -= cost_(old->second);
      kept_.erase(old);
      order_.pop_front();
    }
  }

 private:
  const size_t budget_;
  const std::function<size_t(const Value&)> cost_;
  std::mutex mutex_;
  std::map<Hash128, Value> kept_;
  std::deque<Hash128> order_;
  size_t size_ = 0;
};

}  // namespace hexdom
