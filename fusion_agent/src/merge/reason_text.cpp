#include "mrslam/fusion/merge/reason_text.hpp"

#include <sstream>

namespace mrslam::fusion {

std::string reasonFigure(double value) {
  std::ostringstream text;
  text.precision(3);
  text << value;
  return text.str();
}

}  // namespace mrslam::fusion
