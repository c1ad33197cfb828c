// SPDX-License-Identifier: Apache-2.0
// phasor — `uv_ramp` texture: a scalar varying linearly along a direction in uv.
//
// The coordinate is c = u·cos α + v·sin α for the direction at angle α (`angle`) from the u axis
// towards v; t = clamp((c − start)/(end − start), 0, 1) and the value is value0 + t·(value1 −
// value0) (textures/linear_ramp.h, the ramp `gradient` also uses: uv_ramp with angle 0 or 90 deg
// is gradient with axis "u" or "v"; gradient also runs along world axes). The dimension is that of
// value0 and value1 (`value0 = 200 nm` makes a thickness ramp).
#include <cmath>
#include <memory>
#include <sstream>

#include "core/render/registry.h"
#include "core/render/texture.h"
#include "textures/linear_ramp.h"
#include "textures/texture_common.h"

namespace phasor {

class UvRampTexture final : public ScalarTexture {
  public:
    UvRampTexture(Dim dim, const LinearRamp &ramp, double angle) : ScalarTexture(dim), ramp_(ramp), angle_(angle) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "texture",
            "uv_ramp",
            "a scalar varying linearly between two values along a direction in uv (its dimension is the values')",
            {
                P::Number("value0", "value at 'start' and before it").Required().AnyDim(),
                P::Number("value1", "value at 'end' and after it (same dimension as value0)").Required().AnyDim(),
                P::Angle("angle", "direction of the ramp in uv, from the u axis towards v (0: along u, 90 deg: along v)")
                    .Default(Value::Number(0, Dim::Angle())),
                P::Number("start", "coordinate u·cos(angle) + v·sin(angle) where value0 holds").Default(Value::Number(0)),
                P::Number("end", "coordinate where value1 holds (≠ start)").Default(Value::Number(1)),
            }};
        return s;
    }

    static std::unique_ptr<Texture> Create(const ParamDict &d, BuildContext &) {
        using texture_common::GivenDim;
        const Dim dim = texture_common::CommonDim(d, {{"value0", GivenDim(d, "value0")}, {"value1", GivenDim(d, "value1")}});
        LinearRamp ramp;
        ramp.value0 = d.GetNumber("value0");
        ramp.value1 = d.GetNumber("value1");
        const double angle = d.GetNumber("angle");
        // Exact axes at multiples of 90° (cos 90° is 6e-17 in floating point; 90 deg in radians may
        // be an ulp off π/2).
        const double quarter = angle / (Pi / 2);
        if (std::abs(quarter - std::round(quarter)) < 1e-12) {
            static const Vec3 axes[4] = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
            ramp.axis = axes[((long long)std::round(quarter) % 4 + 4) % 4];
        } else {
            ramp.axis = Vec3(std::cos(angle), std::sin(angle), 0);
        }
        ramp.start = d.GetNumber("start");
        ramp.end = d.GetNumber("end");
        if (ramp.start == ramp.end) throw Error(d.Loc("end"), "'end' must differ from 'start'");
        return std::make_unique<UvRampTexture>(dim, ramp, angle);
    }

    double EvalScalar(const TextureEvalContext &ctx) const override { return ramp_.Eval(ctx); }
    double MinValue() const override { return ramp_.MinValue(); }
    double MaxValue() const override { return ramp_.MaxValue(); }

    std::string ToString() const override {
        std::ostringstream os;
        os << "UvRampTexture[ value0 = " << Value::Number(ramp_.value0, GetDim()).ToString()
           << ", value1 = " << Value::Number(ramp_.value1, GetDim()).ToString()
           << ", angle = " << Value::Number(angle_, Dim::Angle()).ToString() << ", start = " << ramp_.start
           << ", end = " << ramp_.end << " ]";
        return os.str();
    }

  private:
    LinearRamp ramp_;
    double angle_;  // [rad], for ToString
};

PHASOR_EXPORT_PLUGIN(Texture, UvRampTexture)

}  // namespace phasor
