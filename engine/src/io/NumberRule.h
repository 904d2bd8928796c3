// The one rule for numbers that enter the engine (<preskin/Limits.h>): finite, and at most
// limits::kMaxInputMagnitude in magnitude. Every reader (glTF, profiles, manifests, environment
// pixels, command-line options, public setters) asks it, then applies its field's own range.
#pragma once

#include <optional>
#include <string>

namespace preskin::io {

bool acceptedNumber(double value);
inline bool acceptedNumber(float value) { return acceptedNumber(static_cast<double>(value)); }

// Why `value` is refused ("nan is not a finite number", "1e+300 exceeds the limit of 1e+06 in
// magnitude"), or nullopt when it is accepted.
std::optional<std::string> numberProblem(double value);
inline std::optional<std::string> numberProblem(float value) { return numberProblem(static_cast<double>(value)); }

// The shortest text that reads back as `value` (0.5, 1e+300, nan).
std::string numberText(double value);

}  // namespace preskin::io
