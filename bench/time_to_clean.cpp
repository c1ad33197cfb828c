// SPDX-License-Identifier: Apache-2.0
// Time to a clean image (issue 21): for each showcase scene (and the double slit) a reference
// render per integrator at ref_factor × the largest budget, then renders at 1, 2, 4, … spp (the
// double slit: 64, 128, …, its direction lattice needs many);
// prints, per scene and integrator, the CPU time to reach 5 % and 2 % relative RMSE against the
// reference and the cost per sample relative to `ray` (the slope of CPU time against spp over all
// renders and the reference, so start-up does not enter the ratio).
//
// It drives a `phasor` executable (by default this build's), so the same program measures an older
// tree: `bench_time_to_clean --phasor OLD/build/bin/phasor --scenes OLD/scenes`. Times are the CPU
// time (user + system) of each render process on one thread (--threads 1), which a shared machine
// disturbs far less than wall time; each includes start-up (scene build, pilot), as a user's does.
//
// Relative RMSE = √(mean over pixels and R, G, B of (image − reference)²) / mean(reference); the
// reference's own noise adds ~1/ref_factor of the image's variance (≤ 3 % of the RMSE at 16×).
// Reaching a level is interpolated between the bracketing renders (log error linear in log time); a
// level not reached by the largest budget is extrapolated from the last render with error ∝ spp^−½
// at the measured CPU cost per spp (marked ≈).
//
//   bench_time_to_clean [--phasor BIN] [--scenes DIR] [--size N] [--max-spp S] [--ref-factor F]
//                       [--integrators grt,sample_solve,ray] [--only cd,boa,…] [--work DIR]
// Defaults: the issue's 512×512, budgets up to 64 spp, references at 16× (hours on 2 cores; the
// README's table names the size it used).
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/image/film.h"
#include "core/image/image_io.h"

namespace {

struct Options {
    std::string phasor = PHASOR_BINARY;
    std::string scenes = PHASOR_SOURCE_DIR "/scenes";
    std::string work = "out/time_to_clean";
    int size = 512, maxSpp = 64, refFactor = 16;
    std::vector<std::string> integrators{"grt", "sample_solve", "ray"};
    std::vector<std::string> only;
};

std::vector<std::string> Split(const std::string &s) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    for (std::string item; std::getline(ss, item, ',');)
        if (!item.empty()) out.push_back(item);
    return out;
}

double ChildCpuSeconds() {
    rusage u{};
    getrusage(RUSAGE_CHILDREN, &u);
    return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Scene {
    std::string name, file;
    bool square;    // takes -D res=[N N]
    int sppScale;   // the double slit's direction lattice needs many samples: budgets × 64
};

// One render; returns its CPU seconds (or a negative number when it failed).
double Render(const Options &o, const Scene &s, const std::string &integrator, int spp, int seed,
              const std::string &out) {
    std::string cmd = "'" + o.phasor + "' render '" + s.file + "' --integrator " + integrator +
                      " --spp " + std::to_string(spp) + " --seed " + std::to_string(seed) +
                      " --threads 1 --quiet -o '" + out + "'";
    if (s.square) cmd += " -D 'res=[" + std::to_string(o.size) + " " + std::to_string(o.size) + "]'";
    cmd += " > /dev/null 2>&1";
    const double before = ChildCpuSeconds();
    if (std::system(cmd.c_str()) != 0) {
        std::fprintf(stderr, "failed: %s\n", cmd.c_str());
        return -1;
    }
    return ChildCpuSeconds() - before;
}

std::vector<double> Values(const phasor::Image &img) {
    std::vector<double> v;
    const bool rgb = img.ChannelIndex("R") >= 0 && img.ChannelIndex("G") >= 0 && img.ChannelIndex("B") >= 0;
    for (const char *ch : rgb ? std::vector<const char *>{"R", "G", "B"} : std::vector<const char *>{"intensity"}) {
        const std::vector<double> c = phasor::ChannelValues(img, ch);
        v.insert(v.end(), c.begin(), c.end());
    }
    return v;
}

double RelativeRmse(const std::vector<double> &a, const std::vector<double> &ref) {
    double se = 0, mean = 0;
    for (std::size_t i = 0; i < ref.size(); ++i) {
        se += (a[i] - ref[i]) * (a[i] - ref[i]);
        mean += ref[i];
    }
    mean /= ref.size();
    return std::sqrt(se / ref.size()) / mean;
}

double Sqr(double v) { return v * v; }

struct Point {
    int spp;
    double cpu, err;
};

// CPU time at which the error reaches `level` (error ∝ time^−½ between and after the points).
std::string TimeTo(const std::vector<Point> &pts, double level, double cpuPerSpp) {
    char buf[64];
    for (std::size_t i = 0; i < pts.size(); ++i) {
        if (pts[i].err > level) continue;
        if (i == 0) {
            std::snprintf(buf, sizeof buf, "≤ %.2f s", pts[0].cpu);
            return buf;
        }
        // log err linear in log time between i − 1 and i.
        const Point &a = pts[i - 1], &b = pts[i];
        const double slope = std::log(b.err / a.err) / std::log(b.cpu / a.cpu);
        const double t = a.cpu * std::exp(std::log(level / a.err) / slope);
        std::snprintf(buf, sizeof buf, "%.2f s", t);
        return buf;
    }
    // Not reached: the last render plus the samples that would reach it (variance ∝ 1/spp) at the
    // measured CPU cost per spp.
    const Point &l = pts.back();
    std::snprintf(buf, sizeof buf, "≈ %.1f s", l.cpu + cpuPerSpp * l.spp * (Sqr(l.err / level) - 1));
    return buf;
}

}  // namespace

int main(int argc, char **argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "%s needs a value\n", a.c_str());
                std::exit(1);
            }
            return argv[++i];
        };
        if (a == "--phasor") o.phasor = next();
        else if (a == "--scenes") o.scenes = next();
        else if (a == "--work") o.work = next();
        else if (a == "--size") o.size = std::stoi(next());
        else if (a == "--max-spp") o.maxSpp = std::stoi(next());
        else if (a == "--ref-factor") o.refFactor = std::stoi(next());
        else if (a == "--integrators") o.integrators = Split(next());
        else if (a == "--only") o.only = Split(next());
        else {
            std::fprintf(stderr, "unknown option '%s' (see bench/time_to_clean.cpp)\n", a.c_str());
            return 1;
        }
    }
    std::vector<Scene> scenes;
    for (const char *n : {"bornite", "boa", "beetle", "cd", "soap_bubble"})
        scenes.push_back({n, o.scenes + "/showcase/" + n + ".wscene", true, 1});
    scenes.push_back({"double_slit", o.scenes + "/validation/double_slit.wscene", false, 64});
    std::filesystem::create_directories(o.work);

    std::printf("Time to a clean image: %s, %d×%d (double slit: its 48 pixels), 1 thread, CPU seconds;\n"
                "references at %d× %d spp (seed 1000), renders at 1 … %d spp (seed 1)\n\n",
                o.phasor.c_str(), o.size, o.size, o.refFactor, o.maxSpp, o.maxSpp);
    std::printf("| scene | integrator | to 5 %% | to 2 %% | rel. RMSE at %d spp | CPU s per spp | per spp / ray |\n",
                o.maxSpp);
    std::printf("|---|---|---|---|---|---|---|\n");
    for (const Scene &s : scenes) {
        if (!o.only.empty() && std::find(o.only.begin(), o.only.end(), s.name) == o.only.end()) continue;
        std::map<std::string, double> perSpp;
        std::map<std::string, std::vector<Point>> curves;
        for (const std::string &integ : o.integrators) {
            const std::string base = o.work + "/" + s.name + "_" + integ;
            const int refSpp = o.maxSpp * o.refFactor * s.sppScale;
            const double refCpu = Render(o, s, integ, refSpp, 1000, base + "_ref.exr");
            if (refCpu < 0) continue;
            const std::vector<double> ref = Values(phasor::ReadImage(base + "_ref.exr"));
            std::vector<Point> pts;
            for (int spp = s.sppScale; spp <= o.maxSpp * s.sppScale; spp *= 2) {
                const double cpu = Render(o, s, integ, spp, 1, base + ".exr");
                if (cpu < 0) break;
                pts.push_back({spp, cpu, RelativeRmse(Values(phasor::ReadImage(base + ".exr")), ref)});
            }
            if (pts.size() < 2 || !std::isfinite(pts.back().err)) continue;
            // CPU seconds per spp: the least-squares slope of process CPU time against spp over every
            // render, the reference's long lever arm included (start-up is the intercept) — robust on
            // a loaded machine, where the render loop's wall time is not.
            std::vector<Point> fit = pts;
            fit.push_back({refSpp, refCpu, 0});
            double ms = 0, mc = 0, sxx = 0, sxy = 0;
            for (const Point &p : fit) ms += p.spp, mc += p.cpu;
            ms /= fit.size(), mc /= fit.size();
            for (const Point &p : fit) sxx += (p.spp - ms) * (p.spp - ms), sxy += (p.spp - ms) * (p.cpu - mc);
            perSpp[integ] = sxy / sxx;
            curves[integ] = pts;
        }
        for (const auto &[integ, pts] : curves) {
            char ratio[32] = "—";
            if (perSpp.count("ray") && perSpp["ray"] > 0)
                std::snprintf(ratio, sizeof ratio, "%.2f×", perSpp[integ] / perSpp["ray"]);
            std::printf("| %s | %s | %s | %s | %.3f | %.4f | %s |\n", s.name.c_str(), integ.c_str(),
                        TimeTo(pts, 0.05, perSpp[integ]).c_str(), TimeTo(pts, 0.02, perSpp[integ]).c_str(),
                        pts.back().err, perSpp[integ],
                        ratio);
            std::fflush(stdout);
        }
    }
    return 0;
}
