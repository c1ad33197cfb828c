// SPDX-License-Identifier: Apache-2.0
// phasor — rays, surface interactions, shapes and triangle meshes (docs/wscene.md §12).
// World space is right-handed, lengths in metres. Part of the geometry library: it names the
// render layer's Material and Light only through pointers (declared, never included), so nothing
// under core/geometry includes a core/render header (docs/architecture.md, "Libraries").
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/math.h"

namespace phasor {

class Material;
class Light;

struct Ray {
    Vec3 o, d;  // origin [m], unit direction
    Vec3 At(double t) const { return o + t * d; }
};

/// A triangle mesh in world space (transform already applied). Optional per-vertex normals and
/// uvs (same count as positions, or empty).
struct TriangleMesh {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;
    std::vector<Vec2> uvs;
    std::vector<uint32_t> indices;  // 3 per triangle
    std::size_t TriangleCount() const { return indices.size() / 3; }
    Bounds3 Bounds() const;
    double Area() const;
    /// Throws phasor::Error if an index is out of range or an array size is inconsistent.
    void Validate(const std::string &what) const;
    void Transform(const phasor::Transform &t);
};

/// Where a ray met a surface. `n` is the geometric normal, `shading` the shading frame
/// (shading.n may differ from n for interpolated normals); both face the same side as the shape's
/// outward normal (not flipped towards the ray).
struct SurfaceInteraction {
    Vec3 p;
    Vec3 n;
    Frame shading;
    Vec2 uv;
    /// ∂p/∂u and ∂p/∂v [m per unit of u, v], world space, for textures (TextureEvalContext);
    /// zero where a shape's uv parameterisation is degenerate (e.g. a triangle whose uvs are
    /// collinear). Not unit, not necessarily orthogonal.
    Vec3 dpdu, dpdv;
    double t = 0;
    const class Shape *shape = nullptr;
    const Material *material = nullptr;  // null: an interface that only bounds a light, or black
    const Light *areaLight = nullptr;    // the emitter attached to this shape, if any
    /// Offset origin for a ray leaving the surface towards `w` (avoids self-intersection).
    Vec3 SpawnOrigin(const Vec3 &w) const;
};

/// A point sampled on a shape.
struct ShapeSample {
    Vec3 p, n;         // position, outward unit normal
    double pdfArea = 0;  // density w.r.t. surface area [1/m²]
};

/// A point sampled on a shape by the solid angle it subtends at a reference point.
struct ShapeSolidAngleSample {
    Vec3 p, n;        // position, outward unit normal
    double pdf = 0;   // density of the direction from the reference point [1/sr]
};

/// A shape plug-in. Triangle-based shapes (rectangle, meshes, glTF, subdivision) hand Embree a
/// mesh; analytic ones (sphere, disk) are Embree user geometry that calls Intersect().
class Shape {
  public:
    virtual ~Shape() = default;

    /// Triangulated geometry, or nullptr for an analytic shape.
    virtual const TriangleMesh *Mesh() const { return nullptr; }
    /// Analytic shapes: nearest hit with t in (tMin, tMax), computed in double precision.
    virtual std::optional<double> Intersect(const Ray &ray, double tMin, double tMax) const;
    /// Completes an interaction from a hit: for meshes `prim` is the triangle index and (b1, b2)
    /// its barycentrics; for analytic shapes they are unused.
    virtual SurfaceInteraction Interaction(const Ray &ray, double t, unsigned prim, double b1,
                                           double b2) const = 0;
    virtual Bounds3 Bounds() const = 0;
    virtual double Area() const = 0;
    /// Uniform sampling by area.
    virtual ShapeSample Sample(const Vec2 &u) const = 0;
    /// Sampling by solid angle as seen from `ref` [m, world], where the shape offers it for that
    /// point (a rectangle: uniform over its solid angle, core/geometry/spherical_rectangle.h);
    /// nullopt elsewhere, and then callers sample by area. PdfSolidAngle(ref) is the density it
    /// gives every direction from ref that meets the shape [1/sr], 0 exactly where it declines.
    virtual std::optional<ShapeSolidAngleSample> SampleSolidAngle(const Vec3 &ref, const Vec2 &u) const;
    virtual double PdfSolidAngle(const Vec3 &ref) const;
    virtual std::string ToString() const = 0;
    /// True for shapes that lie in their object-space plane z = 0 (rectangle, disk): planar
    /// kernels such as `aperture` need one.
    virtual bool IsPlanar() const { return false; }
    /// Mesh shapes: what determines Mesh() exactly (core/geometry/geometry_cache.h), or "" if
    /// unknown; an accelerator over a shape without one is never shared between scenes.
    virtual std::string MeshKey() const { return ""; }
    /// A cone (unit axis w, cosine of its half-angle) containing the normal that Sample and
    /// SampleSolidAngle report at every point of the shape (an area light's "outside"). Default: all
    /// directions (cosθ = −1); meshes compute it from their triangles.
    struct NormalCone {
        Vec3 w{0, 0, 1};
        double cosTheta = -1;
    };
    virtual NormalCone Normals() const { return {}; }

    const Material *material = nullptr;  // set by the builder from `material = @…`
    phasor::Transform objectToWorld;     // the shape's `to_world` (identity if it has none)
    const Light *areaLight = nullptr;    // set when an `area` light names this shape
    std::string name;
};

/// A triangle mesh with what sampling it needs, immutable once built: shared by every MeshShape
/// built from the same geometry (core/geometry/geometry_cache.h).
struct MeshGeometry {
    /// Validates `mesh` (throws phasor::Error) and computes its bounds and area table. `key` states
    /// what determines the mesh exactly ("" if nothing does: then it is never shared).
    MeshGeometry(TriangleMesh mesh, std::string key);
    TriangleMesh mesh;
    Bounds3 bounds;
    double area = 0;                // [m²]
    std::vector<double> areaCdf;    // running sum of triangle areas [m²]
    std::string key;
    /// Memory held [bytes], roughly.
    std::size_t Bytes() const;
};

/// Shared implementation for triangle meshes (used by every mesh-producing shape plug-in).
class MeshShape : public Shape {
  public:
    /// A mesh of its own (never shared).
    explicit MeshShape(TriangleMesh mesh);
    /// A mesh shared with other shapes (from the geometry cache).
    explicit MeshShape(std::shared_ptr<const MeshGeometry> geometry);
    const TriangleMesh *Mesh() const override { return &geom_->mesh; }
    std::string MeshKey() const override { return geom_->key; }
    SurfaceInteraction Interaction(const Ray &ray, double t, unsigned prim, double b1,
                                   double b2) const override;
    Bounds3 Bounds() const override { return geom_->bounds; }
    double Area() const override { return geom_->area; }
    ShapeSample Sample(const Vec2 &u) const override;  // area-weighted triangle choice
    /// The cone of the triangles' outward normals (PointAt's ng, flipped towards the vertex normals
    /// where they disagree with the winding: a triangle whose corners disagree counts both ways);
    /// all directions when the area-weighted mean normal is shorter than 1e-6 of the area.
    NormalCone Normals() const override;
    std::string ToString() const override;

  protected:
    /// The point at barycentrics (b1, b2) of triangle `prim` [m, world], its unit geometric normal
    /// (from the winding, flipped to the side of the interpolated vertex normals when the mesh has
    /// them) and its unit shading normal (the interpolated vertex normals; else the geometric one).
    struct PointNormals {
        Vec3 p, ng, ns;
    };
    PointNormals PointAt(unsigned prim, double b1, double b2) const;

  private:
    std::shared_ptr<const MeshGeometry> geom_;
};

}  // namespace phasor
