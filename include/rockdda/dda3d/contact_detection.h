/**
 * @file
 * Contact detection of 3D DDA (issue 17): a uniform-grid broad phase on
 * bounding boxes and a narrow phase for vertex-face and edge-edge contacts
 * of convex polyhedra with entrance rules (Shi 2001; Jiang & Yeung 2004;
 * Beyabanaki et al. 2008). The degenerate vertex-edge, vertex-vertex and
 * face-face contacts are represented by their vertex-face and edge-edge
 * contacts (doc/theory/dda3d.md, "Contacts").
 */
#ifndef ROCKDDA_DDA3D_CONTACT_DETECTION_H
#define ROCKDDA_DDA3D_CONTACT_DETECTION_H

#include <rockdda/dda/contact_detection.h>
#include <rockdda/dda3d/polyhedron.h>

#include <array>
#include <utility>
#include <vector>

namespace rockdda::dda3d
{
  /// An axis-aligned box (m).
  struct BoundingBox
  {
    Point lo = Point::Zero(), hi = Point::Zero();
  };

  /// The bounding box of @p p grown by @p margin (m) on every side.
  BoundingBox
  bounding_box(const Polyhedron &p, const double margin = 0.);

  /**
   * Every pair (i < j) of boxes that overlap (touching counts), each once,
   * sorted. A uniform grid with the median box extent as cell (enlarged so
   * that no box spans more than about 4 cells per axis); a pair is reported
   * by the cell that holds the lower corner of the two boxes'
   * intersection. O(N) for boxes of similar size.
   */
  std::vector<std::pair<int, int>>
  broad_phase(const std::vector<BoundingBox> &boxes);

  /// Kind of a contact.
  enum class ContactType : int
  {
    /// A vertex of block i against a face of block j.
    vertex_face = 0,
    /// An edge of block i crossing an edge of block j.
    edge_edge = 1
  };

  /// Convexity of an edge or a vertex of a polyhedron.
  enum class Convexity : int
  {
    /// Edge: interior dihedral angle below pi - flat_angle; vertex: no
    /// reflex edge.
    convex = 0,
    /// Edge: dihedral angle within flat_angle of pi (coplanar faces).
    flat = 1,
    /// Edge: dihedral angle above pi + flat_angle; vertex: every edge
    /// reflex.
    reflex = 2,
    /// Vertex: both convex (or flat) and reflex edges.
    saddle = 3
  };

  /**
   * The edges of a polyhedron with their two faces: edge k runs from
   * vertex v[0] to v[1] (v[0] < v[1]); face[0] traverses it as v[0] -> v[1],
   * face[1] as v[1] -> v[0]. With the convexity of every edge and vertex
   * on the geometry it was computed from (the narrow phase computes it
   * once per block and detection, so it follows the blocks' deformation).
   */
  struct PolyhedronEdges
  {
    std::vector<std::array<int, 2>> v, face;
    /// Edge k of face f's loop (loop[k] -> loop[k + 1]): face_edges[f][k].
    std::vector<std::vector<int>> face_edges;
    /// Interior dihedral angle of each edge (rad, in (0, 2 pi)): the
    /// angle the solid fills about the edge, > pi at a reflex (concave)
    /// edge.
    std::vector<double> dihedral;
    /// Convexity of each edge (convex, flat or reflex).
    std::vector<Convexity> edge_convexity;
    /// Convexity of each vertex (convex, saddle or reflex).
    std::vector<Convexity> vertex_convexity;
    /// Whether no edge is reflex (the polyhedron is convex).
    bool convex = true;
  };

  /// Dihedral angles within this of pi (rad) are flat: round-off and the
  /// strain of a block tilt coplanar faces by 1e-6 to 1e-4 rad (the 2D
  /// engine's flat-corner angle, doc/theory/dda.md).
  constexpr double flat_angle = 1e-3;

  /// The edges of @p p (which must be closed, polyhedron_defect()) with
  /// their convexity.
  PolyhedronEdges
  polyhedron_edges(const Polyhedron &p);

  /**
   * Where the projection of @p x on face @p f's plane lies relative to the
   * face polygon (planar and simple; convex or not): inside (crossing
   * rule in the face's plane), and its distance (m) to the polygon's
   * boundary with the loop position k of the nearest edge
   * (loop[k] -> loop[k + 1]).
   */
  struct FaceLocation
  {
    bool   inside   = false;
    double distance = 0.;
    int    edge     = -1;
  };

  /// FaceLocation of @p x on face @p f of @p p, whose unit normal is
  /// @p normal.
  FaceLocation
  locate_on_face(const Polyhedron &p,
                 const std::size_t f,
                 const Point      &normal,
                 const Point      &x);

  /**
   * One contact found by the narrow phase. Block i owns the vertex (or the
   * first edge), block j the face (or the second edge). p and q are the
   * contact points on i and j (for a vertex-face contact q is the vertex's
   * projection on the face's plane), normal is the unit normal of the
   * contact plane pointing out of j (towards i), gap = normal . (p - q)
   * (m, negative: penetration). score is the entrance score (the smallest
   * cosine between the normal and the directions into i's feature, and
   * minus those into j's; >= 0 where the contact plane separates the two
   * features locally).
   */
  struct ContactCandidate
  {
    ContactType type = ContactType::vertex_face;
    int         i = 0, j = 0;
    /// vertex_face: a = vertex of i, b = face of j; edge_edge: a = edge of
    /// i, b = edge of j (indices into polyhedron_edges()).
    int    a = 0, b = 0;
    Point  p = Point::Zero(), q = Point::Zero(), normal = Point::UnitZ();
    double gap = 0., score = 0.;
  };

  /// Tolerances of the narrow phase: dimensionless multiples of the
  /// blocks' sizes (Polyhedron::size()) or angles (rad).
  struct DetectionTolerances
  {
    /// Contact distance d = distance_factor max(size_i, size_j): features
    /// closer than d (gap <= d) are candidates, and penetrations deeper
    /// than d are no contact (at least twice the largest step
    /// displacement).
    double distance_factor = 0.02;
    /// Points within coincidence_factor min(size_i, size_j) are the same
    /// point (a vertex on
    /// a face's boundary, coincident vertices).
    double coincidence_factor = 1e-6;
    /// Entrance tolerance (rad): a feature enters a face or edge when its
    /// score is >= -sin(entrance_angle), larger than the relative rotation
    /// of two blocks in one step (the 2D engine's 0.2 rad).
    double entrance_angle = 0.2;
    /// Edge pairs more nearly parallel than this (rad) form no edge-edge
    /// contact (their contact is carried by the vertices at their ends).
    double parallel_angle = 0.01;
  };

  /**
   * The narrow phase for the convex polyhedra @p a (block @p ia) and @p b
   * (block @p ib), with their edges; appends the contacts to @p out.
   *
   * Vertex-face (each block's vertices against the other's faces): a
   * vertex P and face F with |gap| <= d whose projection lies in F
   * (within the coincidence tolerance). A vertex outside the other block
   * (or on its surface) is a contact with every such face it enters (score
   * >= -sin(entrance angle), where the score is the smallest cosine between
   * F's normal and P's edges) and is not behind (gap >= -coincidence
   * tolerance); a penetrated vertex with the entered face of shortest
   * exit (least depth; if it enters none, the face of shortest exit).
   * Vertex-vertex: two vertices within the coincidence tolerance give one
   * contact, the vertex-face contact with the larger score (by more than
   * 0.01; on a tie the vertex of the block with the lower index), so that
   * a stack of flush blocks has one contact per corner.
   *
   * Edge-edge: two edges, not nearly parallel, whose closest points are
   * interior to both (beyond the coincidence tolerance from the ends),
   * with |gap| <= d, and a contact plane (normal along the cross product)
   * that separates the two edges' faces locally: the directions into the
   * faces of i's edge have cosine >= -sin(entrance angle) with the normal,
   * those of j's edge <= sin(entrance angle).
   */
  void
  narrow_phase(const Polyhedron              &a,
               const PolyhedronEdges         &a_edges,
               const int                      ia,
               const Polyhedron              &b,
               const PolyhedronEdges         &b_edges,
               const int                      ib,
               const DetectionTolerances     &tolerances,
               std::vector<ContactCandidate> &out);

  /**
   * All contacts of the blocks @p blocks (convex polyhedra): broad phase on
   * the bounding boxes grown by distance_factor x size each, then the
   * narrow phase per pair. Sorted by (i, j, type, a, b). The blocks' edges
   * and the pairs run in fixed chunks through @p run_chunks (possibly on
   * threads, dda::ChunkRunner; serially if empty), each chunk with its own
   * output, joined in order: the same list on any number of threads.
   * If @p edges is given, it receives the edges of every block of a pair
   * of the broad phase (polyhedron_edges(); left empty for the others), so
   * that the caller need not compute them again on the same geometry.
   */
  std::vector<ContactCandidate>
  detect_contacts(const std::vector<const Polyhedron *> &blocks,
                  const DetectionTolerances             &tolerances,
                  const dda::ChunkRunner                &run_chunks = {},
                  std::vector<PolyhedronEdges>          *edges      = nullptr);
} // namespace rockdda::dda3d

#endif
