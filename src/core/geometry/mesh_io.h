// SPDX-License-Identifier: Apache-2.0
// phasor — mesh import: Wavefront OBJ, glTF 2.0 (.gltf/.glb, through tinygltf) and Catmull–Clark
// subdivision (through OpenSubdiv). tinygltf and OpenSubdiv headers stay in the .cpp files.
// All loaders throw phasor::Error naming the file and the reason; none crashes on bad input.
#pragma once

#include <string>
#include <vector>

#include "core/geometry/shape.h"

namespace phasor {

/// A polygon mesh before triangulation (faces of any size ≥ 3), e.g. a subdivision cage.
struct PolyMesh {
    std::vector<Vec3> positions;
    std::vector<int> faceSizes;
    std::vector<int> faceIndices;  // concatenated, counter-clockwise seen from outside
    /// Optional texture coordinates, face-varying: faceUvIndices[c] indexes `uvs` for corner c of
    /// faceIndices (a seam is a vertex whose corners use different uvs). Both empty: no uvs.
    std::vector<Vec2> uvs;
    std::vector<int> faceUvIndices;
};

/// Loads an OBJ file (v, vn, vt, f with any polygon size, negative indices); polygons are fan-
/// triangulated. Materials and groups are ignored (one mesh).
TriangleMesh LoadObj(const std::string &path);
/// Loads the polygons of an OBJ file without triangulating (for subdivision cages), with their
/// texture coordinates (`vt`) when every face corner has one; corners with and without are an error.
PolyMesh LoadObjPolygons(const std::string &path);

/// Loads every triangle primitive of a glTF 2.0 file (.gltf with external or embedded buffers,
/// or .glb) in world space: each mesh is transformed by its node's world matrix (the product of
/// its ancestors' TRS or matrix transforms along the node hierarchy of the default scene).
/// POSITION, NORMAL (transformed by the inverse transpose), TEXCOORD_0 and indices of any
/// component type are read. Non-triangle primitives are skipped (reported in `skipped`).
TriangleMesh LoadGltf(const std::string &path, std::string *skipped = nullptr);

/// Catmull–Clark subdivision of `cage` to `levels` uniform levels with OpenSubdiv (Far), with
/// boundary interpolation of edges and corners; the limit-surface normals are computed from the
/// limit stencils of the final level. Quads are split into two triangles. A cage with uvs gives a
/// mesh with uvs, refined as a face-varying primvar (OpenSubdiv's FVAR_LINEAR_CORNERS_ONLY: smooth
/// inside, seams kept; the mesh repeats a vertex once per distinct uv at a seam).
TriangleMesh SubdivideCatmullClark(const PolyMesh &cage, int levels);

/// A unit cube cage [-1,1]³ with 6 quads (for tests and procedural assets).
PolyMesh CubeCage();

}  // namespace phasor
