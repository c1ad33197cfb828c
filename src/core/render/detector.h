// SPDX-License-Identifier: Apache-2.0
// phasor — detectors: cameras and sensors that generate rays (docs/generalized_rays.md §3).
// Image coordinates: x to the right, y down, pixel (i, j) covers [i, i+1) × [j, j+1).
#pragma once

#include <optional>
#include <string>

#include "core/render/genray.h"
#include "core/math.h"
#include "core/params/dict.h"
#include "core/render/sampler.h"
#include "core/geometry/shape.h"
#include "core/spectrum/spectrum.h"

namespace phasor {

class BuildContext;

struct DetectorSample {
    Ray ray;             // world space, unit direction, leaving the detector into the scene
    double weight = 1;   // importance weight (pixel sensitivity / pdf)
};

/// A generalized-ray sample (theory §0 D2): the mean ray leaving the detector and the GR's
/// footprint at the ray's origin for each carried wavelength (traced convention: ρ > 0 diverges
/// into the scene).
struct DetectorGrSample {
    Ray ray;
    /// 𝒟/p in radiance units: the pixel value is the mean of weight × (radiance measured along the
    /// GR). 1 for cameras; for `virtual_plane` the area of the sampled direction-cosine region, so
    /// that the mean is ∫ L cosθ dω = irradiance (theory §0 D4).
    double weight = 1;
    std::array<double, NumWavelengths> beta2{}, rho{};
    /// True if the detector integrates closed-form sources analytically over its directions (D4a,
    /// IntegrateIncidence); then the sampled GR must not measure them itself.
    bool integratesIncidence = false;
    double maxLambda = 0;  // longest carried wavelength [m] (sensor planes size their regions by it)
    /// Sensor planes: the pixel state the GR stands for (genray.h PixelState); its label may lie
    /// outside the unit disc, and then ray.d only aims the GR at the footprint-aware shape.
    PixelState pixel;
};

/// Where a sample sits among its pixel's samples (for stratifying directions across them, D4b).
struct PixelSampleIndex {
    int index = 0, count = 1;
    uint64_t seed = 0;
};

/// A 2-D sample for a pixel's directions, stratified across the pixel's samples (theory §0 D4b):
/// a Cranley–Patterson-rotated n×n lattice when the sample count is a square n² (n ≥ 2; the shift
/// is fixed per pixel and seed; the cells are visited in a per-pixel pseudo-random order, so any
/// prefix of the samples — a render stopped early — is spread over the whole lattice), otherwise
/// the sampler's next (0,2)-stratified pair.
Vec2 StratifiedPixelSample(int x, int y, const PixelSampleIndex &si, Sampler &sampler);
/// Whether StratifiedPixelSample gives every sample index the same value for sample counts a and
/// b: they are equal, or neither is a square ≥ 4 (both then use the sampler's own pair).
bool SameStratification(int a, int b);

/// Polarisation options of a detector (docs/sample_solve.md): an ideal linear polariser in front
/// of the pixels and/or Stokes output. Only integrators that carry polarisation honour them
/// (IntegratorSupport::polarization: `sample_solve`); Integrator::Validate refuses the others.
/// The frame: x = the image's x axis (Detector::PolarizationX) projected ⊥ to the direction in
/// which the light arrives, y = (that direction) × x — image up for cameras; angles count from x
/// towards y.
struct DetectorPolarization {
    std::optional<double> polarizer;  // transmission axis [rad]
    bool stokes = false;              // EXR channels S0..S3
    FileLoc polarizerLoc, stokesLoc;  // where they were given (for errors)
    bool Any() const { return polarizer.has_value() || stokes; }
};
/// The `polarizer` and `stokes` parameters every detector has, and their values.
std::vector<ParamSpec> PolarizationParams();
DetectorPolarization PolarizationFromParams(const ParamDict &d);

/// How a camera's image is shown (the PNG beside the EXR; the EXR keeps physical values): the
/// display transform of 2^stops × the image, stops = `exposure` [EV] plus, with `auto_exposure`,
/// AutoExposureStops of the image (core/image/image_io.h). README "Using phasor" documents it
/// with the display transform.
struct DetectorExposure {
    double ev = 0;
    bool automatic = false;
};
/// A camera's `exposure` and `auto_exposure` parameters (CameraParams), read.
DetectorExposure CameraExposure(const ParamDict &d);

/// The `response` parameter every detector has ("cie_xyz" or "radiometric"), and its value.
ParamSpec ResponseParam(const char *defaultResponse);
SensorResponse ResponseFromParams(const ParamDict &d);
/// The parameters every camera has (to_world, fov, resolution, pixel, response), followed by
/// `extra`; and the validated resolution they give.
std::vector<ParamSpec> CameraParams(std::vector<ParamSpec> extra = {});
std::pair<int, int> CameraResolution(const ParamDict &d);
/// A camera's response with its `white_balance` applied (CameraParams).
SensorResponse CameraResponse(const ParamDict &d, BuildContext &ctx);

/// Geometry of a sensor plane (`virtual_plane`) for integrators that compute the field on it
/// directly (`rs`): pixel (i, j) has its centre at origin + s·x_i + t·y_j with
/// x_i = −width/2 + (i + ½)·pitchX, y_j = height/2 − (j + ½)·pitchY; its sensitivity is
/// N(0, σ²I) about the centre (gaussian) or 1_box ⊛ N(0, σ²) normalised to unit integral (box,
/// theory §0 D2). Pixels report flux / referenceIrradiance.
struct SensorPlaneGeometry {
    Vec3 origin;
    Frame frame;  // s = image x, t = image −y … up (local +y), n = front normal
    double width = 0, height = 0, pitchX = 0, pitchY = 0, sigma = 0;
    int nx = 0, ny = 0;
    bool gaussianPixel = true;
    double referenceIrradiance = 1;  // [W/m²]
    Vec2 PixelCenter(int i, int j) const {
        return Vec2(-0.5 * width + (i + 0.5) * pitchX, 0.5 * height - (j + 0.5) * pitchY);
    }
};

/// The points whose directions bound a sensor's aimed region (D4b): the corners of an aperture
/// plate's openings (the plate is far larger than what diffracts), else of the shape's bounds.
std::vector<Vec3> AimCorners(const Shape &aim);

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

    // ---- Generalized rays (theory §0 D2, D4, D4a, D4b) ------------------------------------------
    /// True if GenerateGR is implemented (the `grt` integrator needs it).
    virtual bool SupportsGR() const { return false; }
    /// A GR for pixel (x, y), sample `si` of the pixel; draws what it needs from `sampler`
    /// (position in the pixel first, then directions / lens). Wavelengths set the footprint.
    virtual std::optional<DetectorGrSample> GenerateGR(int x, int y, const PixelSampleIndex &si,
                                                       Sampler &sampler, const SampledWavelengths &wl) const;
    /// True if GenerateGR's samples depend on the pixel's sample count (PixelSampleIndex::count:
    /// StratifiedPixelSample's lattice), so that samples taken for one spp differ from those of
    /// another (a render resumed to a new spp then differs from a fresh one: SameStratification).
    virtual bool StratifiesAcrossSamples() const { return false; }
    /// D4a: the pixel value (same units as weight × radiance) contributed by a closed-form source
    /// that reaches the sample's origin unobstructed, integrated analytically over the detector's
    /// directions. Only called when the sample has integratesIncidence.
    virtual SampledSpectrum IntegrateIncidence(const DetectorGrSample &s, const GrIncidence &inc) const;
    /// The image's x axis in world space for the sample's polarisation frame (DetectorPolarization).
    virtual Vec3 PolarizationX(const DetectorGrSample &s) const {
        (void)s;
        return Vec3(1, 0, 0);
    }
    const DetectorPolarization &Polarization() const { return polarization_; }
    void SetPolarization(DetectorPolarization p) { polarization_ = std::move(p); }
    /// How the image is shown (cameras; a sensor plane's default: 0 EV, no automatic exposure).
    const DetectorExposure &Exposure() const { return exposure_; }
    void SetExposure(DetectorExposure e) { exposure_ = e; }

    /// Sensor planes describe themselves for field-based integrators; nullptr for cameras.
    virtual const SensorPlaneGeometry *SensorPlane() const { return nullptr; }
    /// Sensor planes (D4b): the shape whose directions are sampled (nullptr: the whole acceptance
    /// cone); whether the scene may choose one (no `aim`, auto_aim on); and setting it.
    virtual const Shape *AimTarget() const { return nullptr; }
    virtual bool MayAutoAim() const { return false; }
    virtual void AimAt(std::shared_ptr<Shape> shape) { (void)shape; }

    std::string name;

  private:
    int width_, height_;
    SensorResponse response_;
    DetectorPolarization polarization_;
    DetectorExposure exposure_;
};

}  // namespace phasor
