#pragma once
// Runs `f` and expects an InputError whose message contains every one of `words`.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "strictmin/io/input_error.h"

namespace strictmin::test_support {

inline void expect_input_error(const std::function<void()>& f, const std::vector<std::string>& words) {
  try {
    f();
    ADD_FAILURE() << "no InputError thrown (expected one mentioning '" << words.front() << "')";
  } catch (const InputError& e) {
    const std::string message = e.what();
    for (const std::string& w : words) EXPECT_NE(message.find(w), std::string::npos) << "'" << w << "' not in: " << message;
  }
}

}  // namespace strictmin::test_support
