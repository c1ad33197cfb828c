// SPDX-License-Identifier: Apache-2.0
// docs/kernels.md lists the named materials in one table ("Named materials"): the same names, in
// the same order, as core/spectrum/named_ior.h registers — a material added or renamed without
// the table fails here.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/spectrum/named_ior.h"

namespace phasor {
namespace {

TEST(NamedMaterials, TheDocsTableListsEveryOneInOrder) {
    std::ifstream in(std::string(PHASOR_SOURCE_DIR) + "/docs/kernels.md");
    ASSERT_TRUE(in) << "cannot read docs/kernels.md";
    std::string line;
    bool inTable = false, seenHeading = false;
    std::vector<std::string> names;
    while (std::getline(in, line)) {
        if (line.find("**Named materials**") != std::string::npos) {
            seenHeading = true;
            continue;
        }
        if (!seenHeading) continue;
        if (line.rfind("| `", 0) == 0) {
            inTable = true;
            const std::size_t a = line.find('`') + 1, b = line.find('`', a);
            names.push_back(line.substr(a, b - a));
        } else if (inTable) {
            break;  // the end of the table
        }
    }
    ASSERT_TRUE(seenHeading) << "docs/kernels.md has no '**Named materials**' table";
    EXPECT_EQ(names, NamedIndexNames()) << "update the table in docs/kernels.md (Named materials)";
}

}  // namespace
}  // namespace phasor
