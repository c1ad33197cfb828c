// SPDX-License-Identifier: Apache-2.0
// phasor — display transforms through OpenColorIO 2.1 (image_io.h). OCIO 2.1 has no built-in
// configs, so phasor ships a small OCIO v2 config as text below; $OCIO overrides it when set.
// Processors are cached per (config, display, view); OCIO's CPU processors are immutable and
// safe to share between threads.

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <utility>

#include <OpenColorIO/OpenColorIO.h>

#include "core/diagnostics.h"
#include "core/image/color.h"
#include "core/image/image_io.h"

namespace OCIO = OCIO_NAMESPACE;

namespace phasor {
namespace {

// The built-in config. Scene reference = linear Rec.709 primaries with a D65 white (the space of
// the film's R,G,B). Display "sRGB" has three views:
//   Standard — the IEC 61966-2-1 sRGB encoding as OCIO's ExponentWithLinearTransform
//              (gamma 2.4, offset 0.055). Its power segment is the IEC formula; its linear
//              toe is derived by OCIO (break 0.00303993, slope 12.9232 instead of 0.0031308,
//              12.92), within 9.8e-6 of the standard — far below one 8-bit step;
//   Builtin  — Rec.709 → CIE XYZ (D65) matrix as the view transform, then OCIO's
//              "DISPLAY - CIE-XYZ-D65_to_sRGB" builtin as the display colour space;
//   Raw      — no transform.
// The Rec.709 → XYZ matrix is the one of IEC 61966-2-1 / ITU-R BT.709 (D65 white).
constexpr const char *BuiltinConfig = R"ocio(ocio_profile_version: 2

# phasor built-in colour configuration (OpenColorIO >= 2.1).

environment: {}
search_path: ""
strictparsing: true
luma: [0.2126, 0.7152, 0.0722]
name: phasor-builtin
description: phasor's built-in config (scene-linear Rec.709, sRGB display)

roles:
  default: linear_rec709
  reference: linear_rec709
  scene_linear: linear_rec709
  rendering: linear_rec709
  compositing_linear: linear_rec709
  data: raw
  color_picking: srgb_encoded
  texture_paint: srgb_encoded
  matte_paint: srgb_encoded
  color_timing: srgb_encoded
  compositing_log: srgb_encoded
  cie_xyz_d65_interchange: cie_xyz_d65

file_rules:
  - !<Rule> {name: Default, colorspace: default}

displays:
  sRGB:
    - !<View> {name: Standard, colorspace: srgb_encoded}
    - !<View> {name: Builtin, view_transform: rec709_to_xyz_d65, display_colorspace: sRGB display}
    - !<View> {name: Raw, colorspace: raw}

active_displays: [sRGB]
active_views: [Standard, Builtin, Raw]

default_view_transform: rec709_to_xyz_d65

view_transforms:
  - !<ViewTransform>
    name: rec709_to_xyz_d65
    description: linear Rec.709 to CIE XYZ (D65), no tone mapping
    from_scene_reference: !<MatrixTransform>
      matrix: [0.4123907993, 0.3575843394, 0.1804807884, 0,
               0.2126390059, 0.7151686788, 0.0721923154, 0,
               0.0193308187, 0.1191947798, 0.9505321522, 0,
               0, 0, 0, 1]

display_colorspaces:
  - !<ColorSpace>
    name: sRGB display
    family: Display
    encoding: sdr-video
    isdata: false
    from_display_reference: !<BuiltinTransform> {style: "DISPLAY - CIE-XYZ-D65_to_sRGB"}

colorspaces:
  - !<ColorSpace>
    name: linear_rec709
    aliases: [scene_linear_rec709, lin_srgb, linear]
    family: Linear
    encoding: scene-linear
    isdata: false
    description: scene-linear Rec.709 primaries, D65 white (phasor's R,G,B)

  - !<ColorSpace>
    name: srgb_encoded
    aliases: [srgb, sRGB]
    family: Display
    encoding: sdr-video
    isdata: false
    description: Rec.709 primaries with the IEC 61966-2-1 piecewise sRGB encoding
    from_scene_reference: !<ExponentWithLinearTransform> {gamma: 2.4, offset: 0.055, direction: inverse}

  - !<ColorSpace>
    name: cie_xyz_d65
    family: Linear
    encoding: scene-linear
    isdata: false
    description: CIE 1931 XYZ, D65 white
    from_scene_reference: !<MatrixTransform>
      matrix: [0.4123907993, 0.3575843394, 0.1804807884, 0,
               0.2126390059, 0.7151686788, 0.0721923154, 0,
               0.0193308187, 0.1191947798, 0.9505321522, 0,
               0, 0, 0, 1]

  - !<ColorSpace>
    name: raw
    family: Data
    encoding: data
    isdata: true
    description: non-colour data, never transformed
)ocio";

struct ColorState {
    std::mutex mutex;
    bool loaded = false;
    std::string key;  // the $OCIO value the config was loaded for ("" = built-in)
    OCIO::ConstConfigRcPtr config;
    std::map<std::pair<std::string, std::string>, OCIO::ConstCPUProcessorRcPtr> processors;
    std::map<std::string, OCIO::ConstCPUProcessorRcPtr> toLinear;  // by source colour space
};

ColorState &State() {
    static ColorState state;
    return state;
}

std::string EnvConfigPath() {
    const char *env = std::getenv("OCIO");
    return env ? std::string(env) : std::string();
}

// Loads the config for `key` ($OCIO value, or "" for the built-in one). Caller holds the mutex.
OCIO::ConstConfigRcPtr LoadConfig(const std::string &key) {
    if (key.empty()) {
        try {
            std::istringstream in(BuiltinConfig);
            OCIO::ConstConfigRcPtr config = OCIO::Config::CreateFromStream(in);
            config->validate();
            return config;
        } catch (const OCIO::Exception &e) {
            // Only reachable if the embedded text is broken: a bug, but report it, do not crash.
            throw Error(std::string("the built-in OpenColorIO config is invalid: ") + e.what());
        }
    }
    try {
        OCIO::ConstConfigRcPtr config = OCIO::Config::CreateFromFile(key.c_str());
        config->validate();
        return config;
    } catch (const OCIO::Exception &e) {
        throw Error(FileLoc{key}, "cannot use the OpenColorIO config '" + key +
                                      "' named by $OCIO: " + e.what() +
                                      " (unset OCIO to use phasor's built-in config)");
    }
}

// The config for the current $OCIO, (re)loaded when it changed. Caller holds the mutex.
void EnsureConfig(ColorState &st) {
    std::string key = EnvConfigPath();
    if (!st.loaded || key != st.key) {
        st.processors.clear();
        st.toLinear.clear();
        st.loaded = false;
        st.config = LoadConfig(key);
        st.key = key;
        st.loaded = true;
    }
}

OCIO::ConstCPUProcessorRcPtr GetProcessor(const std::string &display, const std::string &view) {
    ColorState &st = State();
    std::lock_guard<std::mutex> lock(st.mutex);
    EnsureConfig(st);
    const std::string &key = st.key;
    auto it = st.processors.find({display, view});
    if (it != st.processors.end()) return it->second;

    const std::string configName = key.empty() ? std::string("built-in") : "'" + key + "'";
    try {
        // Display/view transform from the scene_linear role (the film's linear Rec.709).
        OCIO::DisplayViewTransformRcPtr t = OCIO::DisplayViewTransform::Create();
        t->setSrc(OCIO::ROLE_SCENE_LINEAR);
        t->setDisplay(display.c_str());
        t->setView(view.c_str());
        OCIO::ConstProcessorRcPtr proc = st.config->getProcessor(t);
        // Lossless optimisation: the default level also allows approximations (fast
        // log/exp/pow, LUT inversion) that some user configs would hit.
        OCIO::ConstCPUProcessorRcPtr cpu =
            proc->getOptimizedCPUProcessor(OCIO::OPTIMIZATION_LOSSLESS);
        st.processors.emplace(std::make_pair(display, view), cpu);
        return cpu;
    } catch (const OCIO::Exception &e) {
        std::string views;
        const char *displayName = display.c_str();
        for (int i = 0; i < st.config->getNumViews(displayName); ++i)
            views += std::string(views.empty() ? "" : ", ") + st.config->getView(displayName, i);
        throw Error("cannot build the display transform '" + display + "' / '" + view +
                    "' from the " + configName + " OpenColorIO config: " + e.what() +
                    (views.empty() ? std::string() : " (views of that display: " + views + ")"));
    }
}

// The processor from colour space `name` to the scene_linear role.
OCIO::ConstCPUProcessorRcPtr GetToLinearProcessor(const std::string &name) {
    ColorState &st = State();
    std::lock_guard<std::mutex> lock(st.mutex);
    EnsureConfig(st);
    auto it = st.toLinear.find(name);
    if (it != st.toLinear.end()) return it->second;
    const std::string configName = st.key.empty() ? std::string("built-in") : "'" + st.key + "'";
    if (!st.config->getColorSpace(name.c_str())) {
        std::string names;
        for (int i = 0; i < st.config->getNumColorSpaces(); ++i)
            names += std::string(names.empty() ? "" : ", ") + st.config->getColorSpaceNameByIndex(i);
        throw Error("unknown colour space '" + name + "' in the " + configName + " OpenColorIO config (it has: " +
                    names + ")");
    }
    try {
        OCIO::ConstProcessorRcPtr proc = st.config->getProcessor(name.c_str(), OCIO::ROLE_SCENE_LINEAR);
        OCIO::ConstCPUProcessorRcPtr cpu = proc->getOptimizedCPUProcessor(OCIO::OPTIMIZATION_LOSSLESS);
        st.toLinear.emplace(name, cpu);
        return cpu;
    } catch (const OCIO::Exception &e) {
        throw Error("cannot convert colour space '" + name + "' to scene_linear with the " + configName +
                    " OpenColorIO config: " + e.what());
    }
}

// Applies `cpu` to packed RGB triples in rows of bounded length (PackedImageDesc takes `long`
// dimensions).
void ApplyPacked(const OCIO::ConstCPUProcessorRcPtr &cpu, float *rgb, std::size_t numPixels, const char *what) {
    constexpr std::size_t Chunk = 1 << 20;
    try {
        for (std::size_t start = 0; start < numPixels; start += Chunk) {
            std::size_t n = std::min(Chunk, numPixels - start);
            OCIO::PackedImageDesc desc(rgb + 3 * start, long(n), 1, 3);
            cpu->apply(desc);
        }
    } catch (const OCIO::Exception &e) {
        throw Error(std::string("OpenColorIO ") + what + " failed: " + e.what());
    }
}

}  // namespace

namespace detail {

void ApplyDisplayTransformInPlace(float *rgb, std::size_t numPixels, const DisplayOptions &opt) {
    if (numPixels == 0) return;
    OCIO::ConstCPUProcessorRcPtr cpu = GetProcessor(opt.display, opt.view);
    if (opt.exposure != 0) {
        // Exposure in stops: a scene-linear gain of 2^stops before the view transform.
        const float gain = float(std::exp2(opt.exposure));
        for (std::size_t i = 0; i < 3 * numPixels; ++i) rgb[i] *= gain;
    }
    ApplyPacked(cpu, rgb, numPixels, "display transform");
}

}  // namespace detail

Vec3 ApplyDisplayTransform(const Vec3 &linearRgb, const DisplayOptions &opt) {
    float rgb[3] = {float(linearRgb.x), float(linearRgb.y), float(linearRgb.z)};
    detail::ApplyDisplayTransformInPlace(rgb, 1, opt);
    return {rgb[0], rgb[1], rgb[2]};
}

void ConvertToSceneLinear(float *rgb, std::size_t numPixels, const std::string &colorspace) {
    OCIO::ConstCPUProcessorRcPtr cpu = GetToLinearProcessor(colorspace);
    if (numPixels == 0 || cpu->isNoOp()) return;
    ApplyPacked(cpu, rgb, numPixels, "colour space conversion");
}

std::string ColorConfigDescription() {
    std::string key = EnvConfigPath();
    return key.empty() ? std::string("built-in") : "$OCIO: " + key;
}

}  // namespace phasor
