#pragma once
// Quarter turns of a DFT cross-correlation (the global search's sweep): the scores of an image
// turned by a quarter turn about the centre of its square canvas, against a target, are those of
// the unturned image against the target turned back on the DFT's square torus, read at mapped
// shifts. The sweep so transforms `from`'s turned images for the first quarter of its rotations
// only.
//
// Scores are cross-correlations on an N × N torus, the canvas of side n at its origin:
//   S_A,T(s) = Σ_u A(u) T(u + s).
// With A_q the canvas turned by q quarter turns about its centre ((x, y) → (-y, x) each, image
// coordinates: column x, row y, the turn of GridTransform's rotation by +90°),
//   S_{A_q},T(s) = S_A,U_q(f^q(s)),  U_q(z) = T(R^q z),  R(x, y) = (-y, x),
//   f(s1, s2) = (s2, -(n - 1) - s1),
// every coordinate modulo N: the turn about the canvas centre is a turn about the origin and a
// whole shift of n - 1 cells.

#include <opencv2/core.hpp>

namespace mrslam::fusion {

/// U_q of `image` (CV_32F, at the origin of a side × side torus, no larger than it), q =
/// `quarters` in 1..3.
cv::Mat turnedOnTorus(const cv::Mat& image, int side, int quarters);

/// The scores of the canvas (side `canvas`) turned by `quarters` (1..3) quarter turns from the
/// scores `scores` (square, CV_32F) of the unturned canvas against U_quarters of the target.
cv::Mat quarterTurnScores(const cv::Mat& scores, int canvas, int quarters);

}  // namespace mrslam::fusion
