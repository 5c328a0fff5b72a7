#pragma once
// The figures a merger writes into the reason of a refusal (MergeResult::reason).

#include <string>

namespace mrslam::fusion {

/// `value` to 3 significant digits, as refusals quote their figures ("0.952", "1.5e+03").
std::string reasonFigure(double value);

}  // namespace mrslam::fusion
