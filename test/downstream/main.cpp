// Fills a cube's corner hole through the installed package, as a user's
// project would (nothing but the installed headers and library); exits 0
// only if the input comes back unchanged, a patch is added and every filled
// point lies on the cube.
#include <pcl_holefill/hole_filling.h>

#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

int
main ()
{
  // The three faces of the unit cube that meet at (1, 1, 1), on a 60 x 60
  // grid each, with the samples within 0.2 of the corner left out.
  const int n = 60;
  const Eigen::Vector3f corner (1.f, 1.f, 1.f);
  pcl::PointCloud<pcl::PointNormal>::Ptr cloud (new pcl::PointCloud<pcl::PointNormal>);
  for (int axis = 0; axis < 3; ++axis)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
      {
        pcl::PointNormal p;
        Eigen::Vector3f x;
        x[axis] = 1.f;
        x[(axis + 1) % 3] = (i + 0.5f) / n;
        x[(axis + 2) % 3] = (j + 0.5f) / n;
        if ((x - corner).norm () < 0.2f)
          continue;
        p.getVector3fMap () = x;
        p.getNormalVector3fMap () = Eigen::Vector3f::Unit (axis);
        cloud->push_back (p);
      }

  pcl_holefill::HoleFilling<pcl::PointNormal> filler;
  filler.setInputCloud (cloud);
  pcl::PointCloud<pcl::PointNormal> output;
  filler.filter (output);

  bool unchanged = output.size () >= cloud->size ();
  for (std::size_t i = 0; unchanged && i < cloud->size (); ++i)
    unchanged = std::memcmp (output[i].data, (*cloud)[i].data, sizeof (float) * 3) == 0;
  // Distance of a point near the corner to the cube's surface: to the
  // nearest of the three faces x = 1, y = 1, z = 1 (inside or outside).
  float max_error = 0.f;
  for (std::size_t i = cloud->size (); i < output.size (); ++i)
  {
    const Eigen::Vector3f d = (corner - output[i].getVector3fMap ()).cwiseAbs ();
    const Eigen::Vector3f x = output[i].getVector3fMap ();
    const bool outside = (x.array () > 1.f).any ();
    max_error = std::max (max_error, outside ? (x - x.cwiseMin (corner)).norm () : d.minCoeff ());
  }
  const std::size_t filled = output.size () - cloud->size ();
  std::printf ("downstream: %zu points filled, max error %.5f, %zu hole(s)\n", filled, max_error,
               filler.getReports ().size ());
  // 0.0046: the paper's Table 2 figure for the cube corner.
  return unchanged && filled > 50 && max_error < 0.0046f && filler.getReports ().size () == 1 ? 0 : 1;
}
