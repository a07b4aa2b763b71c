// Several witness pairs for one pair of convex shapes whose nearest features are a face or an edge
// (docs/collision.md, "Several witnesses per pair").
//
// Where two shapes meet face to face, edge to face or along parallel edges, their nearest points
// are not unique: the single witness pair of distance() jumps over the contact region from one
// cycle to the next, and one damper row on it cannot hold the distance while a body turns about
// the point it was given. To first order the distance over the contact region is an affine
// function of the position in it, so its minimum is at a corner of the region; the corners are
//
//   - vertices of A's contact feature that lie over B's (distance from that vertex to B),
//   - vertices of B's contact feature over A's (distance from A to that vertex),
//   - crossings of an edge of A's feature with an edge of B's (segment–segment distance).
//
// The contact feature of a shape along the normal n is the set of its core's vertices within
// `band` of its support plane (a box: a corner, an edge or a face; a capsule: an end or its whole
// segment; a hull: those of its vertices, with the segments between them when there are at most 4).
// Every witness is the distance between a part of A and a part of B (a vertex, a segment between two
// core points, or the whole shape), so every one is at least the pair's distance and each is a
// necessary condition: a row on each keeps the region's corners apart. contactWitnesses() returns
// the nearest pair (distance()'s result, on the whole shapes) first, then the other witnesses whose
// distance is within `band` of it, nearest first, without repeating a witness pair already given.
//
// Real-time: noexcept, allocation-free (fixed-size arrays; the parts are hulls of one or two points
// that live in the Witness itself).
#pragma once

#include <Eigen/Core>

#include <array>

#include "collision/distance.hpp"
#include "collision/shape.hpp"

namespace mrqp::collision {

/// A part of a shape: the whole shape (count 0), one core vertex (1) or the segment between two
/// core points (2), in the shape's own frame; the shape's radius is swept around it.
struct ShapePart {
  int count = 0;
  std::array<Eigen::Vector3d, 2> points{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
};

/// One witness pair: parts of A and B and their distance (distance() of the parts).
struct Witness {
  ShapePart a, b;
  DistanceResult result;
};

/// Distance between part `pa` of A and part `pb` of B (distance() on the parts). The result's
/// witnesses and simplex are material points of A and B.
bool partDistance(const PlacedShape& A, const ShapePart& pa, const PlacedShape& B, const ShapePart& pb,
                  DistanceResult* out) noexcept;

/// Witness band used by the collision constraint (m): features within it of the support plane,
/// witnesses within it of the nearest distance.
inline constexpr double kWitnessBand = 2e-3;
/// Most witnesses returned for one pair: the nearest and up to eight corners (two quadrilateral
/// faces meet in at most an octagon).
inline constexpr int kMaxWitnesses = 9;

/// The witnesses of A and B (see above) into `out[0 … capacity)`, given `nearest` = distance(A, B).
/// Returns how many (≥ 1 when capacity ≥ 1; only the nearest when the shapes penetrate).
int contactWitnesses(const PlacedShape& A, const PlacedShape& B, const DistanceResult& nearest, double band,
                     Witness* out, int capacity) noexcept;

}  // namespace mrqp::collision
