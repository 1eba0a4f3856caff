/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "corpus.h"

#include "off_mesh.h"

#include <pcl_holefill/detail/point_grid.h>

#include <pcl/features/normal_3d.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/search/kdtree.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <tuple>

namespace corpus
{
namespace
{
using V = Eigen::Vector3d;
using pcl_holefill::shapes::Face;

pcl::PointNormal
makePoint (const V &p, const V &n)
{
  pcl::PointNormal q;
  q.getVector3fMap () = p.cast<float> ();
  q.getNormalVector3fMap () = n.cast<float> ();
  q.curvature = 0.f;
  return q;
}

/** Uniform random points by area, with exact normals. */
class SurfaceDarts
{
public:
  SurfaceDarts (const Shape &shape, unsigned seed) : shape_ (shape), rng_ (seed)
  {
    for (const auto &f : shape.faces)
      for (std::size_t k = 1; k + 1 < f.corners.size (); ++k)
      {
        triangles_.push_back ({f.corners[0], f.corners[k], f.corners[k + 1], f.normal ()});
        const double a = 0.5 * (f.corners[k] - f.corners[0]).cross (f.corners[k + 1] - f.corners[0]).norm ();
        cumulative_.push_back ((cumulative_.empty () ? 0.0 : cumulative_.back ()) + a);
      }
  }

  pcl::PointNormal
  next ()
  {
    if (shape_.radius > 0.0)
    {
      V d (gauss_ (rng_), gauss_ (rng_), gauss_ (rng_));
      d.normalize ();
      return makePoint (shape_.centre + shape_.radius * d, d);
    }
    const double pick = unit_ (rng_) * cumulative_.back ();
    const std::size_t t = std::min<std::size_t> (
        triangles_.size () - 1, std::lower_bound (cumulative_.begin (), cumulative_.end (), pick) - cumulative_.begin ());
    double a = unit_ (rng_), b = unit_ (rng_);
    if (a + b > 1.0)
    {
      a = 1.0 - a;
      b = 1.0 - b;
    }
    const Triangle &tr = triangles_[t];
    return makePoint (tr.a + a * (tr.b - tr.a) + b * (tr.c - tr.a), tr.n);
  }

  double
  uniform ()
  {
    return unit_ (rng_);
  }

private:
  struct Triangle
  {
    V a, b, c, n;
  };
  const Shape &shape_;
  std::mt19937 rng_;
  std::normal_distribution<double> gauss_;
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
  std::vector<Triangle> triangles_;
  std::vector<double> cumulative_;
};

void
finish (Cloud &cloud)
{
  cloud.width = static_cast<std::uint32_t> (cloud.size ());
  cloud.height = 1;
  cloud.is_dense = true;
}

/** Appends \a p to \a out (and to \a kept, its grid) unless a kept point
  * lies closer than \a radius: the test of dart throwing. */
void
keepIfApart (const pcl::PointNormal &p, float radius, pcl_holefill::detail::PointGrid &kept, Cloud &out)
{
  thread_local std::vector<pcl_holefill::detail::PointGrid::Neighbour> near;
  kept.withinRadius (p.getVector3fMap (), radius, near, 1);
  if (!near.empty ())
    return;
  kept.insert (p.getVector3fMap (), static_cast<int> (out.size ()));
  out.push_back (p);
}

/** Dart throwing: keeps a dart when no kept point lies closer than
  * min_distance(dart). Stops after \a darts darts or \a points kept. */
template <typename MinDistance> Cloud
poissonDisk (SurfaceDarts &darts, std::size_t points, std::size_t max_darts, float largest, MinDistance min_distance)
{
  Cloud out;
  pcl_holefill::detail::PointGrid kept (largest);
  for (std::size_t d = 0; d < max_darts && out.size () < points; ++d)
  {
    const pcl::PointNormal p = darts.next ();
    keepIfApart (p, min_distance (p.getVector3fMap ()), kept, out);
  }
  return out;
}

/** Lines of a scanner: dense random darts kept in thin slabs between
  * parallel planes, then thinned along each line. Two scan directions, so
  * that no part of the surface lies parallel to the planes of both. */
Cloud
scanLines (const Shape &shape, SurfaceDarts &darts, std::size_t points)
{
  const double p = pitch (shape, points);
  const double across = 2.0 * p, along = 0.5 * p;  // 4 times denser along a line
  const V first = V (1.0, 0.6, 0.35).normalized ();
  const V second = first.unitOrthogonal ();
  Cloud slab;
  const std::size_t candidates = 60 * points;
  for (std::size_t d = 0; d < candidates; ++d)
  {
    const pcl::PointNormal q = darts.next ();
    const V n = q.getNormalVector3fMap ().cast<double> ();
    // The direction whose planes cross this part of the surface most steeply.
    const V s = std::abs (n.dot (first)) < 0.7 ? first : second;
    const V x = q.getVector3fMap ().cast<double> ();
    // Planes 'across' apart: on the surface the lines lie 1 to 1.43 times
    // that apart (the surface meets the planes at 45 to 90 degrees).
    const double u = x.dot (s) / across;
    if (std::abs (u - std::round (u)) < 0.04)
      slab.push_back (q);
  }
  Cloud out;
  pcl_holefill::detail::PointGrid kept (static_cast<float> (along));
  for (const auto &q : slab)
    keepIfApart (q, static_cast<float> (0.9 * along), kept, out);
  return out;
}

Cloud
voxelDownsampled (const Shape &shape, SurfaceDarts &darts, std::size_t points)
{
  Cloud::Ptr dense (new Cloud);
  for (std::size_t i = 0; i < 12 * points; ++i)
    dense->push_back (darts.next ());
  finish (*dense);
  pcl::VoxelGrid<pcl::PointNormal> grid;
  grid.setInputCloud (dense);
  const float leaf = static_cast<float> (1.15 * pitch (shape, points));
  grid.setLeafSize (leaf, leaf, leaf);
  Cloud out;
  grid.filter (out);
  for (auto &q : out)  // VoxelGrid averages normals: make them unit again
    q.getNormalVector3fMap ().normalize ();
  return out;
}

/** Appends a closed convex polygon, oriented so that its normal agrees with \a outward. */
void
addFace (Shape &s, std::vector<V> corners, const V &outward)
{
  Face f{corners};
  if (f.normal ().dot (outward) < 0.0)
    std::reverse (f.corners.begin (), f.corners.end ());
  s.faces.push_back (f);
}

/** An axis-aligned box as six outward faces. */
void
addBox (Shape &s, const V &lo, const V &hi)
{
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side)
    {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      std::vector<V> c;
      for (const auto &uv : {std::pair<int, int>{0, 0}, {1, 0}, {1, 1}, {0, 1}})
      {
        V p;
        p[axis] = side ? hi[axis] : lo[axis];
        p[u] = uv.first ? hi[u] : lo[u];
        p[v] = uv.second ? hi[v] : lo[v];
        c.push_back (p);
      }
      V out = V::Zero ();
      out[axis] = side ? 1.0 : -1.0;
      addFace (s, c, out);
    }
}
}  // namespace

const char *
toString (Sampling s)
{
  switch (s)
  {
  case Sampling::kRandom: return "random";
  case Sampling::kPoisson: return "poisson";
  case Sampling::kJittered: return "jittered";
  case Sampling::kVoxel: return "voxel";
  case Sampling::kScan: return "scan";
  case Sampling::kVarying: return "varying";
  }
  return "?";
}

std::vector<Sampling>
allSamplings ()
{
  return {Sampling::kRandom, Sampling::kPoisson, Sampling::kJittered,
          Sampling::kVoxel,  Sampling::kScan,    Sampling::kVarying};
}

double
pitch (const Shape &shape, std::size_t points)
{
  return std::sqrt (shape.area () / std::max<std::size_t> (points, 1));
}

double
diagonal (const Shape &shape)
{
  if (shape.radius > 0.0)
    return 2.0 * std::sqrt (3.0) * shape.radius;
  V lo = V::Constant (1e300), hi = V::Constant (-1e300);
  for (const auto &f : shape.faces)
    for (const auto &c : f.corners)
    {
      lo = lo.cwiseMin (c);
      hi = hi.cwiseMax (c);
    }
  return (hi - lo).norm ();
}

Cloud
sampleSurface (const Shape &shape, std::size_t points, Sampling sampling, unsigned seed)
{
  SurfaceDarts darts (shape, seed);
  const float p = static_cast<float> (pitch (shape, points));
  Cloud out;
  switch (sampling)
  {
  case Sampling::kRandom:
    for (std::size_t i = 0; i < points; ++i)
      out.push_back (darts.next ());
    break;
  case Sampling::kPoisson:
    out = poissonDisk (darts, points, 30 * points, 0.8f * p, [p] (const Eigen::Vector3f &) { return 0.8f * p; });
    break;
  case Sampling::kJittered:
    out = shape.sample (points, seed);
    break;
  case Sampling::kVoxel:
    out = voxelDownsampled (shape, darts, points);
    break;
  case Sampling::kScan:
    out = scanLines (shape, darts, points);
    break;
  case Sampling::kVarying:
  {
    // Pitch from 0.63 p to 1.26 p along x (density 4 times higher at x = 0
    // than at x = 1): the mean density stays about the same.
    out = poissonDisk (darts, 4 * points, 40 * points, 1.0f * p, [p] (const Eigen::Vector3f &x) {
      return 0.8f * p * 0.63f * std::pow (2.f, std::clamp (x.x (), 0.f, 1.f));
    });
    break;
  }
  }
  finish (out);
  return out;
}

void
addNoise (Cloud &cloud, const Shape &shape, double fraction, unsigned seed)
{
  if (fraction > 0.0)
    pcl_holefill::shapes::addNormalNoise (cloud, fraction * diagonal (shape), seed);
}

void
addStrays (Cloud &cloud, double fraction, double pitch, unsigned seed)
{
  if (!(fraction > 0.0))
    return;
  std::mt19937 rng (seed);
  std::bernoulli_distribution chosen (fraction);
  std::uniform_real_distribution<float> offset (1.f, 4.f);
  std::bernoulli_distribution outward (0.5);
  for (auto &p : cloud)
    if (chosen (rng))
    {
      const float distance = offset (rng) * static_cast<float> (pitch);
      p.getVector3fMap () += (outward (rng) ? distance : -distance) * p.getNormalVector3fMap ();
    }
}

void
estimateNormals (Cloud &cloud)
{
  Cloud::Ptr input (new Cloud (cloud));
  pcl::NormalEstimation<pcl::PointNormal, pcl::Normal> estimation;
  estimation.setInputCloud (input);
  estimation.setSearchMethod (pcl::search::KdTree<pcl::PointNormal>::Ptr (new pcl::search::KdTree<pcl::PointNormal>));
  estimation.setKSearch (16);
  pcl::PointCloud<pcl::Normal> normals;
  estimation.compute (normals);
  for (std::size_t i = 0; i < cloud.size (); ++i)
  {
    Eigen::Vector3f n = normals[i].getNormalVector3fMap ();
    if (!n.allFinite ())
      continue;  // keeps the exact normal: PCL gives none for degenerate neighbourhoods
    if (n.dot (cloud[i].getNormalVector3fMap ()) < 0.f)
      n = -n;
    cloud[i].getNormalVector3fMap () = n;
    cloud[i].curvature = normals[i].curvature;
  }
}

Shape
cylinder ()
{
  Shape s;
  s.name = "cylinder";
  s.closed = true;
  const int segments = 128;
  const double r = 0.3, z0 = 0.1, z1 = 0.9;
  std::vector<V> bottom, top;
  for (int i = 0; i < segments; ++i)
  {
    const double a = 2.0 * M_PI * i / segments, b = 2.0 * M_PI * (i + 1) / segments;
    const V pa (0.5 + r * std::cos (a), 0.5 + r * std::sin (a), 0.0);
    const V pb (0.5 + r * std::cos (b), 0.5 + r * std::sin (b), 0.0);
    const double mid = 0.5 * (a + b);
    addFace (s, {pa + V (0, 0, z0), pb + V (0, 0, z0), pb + V (0, 0, z1), pa + V (0, 0, z1)},
             V (std::cos (mid), std::sin (mid), 0.0));
    bottom.push_back (pa + V (0, 0, z0));
    top.push_back (pa + V (0, 0, z1));
  }
  addFace (s, bottom, V (0, 0, -1));
  addFace (s, top, V (0, 0, 1));
  return s;
}

Shape
torus ()
{
  Shape s;
  s.name = "torus";
  s.closed = true;
  const int nu = 128, nv = 48;
  const double R = 0.32, r = 0.14;
  auto point = [&] (int i, int j) {
    const double u = 2.0 * M_PI * i / nu, v = 2.0 * M_PI * j / nv;
    return V (0.5 + (R + r * std::cos (v)) * std::cos (u), 0.5 + (R + r * std::cos (v)) * std::sin (u),
              0.5 + r * std::sin (v));
  };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
    {
      const double u = 2.0 * M_PI * (i + 0.5) / nu, v = 2.0 * M_PI * (j + 0.5) / nv;
      const V outward (std::cos (v) * std::cos (u), std::cos (v) * std::sin (u), std::sin (v));
      addFace (s, {point (i, j), point (i + 1, j), point (i + 1, j + 1), point (i, j + 1)}, outward);
    }
  return s;
}

Shape
fin ()
{
  Shape s;
  s.name = "fin";
  s.closed = true;
  addBox (s, V (0.05, 0.2, 0.48), V (0.95, 0.8, 0.52));
  return s;
}

Shape
sheet (double thickness)
{
  Shape s;
  s.name = "sheet";
  s.closed = true;
  addBox (s, V (0.05, 0.2, 0.5 - 0.5 * thickness), V (0.95, 0.8, 0.5 + 0.5 * thickness));
  return s;
}

Shape
lBlock ()
{
  Shape s;
  s.name = "lblock";
  s.closed = true;
  // The L in the x-z plane, extruded along y: x in [0.1,0.9], z in [0.1,0.9],
  // the quadrant x > 0.5, z > 0.5 removed (a concave edge along y at x = z = 0.5).
  const double y0 = 0.2, y1 = 0.8;
  const std::vector<std::pair<double, double>> l = {{0.1, 0.1}, {0.9, 0.1}, {0.9, 0.5}, {0.5, 0.5}, {0.5, 0.9}, {0.1, 0.9}};
  const std::size_t n = l.size ();
  for (std::size_t i = 0; i < n; ++i)
  {
    const auto &a = l[i], &b = l[(i + 1) % n];
    const V out = V (b.second - a.second, 0.0, -(b.first - a.first)).normalized ();  // the L runs counter-clockwise in x-z
    addFace (s, {V (a.first, y0, a.second), V (b.first, y0, b.second), V (b.first, y1, b.second), V (a.first, y1, a.second)},
             out);
  }
  // The two L-shaped ends as convex pieces.
  for (const double y : {y0, y1})
  {
    const V out (0.0, y == y0 ? -1.0 : 1.0, 0.0);
    addFace (s, {V (0.1, y, 0.1), V (0.9, y, 0.1), V (0.9, y, 0.5), V (0.1, y, 0.5)}, out);
    addFace (s, {V (0.1, y, 0.5), V (0.5, y, 0.5), V (0.5, y, 0.9), V (0.1, y, 0.9)}, out);
  }
  return s;
}

Shape
starPrism ()
{
  Shape s;
  s.name = "star prism";
  s.closed = true;
  // Not among models (): made to test orientation across acute edges (the
  // tips' 44 degrees), after the corpus's figures were taken.
  constexpr int tips = 5;
  const double z0 = 0.35, z1 = 0.65;
  std::vector<V> outline;  // counter-clockwise seen from +z, tip first
  for (int i = 0; i < 2 * tips; ++i)
  {
    const double a = M_PI / 2 + i * M_PI / tips, r = i % 2 == 0 ? 0.45 : 0.2;
    outline.emplace_back (0.5 + r * std::cos (a), 0.5 + r * std::sin (a), 0.0);
  }
  const std::size_t n = outline.size ();
  for (std::size_t i = 0; i < n; ++i)
  {
    const V a = outline[i], b = outline[(i + 1) % n];
    const V out = V (b.y () - a.y (), -(b.x () - a.x ()), 0.0).normalized ();
    addFace (s, {a + V (0, 0, z0), b + V (0, 0, z0), b + V (0, 0, z1), a + V (0, 0, z1)}, out);
  }
  // The ends as convex pieces: each tip's triangle and the pentagon of the notches.
  for (const double z : {z0, z1})
  {
    const V out (0.0, 0.0, z == z0 ? -1.0 : 1.0), up (0.0, 0.0, z);
    std::vector<V> pentagon;
    for (std::size_t i = 0; i < n; i += 2)
    {
      addFace (s, {outline[(i + n - 1) % n] + up, outline[i] + up, outline[i + 1] + up}, out);
      pentagon.push_back (outline[i + 1] + up);
    }
    addFace (s, pentagon, out);
  }
  return s;
}

Shape
boredCube ()
{
  Shape s;
  s.name = "bored cube";
  s.closed = true;
  const double bore = 0.22;
  const int segments = 128;  // a multiple of 8: the square's corners fall on sector edges
  // The four side faces of the unit cube.
  for (int axis = 0; axis < 2; ++axis)
    for (int side = 0; side < 2; ++side)
    {
      const int u = 1 - axis;
      std::vector<V> c;
      for (const auto &uz : {std::pair<int, int>{0, 0}, {1, 0}, {1, 1}, {0, 1}})
      {
        V p = V::Zero ();
        p[axis] = side;
        p[u] = uz.first;
        p[2] = uz.second;
        c.push_back (p);
      }
      V out = V::Zero ();
      out[axis] = side ? 1.0 : -1.0;
      addFace (s, c, out);
    }
  // Per angular sector: a quad of the bore's wall, and on the bottom and the
  // top a quad from the bore's circle out to the square along the sector's rays.
  const auto on_square = [] (double a) -> V {
    const V ray (std::cos (a), std::sin (a), 0.0);
    return V (0.5, 0.5, 0.0) + ray * (0.5 / std::max (std::abs (ray.x ()), std::abs (ray.y ())));
  };
  for (int i = 0; i < segments; ++i)
  {
    const double a = 2.0 * M_PI * i / segments, b = 2.0 * M_PI * (i + 1) / segments, mid = 0.5 * (a + b);
    const V ca (0.5 + bore * std::cos (a), 0.5 + bore * std::sin (a), 0.0);
    const V cb (0.5 + bore * std::cos (b), 0.5 + bore * std::sin (b), 0.0);
    const V up (0.0, 0.0, 1.0);
    addFace (s, {ca, cb, cb + up, ca + up}, V (-std::cos (mid), -std::sin (mid), 0.0));
    addFace (s, {ca, cb, on_square (b), on_square (a)}, -up);
    addFace (s, {ca + up, cb + up, on_square (b) + up, on_square (a) + up}, up);
  }
  return s;
}

bool
fandisk (Shape &shape, std::string &error)
{
#ifdef PCL_HOLEFILL_FANDISK
  return bench::readOffMesh (PCL_HOLEFILL_FANDISK, shape, error) && (shape.name = "fandisk", true);
#else
  error = "fandisk.off was not found at configure time (apt-get install libcgal-demo)";
  return false;
#endif
}

Cloud
meshVertices (const Shape &mesh)
{
  std::map<std::tuple<double, double, double>, std::size_t> index;
  std::vector<Eigen::Vector3d> positions, normals;
  for (const auto &face : mesh.faces)
  {
    const Eigen::Vector3d n = face.normal ();
    if (!n.allFinite ())
      continue;  // a degenerate face: no direction to add to its corners
    for (std::size_t k = 1; k + 1 < face.corners.size (); ++k)
    {
      const Eigen::Vector3d &a = face.corners[0], &b = face.corners[k], &c = face.corners[k + 1];
      const Eigen::Vector3d weighted = 0.5 * (b - a).cross (c - a).norm () * n;
      for (const Eigen::Vector3d *v : {&a, &b, &c})
      {
        const auto key = std::make_tuple (v->x (), v->y (), v->z ());
        const auto [it, inserted] = index.emplace (key, positions.size ());
        if (inserted)
        {
          positions.push_back (*v);
          normals.push_back (Eigen::Vector3d::Zero ());
        }
        normals[it->second] += weighted;
      }
    }
  }
  Cloud cloud;
  for (std::size_t i = 0; i < positions.size (); ++i)
  {
    pcl::PointNormal q;
    q.getVector3fMap () = positions[i].cast<float> ();
    q.getNormalVector3fMap () = normals[i].normalized ().cast<float> ();
    cloud.push_back (q);
  }
  return cloud;
}

CutCloud
build (const Case &c)
{
  Cloud cloud = sampleSurface (c.shape, c.points, c.sampling, c.seed);
  addNoise (cloud, c.shape, c.noise, c.seed + 101);
  addStrays (cloud, c.strays, pitch (c.shape, c.points), c.seed + 202);
  if (c.estimated)
    estimateNormals (cloud);
  return pcl_holefill::shapes::cutHoles (cloud, c.holes);
}

DetectionScore
scoreDetection (const std::vector<std::vector<Eigen::Vector3f>> &hole_loops, const std::vector<Ball> &holes,
                double pitch)
{
  DetectionScore score;
  score.cut = holes.size ();
  std::vector<char> found (holes.size (), 0);
  for (const auto &loop : hole_loops)
  {
    bool matched = false;
    for (std::size_t b = 0; b < holes.size (); ++b)
    {
      std::size_t near = 0;
      for (const auto &p : loop)
        near += (p.cast<double> () - holes[b].centre).norm () <= holes[b].radius + 3.0 * pitch ? 1 : 0;
      if (2 * near > loop.size ())
      {
        found[b] = 1;
        matched = true;
      }
    }
    score.false_holes += matched ? 0 : 1;
  }
  score.found = static_cast<std::size_t> (std::count (found.begin (), found.end (), 1));
  return score;
}

}  // namespace corpus

namespace corpus
{
std::vector<Ball>
holesOf (const Shape &shape, std::size_t points)
{
  const double p = pitch (shape, points);
  const std::string &n = shape.name;
  // radius in pitches: diameters 10 .. 30 pitches
  auto ball = [p] (const V &c, double diameter_in_pitches) { return Ball{c, 0.5 * diameter_in_pitches * p}; };
  if (n == "cube")
    return {ball (V (1, 1, 1), 20), ball (V (0, 0.5, 0), 14), ball (V (0.5, 0.5, 1), 10)};
  if (n == "sphere")
    return {ball (V (0.5, 0.5, 1.0), 24), ball (V (1.0, 0.5, 0.5), 10)};
  if (n == "pyramid")
    return {ball (V (0.5, 0.5, 1.0), 16), ball (V (0.75, 0.75, 0.5), 12)};
  if (n == "dihedral")
    return {ball (V (0.5, 0.5, 1.0), 16), ball (V (0.5, 0.25, 0.75), 10)};
  if (n == "cylinder")
    return {ball (V (0.8, 0.5, 0.9), 14), ball (V (0.2, 0.5, 0.5), 16)};
  if (n == "torus")
    return {ball (V (0.5, 0.82, 0.5 + 0.14), 10), ball (V (0.5 - 0.46, 0.5, 0.5), 12)};
  if (n == "fin")
    return {ball (V (0.5, 0.5, 0.52), 12), ball (V (0.95, 0.5, 0.5), 10)};
  if (n == "fandisk")
    return {ball (bench::sharpCorner (shape), 14), ball (bench::sharpEdgePoint (shape), 12)};
  if (n == "lblock")
    return {ball (V (0.5, 0.5, 0.5), 14), ball (V (0.9, 0.2, 0.1), 14), ball (V (0.3, 0.5, 0.9), 10)};
  return {};
}

std::vector<Ball>
finCornerHoles (std::size_t points)
{
  const double radius = 10.0 * pitch (fin (), points);
  std::vector<Ball> balls;
  for (const double x : {0.05, 0.95})
    for (const double y : {0.2, 0.8})
      for (const double z : {0.48, 0.52})
        balls.push_back ({V (x, y, z), radius});
  return balls;
}

std::vector<Shape>
models ()
{
  using namespace pcl_holefill::shapes;
  std::vector<Shape> all = {cube (), sphere (), openPyramid (), dihedral (), cylinder (), torus (), fin (), lBlock ()};
  Shape f;
  std::string error;
  if (fandisk (f, error))
    all.push_back (f);
  return all;
}
}  // namespace corpus

#include <pcl_holefill/hole_boundary_estimation.h>
#include <pcl_holefill/hole_filling.h>

#include <chrono>

namespace corpus
{
namespace
{
/** A grid over the points of \a cloud, whose positions go to \a positions. */
pcl_holefill::detail::PointGrid
gridOf (const Cloud &cloud, std::vector<Eigen::Vector3f> &positions)
{
  positions.clear ();
  for (const auto &q : cloud)
    positions.push_back (q.getVector3fMap ());
  pcl_holefill::detail::PointGrid grid (pcl_holefill::detail::PointGrid::suggestCellSize (positions, 8));
  grid.build (positions);
  return grid;
}

/** Per cut ball: the share of its removed samples covered (within 1.5
  * pitches of an output point); 1 for a ball that removed none. */
std::vector<double>
ballCoverage (const CutCloud &cut, const std::vector<Ball> &balls, const Cloud &output, double p)
{
  std::vector<Eigen::Vector3f> positions;
  const pcl_holefill::detail::PointGrid grid = gridOf (output, positions);
  std::vector<std::size_t> total (balls.size (), 0), covered (balls.size (), 0);
  std::vector<pcl_holefill::detail::PointGrid::Neighbour> nearest;
  for (const auto &q : cut.removed)
  {
    const Eigen::Vector3d x = q.getVector3fMap ().cast<double> ();
    std::size_t b = 0;
    for (std::size_t i = 1; i < balls.size (); ++i)
      if ((x - balls[i].centre).norm () - balls[i].radius < (x - balls[b].centre).norm () - balls[b].radius)
        b = i;
    ++total[b];
    grid.nearestK (q.getVector3fMap (), 1, nearest);
    covered[b] += !nearest.empty () && nearest[0].sqr_distance <= 2.25 * p * p ? 1 : 0;
  }
  std::vector<double> share (balls.size (), 1.0);
  for (std::size_t b = 0; b < balls.size (); ++b)
    if (total[b] > 0)
      share[b] = static_cast<double> (covered[b]) / static_cast<double> (total[b]);
  return share;
}

/** Mean nearest-neighbour distance of the filled points over that of the
  * kept points around the cut balls (within 3 pitches of a ball). */
double
fillSpacingRatio (const CutCloud &cut, const std::vector<Ball> &balls, const Cloud &output, double p)
{
  std::vector<Eigen::Vector3f> positions;
  const pcl_holefill::detail::PointGrid grid = gridOf (output, positions);
  std::vector<pcl_holefill::detail::PointGrid::Neighbour> nearest;
  double rim_sum = 0.0, fill_sum = 0.0;
  std::size_t rim_count = 0, fill_count = 0;
  for (std::size_t i = 0; i < positions.size (); ++i)
  {
    const bool filled = i >= cut.kept.size ();
    const Eigen::Vector3d x = positions[i].cast<double> ();
    const bool near_rim = std::any_of (balls.begin (), balls.end (), [&] (const Ball &b) {
      return (x - b.centre).norm () <= b.radius + 3.0 * p;
    });
    if (!filled && !near_rim)
      continue;
    grid.nearestK (positions[i], 2, nearest);
    if (nearest.size () < 2)
      continue;
    (filled ? fill_sum : rim_sum) += std::sqrt (nearest[1].sqr_distance);
    ++(filled ? fill_count : rim_count);
  }
  return fill_count && rim_count ? (fill_sum / fill_count) / (rim_sum / rim_count) : 0.0;
}
}  // namespace

namespace
{
/** The samples a hole removed, at their noise-free positions: what a fill
  * has to cover. The noisy ones lie up to 3 sigma off the surface, farther
  * than the 1.5 pitches of the coverage test once sigma nears half a pitch,
  * and no fill on the true surface could come near them. */
Cloud
missingSurface (const Case &c)
{
  if (c.noise == 0.0)
    return build (c).removed;
  Case clean = c;
  clean.noise = 0.0;
  clean.estimated = false;
  return build (clean).removed;
}
}  // namespace

DetectionScore
detectHoles (const Cloud::Ptr &kept, const std::vector<Ball> &holes, double pitch)
{
  pcl_holefill::HoleBoundaryEstimation<pcl::PointNormal> estimation;
  estimation.setInputCloud (kept);
  std::vector<pcl_holefill::BoundaryLoop> loops;
  estimation.compute (loops);
  std::vector<std::vector<Eigen::Vector3f>> loop_positions;
  for (const auto &l : loops)
    if (l.is_hole)
    {
      loop_positions.emplace_back ();
      for (const auto i : l.indices)
        loop_positions.back ().push_back ((*kept)[i].getVector3fMap ());
    }
  return scoreDetection (loop_positions, holes, pitch);
}

Outcome
runCase (const Case &c)
{
  auto cut = build (c);
  const Cloud::Ptr kept (new Cloud (cut.kept));
  const double p = pitch (c.shape, c.points);
  Outcome o;
  o.detection = detectHoles (kept, c.holes, p);

  pcl_holefill::HoleFilling<pcl::PointNormal> filler;  // no option at all
  filler.setInputCloud (kept);
  Cloud output;
  const auto start = std::chrono::steady_clock::now ();
  filler.filter (output);
  o.seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
  o.fill = pcl_holefill::shapes::evaluateFill (c.shape, cut, c.holes, output, p);
  if (c.noise > 0.0)
  {
    cut.removed = missingSurface (c);
    o.fill.coverage = pcl_holefill::shapes::evaluateFill (c.shape, cut, c.holes, output, p).coverage;
  }
  const std::vector<double> share = ballCoverage (cut, c.holes, output, p);
  const auto covered = [&] (std::size_t b) { return share[b] >= 0.99; };  // Outcome::covered_balls
  for (std::size_t b = 0; b < share.size (); ++b)
    o.covered_balls += covered (b) ? 1 : 0;
  o.reports_per_ball.assign (c.holes.size (), 0);
  for (const auto &r : filler.getReports ())
  {
    o.min_sigma_n = o.reported ? std::min (o.min_sigma_n, r.sigma_n) : r.sigma_n;
    o.max_sigma_n = std::max (o.max_sigma_n, r.sigma_n);
    o.min_noise = o.reported ? std::min (o.min_noise, r.noise) : r.noise;
    o.max_noise = std::max (o.max_noise, r.noise);
    ++o.reported;
    o.closed += r.closed ? 1 : 0;
    o.resumed += r.resumed > 0 ? 1 : 0;
    std::size_t b = 0;  // the cut ball the report is about: the nearest to its rim's centre
    for (std::size_t i = 1; i < c.holes.size (); ++i)
      if ((r.centre.cast<double> () - c.holes[i].centre).norm () < (r.centre.cast<double> () - c.holes[b].centre).norm ())
        b = i;
    if (c.holes.empty ())
      continue;
    ++o.reports_per_ball[b];
    o.closed_but_open += r.closed && !covered (b) ? 1 : 0;
    if (r.closed)
      o.min_closed_coverage = std::min (o.min_closed_coverage, share[b]);
    o.open_but_covered += !r.closed && covered (b) ? 1 : 0;
  }
  o.spacing_ratio = fillSpacingRatio (cut, c.holes, output, p);
  o.density = cut.removed.empty () ? 0.0 : static_cast<double> (o.fill.filled) / cut.removed.size ();
  o.input = kept->size ();
  o.output = output.size ();
  return o;
}
}  // namespace corpus

namespace corpus
{
MethodScore
scoreMethod (const Case &c, const CutCloud &cut, const Cloud &output)
{
  const double p = pitch (c.shape, c.points);
  std::vector<Eigen::Vector3f> input_positions, output_positions;
  const pcl_holefill::detail::PointGrid input_grid = gridOf (cut.kept, input_positions);
  const pcl_holefill::detail::PointGrid output_grid = gridOf (output, output_positions);
  MethodScore s;
  std::vector<pcl_holefill::detail::PointGrid::Neighbour> nearest;
  for (const auto &x : output_positions)
  {
    const Eigen::Vector3d xd = x.cast<double> ();
    const bool in_a_hole = std::any_of (c.holes.begin (), c.holes.end (), [&] (const Ball &b) {
      return (xd - b.centre).norm () <= b.radius + p;
    });
    input_grid.nearestK (x, 1, nearest);
    if (!in_a_hole || (!nearest.empty () && nearest[0].sqr_distance == 0.f))
      continue;
    const double e = c.shape.distance (xd);
    s.max_error = std::max (s.max_error, e);
    s.mean_error += e;
    ++s.fill;
  }
  s.mean_error = s.fill ? s.mean_error / s.fill : 0.0;
  std::size_t covered = 0;
  const Cloud missing = missingSurface (c);
  for (const auto &q : missing)
  {
    output_grid.nearestK (q.getVector3fMap (), 1, nearest);
    covered += !nearest.empty () && nearest[0].sqr_distance <= 2.25 * p * p ? 1 : 0;
  }
  s.coverage = missing.empty () ? 1.0 : static_cast<double> (covered) / missing.size ();
  return s;
}
}  // namespace corpus

