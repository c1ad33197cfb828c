// SPDX-License-Identifier: Apache-2.0
// phasor — detectors: cameras and sensors that generate rays (design.md §3 "detectors").
// Image coordinates: x to the right, y down, pixel (i, j) covers [i, i+1) × [j, j+1).
#pragma once

#include <optional>
#include <string>

#include "core/math.h"
#include "core/params.h"
#include "core/shape.h"
#include "core/spectrum.h"

namespace phasor {

struct DetectorSample {
    Ray ray;             // world space, unit direction, leaving the detector into the scene
    double weight = 1;   // importance weight (pixel sensitivity / pdf)
};

/// The `response` parameter every detector has ("cie_xyz" or "radiometric"), and its value.
ParamSpec ResponseParam(const char *defaultResponse);
SensorResponse ResponseFromParams(const ParamDict &d);

class Detector {
  public:
    explicit Detector(int width, int height, SensorResponse response)
        : width_(width), height_(height), response_(response) {}
    virtual ~Detector() = default;
    int Width() const { return width_; }
    int Height() const { return height_; }
    const SensorResponse &Response() const { return response_; }

    /// A ray through continuous image position pFilm (pixel units) using lens sample uLens.
    virtual std::optional<DetectorSample> Generate(const Vec2 &pFilm, const Vec2 &uLens) const = 0;
    virtual std::string ToString() const = 0;

    std::string name;

  private:
    int width_, height_;
    SensorResponse response_;
};

}  // namespace phasor
