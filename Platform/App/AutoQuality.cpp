// --quality auto's choice rules over measured points (AutoQuality.hpp).
#include "Platform/App/AutoQuality.hpp"

namespace sr::app {
namespace {

// a before b: the lower `first` key, then the lower `second`, then the earlier index.
bool ahead(double a1, double a2, double b1, double b2) { return a1 < b1 || (a1 == b1 && a2 < b2); }

} // namespace

int chooseForBudget(const std::vector<QualityPoint>& points, double budgetMs) {
    int best = -1, fastest = -1;
    for (int i = 0; i < int(points.size()); ++i) {
        const QualityPoint& p = points[std::size_t(i)];
        if (fastest < 0 || ahead(p.ms, p.error, points[std::size_t(fastest)].ms, points[std::size_t(fastest)].error)) fastest = i;
        if (!(p.ms <= budgetMs)) continue;
        if (best < 0 || ahead(p.error, p.ms, points[std::size_t(best)].error, points[std::size_t(best)].ms)) best = i;
    }
    return best >= 0 ? best : fastest;
}

int chooseForError(const std::vector<QualityPoint>& points, double maxError) {
    int best = -1, accurate = -1;
    for (int i = 0; i < int(points.size()); ++i) {
        const QualityPoint& p = points[std::size_t(i)];
        if (accurate < 0 || ahead(p.error, p.ms, points[std::size_t(accurate)].error, points[std::size_t(accurate)].ms)) accurate = i;
        if (!(p.error <= maxError)) continue;
        if (best < 0 || ahead(p.ms, p.error, points[std::size_t(best)].ms, points[std::size_t(best)].error)) best = i;
    }
    return best >= 0 ? best : accurate;
}

} // namespace sr::app
