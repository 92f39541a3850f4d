#pragma once
// Waits for a task group's tasks when the scope ends, by return or by exception (an
// Interrupted from check_interrupt, an InputError), before the locals they reference are gone.
// Declare it after the group and after everything its tasks use. A group destroyed with
// tasks still running cancels them first, and a cancelled group's tasks see every parallel
// algorithm they start return early with its work half done (the normal equations' pattern
// half built: a segfault after Ctrl-C during a probe's restricted solve); waiting here runs
// them to their end instead. A task's own exception is dropped here (the scope is already
// ending; when it ends normally the caller's wait() has rethrown it).
#include <tbb/task_group.h>

namespace strictmin {

class JoinOnExit {
 public:
  explicit JoinOnExit(tbb::task_group& group, bool active = true) : group_(group), active_(active) {}
  ~JoinOnExit() {
    if (!active_) return;
    try {
      group_.wait();
    } catch (...) {
    }
  }
  JoinOnExit(const JoinOnExit&) = delete;
  JoinOnExit& operator=(const JoinOnExit&) = delete;

 private:
  tbb::task_group& group_;
  bool active_;
};

}  // namespace strictmin
