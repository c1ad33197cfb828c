// SPDX-License-Identifier: Apache-2.0
// The plug-in families are written once (core/plugin_families.h): the generated tables (from
// phasor_add_plugin), the registry and every schema agree with that list.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/plugin_families.h"
#include "core/render/registry.h"

namespace phasor {
namespace {

// Every entry's CMake name (phasor_add_plugin's scene name, the generated table's) is its
// schema's name, and its family is the schema's family.
template <typename T>
int CheckFamily(const std::string &family) {
    EXPECT_EQ(Registry<T>::Family(), family);
    std::set<std::string> names;
    for (const PluginEntry<T> &e : Registry<T>::Entries()) {
        const Schema &s = e.schema();
        EXPECT_EQ(s.name, e.name) << family << " '" << e.name << "' is registered under another name than its schema's";
        EXPECT_EQ(s.family, family) << family << " '" << e.name << "' has a schema of family '" << s.family << "'";
        EXPECT_TRUE(names.insert(e.name).second) << family << " '" << e.name << "' is registered twice";
        EXPECT_EQ(Registry<T>::Find(e.name), &e);
    }
    return int(Registry<T>::Entries().size());
}

TEST(PluginFamilies, EveryPluginsCMakeNameAndFamilyEqualItsSchemas) {
    int plugins = 0;
#define PHASOR_CHECK_FAMILY(Keyword, family, Interface, Example) plugins += CheckFamily<Interface>(#family);
    PHASOR_PLUGIN_FAMILIES(PHASOR_CHECK_FAMILY)
#undef PHASOR_CHECK_FAMILY
    EXPECT_GE(plugins, 30);  // the tables are filled (33 plug-ins when this test was written)
}

TEST(PluginFamilies, TheRegistryListsTheFamiliesOfTheOneList) {
    std::vector<std::pair<std::string, std::string>> listed;
#define PHASOR_LIST_FAMILY(Keyword, family, Interface, Example) listed.emplace_back(#Keyword, #family);
    PHASOR_PLUGIN_FAMILIES(PHASOR_LIST_FAMILY)
#undef PHASOR_LIST_FAMILY
    const std::vector<FamilyInfo> all = AllFamilies();
    ASSERT_EQ(all.size(), listed.size());
    for (std::size_t i = 0; i < all.size(); ++i) {
        EXPECT_EQ(all[i].keyword, listed[i].first);
        EXPECT_EQ(all[i].family, listed[i].second);
        for (const Schema *s : all[i].schemas) {
            EXPECT_EQ(FindSchema(all[i].family, s->name), s);
            EXPECT_EQ(FindSchema(all[i].keyword, s->name), s);  // by keyword too
        }
    }
}

TEST(PluginFamilies, EachFamilysExampleIsOneOfItsPlugins) {
    // The parser's messages name it ("e.g. Material \"dielectric\" { … }").
#define PHASOR_CHECK_EXAMPLE(Keyword, family, Interface, Example) \
    EXPECT_NE(FindSchema(#family, #Example), nullptr) << #family " " #Example;
    PHASOR_PLUGIN_FAMILIES(PHASOR_CHECK_EXAMPLE)
#undef PHASOR_CHECK_EXAMPLE
}

}  // namespace
}  // namespace phasor
