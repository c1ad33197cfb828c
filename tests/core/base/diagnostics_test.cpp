// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <sstream>

#include "core/diagnostics.h"

namespace phasor {
namespace {

TEST(EditDistance, CountsInsertionsDeletionsSubstitutionsAndSwaps) {
    EXPECT_EQ(EditDistance("", "abc"), 3u);
    EXPECT_EQ(EditDistance("kitten", "sitting"), 3u);
    EXPECT_EQ(EditDistance("width", "widht"), 1u);  // adjacent swap
    EXPECT_EQ(EditDistance("radius", "radius"), 0u);
}

TEST(Suggest, FindsPlausibleTyposOnly) {
    std::vector<std::string> names = {"width", "height", "radius", "material"};
    EXPECT_EQ(Suggest("widht", names), "width");
    EXPECT_EQ(Suggest("radus", names), "radius");
    EXPECT_EQ(Suggest("matrial", names), "material");
    EXPECT_EQ(Suggest("colour", names), "");
}

TEST(Diagnostics, QuotesTheSourceLineWithACaretAndNotes) {
    Diagnostics d;
    d.AddSource("s.wscene", "wscene 1\nShape \"sphere\" { radius = 1 }\n");
    d.Error(FileLoc{"s.wscene", 2, 27, 1}, "'radius' expects a length",
            {Diagnostic{Severity::Note, FileLoc{"main.wscene", 4, 1, 1}, "included from here", {}}});
    std::ostringstream os;
    d.Print(os);
    EXPECT_EQ(os.str(),
              "s.wscene:2:27: error: 'radius' expects a length\n"
              "    Shape \"sphere\" { radius = 1 }\n"
              "                              ^\n"
              "main.wscene:4:1: note: included from here\n");
    EXPECT_EQ(d.ErrorCount(), 1u);
}

TEST(Diagnostics, StrictTurnsWarningsIntoErrorsAndDuplicatesAreReportedOnce) {
    Diagnostics d(true);
    FileLoc loc{"a.wscene", 1, 1, 1};
    d.Warning(loc, "unused parameter 'x'");
    d.Warning(loc, "unused parameter 'x'");
    EXPECT_EQ(d.ErrorCount(), 1u);
    EXPECT_EQ(d.All().size(), 1u);
}

TEST(Diagnostics, StopsStoringAfterTheLimitButKeepsCounting) {
    Diagnostics d(false, 3);
    for (int i = 0; i < 5; ++i) d.Error(FileLoc{"a", i + 1, 1, 1}, "e");
    EXPECT_EQ(d.ErrorCount(), 5u);
    EXPECT_EQ(d.All().size(), 3u);
    EXPECT_TRUE(d.TooManyErrors());
}

}  // namespace
}  // namespace phasor
