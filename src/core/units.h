// SPDX-License-Identifier: Apache-2.0
// phasor — physical dimensions and units. Internal values are SI: metres, radians, steradians,
// watts, kelvin, seconds (theory §0 D12). Conversion happens once, when a scene value is read.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace phasor {

/// Exponents of the base dimensions. Angle and solid angle are kept as dimensions of their own so
/// that adding a length to an angle, or giving `deg` where `sr` is expected, is an error.
struct Dim {
    int8_t length = 0, angle = 0, solidAngle = 0, power = 0, temperature = 0, time = 0;

    static constexpr Dim None() { return {}; }
    static constexpr Dim Length() { return {1, 0, 0, 0, 0, 0}; }
    static constexpr Dim Area() { return {2, 0, 0, 0, 0, 0}; }
    static constexpr Dim Angle() { return {0, 1, 0, 0, 0, 0}; }
    static constexpr Dim SolidAngle() { return {0, 0, 1, 0, 0, 0}; }
    static constexpr Dim Power() { return {0, 0, 0, 1, 0, 0}; }
    static constexpr Dim Temperature() { return {0, 0, 0, 0, 1, 0}; }
    static constexpr Dim Time() { return {0, 0, 0, 0, 0, 1}; }
    static constexpr Dim Irradiance() { return {-2, 0, 0, 1, 0, 0}; }        // W/m^2
    static constexpr Dim Radiance() { return {-2, 0, -1, 1, 0, 0}; }         // W/m^2/sr
    static constexpr Dim Intensity() { return {0, 0, -1, 1, 0, 0}; }         // W/sr
    static constexpr Dim SpectralRadiance() { return {-3, 0, -1, 1, 0, 0}; } // W/m^2/sr/m

    constexpr Dim operator*(Dim o) const {
        return {int8_t(length + o.length), int8_t(angle + o.angle), int8_t(solidAngle + o.solidAngle),
                int8_t(power + o.power), int8_t(temperature + o.temperature), int8_t(time + o.time)};
    }
    constexpr Dim operator/(Dim o) const {
        return {int8_t(length - o.length), int8_t(angle - o.angle), int8_t(solidAngle - o.solidAngle),
                int8_t(power - o.power), int8_t(temperature - o.temperature), int8_t(time - o.time)};
    }
    constexpr Dim Pow(int n) const {
        return {int8_t(length * n), int8_t(angle * n), int8_t(solidAngle * n), int8_t(power * n),
                int8_t(temperature * n), int8_t(time * n)};
    }
    constexpr bool IsNone() const { return *this == Dim{}; }
    constexpr bool operator==(const Dim &) const = default;

    /// SI rendering, e.g. "m", "W/m^2/sr", "1" for dimensionless.
    std::string ToString() const;
    /// Words for messages: "a length", "an angle", "an irradiance", "a quantity of dimension W/m".
    std::string Describe() const;
};

struct Unit {
    double scale = 1;  // multiply a value in this unit by `scale` to get SI
    Dim dim;
};

/// Parses a unit expression such as "nm", "um", "µm" (U+00B5 or U+03BC), "deg", "W/m^2",
/// "W/m^2/sr", "mm^2", "1/m". Returns nullopt for an unknown unit.
std::optional<Unit> ParseUnit(const std::string &text);
/// All simple unit names (for suggestions and docs).
const std::vector<std::string> &KnownUnitNames();
/// A conventional unit for showing a value of this dimension to a user (e.g. nm for
/// wavelength-sized lengths is chosen by the caller; here: "m", "deg", "W/m^2" …).
std::string PreferredUnit(Dim d, double siValue, double *scaleOut);

}  // namespace phasor
