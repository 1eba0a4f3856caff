/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>

#include <string>
#include <vector>

/** \brief Synthetic models with exact normals and an exact distance to their
  * surface: the paper's test shapes (section 5), shared by the tests, the
  * benchmark and the demo. All fit the unit cube [0,1]^3 and are sampled with
  * a fixed seed, so every run sees the same cloud. */
namespace pcl_holefill
{
namespace shapes
{
using Cloud = pcl::PointCloud<pcl::PointNormal>;

/** \brief A convex planar polygon, counter-clockwise seen from its outward normal. */
struct Face
{
  std::vector<Eigen::Vector3d> corners;

  /** \brief Unit normal (Newell's sum over the edges); NaN for a degenerate face. */
  Eigen::Vector3d
  normal () const;
};

/** \brief A surface made of planar faces, or a sphere when radius > 0. */
struct Shape
{
  std::string name;
  std::vector<Face> faces;
  Eigen::Vector3d centre = Eigen::Vector3d::Constant (0.5);
  double radius = 0.0;
  bool closed = false;

  /** \brief Distance from \a p to the true surface. */
  double
  distance (const Eigen::Vector3d &p) const;

  /** \brief About \a points samples, evenly spread (a jittered grid on each
    * face, a jittered Fibonacci lattice on the sphere, a Poisson-disk sampling
    * on meshes of more than 64 faces), exact outward normals. */
  Cloud
  sample (std::size_t points, unsigned seed = 1) const;

  double
  area () const;
};

Shape sphere ();               //!< centre (0.5,0.5,0.5), radius 0.5
Shape cube ();                 //!< the closed unit cube
Shape openPyramid ();          //!< square base [0,1]^2 at z=0 (open), apex (0.5,0.5,1)
Shape dihedral ();             //!< two planes meeting at a 90 degree ridge along x, open
Shape flatPatch ();            //!< the square [0,1]^2 at z = 0.5, open

/** \brief A ball to cut out of a cloud. */
struct Ball
{
  Eigen::Vector3d centre;
  double radius;
};

/** \brief A cloud with holes and what was cut out of it (the ground truth of
  * what each hole should contain). */
struct CutCloud
{
  Cloud kept;
  Cloud removed;
};

/** \brief One of the paper's Table 2 cases: a shape, how many samples, the
  * hole cut at a sharp feature (or the sphere's smooth cap), and the max
  * error the paper reports for its method (0: none). */
struct PaperCase
{
  const char *name;
  Shape shape;
  std::size_t points;
  Ball hole;
  bool smooth;              //!< judged with sigma_n = kSup (round), not 0.1 (sharp)
  double paper_max_error;
};

/** \brief The paper's Table 2 cases, in its order: cube corner, pyramid apex,
  * dihedral edge, sphere cap. The one table of the tests, the bench and the
  * command's -demo. */
std::vector<PaperCase>
paperCases ();

/** \brief The case of paperCases () named \a name ("cube (corner)", ...). */
PaperCase
paperCase (const std::string &name);

/** \brief Removes every sample inside any of \a balls. */
CutCloud
cutHoles (const Cloud &cloud, const std::vector<Ball> &balls);

/** \brief Moves every point along its normal by Gaussian noise of std \a sigma. */
void
addNormalNoise (Cloud &cloud, double sigma, unsigned seed = 7);

/** \brief Mean distance from each point to its nearest neighbour. */
double
meanSpacing (const Cloud &cloud);

/** \brief How well a filled cloud repairs a cut (the paper's Table 2 protocol
  * plus completeness). */
struct FillQuality
{
  std::size_t filled = 0;          //!< points after the kept ones
  double max_error = 0.0;          //!< filled point to the true surface
  double mean_error = 0.0;
  double coverage = 0.0;           //!< share of removed samples within 1.5 spacings of an output point
  double mean_gap = 0.0;           //!< removed sample to the nearest output point: mean
  double max_gap = 0.0;            //!< ... and max
  std::size_t outside = 0;         //!< filled points farther than one spacing outside every ball
  bool kept_unchanged = false;     //!< the first kept.size() output points equal kept, byte for byte
};

/** \brief Compares \a output (kept points first, then the fill) with the
  * truth. \a spacing is the input's mean spacing (meanSpacing of kept). */
template <typename PointT> FillQuality
evaluateFill (const Shape &shape, const CutCloud &cut, const std::vector<Ball> &balls,
              const pcl::PointCloud<PointT> &output, double spacing);

}  // namespace shapes
}  // namespace pcl_holefill
