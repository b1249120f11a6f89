// --quality auto's choice rules: the most accurate within a budget, the cheapest within an error bound, ties and misses.
#include "TestFramework.hpp"

#include <vector>

#include "Platform/App/AutoQuality.hpp"

using namespace sr::app;

TEST_CASE("auto quality: the most accurate setting within the budget; none fits: the fastest", "[platform][auto]") {
    // A front as the report draws one, and a point off it (slower and worse than #2).
    const std::vector<QualityPoint> points = {{2.0, 0.08}, {5.0, 0.03}, {4.0, 0.05}, {6.0, 0.06}, {20.0, 0.01}, {100.0, 0.0}};
    CHECK(chooseForBudget(points, 1.0) == 0);   // nothing fits: the fastest
    CHECK(chooseForBudget(points, 2.0) == 0);   // exactly at the budget fits
    CHECK(chooseForBudget(points, 4.5) == 2);   // 0.05 beats 0.08
    CHECK(chooseForBudget(points, 5.0) == 1);
    CHECK(chooseForBudget(points, 6.0) == 1);   // #3 fits too but is less accurate
    CHECK(chooseForBudget(points, 19.9) == 1);
    CHECK(chooseForBudget(points, 20.0) == 4);
    CHECK(chooseForBudget(points, 1e9) == 5);   // the truth
    CHECK(chooseForBudget({}, 5.0) == -1);
    // Ties in error: the faster; ties in both: the first.
    CHECK(chooseForBudget({{3.0, 0.02}, {2.0, 0.02}, {2.0, 0.02}}, 10.0) == 1);
    // None fits, two equally fast: the more accurate of them.
    CHECK(chooseForBudget({{3.0, 0.05}, {3.0, 0.01}}, 1.0) == 1);
}

TEST_CASE("auto quality: the cheapest setting within the error bound; none is good enough: the most accurate", "[platform][auto]") {
    const std::vector<QualityPoint> points = {{2.0, 0.08}, {5.0, 0.03}, {4.0, 0.05}, {6.0, 0.06}, {20.0, 0.01}, {100.0, 0.0}};
    CHECK(chooseForError(points, 1.0) == 0);
    CHECK(chooseForError(points, 0.08) == 0);  // at the bound counts
    CHECK(chooseForError(points, 0.079) == 2); // 0.05 at 4 ms is cheaper than 0.03 at 5
    CHECK(chooseForError(points, 0.04) == 1);
    CHECK(chooseForError(points, 0.02) == 4);
    CHECK(chooseForError(points, 0.0) == 5);
    CHECK(chooseForError({{5.0, 0.2}, {9.0, 0.1}}, 0.01) == 1); // none: the most accurate
    CHECK(chooseForError({}, 0.1) == -1);
    CHECK(chooseForError({{4.0, 0.02}, {4.0, 0.01}}, 0.05) == 1); // equally fast: the more accurate
}
