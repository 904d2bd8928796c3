// The finiteness and magnitude rule for input numbers (see NumberRule.h).
#include "io/NumberRule.h"

#include <preskin/Limits.h>

#include <cmath>
#include <sstream>

namespace preskin::io {

bool acceptedNumber(double value) { return std::isfinite(value) && std::abs(value) <= limits::kMaxInputMagnitude; }

std::string numberText(double value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

std::optional<std::string> numberProblem(double value) {
    if (!std::isfinite(value)) return numberText(value) + " is not a finite number";
    if (std::abs(value) > limits::kMaxInputMagnitude) {
        return numberText(value) + " exceeds the limit of " + numberText(limits::kMaxInputMagnitude) + " in magnitude";
    }
    return std::nullopt;
}

}  // namespace preskin::io
