// SPDX-License-Identifier: Apache-2.0
// phasor — the Embree 3 accelerator. The only translation unit that includes Embree.
//
// Precision: Embree traverses and intersects in float. Every hit handed back to the renderer is
// recomputed in double: triangles by a double-precision Möller–Trumbore test of the winning
// triangle against the caller's double ray, analytic shapes (Embree user geometry) by calling
// Shape::Intersect with the caller's double ray, which reaches the callbacks through an extended
// RTCIntersectContext. Float only decides *which* primitive is nearest.
//
// Sharing (core/geometry/geometry_cache.h): the Embree scene holds copies of the meshes' vertices
// and indices and, for an analytic shape, only its bounds; the callbacks find the shape through
// the querying Accel's shape list, never through a pointer kept in Embree. So one BVH serves every
// Accel whose shapes have the same geometry keys in the same order, whichever Scene owns them.
#include "core/geometry/accel.h"

#include <embree3/rtcore.h>

#include <cfloat>
#include <cmath>
#include <string>

#if defined(__SSE__) || defined(__x86_64__)
#include <pmmintrin.h>
#include <xmmintrin.h>
#define PHASOR_HAVE_MXCSR 1
#endif

#include "core/diagnostics.h"
#include "core/geometry/geometry_cache.h"
#include "core/geometry/intersect.h"

namespace phasor {

namespace {

/// Embree recommends flush-to-zero and denormals-are-zero on every thread that traces. We set
/// both for the duration of one query and restore the caller's mode afterwards, so double
/// arithmetic elsewhere in the thread is unaffected.
class FtzDazScope {
  public:
#ifdef PHASOR_HAVE_MXCSR
    FtzDazScope() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | 0x8040u); }  // FTZ | DAZ
    ~FtzDazScope() { _mm_setcsr(saved_); }

  private:
    unsigned saved_;
#endif
};

/// The context Embree passes to the user-geometry callbacks. `context` must come first (Embree
/// hands the callbacks a pointer to it).
struct QueryContext {
    RTCIntersectContext context;
    const std::vector<const Shape *> *shapes = nullptr;  // the querying Accel's, by geomID
    const Ray *ray = nullptr;   // the caller's double-precision ray (null: use Embree's float ray)
    double tMin = 0, tMax = 0;  // the caller's interval
    float tMaxF = 0;            // tMax as handed to Embree (tfar still equal → no hit so far)
    double analyticT = 0;       // double t of the last accepted analytic hit
};

float ToFloat(double v) {
    if (v >= double(FLT_MAX)) return v == Infinity ? INFINITY : FLT_MAX;
    if (v <= -double(FLT_MAX)) return -FLT_MAX;
    return float(v);
}

/// The double ray and interval for a callback: the caller's if known, else Embree's float ray.
Ray CallbackRay(const QueryContext &qc, const RTCRay &r, double *tMin, double *tMax) {
    if (qc.ray) {
        *tMin = qc.tMin;
        // While tfar still holds the caller's tMax nothing has been hit: use the exact double.
        *tMax = r.tfar == qc.tMaxF ? qc.tMax : double(r.tfar);
        return *qc.ray;
    }
    *tMin = r.tnear;
    *tMax = r.tfar;
    return Ray{Vec3(r.org_x, r.org_y, r.org_z), Vec3(r.dir_x, r.dir_y, r.dir_z)};
}

void UserBounds(const RTCBoundsFunctionArguments *args) {
    const Bounds3 &b = *static_cast<const Bounds3 *>(args->geometryUserPtr);
    // Round outwards (plus a relative margin) so float traversal never culls a double hit.
    Vec3 pad = 1e-6 * (Max(b.hi, -b.lo) + Vec3(1e-30, 1e-30, 1e-30));
    Vec3 lo = b.lo - pad, hi = b.hi + pad;
    RTCBounds *o = args->bounds_o;
    o->lower_x = std::nextafter(ToFloat(lo.x), -INFINITY);
    o->lower_y = std::nextafter(ToFloat(lo.y), -INFINITY);
    o->lower_z = std::nextafter(ToFloat(lo.z), -INFINITY);
    o->upper_x = std::nextafter(ToFloat(hi.x), INFINITY);
    o->upper_y = std::nextafter(ToFloat(hi.y), INFINITY);
    o->upper_z = std::nextafter(ToFloat(hi.z), INFINITY);
}

void UserIntersect(const RTCIntersectFunctionNArguments *args) {
    if (args->N != 1 || !args->valid[0]) return;  // only rtcIntersect1 is used
    auto *qc = reinterpret_cast<QueryContext *>(args->context);
    auto *rh = reinterpret_cast<RTCRayHit *>(args->rayhit);
    const Shape *shape = (*qc->shapes)[args->geomID];
    double tMin, tMax;
    Ray ray = CallbackRay(*qc, rh->ray, &tMin, &tMax);
    std::optional<double> t = shape->Intersect(ray, tMin, tMax);
    if (!t) return;
    float tf = float(*t);
    if (!(tf <= rh->ray.tfar)) return;
    rh->ray.tfar = tf;
    rh->hit.u = 0;
    rh->hit.v = 0;
    rh->hit.Ng_x = 0;
    rh->hit.Ng_y = 0;
    rh->hit.Ng_z = 1;
    rh->hit.primID = args->primID;
    rh->hit.geomID = args->geomID;
    rh->hit.instID[0] = args->context->instID[0];
    qc->analyticT = *t;
}

void UserOccluded(const RTCOccludedFunctionNArguments *args) {
    if (args->N != 1 || !args->valid[0]) return;
    auto *qc = reinterpret_cast<QueryContext *>(args->context);
    auto *r = reinterpret_cast<RTCRay *>(args->ray);
    const Shape *shape = (*qc->shapes)[args->geomID];
    double tMin, tMax;
    Ray ray = CallbackRay(*qc, *r, &tMin, &tMax);
    if (shape->Intersect(ray, tMin, tMax)) r->tfar = -INFINITY;  // Embree's "occluded" marker
}

void ErrorCallback(void *user, RTCError code, const char *message) {
    auto *sink = static_cast<std::string *>(user);
    if (sink->empty()) *sink = "Embree error " + std::to_string(int(code)) + ": " + (message ? message : "");
}

}  // namespace

/// One Embree BVH, immutable once built; shared by the Accels whose shapes have its key.
struct Accel::Bvh {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::vector<Bounds3> userBounds;  // analytic shapes' bounds by shape index (Embree's user data)
    std::size_t triangles = 0, vertices = 0;
    std::string error;  // first error reported by Embree's callback

    /// Builds the BVH over `shapes`. Throws phasor::Error.
    static std::shared_ptr<const Bvh> Build(const std::vector<const Shape *> &shapes);
    Bvh() = default;
    ~Bvh() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
    Bvh(const Bvh &) = delete;
    Bvh &operator=(const Bvh &) = delete;
    void Check(const char *what) {
        RTCError code = rtcGetDeviceError(device);
        if (code != RTC_ERROR_NONE || !error.empty()) {
            std::string msg = error.empty() ? "Embree error " + std::to_string(int(code)) : error;
            throw Error(std::string("accelerator: ") + what + ": " + msg);
        }
    }
    /// Memory held [bytes], roughly (Embree's BVH nodes and its copy of the triangles).
    std::size_t Bytes() const { return 64 * triangles + 16 * vertices + 256 * userBounds.size(); }

    /// Initialises a float ray for Embree from the caller's double ray.
    static void SetRay(RTCRay &r, const Ray &ray, float tnear, float tfar) {
        r.org_x = float(ray.o.x);
        r.org_y = float(ray.o.y);
        r.org_z = float(ray.o.z);
        r.dir_x = float(ray.d.x);
        r.dir_y = float(ray.d.y);
        r.dir_z = float(ray.d.z);
        r.tnear = tnear;
        r.tfar = tfar;
        r.time = 0;
        r.mask = 0xFFFFFFFFu;
        r.id = 0;
        r.flags = 0;
    }
    static void ResetHit(RTCHit &h) {
        h.geomID = RTC_INVALID_GEOMETRY_ID;
        h.primID = RTC_INVALID_GEOMETRY_ID;
        h.instID[0] = RTC_INVALID_GEOMETRY_ID;
        h.u = h.v = 0;
    }
};

namespace {

SharedCache<Accel::Bvh> &Bvhs() {
    // As the meshes' budget (geometry_cache.cpp): recent BVHs up to 1 GiB stay between scenes.
    static SharedCache<Accel::Bvh> cache(std::size_t(1) << 30, [](const Accel::Bvh &b) { return b.Bytes(); });
    return cache;
}

/// What determines the BVH of `shapes` exactly: each mesh's geometry key and each analytic shape's
/// bounds, in order; "" if a mesh has no key (its BVH is then built for this Accel alone).
std::string BvhKey(const std::vector<const Shape *> &shapes) {
    GeometryKey key("bvh");
    for (const Shape *shape : shapes) {
        if (shape->Mesh()) {
            const std::string k = shape->MeshKey();
            if (k.empty()) return "";
            key.Text("mesh", k);
        } else {
            const Bounds3 b = shape->Bounds();
            key.Numbers("user", {b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z});
        }
    }
    return key.Str();
}

}  // namespace

std::shared_ptr<const Accel::Bvh> Accel::Bvh::Build(const std::vector<const Shape *> &shapes) {
    FtzDazScope ftz;
    auto bvh = std::make_shared<Bvh>();  // released by its destructor if anything below throws
    Bvh &b = *bvh;
    RTCDevice &device = b.device;
    RTCScene &scene = b.scene;
    b.userBounds.resize(shapes.size());
    device = rtcNewDevice(nullptr);
    if (!device)
        throw Error("accelerator: cannot create the Embree device (error " +
                    std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
    rtcSetDeviceErrorFunction(device, ErrorCallback, &b.error);
    scene = rtcNewScene(device);
    b.Check("creating the scene");
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);

    for (std::size_t i = 0; i < shapes.size(); ++i) {
        const Shape *shape = shapes[i];
        RTCGeometry geom;
        if (const TriangleMesh *mesh = shape->Mesh()) {
            if (mesh->TriangleCount() == 0) continue;
            if (mesh->positions.size() > 0xFFFFFFFFull || mesh->TriangleCount() > 0xFFFFFFFFull)
                throw Error("accelerator: mesh " + std::to_string(i) + " is too large for Embree");
            geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
            auto *v = static_cast<float *>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                   RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                                   mesh->positions.size()));
            auto *idx = static_cast<unsigned *>(
                rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                        3 * sizeof(unsigned), mesh->TriangleCount()));
            if (!v || !idx) {
                rtcReleaseGeometry(geom);
                b.Check("allocating mesh buffers");
                throw Error("accelerator: cannot allocate mesh buffers");
            }
            for (std::size_t k = 0; k < mesh->positions.size(); ++k) {
                v[3 * k] = float(mesh->positions[k].x);
                v[3 * k + 1] = float(mesh->positions[k].y);
                v[3 * k + 2] = float(mesh->positions[k].z);
            }
            for (std::size_t k = 0; k < mesh->indices.size(); ++k) {
                if (mesh->indices[k] >= mesh->positions.size()) {
                    rtcReleaseGeometry(geom);
                    throw Error("accelerator: mesh " + std::to_string(i) + " has an index out of range");
                }
                idx[k] = mesh->indices[k];
            }
            b.triangles += mesh->TriangleCount();
            b.vertices += mesh->positions.size();
        } else {
            b.userBounds[i] = shape->Bounds();
            geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
            rtcSetGeometryUserPrimitiveCount(geom, 1);
            rtcSetGeometryUserData(geom, &b.userBounds[i]);
            rtcSetGeometryBoundsFunction(geom, UserBounds, nullptr);
            rtcSetGeometryIntersectFunction(geom, UserIntersect);
            rtcSetGeometryOccludedFunction(geom, UserOccluded);
        }
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(scene, geom, unsigned(i));  // geomID == shape index
        rtcReleaseGeometry(geom);
        b.Check("adding a shape");
    }
    rtcCommitScene(scene);
    b.Check("building the BVH");
    return bvh;
}

Accel::Accel(std::vector<const Shape *> shapes) : shapes_(std::move(shapes)) {
    for (std::size_t i = 0; i < shapes_.size(); ++i) {
        if (!shapes_[i]) throw Error("accelerator: shape " + std::to_string(i) + " is null");
        bounds_.Extend(shapes_[i]->Bounds());
    }
    const std::string key = BvhKey(shapes_);
    const auto build = [&] { return Bvh::Build(shapes_); };
    bvh_ = key.empty() ? build() : Bvhs().GetOrBuild(key, build);
}

Accel::CacheCounts Accel::BvhCacheCounts() { return CacheCounts{Bvhs().Builds(), Bvhs().Reuses()}; }

void Accel::ClearBvhCache() { Bvhs().Clear(); }

Accel::~Accel() = default;

std::optional<Hit> Accel::Intersect(const Ray &ray, double tMin, double tMax, HitPrecision precision) const {
    FtzDazScope ftz;
    QueryContext qc;
    rtcInitIntersectContext(&qc.context);
    qc.shapes = &shapes_;
    qc.ray = &ray;
    qc.tMin = tMin;
    qc.tMax = tMax;
    qc.tMaxF = ToFloat(tMax);
    RTCRayHit rh;
    Bvh::SetRay(rh.ray, ray, std::max(0.f, ToFloat(tMin)), qc.tMaxF);
    Bvh::ResetHit(rh.hit);
    rtcIntersect1(bvh_->scene, &qc.context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

    Hit hit;
    hit.shapeIndex = rh.hit.geomID;
    hit.prim = rh.hit.primID;
    const Shape *shape = shapes_[hit.shapeIndex];
    if (const TriangleMesh *mesh = shape->Mesh()) {
        // Recompute t and the barycentrics of the winning triangle in double precision.
        const uint32_t *idx = &mesh->indices[3 * std::size_t(hit.prim)];
        auto th = precision == HitPrecision::Double ? RayTrianglePlane(ray, mesh->positions[idx[0]],
                                                                       mesh->positions[idx[1]], mesh->positions[idx[2]])
                                                    : std::nullopt;
        if (th) {
            hit.t = th->t;
            hit.b1 = th->b1;
            hit.b2 = th->b2;
        } else {
            hit.t = rh.ray.tfar;
            hit.b1 = rh.hit.u;
            hit.b2 = rh.hit.v;
        }
    } else {
        hit.t = qc.analyticT;
    }
    return hit;
}

bool Accel::Occluded(const Ray &ray, double tMin, double tMax) const {
    FtzDazScope ftz;
    QueryContext qc;
    rtcInitIntersectContext(&qc.context);
    qc.shapes = &shapes_;
    qc.ray = &ray;
    qc.tMin = tMin;
    qc.tMax = tMax;
    qc.tMaxF = ToFloat(tMax);
    RTCRay r;
    Bvh::SetRay(r, ray, std::max(0.f, ToFloat(tMin)), qc.tMaxF);
    rtcOccluded1(bvh_->scene, &qc.context, &r);
    return r.tfar == -INFINITY;
}

std::optional<SurfaceInteraction> Accel::IntersectSurface(const Ray &ray, double tMin, double tMax,
                                                          HitPrecision precision) const {
    std::optional<Hit> hit = Intersect(ray, tMin, tMax, precision);
    if (!hit) return std::nullopt;
    return shapes_[hit->shapeIndex]->Interaction(ray, hit->t, hit->prim, hit->b1, hit->b2);
}

namespace {

struct NearQuery {
    const std::function<void(unsigned, unsigned)> *f;
};

bool NearCallback(RTCPointQueryFunctionArguments *args) {
    const auto *q = static_cast<const NearQuery *>(args->userPtr);
    (*q->f)(args->geomID, args->primID);
    return false;  // the query radius is not changed
}

}  // namespace

void Accel::ForEachNear(const Vec3 &center, double radius,
                        const std::function<void(unsigned shapeIndex, unsigned prim)> &f) const {
    if (!(radius >= 0) || !std::isfinite(radius)) return;
    FtzDazScope ftz;
    RTCPointQuery q;
    q.x = float(center.x);
    q.y = float(center.y);
    q.z = float(center.z);
    q.time = 0;
    // Float rounding of the centre and radius: widen by a relative margin (conservative).
    const double pad = 1e-6 * (std::abs(center.x) + std::abs(center.y) + std::abs(center.z) + radius);
    q.radius = std::nextafter(ToFloat(radius + pad), INFINITY);
    RTCPointQueryContext ctx;
    rtcInitPointQueryContext(&ctx);
    NearQuery nq{&f};
    rtcPointQuery(bvh_->scene, &q, &ctx, NearCallback, &nq);
}

std::size_t Accel::RawIntersectCount(const std::vector<Ray> &rays) const {
    FtzDazScope ftz;
    std::size_t hits = 0;
    QueryContext qc;
    RTCRayHit rh;
    qc.shapes = &shapes_;
    for (const Ray &ray : rays) {
        rtcInitIntersectContext(&qc.context);
        Bvh::SetRay(rh.ray, ray, 0.f, INFINITY);
        Bvh::ResetHit(rh.hit);
        rtcIntersect1(bvh_->scene, &qc.context, &rh);
        hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
    return hits;
}

}  // namespace phasor
