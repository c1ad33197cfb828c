// SPDX-License-Identifier: Apache-2.0
// phasor — `phasor probe`: one diffraction kernel of a scene, at one incidence and wavelength, for
// kernel authors (README "Using phasor", docs/kernels.md "Probing a kernel"). The measurement is
// a library function of its own (ProbeKernel), which the Python module's phasor.probe calls too.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/cli.h"
#include "core/math.h"

namespace phasor {

class Diagnostics;
class Material;
class OutputFiles;
struct SceneDesc;

/// Light of vacuum wavelength `lambda` [m] from (theta, phi) [rad] (θ from the normal, above 90°
/// from below; φ from the kernel's reference direction, else dp/du) on the plane z = 0 at texture
/// coordinates `uv`; the continuous lobes by `samples` Monte-Carlo samples from `seed`;
/// `rayOptics`: the ray-optics limit (ScatterQuery::rayOptics); `progressBar`: a progress bar on
/// stderr while sampling (the command line on a terminal). probe.cpp's file comment has the frame
/// and what is measured.
struct ProbeRequest {
    double theta = 0, phi = 0, lambda = 550e-9;
    Vec2 uv{0.5, 0.5};
    long long samples = 100000;
    uint64_t seed = 0;
    bool rayOptics = false;
    bool progressBar = false;
};

/// One near-delta lobe: its id and the kernel's name of it (Material::LobeName: a grating's order),
/// side, direction in the probe's frame (z = the normal, x = the kernel's reference direction or
/// dp/du) and efficiency (a power fraction).
struct ProbeLobe {
    int id = 0;
    std::string name;
    bool transmission = false;
    Vec3 wo;
    double efficiency = 0;
};
/// What probe measured: power fractions R and T, split into near-delta (exact) and continuous
/// (Monte Carlo, with the standard errors of their means) parts.
struct ProbeResult {
    bool continuous = false;  // the kernel has a continuous lobe for this query (Monte Carlo ran)
    double discreteR = 0, discreteT = 0;
    double contR = 0, contT = 0, seR = 0, seT = 0;  // continuous part, standard errors of the mean
    long long nonFinite = 0;                        // samples with a NaN/Inf weight (a kernel bug)
    std::vector<ProbeLobe> lobes;
    double psi = 0;             // the kernel's reference angle from dp/du [rad] (0 without one)
    bool hasReference = false;  // the kernel has a reference direction (Material::ReferenceAngle)
    double R() const { return discreteR + contR; }
    double T() const { return discreteT + contT; }
};

/// One named material of a scene description (`material` with or without '@'), built alone with
/// what it references, so that a material library without lights or a detector can be probed.
/// Throws phasor::Error (no location) when the name is not a Material of the scene, with a
/// suggestion; the errors of its build go to `diag` (`material` is then null).
struct ProbedMaterial {
    std::shared_ptr<Material> material;
    std::string name, type;  // the scene name and the plug-in's
};
ProbedMaterial BuildProbedMaterial(const SceneDesc &desc, const std::string &material, const std::string &scenePath,
                                   Diagnostics &diag);

/// Measures R, T and the near-delta lobes. Throws phasor::Error for a footprint-aware kernel (a
/// plane wave has no footprint) and for one whose continuous transmission probe cannot weigh.
/// The request is not checked (θ in [0, π] and not grazing, λ > 0: the callers' argument checks).
ProbeResult ProbeKernel(const ProbedMaterial &m, const ProbeRequest &r);
/// The CSV probe writes: `kind,order,theta_o,phi_o,value,stderr`, R and T, then one row per lobe.
std::string ProbeCsv(const ProbeResult &r);
/// θ from the +z normal in [0, π] and φ from +x in (−π, π] (0 on the normal) of a direction.
double ProbeTheta(const Vec3 &w);
double ProbePhi(const Vec3 &w);
/// Stages `probe --plot`'s angular map at `path` (matplotlib); without matplotlib its data is
/// staged beside (`.map.csv`) instead. Returns the file staged. Throws phasor::Error.
std::string StageProbeMap(OutputFiles &files, const std::string &path, const ProbedMaterial &m,
                          const ProbeRequest &r, const ProbeResult &result);

/// Runs `phasor probe` with the parsed options (o.scene, o.probe, o.defines, o.seed, strictness):
/// builds only the named material (and what it references) from the scene, prints R, T and the
/// near-delta lobes, and writes the CSV and the plot all or nothing. Errors are printed to stderr;
/// returns the exit status (0, or 1 with no output file written).
int RunProbe(const CliOptions &o);

}  // namespace phasor
