// stipple-inspect --quality: how evenly an asset's point hierarchy is spread. For a prefix
// of n points (a coarser level, thesis §3.1.1), the nearest-neighbour distance of every point
// of the prefix to the rest of it, in bind pose, normalised by sqrt(area / n) (the spacing
// of an even distribution), and the tone calibration there.
#pragma once
#include <cstdint>
#include <vector>

#include "runtime/asset.h"

namespace stipple::tools {

struct Spacing {
    double mean = 0, cv = 0, min_over_mean = 0;
    double density_cv = 0;  // of the point count within 3 even spacings of each point
};

double surface_area(const MeshView& mesh);

// Over the first n points of `xyz` (3 floats per point): nearest-neighbour distances
// (exact, through the runtime's SpatialGrid) and the large-scale density spread.
Spacing nearest_neighbour_spacing(const std::vector<float>& xyz, uint32_t n, double area);

// Tone calibration (runtime/stipple_size.h): the area per point of an n-point prefix over
// the squared radius of its last points, mean over ranks [0.9 n, n); 1.0 is what the
// runtime's kRegionPerRadiusSquared assumes.
double region_per_radius2(const PointsView& points, uint32_t n, double area);

}  // namespace stipple::tools
