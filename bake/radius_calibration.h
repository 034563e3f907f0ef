// Tone calibration of relevance radii: the runtime's region of influence is r^2 per point
// (kRegionPerRadiusSquared = 1, runtime/stipple_size.h); radii measured as neighbour
// distances are scaled once per hierarchy so that holds on average over its levels.
#pragma once
#include "bake/point_hierarchy.h"

namespace stipple::bake {

// Scales every radius of `p` (ordered coarse to fine) by one factor; `area` is the surface's.
void calibrate_radii(double area, PointHierarchy* p);

}  // namespace stipple::bake
