#include "hexdom/common/thread_grant.h"

namespace hexdom {

namespace {
thread_local const ThreadGrant* current = nullptr;
}

ThreadGrantScope::ThreadGrantScope(const ThreadGrant* grant) : previous_(current) { current = grant; }

ThreadGrantScope::~ThreadGrantScope() { current = previous_; }

const ThreadGrant* current_thread_grant() { return current; }

}  // namespace hexdom
