# COST (the seconds under ASan+UBSan, scripts/test.sh --sanitize on 2 cores, measured in a
# full ctest -j2 run in December 2026) of the longest tests,
# so that ctest -j starts them first in a fresh build (tests/CMakeLists.txt includes this file
# in every test directory). Once a build has run its tests, ctest's own measurements
# (Testing/Temporary/CTestCostData.txt) take over. Re-measure: ctest --test-dir BUILD -j2, then
# sort that file by its third column.
set(_stipple_costs
  # The fixture bakes (FIXTURES_SETUP test_assets): every test that reads a baked asset waits
  # for the last of them, so the longest start first.
  bake_test_assets.horse_occluder 31
  bake_test_assets.bunny_262k_simplify_particles 26
  bake_test_assets.bunny_262k 18
  bake_test_assets.tube_100k 5
  bake_test_assets.cesium_occluder 5
  bake_test_assets.bunny_curvature 4
  bake_test_assets.cesium_60k 3
  bake_test_assets.cesium_20k_relax 3
  # The tests.
  Examples.BuildThreeWalkers 21
  FrameChecks.ToneIsKeptUnderDeformationWithRelevanceUpdates 14
  ParticleFrames.EveryStyleIsDistinctAndDeterministicOnTheBunny 14
  Coherence.ZoomFromOneToSixteenDoesNotPop 13
  FrameChecks.ToneIsKeptUnderScale 13
  ParticleFrames.StrokeDensityHoldsAt640x480WithABoundedList 13
  ParticleFrames.EveryStyleIsDistinctAndDeterministicOnTheWalk 12
  BakeFiles.SigtermDuringTheWriteLeavesNoTempFile 12
  ParticleAllocation.ParticleFramesAllocateNothingAfterInit 11
  ThreadAllocation.FramesOnThreeThreadsAllocateNothing 9
  PointStagesTest.ThreadsGiveByteIdenticalPointsOnTheWalk 9
  Styles.EachStyleIsItsOwnDeterministicFrame 8
  # The sanitizer build's shards (tests/CMakeLists.txt: one process per shard), longest first
  # so that no long shard runs alone at the end.
  stipple_frame_tests.shard2 86
  stipple_frame_tests.shard6 73
  stipple_frame_tests.shard7 67
  stipple_frame_tests.shard1 66
  stipple_frame_tests.shard5 66
  stipple_frame_tests.shard4 64
  stipple_frame_tests.shard3 58
  stipple_frame_tests.shard0 57
  stipple_alloc_tests.shard1 49
  stipple_tools_tests.shard2 48
  stipple_alloc_tests.shard0 44
  stipple_runtime_tests.shard2 38
  stipple_runtime_tests.shard0 37
  stipple_bake_tests.shard1 35
  stipple_runtime_tests.shard1 29
  stipple_runtime_tests.shard3 29
  stipple_tools_tests.shard0 28
  stipple_tools_tests.shard3 27
  stipple_bake_tests.shard0 23
  stipple_tools_tests.shard1 12)
list(LENGTH _stipple_costs _n)
math(EXPR _last "${_n} - 1")
foreach(_i RANGE 0 ${_last} 2)
  math(EXPR _j "${_i} + 1")
  list(GET _stipple_costs ${_i} _test)
  list(GET _stipple_costs ${_j} _cost)
  set_tests_properties(${_test} PROPERTIES COST ${_cost})
endforeach()
