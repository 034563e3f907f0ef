#include "bake/radius_calibration.h"

#include <cmath>

namespace stipple::bake {

// The runtime gives a point of radius r a region of influence r^2 (kRegionPerRadiusSquared
// = 1, runtime/stipple_size.h), which is right when the n-th point's r^2 is the area per
// point of an n-point prefix, area / n. Mean one-ring distances miss that by a factor set
// by the mesh (a regular triangulation of edge L has sqrt(3)/2 L^2 per vertex: 0.87; the
// bunny and horse measure 0.82-0.99 along the hierarchy). One factor per hierarchy, the
// geometric mean of area / (n r_n^2) with every octave of prefix sizes weighted alike,
// makes the tone right on average over the levels while keeping each radius's local
// meaning and the order (bunny, 100k points: 0.96-1.03 from 300 to 64k points, tone 0.30-0.31
// for a target of 0.3, instead of 0.91-0.97 and 0.34-0.35). Prefixes under 256 points,
// whose radii scatter most, and the last tenth, a generation of splits cut short by the
// point budget, are left out of the fit.
void calibrate_radii(double area, PointHierarchy* p) {
    double sum = 0, weights = 0;
    for (size_t i = 256; i < p->size() - p->size() / 10; ++i) {
        const double r = p->radius[i];
        if (!(r > 0)) continue;
        const double w = 1.0 / double(i + 1);
        sum += w * std::log(area / (double(i + 1) * r * r));
        weights += w;
    }
    if (weights == 0) return;
    const float scale = float(std::exp(0.5 * sum / weights));
    for (float& r : p->radius) r *= scale;
}

}  // namespace stipple::bake
