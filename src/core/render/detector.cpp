// SPDX-License-Identifier: Apache-2.0
#include "core/render/detector.h"

#include <cmath>

#include "core/render/aperture.h"
#include "core/render/material.h"
#include "core/render/registry.h"

namespace phasor {

ParamSpec ResponseParam(const char *defaultResponse) {
    return P::String("response", "sensor response: CIE XYZ (RGB output) or flat radiometric")
        .Default(Value::String(defaultResponse))
        .Choices({"cie_xyz", "radiometric"});
}

SensorResponse ResponseFromParams(const ParamDict &d) {
    return SensorResponse(d.GetString("response") == "radiometric" ? SensorResponse::Kind::Radiometric
                                                                   : SensorResponse::Kind::CieXyz);
}

namespace {

// A pseudo-random permutation of [0, l) chosen by p: element i of it (Kensler 2013, "Correlated
// Multi-Jittered Sampling", Pixar Technical Memo 13-01, §3: a hash that is a bijection on the
// smallest power-of-two domain, cycle-walked into [0, l)).
uint32_t PermutationElement(uint32_t i, uint32_t l, uint32_t p) {
    uint32_t w = l - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    do {
        i ^= p;
        i *= 0xe170893d;
        i ^= p >> 16;
        i ^= (i & w) >> 4;
        i ^= p >> 8;
        i *= 0x0929eb3f;
        i ^= p >> 23;
        i ^= (i & w) >> 1;
        i *= 1 | p >> 27;
        i *= 0x6935fa69;
        i ^= (i & w) >> 11;
        i *= 0x74dcb303;
        i ^= (i & w) >> 2;
        i *= 0x9e501cc3;
        i ^= (i & w) >> 2;
        i *= 0xc860a3df;
        i &= w;
        i ^= i >> 5;
    } while (i >= l);
    return (i + p) % l;
}

}  // namespace

namespace {
// n ≥ 2 when `count` is the square n² (StratifiedPixelSample lays an n×n lattice), else 0.
int LatticeSide(int count) {
    const int n = int(std::lround(std::sqrt(double(count))));
    return n >= 2 && n * n == count ? n : 0;
}
}  // namespace

bool SameStratification(int a, int b) { return a == b || (LatticeSide(a) == 0 && LatticeSide(b) == 0); }

Vec2 StratifiedPixelSample(int x, int y, const PixelSampleIndex &si, Sampler &sampler) {
    const int n = LatticeSide(si.count);
    if (n == 0 || si.index < 0 || si.index >= si.count) return sampler.Get2D();
    // One shift per (seed, pixel): the same rotated lattice for all of the pixel's samples.
    const uint64_t h = Hash(si.seed, uint64_t(uint32_t(x)), uint64_t(uint32_t(y)), 0x6c61747469636521ULL);
    const double sx = double(h >> 11) * 0x1p-53, sy = double(MixBits(h) >> 11) * 0x1p-53;
    // The cells are visited in a per-pixel pseudo-random order, so that the first k < n² samples
    // of a render stopped early are spread over the whole lattice (each one uniformly over the
    // pixel's directions: the partial mean stays unbiased), not confined to its first rows.
    const int cell = int(PermutationElement(uint32_t(si.index), uint32_t(si.count), uint32_t(MixBits(h ^ 0x9e3779b97f4a7c15ULL))));
    const int i = cell / n, j = cell % n;
    return {std::min((i + sx) / n, 0x1.fffffffffffffp-1), std::min((j + sy) / n, 0x1.fffffffffffffp-1)};
}

std::optional<DetectorGrSample> Detector::GenerateGR(int, int, const PixelSampleIndex &, Sampler &,
                                                    const SampledWavelengths &) const {
    return std::nullopt;
}

SampledSpectrum Detector::IntegrateIncidence(const DetectorGrSample &, const GrIncidence &) const {
    return SampledSpectrum(0.0);
}

std::vector<ParamSpec> PolarizationParams() {
    return {P::Angle("polarizer",
                     "ideal linear polariser in front of the pixels: its transmission axis, from the image x axis "
                     "towards image up (cameras; a virtual_plane's frame: docs/sample_solve.md); needs sample_solve")
                .Min(-2 * Pi)
                .Max(2 * Pi),
            P::Bool("stokes", "write the Stokes parameters S0, S1, S2, S3 as EXR channels (needs sample_solve)")
                .Default(Value::Bool(false))};
}

DetectorPolarization PolarizationFromParams(const ParamDict &d) {
    DetectorPolarization p;
    if (d.Has("polarizer")) {
        p.polarizer = d.GetNumber("polarizer");
        p.polarizerLoc = d.Loc("polarizer");
    }
    p.stokes = d.GetBool("stokes");
    if (p.stokes) p.stokesLoc = d.Loc("stokes");
    return p;
}

std::vector<ParamSpec> CameraParams(std::vector<ParamSpec> extra) {
    std::vector<ParamSpec> p = {
        P::Transform("to_world", "camera-to-world transform, e.g. lookat(eye, target, up)")
            .Default(Value::Call("lookat",
                                 {Value::Vector({0, 0, 0}, Dim::Length()), Value::Vector({0, 0, 1}, Dim::Length()),
                                  Value::Vector({0, 1, 0})},
                                 {"eye", "target", "up"})),
        P::Angle("fov", "field of view across the shorter image side")
            .Default(Value::Number(Radians(40), Dim::Angle()))
            .Min(0, true)
            .Max(Radians(179)),
        P::IntegerList("resolution", "image width and height in pixels")
            .Default(Value::List({Value::Integer(256), Value::Integer(256)}))
            .Size(2)
            .Min(1)};
    for (ParamSpec &e : extra) p.push_back(std::move(e));
    p.push_back(P::String("pixel",
                          "pixel sensitivity: box (jittered over the pixel) or gaussian (centred GR of the "
                          "pixel's angular std)")
                    .Default(Value::String("box"))
                    .Choices({"box", "gaussian"}));
    p.push_back(ResponseParam("cie_xyz"));
    p.push_back(P::Spectrum("white_balance",
                            "illuminant whose white is shown as white, e.g. blackbody(4500 K) or @lamp_spectrum "
                            "(Bradford adaptation to D65 in XYZ; cie_xyz only; default: none)"));
    for (ParamSpec &e : PolarizationParams()) p.push_back(std::move(e));
    return p;
}

SensorResponse CameraResponse(const ParamDict &d, BuildContext &ctx) {
    SensorResponse r = ResponseFromParams(d);
    if (!d.Has("white_balance")) return r;
    if (r.GetKind() != SensorResponse::Kind::CieXyz)
        throw Error(d.Loc("white_balance"), "'white_balance' needs response = \"cie_xyz\" (a radiometric "
                                            "sensor has no colour to balance)");
    try {
        r.SetWhiteBalance(*ctx.GetSpectrum(d, "white_balance"));
    } catch (const Error &e) {
        throw Error(e.Loc().Known() ? e.Loc() : d.Loc("white_balance"), e.Message());
    }
    return r;
}

std::vector<Vec3> AimCorners(const Shape &aim) {
    std::vector<Vec3> out;
    const ApertureMask *open = aim.material ? aim.material->Openings() : nullptr;
    if (open && !open->Empty()) {
        // Through the transform itself: a plate that is not a rigid motion is the shape's error
        // (Material::CheckShape reports it at its definition), not the sensor's.
        const Bounds2 b = open->Bounds();
        for (int i = 0; i < 4; ++i)
            out.push_back(aim.objectToWorld.Point(Vec3((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, 0)));
        return out;
    }
    const Bounds3 b = aim.Bounds();
    for (int i = 0; i < 8; ++i)
        out.push_back(Vec3((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z));
    return out;
}

std::pair<int, int> CameraResolution(const ParamDict &d) {
    std::vector<int> res = d.GetInts("resolution");
    if (res[0] > 65536 || res[1] > 65536 || (long long)res[0] * res[1] > (1LL << 28))
        throw Error(d.Loc("resolution"), "resolution is too large (at most 65536 per side and 2^28 pixels)");
    return {res[0], res[1]};
}

}  // namespace phasor
