// SPDX-License-Identifier: Apache-2.0
// `table`: a tabulated spectrum, linearly interpolated between strictly increasing wavelengths
// and 0 outside the table (so an emission table has exactly the support it lists).
#include <algorithm>

#include "core/render/registry.h"
#include "spectra/common.h"
#include "core/spectrum/spectrum.h"

namespace phasor {

class TableSpectrum final : public Spectrum {
  public:
    /// `lambda` [m] strictly increasing, same size as `values` (≥ 2 entries).
    TableSpectrum(std::vector<double> lambda, std::vector<double> values)
        : lambda_(std::move(lambda)), values_(std::move(values)) {
        max_ = *std::max_element(values_.begin(), values_.end());
    }

    static const Schema &GetSchema() {
        static const Schema s{
            "spectrum",
            "table",
            "Tabulated spectrum: linear interpolation between samples, 0 outside the table.",
            {P::NumberList("wavelengths", "sample wavelengths, strictly increasing", Dim::Length())
                 .Required()
                 .Min(0, true),
             P::NumberList("values", "values at the sample wavelengths (same count)").Required().Min(0)}};
        return s;
    }
    static std::unique_ptr<Spectrum> Create(const ParamDict &d, BuildContext &ctx) {
        std::vector<double> lambda = d.GetNumbers("wavelengths"), values = d.GetNumbers("values");
        if (lambda.size() != values.size())
            throw Error(d.Loc("values"), "table has " + std::to_string(lambda.size()) + " wavelengths but " +
                                             std::to_string(values.size()) +
                                             " values; the counts must match");
        if (lambda.empty()) throw Error(d.Loc("wavelengths"), "table needs at least one sample");
        for (std::size_t i = 1; i < lambda.size(); ++i)
            if (!(lambda[i] > lambda[i - 1]))
                throw Error(d.Loc("wavelengths"), "table wavelengths must strictly increase: entry " +
                                                      std::to_string(i + 1) + " (" + spectra::Nm(lambda[i]) +
                                                      ") is not greater than entry " + std::to_string(i) +
                                                      " (" + spectra::Nm(lambda[i - 1]) + ")");
        if (lambda.size() == 1) {
            ctx.Diag().Warning(
                d.Loc("wavelengths"),
                "table has a single sample; it is treated as a constant " + spectra::Num(values[0]));
            return std::make_unique<ConstantSpectrum>(values[0]);
        }
        return std::make_unique<TableSpectrum>(std::move(lambda), std::move(values));
    }
    static std::vector<ParamDict> TestPresets() {
        return {ParamDict()
                    .Set("wavelengths", Value::List({Value::Number(400e-9, Dim::Length()),
                                                     Value::Number(550e-9, Dim::Length()),
                                                     Value::Number(700e-9, Dim::Length())}))
                    .Set("values", Value::List({Value::Number(0.2), Value::Number(1), Value::Number(0.5)}))};
    }

    double Eval(double lambda) const override {
        // A relative slack of 1e-12 at the ends absorbs unit-conversion round-off (400 · 1e-9 ≠ 400e-9).
        const double slack = 1e-12 * lambda_.back();
        if (!(lambda >= lambda_.front() - slack) || !(lambda <= lambda_.back() + slack)) return 0;
        lambda = std::clamp(lambda, lambda_.front(), lambda_.back());
        auto it = std::upper_bound(lambda_.begin(), lambda_.end(), lambda);
        std::size_t i = std::min<std::size_t>(std::size_t(it - lambda_.begin()), lambda_.size() - 1) - 1;
        const double t = (lambda - lambda_[i]) / (lambda_[i + 1] - lambda_[i]);
        return (1 - t) * values_[i] + t * values_[i + 1];
    }
    double MaxValue() const override { return max_; }
    std::pair<double, double> Support() const override { return {lambda_.front(), lambda_.back()}; }
    std::string ToString() const override {
        std::string s = "table([";
        for (std::size_t i = 0; i < lambda_.size(); ++i) s += (i ? " " : "") + spectra::Num(lambda_[i] * 1e9);
        s += "] nm, [";
        for (std::size_t i = 0; i < values_.size(); ++i) s += (i ? " " : "") + spectra::Num(values_[i]);
        return s + "])";
    }

  private:
    std::vector<double> lambda_, values_;
    double max_ = 0;
};

PHASOR_EXPORT_PLUGIN(Spectrum, TableSpectrum)

}  // namespace phasor
