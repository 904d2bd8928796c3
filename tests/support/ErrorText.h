// The message of the preskin::Error a call throws, for tests that check what a refusal says.
#pragma once

#include <preskin/Error.h>

#include <functional>
#include <string>

namespace preskin::test {

// `f()`'s preskin::Error message, or "(no error)" when it returns.
inline std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace preskin::test
