#include "hexdom/common/interrupt.h"

namespace hexdom {

namespace {
thread_local const Interrupt* current = nullptr;
}

InterruptScope::InterruptScope(const Interrupt* interrupt) : previous_(current) { current = interrupt; }

InterruptScope::~InterruptScope() { current = previous_; }

const Interrupt* current_interrupt() { return current; }

}  // namespace hexdom
