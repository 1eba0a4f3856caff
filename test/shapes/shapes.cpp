/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/point_grid.h>
#include "shapes.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <stdexcept>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

namespace pcl_holefill
{
namespace shapes
{
Eigen::Vector3d
Face::normal () const
{
  Eigen::Vector3d n = Eigen::Vector3d::Zero ();
  for (std::size_t i = 0; i < corners.size (); ++i)
    n += corners[i].cross (corners[(i + 1) % corners.size ()]);
  return n.normalized ();
}

namespace
{

double
faceArea (const Face &f)
{
  Eigen::Vector3d n = Eigen::Vector3d::Zero ();
  for (std::size_t i = 0; i < f.corners.size (); ++i)
    n += f.corners[i].cross (f.corners[(i + 1) % f.corners.size ()]);
  return 0.5 * n.norm ();
}

double
segmentDistance (const Eigen::Vector3d &p, const Eigen::Vector3d &a, const Eigen::Vector3d &b)
{
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp ((p - a).dot (ab) / ab.squaredNorm (), 0.0, 1.0);
  return (a + t * ab - p).norm ();
}

/** Inside test on the face's plane: p is left of every edge (counter-clockwise). */
bool
projectsInside (const Face &f, const Eigen::Vector3d &normal, const Eigen::Vector3d &p)
{
  for (std::size_t i = 0; i < f.corners.size (); ++i)
  {
    const Eigen::Vector3d &a = f.corners[i];
    const Eigen::Vector3d &b = f.corners[(i + 1) % f.corners.size ()];
    if ((b - a).cross (p - a).dot (normal) < 0.0)
      return false;
  }
  return true;
}

double
faceDistance (const Face &f, const Eigen::Vector3d &p)
{
  const Eigen::Vector3d n = f.normal ();
  const double height = (p - f.corners[0]).dot (n);
  if (projectsInside (f, n, p - height * n))
    return std::abs (height);
  double best = std::numeric_limits<double>::max ();
  for (std::size_t i = 0; i < f.corners.size (); ++i)
    best = std::min (best, segmentDistance (p, f.corners[i], f.corners[(i + 1) % f.corners.size ()]));
  return best;
}

// Shapes with at most this many faces are sampled by a jittered grid per face.
constexpr std::size_t kGridSampledFaces = 64;

pcl::PointNormal
makePoint (const Eigen::Vector3d &p, const Eigen::Vector3d &n)
{
  pcl::PointNormal q;
  q.getVector3fMap () = p.cast<float> ();
  q.getNormalVector3fMap () = n.cast<float> ();
  q.curvature = 0.f;
  return q;
}

/** A jittered grid of pitch \a spacing over the face, clipped to it. */
void
sampleFace (const Face &f, double spacing, std::mt19937 &rng, Cloud &out)
{
  const Eigen::Vector3d n = f.normal ();
  const Eigen::Vector3d u = (f.corners[1] - f.corners[0]).normalized ();
  const Eigen::Vector3d v = n.cross (u);
  double lo_u = std::numeric_limits<double>::max (), hi_u = -lo_u, lo_v = lo_u, hi_v = -lo_u;
  for (const auto &c : f.corners)
  {
    const Eigen::Vector3d d = c - f.corners[0];
    lo_u = std::min (lo_u, d.dot (u));
    hi_u = std::max (hi_u, d.dot (u));
    lo_v = std::min (lo_v, d.dot (v));
    hi_v = std::max (hi_v, d.dot (v));
  }
  std::uniform_real_distribution<double> jitter (-0.3 * spacing, 0.3 * spacing);
  for (double a = lo_u + 0.5 * spacing; a < hi_u; a += spacing)
    for (double b = lo_v + 0.5 * spacing; b < hi_v; b += spacing)
    {
      const Eigen::Vector3d p = f.corners[0] + (a + jitter (rng)) * u + (b + jitter (rng)) * v;
      if (projectsInside (f, n, p))
        out.push_back (makePoint (p, n));
    }
}

Face
quad (const Eigen::Vector3d &a, const Eigen::Vector3d &b, const Eigen::Vector3d &c,
      const Eigen::Vector3d &d)
{
  return Face{{a, b, c, d}};
}
}  // namespace

double
Shape::area () const
{
  if (radius > 0.0)
    return 4.0 * M_PI * radius * radius;
  double a = 0.0;
  for (const auto &f : faces)
    a += faceArea (f);
  return a;
}

double
Shape::distance (const Eigen::Vector3d &p) const
{
  if (radius > 0.0)
    return std::abs ((p - centre).norm () - radius);
  double best = std::numeric_limits<double>::max ();
  for (const auto &f : faces)
    best = std::min (best, faceDistance (f, p));
  return best;
}

Cloud
Shape::sample (std::size_t points, unsigned seed) const
{
  Cloud out;
  std::mt19937 rng (seed);
  const double spacing = std::sqrt (area () / std::max<std::size_t> (points, 1));
  if (radius > 0.0)
  {
    // Fibonacci lattice: even spacing with no poles; a little tangent jitter
    // so that no two rims of a cut look alike.
    std::uniform_real_distribution<double> jitter (-0.25 * spacing, 0.25 * spacing);
    const double golden = M_PI * (3.0 - std::sqrt (5.0));
    for (std::size_t i = 0; i < points; ++i)
    {
      const double z = 1.0 - 2.0 * (i + 0.5) / points;
      const double ring = std::sqrt (1.0 - z * z);
      Eigen::Vector3d d (ring * std::cos (golden * i), ring * std::sin (golden * i), z);
      const Eigen::Vector3d t1 = d.unitOrthogonal ();
      const Eigen::Vector3d t2 = d.cross (t1);
      d = (radius * d + jitter (rng) * t1 + jitter (rng) * t2).normalized ();
      out.push_back (makePoint (centre + radius * d, d));
    }
  }
  else if (faces.size () <= kGridSampledFaces)
  {
    for (const auto &f : faces)
      sampleFace (f, spacing, rng, out);
  }
  else
  {
    // A mesh of many small faces: a grid per face would clump at face
    // borders, so throw darts by area and keep those at least 0.8 spacing
    // from every kept one (a maximal Poisson-disk sampling, ~as dense as the grid).
    std::vector<double> cumulative;
    double total = 0.0;
    for (const auto &f : faces)
      cumulative.push_back (total += faceArea (f));
    std::uniform_real_distribution<double> unit (0.0, 1.0);
    const float min_distance = static_cast<float> (0.8 * spacing);
    detail::PointGrid kept (min_distance);
    std::vector<detail::PointGrid::Neighbour> near;
    for (std::size_t dart = 0; dart < 8 * points; ++dart)
    {
      const std::size_t f = std::min<std::size_t> (
          faces.size () - 1, std::lower_bound (cumulative.begin (), cumulative.end (), unit (rng) * total) - cumulative.begin ());
      // A uniform point of a fan triangle of the (convex) face, by area.
      const auto &c = faces[f].corners;
      std::vector<double> fan;
      double fan_total = 0.0;
      for (std::size_t k = 1; k + 1 < c.size (); ++k)
        fan.push_back (fan_total += 0.5 * (c[k] - c[0]).cross (c[k + 1] - c[0]).norm ());
      const std::size_t t = std::min<std::size_t> (
          c.size () - 3, std::lower_bound (fan.begin (), fan.end (), unit (rng) * fan_total) - fan.begin ());
      double a = unit (rng), b = unit (rng);
      if (a + b > 1.0)
      {
        a = 1.0 - a;
        b = 1.0 - b;
      }
      const Eigen::Vector3d p = c[0] + a * (c[t + 1] - c[0]) + b * (c[t + 2] - c[0]);
      kept.withinRadius (p.cast<float> (), min_distance, near);
      if (!near.empty ())
        continue;
      kept.insert (p.cast<float> (), static_cast<int> (out.size ()));
      out.push_back (makePoint (p, faces[f].normal ()));
    }
  }
  out.width = static_cast<std::uint32_t> (out.size ());
  out.height = 1;
  out.is_dense = true;
  return out;
}

Shape
sphere ()
{
  Shape s;
  s.name = "sphere";
  s.radius = 0.5;
  s.closed = true;
  return s;
}

Shape
cube ()
{
  using V = Eigen::Vector3d;
  Shape s;
  s.name = "cube";
  s.closed = true;
  s.faces = {
      quad (V (0, 0, 0), V (0, 1, 0), V (1, 1, 0), V (1, 0, 0)),  // z = 0, normal -z
      quad (V (0, 0, 1), V (1, 0, 1), V (1, 1, 1), V (0, 1, 1)),  // z = 1, normal +z
      quad (V (0, 0, 0), V (1, 0, 0), V (1, 0, 1), V (0, 0, 1)),  // y = 0, normal -y
      quad (V (0, 1, 0), V (0, 1, 1), V (1, 1, 1), V (1, 1, 0)),  // y = 1, normal +y
      quad (V (0, 0, 0), V (0, 0, 1), V (0, 1, 1), V (0, 1, 0)),  // x = 0, normal -x
      quad (V (1, 0, 0), V (1, 1, 0), V (1, 1, 1), V (1, 0, 1)),  // x = 1, normal +x
  };
  return s;
}

Shape
openPyramid ()
{
  using V = Eigen::Vector3d;
  Shape s;
  s.name = "pyramid";
  const V apex (0.5, 0.5, 1.0);
  const V a (0, 0, 0), b (1, 0, 0), c (1, 1, 0), d (0, 1, 0);
  s.faces = {Face{{a, b, apex}}, Face{{b, c, apex}}, Face{{c, d, apex}}, Face{{d, a, apex}}};
  return s;
}

Shape
dihedral ()
{
  using V = Eigen::Vector3d;
  Shape s;
  s.name = "dihedral";
  // z = 0.5 + y for y < 0.5 and z = 1.5 - y beyond: a 90 degree ridge at y = 0.5.
  s.faces = {quad (V (0, 0, 0.5), V (1, 0, 0.5), V (1, 0.5, 1), V (0, 0.5, 1)),
             quad (V (0, 0.5, 1), V (1, 0.5, 1), V (1, 1, 0.5), V (0, 1, 0.5))};
  return s;
}

Shape
flatPatch ()
{
  using V = Eigen::Vector3d;
  Shape s;
  s.name = "flat";
  s.faces = {quad (V (0, 0, 0.5), V (1, 0, 0.5), V (1, 1, 0.5), V (0, 1, 0.5))};
  return s;
}

std::vector<PaperCase>
paperCases ()
{
  using V = Eigen::Vector3d;
  return {
      {"cube (corner)", cube (), 9192, {V (1, 1, 1), 0.2}, false, 0.0046},
      {"pyramid (apex)", openPyramid (), 4000, {V (0.5, 0.5, 1), 0.25}, false, 0.0114},
      {"dihedral (edge)", dihedral (), 4000, {V (0.5, 0.5, 1), 0.2}, false, 0.0034},
      {"sphere (cap)", sphere (), 4320, {V (0.5, 0.5, 1), 0.35}, true, 0.0},
  };
}

PaperCase
paperCase (const std::string &name)
{
  for (auto &c : paperCases ())
    if (name == c.name)
      return c;
  throw std::invalid_argument ("no paper case named '" + name + "'");
}

CutCloud
cutHoles (const Cloud &cloud, const std::vector<Ball> &balls)
{
  CutCloud cut;
  for (const auto &p : cloud)
  {
    const Eigen::Vector3d q = p.getVector3fMap ().cast<double> ();
    const bool inside = std::any_of (balls.begin (), balls.end (), [&q] (const Ball &b) {
      return (q - b.centre).norm () < b.radius;
    });
    (inside ? cut.removed : cut.kept).push_back (p);
  }
  for (Cloud *c : {&cut.kept, &cut.removed})
  {
    c->width = static_cast<std::uint32_t> (c->size ());
    c->height = 1;
    c->is_dense = true;
  }
  return cut;
}

void
addNormalNoise (Cloud &cloud, double sigma, unsigned seed)
{
  std::mt19937 rng (seed);
  std::normal_distribution<float> noise (0.f, static_cast<float> (sigma));
  for (auto &p : cloud)
    p.getVector3fMap () += noise (rng) * p.getNormalVector3fMap ();
}

double
meanSpacing (const Cloud &cloud)
{
  std::vector<Eigen::Vector3f> positions;
  for (const auto &p : cloud)
    positions.push_back (p.getVector3fMap ());
  detail::PointGrid grid (detail::PointGrid::suggestCellSize (positions, 4));
  grid.build (positions);
  double sum = 0.0;
  std::size_t count = 0;
  std::vector<detail::PointGrid::Neighbour> found;
  for (const auto &p : positions)
  {
    grid.nearestK (p, 2, found);
    if (found.size () == 2)
    {
      sum += std::sqrt (found[1].sqr_distance);
      ++count;
    }
  }
  return count ? sum / count : 0.0;
}

template <typename PointT> FillQuality
evaluateFill (const Shape &shape, const CutCloud &cut, const std::vector<Ball> &balls,
              const pcl::PointCloud<PointT> &output, double spacing)
{
  FillQuality q;
  const std::size_t kept = cut.kept.size ();
  q.kept_unchanged = output.size () >= kept;
  for (std::size_t i = 0; q.kept_unchanged && i < kept; ++i)
    q.kept_unchanged = std::memcmp (output[i].data, cut.kept[i].data, sizeof (float) * 4) == 0 &&
                       std::memcmp (output[i].data_n, cut.kept[i].data_n, sizeof (float) * 3) == 0;
  std::vector<Eigen::Vector3f> positions;
  for (const auto &p : output)
    positions.push_back (p.getVector3fMap ());
  for (std::size_t i = kept; i < output.size (); ++i)
  {
    const Eigen::Vector3d p = positions[i].cast<double> ();
    const double e = shape.distance (p);
    q.max_error = std::max (q.max_error, e);
    q.mean_error += e;
    const bool inside = std::any_of (balls.begin (), balls.end (), [&] (const Ball &b) {
      return (p - b.centre).norm () <= b.radius + spacing;
    });
    q.outside += inside ? 0 : 1;
  }
  q.filled = output.size () > kept ? output.size () - kept : 0;
  q.mean_error = q.filled ? q.mean_error / q.filled : 0.0;
  if (cut.removed.empty () || positions.empty ())
  {
    q.coverage = cut.removed.empty () ? 1.0 : 0.0;
    return q;
  }
  detail::PointGrid grid (detail::PointGrid::suggestCellSize (positions, 8));
  grid.build (positions);
  std::vector<detail::PointGrid::Neighbour> nearest;
  std::size_t covered = 0;
  for (const auto &p : cut.removed)
  {
    grid.nearestK (p.getVector3fMap (), 1, nearest);
    const double gap = nearest.empty () ? std::numeric_limits<double>::infinity () : std::sqrt (nearest[0].sqr_distance);
    q.mean_gap += gap;
    q.max_gap = std::max (q.max_gap, gap);
    covered += gap <= 1.5 * spacing ? 1 : 0;
  }
  q.mean_gap /= cut.removed.size ();
  q.coverage = static_cast<double> (covered) / cut.removed.size ();
  return q;
}

template FillQuality evaluateFill (const Shape &, const CutCloud &, const std::vector<Ball> &,
                                   const pcl::PointCloud<pcl::PointNormal> &, double);
template FillQuality evaluateFill (const Shape &, const CutCloud &, const std::vector<Ball> &,
                                   const pcl::PointCloud<pcl::PointXYZRGBNormal> &, double);

}  // namespace shapes
}  // namespace pcl_holefill
