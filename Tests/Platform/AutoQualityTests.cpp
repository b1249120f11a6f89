// --quality auto's choice rules: the most accurate within a budget, the cheapest within an error bound, ties and misses.
#include "TestFramework.hpp"

#include <limits>
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

TEST_CASE("auto quality in motion: a budget between two settings does not alternate; load changes move the choice after a hold",
          "[platform][auto]") {
    const std::vector<QualityPoint> points = {{5.0, 0.05}, {10.0, 0.02}, {40.0, 0.0}};
    // The budget sits between the first two: the first fits, the second does not.
    AutoQualitySelector s(points, 9.5, 15);
    CHECK(s.current() == 0);
    int switches = 0, last = s.current();
    for (int f = 0; f < 300; ++f) { // frames at the probe's time, +-10%
        const int now = s.update(5.0 * (f % 2 ? 1.1 : 0.9));
        switches += now != last;
        last = now;
    }
    CHECK(switches == 0);
    CHECK(s.current() == 0);
    // A budget with room for the second: taken, after the hold, and kept.
    AutoQualitySelector up(points, 12.0, 15);
    CHECK(up.current() == 1);
    // The scene gets twice as dear (frames at 20 ms): down to the first, not at once.
    int frames = 0;
    while (up.current() == 1 && frames < 100) {
        up.update(20.0);
        ++frames;
    }
    CHECK(up.current() == 0);
    CHECK(frames >= 15);
    // Back to the probe's cost (5 ms at the first): up again once the prediction (10 ms) is within
    // 90% of the budget (10.8), after the hold.
    frames = 0;
    while (up.current() == 0 && frames < 200) {
        up.update(5.0);
        ++frames;
    }
    CHECK(up.current() == 1);
    CHECK(frames >= 15);
    // A budget the second only just meets (10.5: within it, not within 90%) is never climbed to.
    AutoQualitySelector tight(points, 10.5, 5);
    CHECK(tight.current() == 1); // chosen at the start by the rule itself
    AutoQualitySelector fromBelow(points, 10.5, 5);
    for (int f = 0; f < 50; ++f) fromBelow.update(10.0 * 1.2); // too dear: down
    CHECK(fromBelow.current() == 0);
    for (int f = 0; f < 200; ++f) fromBelow.update(5.0); // back to 10 ms predicted: above 9.45
    CHECK(fromBelow.current() == 0);
    // Nonsense frame times change nothing.
    AutoQualitySelector still(points, 12.0, 1);
    still.update(std::numeric_limits<double>::quiet_NaN());
    still.update(-1.0);
    CHECK(still.current() == 1);
}
