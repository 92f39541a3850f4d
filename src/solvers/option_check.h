#pragma once
// Range checks for the Options structs' is_valid (private): each check names the option and
// the range it must lie in, and the first failure is the message. NaN fails every check.
#include <cmath>
#include <sstream>
#include <string>

namespace strictmin {

class OptionCheck {
 public:
  explicit OptionCheck(std::string* why) : why_(why) {}

  OptionCheck& positive(const char* name, double v) { return require(v > 0 && std::isfinite(v), name, v, "> 0"); }
  OptionCheck& non_negative(const char* name, double v) {
    return require(v >= 0 && std::isfinite(v), name, v, ">= 0");
  }
  OptionCheck& below_one(const char* name, double v) { return require(v > 0 && v < 1, name, v, "in (0, 1)"); }
  OptionCheck& at_least(const char* name, double v, double min) {
    return require(v >= min && std::isfinite(v), name, v, ">= " + format(min));
  }
  OptionCheck& between(const char* name, double v, double lo, double hi) {
    return require(v >= lo && v <= hi, name, v, "in [" + format(lo) + ", " + format(hi) + "]");
  }
  OptionCheck& that(bool ok, const std::string& message) {
    if (!ok && ok_) fail(message);
    return *this;
  }
  // Another options struct's is_valid, its message prefixed with where it sits.
  template <class Options>
  OptionCheck& nested(const char* name, const Options& o) {
    std::string inner;
    if (ok_ && !o.is_valid(&inner)) fail(std::string(name) + "." + inner);
    return *this;
  }
  bool ok() const { return ok_; }

 private:
  static std::string format(double v) {
    std::ostringstream os;
    os << v;
    return os.str();
  }
  OptionCheck& require(bool ok, const char* name, double v, const std::string& range) {
    if (!ok && ok_) fail(std::string(name) + " must be " + range + " (got " + format(v) + ")");
    return *this;
  }
  void fail(const std::string& message) {
    ok_ = false;
    if (why_) *why_ = message;
  }
  std::string* why_;
  bool ok_ = true;
};

}  // namespace strictmin
