// --quality auto: choosing a setting from measured (time, error) points, by a frame-time budget or an error bound.
#pragma once

#include <vector>

namespace sr::app {

// One setting as measured: its frame time and its error against the ground truth (1 - SSIM: 0
// for the truth itself, larger is worse).
struct QualityPoint {
    double ms = 0.0;
    double error = 0.0;
};

// The point to draw within a frame-time budget: the most accurate (lowest error) whose time is at
// most budgetMs; among equally accurate ones the faster, then the first. When none fits: the
// fastest (then the more accurate). -1 for no points.
int chooseForBudget(const std::vector<QualityPoint>& points, double budgetMs);

// The cheapest point whose error is at most maxError: the lowest time; among equally fast ones the
// more accurate, then the first. When none is accurate enough: the most accurate (then the
// faster). -1 for no points.
int chooseForError(const std::vector<QualityPoint>& points, double maxError);

} // namespace sr::app
