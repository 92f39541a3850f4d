#pragma once
// The optimization methods a task can run.
#include <optional>
#include <string>

namespace strictmin {

enum class Method { L2, Linf };

std::string method_name(Method m);  // "l2", "linf"
std::optional<Method> parse_method(const std::string& name);
std::string method_list();  // "l2, linf" for help and error messages

}  // namespace strictmin
