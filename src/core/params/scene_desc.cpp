// SPDX-License-Identifier: Apache-2.0
#include "core/params/scene_desc.h"

#include <filesystem>

namespace phasor {

std::string AnonymousName(const std::string &type, const FileLoc &loc) {
    if (!loc.Known()) return type;
    return type + "@" + std::filesystem::path(loc.file).filename().string() + ":" + std::to_string(loc.line);
}

std::string SceneEntity::DisplayName() const { return name.empty() ? AnonymousName(type, loc) : name; }

}  // namespace phasor
