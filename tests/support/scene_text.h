// SPDX-License-Identifier: Apache-2.0
// phasor test support — a scene from a string of .wscene text, built; a failed parse or build is
// a test failure that prints the diagnostics.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <sstream>
#include <string>

#include "core/render/scene.h"
#include "parser/parser.h"

namespace phasor::test {

/// The scene `text` describes (errors located in `name`), or nullptr after a test failure.
inline std::unique_ptr<Scene> SceneFromText(const std::string &text, const std::string &name = "test.wscene") {
    Diagnostics diag;
    auto desc = ParseSceneString(text, name, DefineList{}, diag);
    auto scene = desc ? Scene::Build(*desc, diag) : nullptr;
    std::ostringstream os;
    diag.Print(os);
    EXPECT_TRUE(scene) << os.str();
    return scene;
}

}  // namespace phasor::test
