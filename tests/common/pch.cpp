// The translation unit the tests' shared precompiled header is built with (tests/CMakeLists.txt:
// stipple_test_pch); every test executable reuses that header.
