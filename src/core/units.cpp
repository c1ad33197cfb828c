// SPDX-License-Identifier: Apache-2.0
#include "core/units.h"

#include <cmath>
#include <map>

#include "core/math.h"

namespace phasor {

namespace {

struct NamedUnit {
    const char *name;
    double scale;
    Dim dim;
};

// Simple (non-compound) units. Micro is written u, µ (U+00B5) or μ (U+03BC).
const NamedUnit kUnits[] = {
    {"pm", 1e-12, Dim::Length()}, {"nm", 1e-9, Dim::Length()}, {"um", 1e-6, Dim::Length()},
    {"mm", 1e-3, Dim::Length()},  {"cm", 1e-2, Dim::Length()}, {"m", 1.0, Dim::Length()},
    {"km", 1e3, Dim::Length()},
    {"rad", 1.0, Dim::Angle()},   {"mrad", 1e-3, Dim::Angle()}, {"urad", 1e-6, Dim::Angle()},
    {"deg", Pi / 180, Dim::Angle()},
    {"sr", 1.0, Dim::SolidAngle()}, {"msr", 1e-3, Dim::SolidAngle()},
    {"W", 1.0, Dim::Power()},     {"mW", 1e-3, Dim::Power()},  {"uW", 1e-6, Dim::Power()},
    {"nW", 1e-9, Dim::Power()},   {"kW", 1e3, Dim::Power()},
    {"K", 1.0, Dim::Temperature()},
    {"s", 1.0, Dim::Time()},      {"ms", 1e-3, Dim::Time()},   {"us", 1e-6, Dim::Time()},
    {"ns", 1e-9, Dim::Time()},    {"ps", 1e-12, Dim::Time()},  {"fs", 1e-15, Dim::Time()},
};

// Replace the two micro signs by 'u'.
std::string NormaliseMicro(const std::string &s) {
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
        unsigned char c = s[i];
        if (c == 0xC2 && i + 1 < s.size() && (unsigned char)s[i + 1] == 0xB5) { out += 'u'; ++i; continue; }
        if (c == 0xCE && i + 1 < s.size() && (unsigned char)s[i + 1] == 0xBC) { out += 'u'; ++i; continue; }
        out += s[i];
    }
    return out;
}

std::optional<Unit> SimpleUnit(const std::string &name) {
    for (const NamedUnit &u : kUnits)
        if (name == u.name) return Unit{u.scale, u.dim};
    return std::nullopt;
}

// factor := "1" | simple [ "^" [-] digits ]
std::optional<Unit> ParseFactor(const std::string &f) {
    if (f == "1") return Unit{1.0, Dim::None()};
    std::string base = f;
    int power = 1;
    if (auto caret = f.find('^'); caret != std::string::npos) {
        base = f.substr(0, caret);
        std::string p = f.substr(caret + 1);
        if (p.empty() || p.size() > 3) return std::nullopt;
        std::size_t i = (p[0] == '-') ? 1 : 0;
        if (i == p.size()) return std::nullopt;
        for (std::size_t j = i; j < p.size(); ++j)
            if (p[j] < '0' || p[j] > '9') return std::nullopt;
        power = std::stoi(p);
        if (power == 0) return std::nullopt;
    }
    auto u = SimpleUnit(base);
    if (!u) return std::nullopt;
    return Unit{std::pow(u->scale, power), u->dim.Pow(power)};
}

}  // namespace

std::optional<Unit> ParseUnit(const std::string &text) {
    std::string s = NormaliseMicro(text);
    if (s.empty()) return std::nullopt;
    Unit result{1.0, Dim::None()};
    char op = '*';
    std::size_t start = 0;
    for (std::size_t i = 0; i <= s.size(); ++i) {
        if (i == s.size() || s[i] == '/' || s[i] == '*') {
            auto f = ParseFactor(s.substr(start, i - start));
            if (!f) return std::nullopt;
            if (op == '*') { result.scale *= f->scale; result.dim = result.dim * f->dim; }
            else { result.scale /= f->scale; result.dim = result.dim / f->dim; }
            if (i < s.size()) op = s[i];
            start = i + 1;
        }
    }
    return result;
}

const std::vector<std::string> &KnownUnitNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> v;
        for (const NamedUnit &u : kUnits) v.push_back(u.name);
        for (const char *c : {"W/m^2", "W/m^2/sr", "W/sr", "um^2", "mm^2", "m^2", "1/m"}) v.push_back(c);
        return v;
    }();
    return names;
}

std::string Dim::ToString() const {
    struct Part { int e; const char *name; };
    const Part parts[] = {{power, "W"}, {length, "m"}, {angle, "rad"}, {solidAngle, "sr"},
                          {temperature, "K"}, {time, "s"}};
    std::string num, den;
    for (const Part &p : parts) {
        if (p.e == 0) continue;
        int e = std::abs(p.e);
        std::string t = std::string(p.name) + (e != 1 ? "^" + std::to_string(e) : "");
        if (p.e > 0) num += (num.empty() ? "" : "*") + t;
        else den += "/" + t;
    }
    if (num.empty() && den.empty()) return "1";
    if (num.empty()) num = "1";
    return num + den;
}

std::string Dim::Describe() const {
    if (IsNone()) return "a plain number";
    if (*this == Length()) return "a length";
    if (*this == Area()) return "an area";
    if (*this == Angle()) return "an angle";
    if (*this == SolidAngle()) return "a solid angle";
    if (*this == Power()) return "a power";
    if (*this == Temperature()) return "a temperature";
    if (*this == Time()) return "a time";
    if (*this == Irradiance()) return "an irradiance";
    if (*this == Radiance()) return "a radiance";
    if (*this == Intensity()) return "a radiant intensity";
    return "a quantity in " + ToString();
}

std::string PreferredUnit(Dim d, double v, double *scale) {
    struct Choice { Dim dim; const char *unit; double s; };
    *scale = 1;
    if (d == Dim::Length()) {
        double a = std::abs(v);
        if (a == 0 || a >= 1) return "m";
        if (a >= 1e-2) { *scale = 1e-2; return "cm"; }
        if (a >= 1e-3) { *scale = 1e-3; return "mm"; }
        if (a >= 1e-6) { *scale = 1e-6; return "um"; }
        *scale = 1e-9;
        return "nm";
    }
    if (d == Dim::Angle()) { *scale = Pi / 180; return "deg"; }
    if (d.IsNone()) return "";
    return d.ToString();
}

}  // namespace phasor
