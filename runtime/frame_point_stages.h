// The frame's point stages (Thesis Alg. 6.3, 6.4, 3.2) and the run-time refinement after them
// (§4.5, §9.1.1; runtime/point_refinement.h), over every baked point or over the level of
// detail's selection (runtime/point_clusters.h): what pipeline_update runs between the pose
// and the compaction of the drawn dots (runtime/frame_pipeline.cpp).
#pragma once
#include "runtime/frame_pipeline.h"
#include "runtime/stage_clock.h"

namespace stipple {

// Places, re-scales and sizes the baked points (the selection's when `lod`), then continues
// the hierarchy where it runs out: sets p->refined_count and p->refinement_stats. Stage times
// go to t (when not null) from *clock on.
void pipeline_point_stages(Pipeline* p, bool lod, StageTimes* t, StageClock::time_point* clock);

// The run-time refinement after the baked points are sized (runtime/frame_refine_stage.cpp):
// places the extra points, sizes them and fades the baked ones they replace.
void pipeline_refine_stage(Pipeline* p, bool lod, StageTimes* t, StageClock::time_point* clock);

}  // namespace stipple
