// SPDX-License-Identifier: Apache-2.0
// `perspective`: a pinhole camera. Pixels report radiance (design.md §4.2, theory §0 D4).
// Camera frame from `to_world` (e.g. lookat): +z is the viewing direction, +y is up; image x
// grows to the right, image y downwards. `fov` spans the shorter image side.
#include "core/detector.h"
#include "core/registry.h"

namespace phasor {

class PerspectiveCamera final : public Detector {
  public:
    PerspectiveCamera(int w, int h, SensorResponse r, Transform toWorld, double fov)
        : Detector(w, h, r), toWorld_(toWorld) {
        // Half-extent of the image plane at unit distance along the shorter side.
        double half = std::tan(0.5 * fov);
        scale_ = 2 * half / std::min(w, h);
    }

    static const Schema &GetSchema() {
        static const Schema s{
            "detector", "perspective", "Pinhole camera; pixels report radiance.",
            {P::Transform("to_world", "camera-to-world transform, e.g. lookat(eye, target, up)")
                 .Default(Value::Call("lookat", {Value::Vector({0, 0, 0}, Dim::Length()),
                                                 Value::Vector({0, 0, 1}, Dim::Length()), Value::Vector({0, 1, 0})},
                                      {"eye", "target", "up"})),
             P::Angle("fov", "field of view across the shorter image side")
                 .Default(Value::Number(Radians(40), Dim::Angle()))
                 .Min(0, true)
                 .Max(Radians(179)),
             P::IntegerList("resolution", "image width and height in pixels")
                 .Default(Value::List({Value::Integer(256), Value::Integer(256)}))
                 .Size(2)
                 .Min(1),
             ResponseParam("cie_xyz")}};
        return s;
    }
    static std::unique_ptr<Detector> Create(const ParamDict &d, BuildContext &ctx) {
        std::vector<int> res = d.GetInts("resolution");
        if (res[0] > 65536 || res[1] > 65536 || (long long)res[0] * res[1] > (1LL << 28))
            throw Error(d.Loc("resolution"), "resolution is too large");
        return std::make_unique<PerspectiveCamera>(res[0], res[1], ResponseFromParams(d), ctx.GetTransform(d, "to_world"),
                                                   d.GetNumber("fov"));
    }

    std::optional<DetectorSample> Generate(const Vec2 &pFilm, const Vec2 &) const override {
        // Screen offsets: right and up on the image plane at unit distance. With a right-handed
        // lookat frame (x = up × forward), screen-right is −x.
        double sx = (pFilm.x - 0.5 * Width()) * scale_;
        double sy = (0.5 * Height() - pFilm.y) * scale_;
        Vec3 dCam(-sx, sy, 1);
        Vec3 d = Normalize(toWorld_.Vector(dCam));
        return DetectorSample{Ray{toWorld_.Point(Vec3(0, 0, 0)), d}, 1.0};
    }
    std::string ToString() const override {
        return "perspective { resolution = [" + std::to_string(Width()) + " " + std::to_string(Height()) + "] }";
    }

  private:
    Transform toWorld_;
    double scale_;
};

PHASOR_EXPORT_PLUGIN(Detector, PerspectiveCamera)

}  // namespace phasor
