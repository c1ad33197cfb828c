// SPDX-License-Identifier: Apache-2.0
// phasor test support — honest error estimates for renders (issue 11 item 13).
//
// The film's `variance` channel is the i.i.d. variance of the pixel mean, s²/n. With the default
// Owen-scrambled Sobol' sampler the samples of a pixel are not independent and the real error of
// the mean is typically ~10× smaller, so a t-test on that channel has little power: a biased
// render passes. Independent scramble replicas fix this: R renders with different seeds are R
// independent draws of the randomised-QMC estimator, so the spread of their R means is an unbiased
// estimate of the error of their average (R − 1 degrees of freedom). Every statistical render test
// uses this (or the `independent` sampler, for which the channel is honest).
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "support/scene_builder.h"

namespace phasor::test {

/// `count` renders of `scene` at `sppPerReplica` with the seeds seed0, seed0 + 1, … (any sampler;
/// the point is the Sobol' default).
inline std::vector<Image> RenderReplicas(const Scene &scene, int sppPerReplica, int count, uint64_t seed0,
                                         const std::string &sampler = "sobol") {
    std::vector<Image> out;
    for (int r = 0; r < count; ++r) out.push_back(RenderImage(scene, sppPerReplica, seed0 + uint64_t(r), sampler));
    return out;
}

/// The mean of a channel over a pixel block [x0, x1) × [y0, y1), averaged over the replicas, and
/// the variance of that average from the spread of the replicas' block means: var = s²_R / R,
/// dof = R − 1 (no assumption on the correlation of samples or pixels within a replica).
struct ReplicaEstimate {
    double mean = 0, varianceOfMean = 0, dof = 0;
    double StdError() const { return std::sqrt(varianceOfMean); }
};
inline ReplicaEstimate BlockOverReplicas(const std::vector<Image> &replicas, int x0, int y0, int x1, int y1,
                                         const std::string &channel = "intensity") {
    std::vector<double> means;
    for (const Image &img : replicas) {
        const int c = img.ChannelIndex(channel);
        double sum = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) sum += img.At(x, y, c);
        means.push_back(sum / (double(x1 - x0) * (y1 - y0)));
    }
    ReplicaEstimate e;
    const double n = double(means.size());
    for (double m : means) e.mean += m / n;
    double ss = 0;
    for (double m : means) ss += (m - e.mean) * (m - e.mean);
    e.varianceOfMean = n > 1 ? ss / (n - 1) / n : 0;
    e.dof = n - 1;
    return e;
}
/// The whole image as one block.
inline ReplicaEstimate ImageOverReplicas(const std::vector<Image> &replicas, const std::string &channel = "intensity") {
    return BlockOverReplicas(replicas, 0, 0, replicas.at(0).width, replicas.at(0).height, channel);
}

}  // namespace phasor::test
