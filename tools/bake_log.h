// stipple-bake's capture of what libraries print on std::cerr during the whole bake:
// OpenMesh reports every face it cannot add ("PolyMeshT::add_face: complex vertex" or
// "complex edge", the bake then splits that face's corners) through omerr(), which writes to
// std::cerr, one line per face. A LibraryLog swaps std::cerr's buffer for a string while it is
// alive, and summary() turns the lines into one warning per distinct message with its count. The
// bake library itself is left alone. (C stdio's stderr, which the progress bar uses, is not
// affected.)
#pragma once
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace stipple::tools {

class LibraryLog {
  public:
    LibraryLog() : previous_(std::cerr.rdbuf(captured_.rdbuf())) {}
    ~LibraryLog() { stop(); }
    LibraryLog(const LibraryLog&) = delete;
    LibraryLog& operator=(const LibraryLog&) = delete;

    // Restores std::cerr (idempotent).
    void stop();
    // "N faces hit a complex vertex/edge (...)" for OpenMesh's add_face lines, "LINE (N times)"
    // for any other repeated line; in order of first appearance.
    std::vector<std::string> summary() const;

  private:
    std::ostringstream captured_;
    std::streambuf* previous_;
};

}  // namespace stipple::tools
