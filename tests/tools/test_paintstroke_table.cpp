// stipple-paintstroke-table (GI'98 Table 1 rerun, docs/paintstrokes.md) keeps working: a short
// run writes both marked sections with a row per model and scale, a verdict per scale, and
// counts that follow the paper's structure (quality q draws 2^q polygons per side).
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "tests/common/fixtures.h"

namespace {

using namespace stipple::test;

// Total triangles per tube of each "| scale | model | total |" row of the table.
std::map<std::string, double> total_triangles(const std::string& markdown) {
    std::map<std::string, double> rows;
    std::istringstream in(markdown);
    std::string line;
    while (std::getline(in, line)) {
        char scale[32] = {}, model[64] = {};
        double total = 0;
        if (std::sscanf(line.c_str(), "| %31[a-z] | %63[a-z0-9-] | %lf |", scale, model, &total) ==
            3)
            rows[std::string(scale) + "/" + model] = total;
    }
    return rows;
}

TEST(PaintstrokeTable, ShortRunWritesTheTableAndVerdicts) {
    ScratchDir dir;
    const std::string out = dir.file("paintstrokes.md");
    std::string log;
    ASSERT_EQ(run(bin("stipple-paintstroke-table") + " --frames 2 --runs 1 --images none " +
                      "--oit-frames 1 --out " + out,
                  &log),
              0)
        << log;
    std::ifstream f(out);
    std::stringstream text;
    text << f.rdbuf();
    const std::string md = text.str();
    for (const char* marker :
         {"<!-- table1:begin -->", "<!-- table1:end -->", "<!-- oit:begin -->", "<!-- oit:end -->"})
        EXPECT_NE(md.find(marker), std::string::npos) << marker;
    const std::map<std::string, double> rows = total_triangles(md);
    for (const char* scale : {"large", "medium", "small"}) {
        const std::string s(scale);
        ASSERT_EQ(rows.count(s + "/paintstroke-q2"), 1u) << scale << "\n" << md;
        ASSERT_EQ(rows.count(s + "/static-9gon"), 1u) << scale;
        ASSERT_EQ(rows.count(s + "/reference-64gon"), 1u) << scale;
        // Same segments, 4 / 2 / 1 polygons per side (end caps aside): q2 about twice q1.
        const double q2 = rows.at(s + "/paintstroke-q2"), q1 = rows.at(s + "/paintstroke-q1"),
                     q0 = rows.at(s + "/paintstroke-q0");
        EXPECT_GT(q2, 1.6 * q1) << scale;
        EXPECT_GT(q1, q0) << scale;
        // View-dependent: fewer triangles as the tubes get smaller on screen.
        EXPECT_NE(md.find("- **" + s + "**"), std::string::npos) << "no verdict for " << scale;
    }
    EXPECT_GT(rows.at("large/paintstroke-q2"), rows.at("small/paintstroke-q2"));
    EXPECT_EQ(rows.at("large/static-9gon"), rows.at("small/static-9gon"));  // static is static
}

}  // namespace
