#pragma once
// When back-face culling of a mesh is sound, proved from its camera-space flightplans alone
// (docs/kinetic_grid.md, "Back-face culling"): no producer has to promise anything.
//
// The proof. Split the mesh into its connected components (triangles sharing vertices). For each
// component take c(t), the linear interpolation over each flightplan segment of the centroids of
// its vertices at the segment's two keys (continuous, piecewise linear). Require
//  (1) the mesh is a closed, consistently oriented 2-manifold (every directed edge once, its
//      reverse once), once the vertices at the same position at every key are welded into one
//      (loaders split them along normal and texture seams; they move together) and the triangles
//      left as segments are dropped;
//  (2) on every segment, every triangle has det(v0 - c, v1 - c, v2 - c) of one strict sign sigma,
//      the same for all triangles, throughout the segment (a cubic in t, proved by its Bernstein
//      coefficients with a relative margin far above rounding, subdividing a few times);
//  (3) at the first key, the triangles around each vertex, seen from c, turn exactly once around
//      it (the angles they span at the vertex sum to less than 3 pi, i.e. to 2 pi);
//  (4) on every segment the eye (the origin) is outside the bounding box of each component.
// By (2) the radial projection from c(t) onto the sphere of directions maps every triangle onto a
// non-degenerate spherical triangle of one orientation, and by (1) two triangles sharing an edge
// land on the two sides of the edge's great circle: the projection is a local homeomorphism off
// the vertices, and by (3) at them too (the turn count is an integer that cannot change while (2)
// holds, so one instant suffices). A local homeomorphism from a compact connected surface onto the
// sphere is a covering, and the sphere is simply connected: each component maps one to one, so
// it is a radial graph r(dir) > 0 around c(t) -- embedded, bounding a star-shaped solid that holds
// c, with its normals all outward (sigma > 0) or all inward (sigma < 0). Components may cross
// each other. By (4) the eye is outside every component's solid, so along any ray, up to its first
// hit the ray is outside all of them, and the first hit enters one: it is a triangle facing the
// eye. The triangles facing away can be dropped. The test is sufficient, not necessary: a closed
// solid that is not star-shaped around its vertex centroid (a torus, an L-shaped box whose
// centroid lies on a face plane) keeps every face.
#include <array>
#include <cstddef>

#include "kinetic/motion/flightplan_mesh.h"
#include "util/work_progress.h"

namespace kinray {

/// 0 when culling mesh `mesh` is not proved sound, else the sign of O
/// (TriangleMotion::orientation, det(v0, v1, v2)) of the triangles that face the eye. The proof
/// runs on `threads` workers (0: all cores); its answer does not depend on them. When given,
/// `progress` counts the (triangle, segment) pairs examined: at most the triangles times
/// culling_proof_segments(mesh).
[[nodiscard]] int back_face_cull_sign(const FlightplanMesh& mesh, int threads = 1,
                                      WorkProgress* progress = nullptr);

/// The segments the proof examines each triangle on: every segment between keys (one constant
/// segment for a standing mesh).
[[nodiscard]] inline size_t culling_proof_segments(const FlightplanMesh& mesh) {
  const size_t keys = mesh.is_static ? 1 : mesh.key_count();
  return keys > 1 ? keys - 1 : 1;
}

/// Sign (+1 or -1) that the cubic with Bernstein coefficients `b` on [0, 1] keeps strictly, each
/// coefficient beyond `margin` in absolute value, after at most `depth` halvings; 0 if unproved.
[[nodiscard]] int cubic_sign_on_unit_interval(const std::array<double, 4>& b, double margin, int depth);

}  // namespace kinray
