// SPDX-License-Identifier: Apache-2.0
// phasor — `gradient` texture: a scalar varying linearly along u, v or a world axis.
//
// With c the coordinate along `axis` (u or v of the surface parameterisation, or the world
// x, y or z of the point [m]), t = clamp((c − start)/(end − start), 0, 1) and the value is
// value0 + t·(value1 − value0): value0 up to `start`, value1 from `end` on (textures/linear_ramp.h,
// shared with `uv_ramp`, which also takes a direction in uv). The dimension is that of value0 and
// value1 (e.g. `value0 = 100 nm` makes a length texture).
#include <memory>
#include <sstream>

#include "core/render/registry.h"
#include "core/render/texture.h"
#include "textures/linear_ramp.h"
#include "textures/texture_common.h"

namespace phasor {

class GradientTexture final : public ScalarTexture {
  public:
    /// `axis`: 0, 1 = u, v; 2, 3, 4 = world x, y, z. start, end in the axis' unit (m for world).
    GradientTexture(Dim dim, double value0, double value1, int axis, double start, double end)
        : ScalarTexture(dim), axis_(axis) {
        ramp_.value0 = value0;
        ramp_.value1 = value1;
        ramp_.world = axis >= 2;
        static const Vec3 directions[5] = {{1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        ramp_.axis = directions[axis];
        ramp_.start = start;
        ramp_.end = end;
    }

    static const Schema &GetSchema() {
        static const Schema s{
            "texture",
            "gradient",
            "a scalar varying linearly between two values along u, v or a world axis (its dimension is "
            "the values')",
            {
                P::Number("value0", "value at 'start' and before it").Required().AnyDim(),
                P::Number("value1", "value at 'end' and after it (same dimension as value0)").Required().AnyDim(),
                P::String("axis", "coordinate the value varies along: surface u or v, or world x, y or z")
                    .Default(Value::String("u"))
                    .Choices({"u", "v", "x", "y", "z"}),
                P::Number("start", "coordinate where value0 holds: a plain number for u, v; a length for x, y, z")
                    .Default(Value::Number(0))
                    .AnyDim(),
                P::Number("end", "coordinate where value1 holds (≠ start): a plain number for u, v; a length for x, y, z")
                    .Default(Value::Number(1))
                    .AnyDim(),
            }};
        return s;
    }

    static std::unique_ptr<Texture> Create(const ParamDict &dict, BuildContext &) {
        using texture_common::GivenDim;
        const Dim dim = texture_common::CommonDim(dict, {{"value0", GivenDim(dict, "value0")},
                                                         {"value1", GivenDim(dict, "value1")}});
        const std::string axisName = dict.GetString("axis");
        const int axis = axisName == "u" ? 0 : axisName == "v" ? 1 : axisName == "x" ? 2 : axisName == "y" ? 3 : 4;
        const Dim coordDim = axis >= 2 ? Dim::Length() : Dim::None();
        for (const char *p : {"start", "end"}) {
            const std::optional<Dim> d = GivenDim(dict, p);
            if (d ? *d != coordDim : coordDim != Dim::None())
                throw Error(dict.Loc(d ? p : "axis"), "'" + std::string(p) + "' along axis \"" + axisName + "\" must be " +
                                             coordDim.Describe() +
                                             (d ? "; got " + d->Describe() : " (give it, e.g. 1 m)"));
        }
        const double start = dict.GetNumber("start"), end = dict.GetNumber("end");
        if (start == end) throw Error(dict.Loc("end"), "'end' must differ from 'start'");
        return std::make_unique<GradientTexture>(dim, dict.GetNumber("value0"), dict.GetNumber("value1"), axis,
                                                 start, end);
    }

    double EvalScalar(const TextureEvalContext &ctx) const override { return ramp_.Eval(ctx); }

    double MinValue() const override { return ramp_.MinValue(); }
    double MaxValue() const override { return ramp_.MaxValue(); }

    std::string ToString() const override {
        static const char *names[] = {"u", "v", "x", "y", "z"};
        const Dim cd = axis_ >= 2 ? Dim::Length() : Dim::None();
        std::ostringstream os;
        os << "GradientTexture[ value0 = " << Value::Number(ramp_.value0, GetDim()).ToString()
           << ", value1 = " << Value::Number(ramp_.value1, GetDim()).ToString() << ", axis = " << names[axis_]
           << ", start = " << Value::Number(ramp_.start, cd).ToString()
           << ", end = " << Value::Number(ramp_.end, cd).ToString() << " ]";
        return os.str();
    }

  private:
    int axis_;  // 0, 1 = u, v; 2, 3, 4 = world x, y, z
    LinearRamp ramp_;
};

PHASOR_EXPORT_PLUGIN(Texture, GradientTexture)

}  // namespace phasor
