#include "strictmin/tasks/method.h"

namespace strictmin {

std::string method_name(Method m) {
  switch (m) {
    case Method::L2: return "l2";
    case Method::Linf: return "linf";
  }
  return "?";
}

std::optional<Method> parse_method(const std::string& name) {
  if (name == "l2") return Method::L2;
  if (name == "linf") return Method::Linf;
  return std::nullopt;
}

std::string method_list() { return "l2, linf"; }

}  // namespace strictmin
