// SPDX-License-Identifier: Apache-2.0
// Fig. S10e of the supplement — "PLT as a variance reduction technique" — on
// scenes/validation/sample_solve_gratings.wscene (issue 13): the error in the shadowed strip, which
// only the gratings' diffraction orders light, against samples per pixel, for
//   * sample_solve (the partially coherent solve: a distant source measured in closed form through
//     the orders integrates its whole angular profile),
//   * sample_solve with force_coherent = true (fully coherent transport: one coherent plane wave drawn
//     from the profile per measurement; the same image in expectation),
//   * grt (its closed-form measurement is the same ensemble average: on this scene it is the
//     partially coherent solve without polarisation, sample by sample).
// The strip: the pixels whose camera ray meets the floor at 2 cm < x < 9 cm, |y| < 9 cm; only those
// are rendered (the integrators' per-pixel estimates, one thread, the independent sampler so that
// samples are i.i.d.). Each run draws `--max-spp` samples per pixel; the variance of one sample
// (averaged over the strip) gives the spp ratio at equal error (RMSE = √(σ²/spp) for these unbiased
// estimators — the light reaching the strip is a caustic of the gratings' orders, heavy-tailed, so
// the variance, not a fit to a few noisy renders, is what is compared); the RMSE curves are
// measured over disjoint batches against the reference (sample_solve at `--ref-spp`, its own
// variance subtracted). Printed: a Markdown table, the ratio, CSV and a plot (the plot module's
// convergence figure) in `--out`. Then sample_solve/grt time at equal spp on whole images (this
// scene and a Cornell box with a glass sphere, where sample_solve's solve has most to do).
//
//   bench_sample_solve [--illumination diffuse|collimated] [--max-spp N] [--ref-spp N] [--res N]
//                      [--out DIR] [--threads T (timing; default 1)] [--time-spp N]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>

#include "app/plot.h"
#include "core/image/output_file.h"
#include "core/render/pixel_integrator.h"
#include "parser/parser.h"
#include "support/scene_builder.h"

using namespace phasor;

namespace {

std::unique_ptr<Scene> Load(const std::string &file, const DefineList &defines, const std::string &integrator) {
    Diagnostics diag;
    auto desc = ParseSceneFile(std::string(PHASOR_SOURCE_DIR) + "/scenes/validation/" + file, defines, diag);
    std::unique_ptr<Scene> scene;
    if (desc) scene = Scene::Build(*desc, diag, integrator);
    if (!scene) {
        diag.Print(std::cerr);
        std::exit(1);
    }
    return scene;
}

struct Pixel {
    int x, y;
};

/// `n` samples of pixel p with the independent sampler (seed `seed`): each sample's intensity, as
/// the film reduces it (Film::AddSample).
std::vector<double> PixelSamples(const Scene &scene, const Pixel &p, int n, uint64_t seed) {
    const auto &in = dynamic_cast<const PixelIntegrator &>(scene.GetIntegrator());
    const SensorResponse &response = scene.GetDetector().Response();
    auto sampler = MakeIndependentSampler(seed);
    std::vector<double> v(std::size_t(n), 0.0);
    for (int s = 0; s < n; ++s) {
        sampler->StartPixelSample(p.x, p.y, s);
        PathStats ps;
        ps.sample = PixelSampleIndex{s, n, seed};
        SampledWavelengths wl = scene.Wavelengths().Sample(sampler->Get1D());
        ScratchBuffer scratch;
        const SampledSpectrum L = in.EstimatePixel(scene, p.x, p.y, wl, *sampler, scratch, ps);
        double sum = 0;
        for (int i = 0; i < wl.Count(); ++i)
            if (wl.pdf[i] > 0) sum += L[i] / wl.pdf[i] * response.Intensity(wl.lambda[i]);
        v[std::size_t(s)] = sum / wl.Count();
    }
    return v;
}

double WholeImageSeconds(const Scene &scene, int spp, int threads) {
    const Detector &d = scene.GetDetector();
    double best = 1e300;
    for (int r = 0; r < 3; ++r) {
        Film film(d.Width(), d.Height(), d.Response());
        RenderOptions opt;
        opt.spp = spp;
        opt.seed = 1;
        opt.threads = threads;
        best = std::min(best, scene.GetIntegrator().Render(scene, film, opt).seconds);
    }
    return best;
}

}  // namespace

int main(int argc, char **argv) {
    std::string illumination = "diffuse", out = "out/bench_sample_solve";
    int maxSpp = 4096, refSpp = 16384, res = 96, threads = 1, timeSpp = 64;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string a = argv[i], v = argv[i + 1];
        if (a == "--illumination") illumination = v;
        else if (a == "--max-spp") maxSpp = std::atoi(v.c_str());
        else if (a == "--ref-spp") refSpp = std::atoi(v.c_str());
        else if (a == "--res") res = std::atoi(v.c_str());
        else if (a == "--out") out = v;
        else if (a == "--threads") threads = std::atoi(v.c_str());
        else if (a == "--time-spp") timeSpp = std::atoi(v.c_str());
        else {
            std::cerr << "unknown option " << a << "\n";
            return 1;
        }
    }
    const DefineList defines = {{"illumination", "\"" + illumination + "\""}, {"res", std::to_string(res)}};
    const std::map<std::string, std::string> runs = {
        {"sample_solve", "solve"}, {"sample_solve force_coherent", "coherent"}, {"grt", "gr"}};
    std::map<std::string, std::unique_ptr<Scene>> scenes;
    for (const auto &[label, name] : runs) scenes[label] = Load("sample_solve_gratings.wscene", defines, name);
    const Scene &ref = *scenes["sample_solve"];

    // The shadowed strip's pixels: camera rays (pixel centres) that meet the floor inside it.
    std::vector<Pixel> strip;
    const Detector &det = ref.GetDetector();
    for (int y = 0; y < det.Height(); ++y)
        for (int x = 0; x < det.Width(); ++x) {
            auto ds = det.Generate(Vec2(x + 0.5, y + 0.5), Vec2(0.5, 0.5));
            auto si = ds ? ref.Intersect(ds->ray) : std::nullopt;
            if (si && si->shape->name == "floor" && si->p.x > 0.02 && si->p.x < 0.09 && std::abs(si->p.y) < 0.09)
                strip.push_back({x, y});
        }
    std::printf("## sample_solve: Fig. S10e (error in the shadowed strip vs spp)\n\n");
    std::printf("scene: scenes/validation/sample_solve_gratings.wscene, illumination = %s, %d×%d camera; the strip: "
                "%zu pixels; %d independent samples per pixel and run; reference: sample_solve at %d spp\n\n",
                illumination.c_str(), det.Width(), det.Height(), strip.size(), maxSpp, refSpp);

    // The reference: sample_solve with `refSpp` samples per pixel (independent seeds).
    std::vector<double> refMean(strip.size());
    double refVar = 0;  // Σ over the strip of the reference's variance of the mean
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t k = 0; k < strip.size(); ++k) {
        const std::vector<double> v = PixelSamples(ref, strip[k], refSpp, 1000 + k);
        double m = 0, m2 = 0;
        for (double x : v) m += x / double(v.size());
        for (double x : v) m2 += Sqr(x - m);
        refMean[k] = m;
        refVar += m2 / double(v.size() - 1) / double(v.size());
    }
    double refLevel = 0;
    for (double v : refMean) refLevel += v / double(strip.size());
    const double refRmse = std::sqrt(refVar / double(strip.size()));
    std::printf("reference: mean %.5g over the strip, its own RMSE %.3g (%.1f s)\n\n", refLevel, refRmse,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());

    // Each run: `maxSpp` independent samples per strip pixel. The variance of one sample (per pixel,
    // averaged over the strip) sets the error at any spp, RMSE = √(σ²/spp), for these unbiased
    // estimators, and so the spp ratio at equal error = σ²_a/σ²_b. The curves are measured: every
    // disjoint batch of `spp` samples is one estimate, its squared error against the reference
    // (minus the reference's own variance) averaged over batches and pixels.
    std::string csv = "run,spp,seconds,rmse\n";
    std::map<std::string, double> sampleVar, sampleSeconds;
    std::map<std::string, std::map<int, double>> curve;
    for (const auto &[label, name] : runs) {
        const Scene &scene = *scenes[label];
        const auto start = std::chrono::steady_clock::now();
        double var = 0;
        std::map<int, double> se;
        std::map<int, int> batches;
        for (std::size_t k = 0; k < strip.size(); ++k) {
            const std::vector<double> v = PixelSamples(scene, strip[k], maxSpp, 500000 + 7919 * k + label.size());
            double m = 0, m2 = 0;
            for (double x : v) m += x / double(v.size());
            for (double x : v) m2 += Sqr(x - m);
            var += m2 / double(v.size() - 1);
            for (int spp = 1; spp <= maxSpp; spp *= 4)
                for (int b = 0; b + spp <= maxSpp; b += spp) {
                    double bm = 0;
                    for (int j = b; j < b + spp; ++j) bm += v[std::size_t(j)] / spp;
                    se[spp] += Sqr(bm - refMean[k]);
                    ++batches[spp];
                }
        }
        sampleSeconds[label] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
                               (double(strip.size()) * maxSpp);
        sampleVar[label] = var / double(strip.size());
        for (auto &[spp, e] : se) {
            const double mse = std::max(0.0, e / batches[spp] - refRmse * refRmse);
            curve[label][spp] = std::sqrt(mse);
            char line[160];
            std::snprintf(line, sizeof line, "%s,%d,%.6g,%.6g\n", label.c_str(), spp, sampleSeconds[label] * spp,
                          curve[label][spp]);
            csv += line;
        }
    }
    std::printf("| spp | sample_solve RMSE | force_coherent RMSE | grt RMSE |\n|---:|---:|---:|---:|\n");
    for (const auto &[spp, e] : curve["sample_solve"])
        std::printf("| %d | %.4g | %.4g | %.4g |\n", spp, e, curve["sample_solve force_coherent"][spp], curve["grt"][spp]);
    std::printf("\nvariance of one sample (strip average): sample_solve %.4g, force_coherent %.4g, grt %.4g; time per "
                "sample: %.3g / %.3g / %.3g µs\n",
                sampleVar["sample_solve"], sampleVar["sample_solve force_coherent"], sampleVar["grt"],
                sampleSeconds["sample_solve"] * 1e6, sampleSeconds["sample_solve force_coherent"] * 1e6,
                sampleSeconds["grt"] * 1e6);
    const double ratio = sampleVar["sample_solve"] / sampleVar["sample_solve force_coherent"];
    std::printf("\n**partially coherent / fully coherent spp at equal error: %.3gx** (goal ≤ 0.5x; the paper: 1/5–1/2); "
                "grt / partially coherent: %.3gx\n",
                ratio, sampleVar["grt"] / sampleVar["sample_solve"]);

    // CSV and plot.
    std::filesystem::create_directories(out);
    {
        OutputFiles files;
        files.Stage(out + "/fig_s10e.csv", csv);
        PlotRequest plot;
        plot.command = "convergence";
        plot.data = csv;
        plot.args = {"--title", "Fig. S10e: error in the shadowed strip (" + illumination + " illumination)"};
        const bool drawn = StagePlot(files, out + "/fig_s10e.png", plot);
        files.Commit();
        std::printf("\nwrote %s/fig_s10e.csv%s\n", out.c_str(), drawn ? (" and " + out + "/fig_s10e.png").c_str() : "");
        if (!drawn) std::printf("(%s)\n", MatplotlibMissing().c_str());
    }

    // Time at equal spp on whole images.
    std::printf("\n## sample_solve vs grt time at equal spp\n\n| scene | spp | grt | sample_solve | ratio |\n"
                "|---|---:|---:|---:|---:|\n");
    {
        const double tg = WholeImageSeconds(*scenes["grt"], timeSpp, threads),
                     ts = WholeImageSeconds(*scenes["sample_solve"], timeSpp, threads);
        std::printf("| sample_solve_gratings (%s, %d×%d) | %d | %.3f s | %.3f s | %.2fx |\n", illumination.c_str(),
                    det.Width(), det.Height(), timeSpp, tg, ts, ts / tg);
    }
    {
        auto g = Load("grt_cornell.wscene", {}, "grt"), s = Load("grt_cornell.wscene", {}, "sample_solve");
        const double tg = WholeImageSeconds(*g, timeSpp, threads), ts = WholeImageSeconds(*s, timeSpp, threads);
        std::printf("| grt_cornell (%d×%d) | %d | %.3f s | %.3f s | %.2fx |\n", g->GetDetector().Width(),
                    g->GetDetector().Height(), timeSpp, tg, ts, ts / tg);
    }
    std::printf("\n(goal ≤ 1.5x; fastest of 3 runs each, %d thread%s)\n", threads, threads == 1 ? "" : "s");
    return 0;
}
