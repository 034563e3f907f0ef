#include "tools/bake_log.h"

#include <algorithm>
#include <utility>

namespace stipple::tools {

void LibraryLog::stop() {
    if (!previous_) return;
    std::cerr.flush();
    std::cerr.rdbuf(previous_);
    previous_ = nullptr;
}

std::vector<std::string> LibraryLog::summary() const {
    std::vector<std::pair<std::string, size_t>> counted;
    std::istringstream in(captured_.str());
    std::string line;
    while (std::getline(in, line)) {
        const size_t a = line.find_first_not_of(" \t\r");
        if (a == std::string::npos) continue;
        line = line.substr(a, line.find_last_not_of(" \t\r") - a + 1);
        auto same = [&](const std::pair<std::string, size_t>& c) { return c.first == line; };
        auto it = std::find_if(counted.begin(), counted.end(), same);
        if (it != counted.end())
            ++it->second;
        else
            counted.emplace_back(line, 1);
    }
    std::vector<std::string> out;
    for (const auto& c : counted) {
        const std::string n = std::to_string(c.second);
        const bool vertex = c.first.find("add_face: complex vertex") != std::string::npos;
        const bool edge = c.first.find("add_face: complex edge") != std::string::npos;
        if (vertex || edge)
            out.push_back(n + (c.second == 1 ? " face" : " faces") + " hit a complex " +
                          (vertex ? "vertex" : "edge") +
                          " (OpenMesh add_face); their corners were split");
        else
            out.push_back(c.first + (c.second == 1 ? "" : " (" + n + " times)"));
    }
    return out;
}

}  // namespace stipple::tools
