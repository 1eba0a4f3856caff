/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "off_mesh.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

namespace bench
{
namespace
{
using pcl_holefill::shapes::Face;
using pcl_holefill::shapes::Shape;

/** A key for a position, so that faces sharing a vertex find each other. */
std::tuple<long, long, long>
keyOf (const Eigen::Vector3d &p)
{
  return {std::lround (p.x () * 1e7), std::lround (p.y () * 1e7), std::lround (p.z () * 1e7)};
}

constexpr double kSharpCosine = 0.866;  // 30 degrees
}  // namespace

bool
readOffMesh (const std::string &path, Shape &shape, std::string &error)
{
  std::ifstream in (path);
  std::string magic;
  std::size_t vertices = 0, faces = 0, edges = 0;
  if (!(in >> magic) || magic != "OFF" || !(in >> vertices >> faces >> edges) || vertices == 0 || faces == 0 ||
      vertices > 10000000 || faces > 20000000)
  {
    error = "'" + path + "' is not an OFF mesh";
    return false;
  }
  std::vector<Eigen::Vector3d> points (vertices);
  for (auto &p : points)
    if (!(in >> p.x () >> p.y () >> p.z ()))
    {
      error = "'" + path + "': truncated vertex list";
      return false;
    }
  Eigen::Vector3d lo = points[0], hi = points[0];
  for (const auto &p : points)
  {
    lo = lo.cwiseMin (p);
    hi = hi.cwiseMax (p);
  }
  const double scale = 1.0 / (hi - lo).maxCoeff ();
  for (auto &p : points)
    p = (p - lo) * scale;
  shape = Shape ();
  shape.name = "fandisk";
  shape.closed = true;
  for (std::size_t f = 0; f < faces; ++f)
  {
    std::size_t n = 0;
    if (!(in >> n) || n < 3 || n > 64)
    {
      error = "'" + path + "': bad face " + std::to_string (f);
      return false;
    }
    Face face;
    for (std::size_t k = 0; k < n; ++k)
    {
      std::size_t v = 0;
      if (!(in >> v) || v >= vertices)
      {
        error = "'" + path + "': bad vertex index in face " + std::to_string (f);
        return false;
      }
      face.corners.push_back (points[v]);
    }
    std::string rest;
    std::getline (in, rest);  // optional colour
    if (face.normal ().allFinite ())
      shape.faces.push_back (face);
  }
  return true;
}

Eigen::Vector3d
sharpCorner (const Shape &shape)
{
  std::map<std::tuple<long, long, long>, std::vector<Eigen::Vector3d>> normals_at;
  std::map<std::tuple<long, long, long>, Eigen::Vector3d> position_of;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero ();
  for (const auto &f : shape.faces)
    for (const auto &c : f.corners)
    {
      normals_at[keyOf (c)].push_back (f.normal ());
      position_of[keyOf (c)] = c;
      centroid += c;
    }
  centroid /= static_cast<double> (position_of.size ());
  Eigen::Vector3d best = centroid;
  double best_distance = -1.0;
  for (const auto &[key, normals] : normals_at)
  {
    // Cluster the incident normals greedily; three clusters make a corner.
    std::vector<Eigen::Vector3d> clusters;
    for (const auto &n : normals)
      if (std::none_of (clusters.begin (), clusters.end (), [&] (const auto &c) { return c.dot (n) > kSharpCosine; }))
        clusters.push_back (n);
    const double distance = (position_of[key] - centroid).norm ();
    if (clusters.size () >= 3 && distance > best_distance)
    {
      best_distance = distance;
      best = position_of[key];
    }
  }
  return best;
}

Eigen::Vector3d
sharpEdgePoint (const Shape &shape)
{
  using Key = std::tuple<long, long, long>;
  std::map<std::pair<Key, Key>, std::vector<Eigen::Vector3d>> faces_of_edge;
  std::map<std::pair<Key, Key>, Eigen::Vector3d> midpoint_of;
  for (const auto &f : shape.faces)
    for (std::size_t i = 0; i < f.corners.size (); ++i)
    {
      Key a = keyOf (f.corners[i]), b = keyOf (f.corners[(i + 1) % f.corners.size ()]);
      if (b < a)
        std::swap (a, b);
      faces_of_edge[{a, b}].push_back (f.normal ());
      midpoint_of[{a, b}] = 0.5 * (f.corners[i] + f.corners[(i + 1) % f.corners.size ()]);
    }
  const Eigen::Vector3d corner = sharpCorner (shape);
  std::vector<Eigen::Vector3d> sharp;
  for (const auto &[edge, normals] : faces_of_edge)
    if (normals.size () == 2 && normals[0].dot (normals[1]) < kSharpCosine)
      sharp.push_back (midpoint_of[edge]);
  // Far from the chosen corner, and with sharp edges on both sides (mid-edge).
  Eigen::Vector3d best = corner;
  double best_score = -1.0;
  for (const auto &m : sharp)
  {
    int around = 0;
    for (const auto &other : sharp)
      around += (other - m).norm () < 0.06 ? 1 : 0;
    const double score = (m - corner).norm () * std::min (around, 6);
    if (score > best_score)
    {
      best_score = score;
      best = m;
    }
  }
  return best;
}

}  // namespace bench
