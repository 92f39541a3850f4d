#pragma once
// Cooperative interruption of a long solve (the Python module's Ctrl-C, any host that wants
// to cancel). A caller installs a flag for the current thread with InterruptScope and sets
// it from elsewhere; every solver calls check_interrupt() once per iteration (interior-point
// iteration, relax sweep, local-global iteration, lp Newton step, irls solve, strict level),
// which throws Interrupted when the flag is set. The solve is abandoned: no Result is
// returned. Without a scope on the thread check_interrupt() does nothing, so the library's
// behaviour is unchanged for callers that never interrupt.
#include <atomic>
#include <stdexcept>

namespace strictmin {

class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted") {}
};

// While alive, check_interrupt() on this thread throws Interrupted once `flag` is true.
// Scopes nest (the innermost flag is checked).
class InterruptScope {
 public:
  explicit InterruptScope(const std::atomic<bool>& flag);
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  const std::atomic<bool>* previous_;
};

void check_interrupt();

}  // namespace strictmin
