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

TEST(Suggest, CaseAloneIsOneEdit) {
    // Named materials are case-sensitive; a name that differs only in case is suggested.
    std::vector<std::string> names = {"Cu2O", "TiO2", "BK7", "chitin"};
    EXPECT_EQ(Suggest("cu2o", names), "Cu2O");  // 2 substitutions by plain distance, over the limit of 1
    EXPECT_EQ(Suggest("bk7", names), "BK7");
    EXPECT_EQ(Suggest("Chitin", names), "chitin");
    EXPECT_EQ(Suggest("zno", names), "");
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
    d.Error(FileLoc{"a", 5, 1, 1}, "e");  // a duplicate beyond the limit is not counted
    for (int i = 0; i < 4; ++i) d.Warning(FileLoc{"a", i + 1, 1, 1}, "w");
    EXPECT_EQ(d.ErrorCount(), 5u);
    EXPECT_EQ(d.WarningCount(), 4u);
    EXPECT_EQ(d.All().size(), 6u);
    EXPECT_TRUE(d.TooManyErrors());
    std::ostringstream os;
    d.Print(os);
    EXPECT_NE(os.str().find("\n2 more errors not shown\n1 more warning not shown\n"), std::string::npos) << os.str();
}

TEST(Diagnostics, UnknownNamesAreErrorsUnlessPermissive) {
    Diagnostics d;
    d.UnknownName(FileLoc{"a", 1, 1, 1}, "unknown parameter 'x'");
    EXPECT_EQ(d.ErrorCount(), 1u);
    Diagnostics permissive;
    permissive.SetPermissive(true);
    permissive.UnknownName(FileLoc{"a", 1, 1, 1}, "unknown parameter 'x'");
    EXPECT_EQ(permissive.ErrorCount(), 0u);
    EXPECT_EQ(permissive.WarningCount(), 1u);
}

TEST(Diagnostics, ConsequencesOfReportedErrorsAreNotReported) {
    Diagnostics d;
    d.Report(Error::Consequence(FileLoc{"a", 1, 1, 1}));
    EXPECT_EQ(d.ErrorCount(), 0u);
    d.Report(Error(FileLoc{"a", 1, 1, 1}, "bad"));
    EXPECT_EQ(d.ErrorCount(), 1u);
}

}  // namespace
}  // namespace phasor
