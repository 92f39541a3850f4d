#include "strictmin/solvers/interrupt.h"

namespace strictmin {
namespace {
thread_local const std::atomic<bool>* current_flag = nullptr;
}  // namespace

InterruptScope::InterruptScope(const std::atomic<bool>& flag) : previous_(current_flag) { current_flag = &flag; }

InterruptScope::~InterruptScope() { current_flag = previous_; }

void check_interrupt() {
  if (current_flag && current_flag->load(std::memory_order_relaxed)) throw Interrupted();
}

}  // namespace strictmin
