// Fills a cube's corner hole through the installed package; exits 0 only if
// the input comes back unchanged and the patch lies on the cube.
#include <pcl_holefill/hole_filling.h>
#include <pcl_holefill/shapes.h>

#include <cstdio>

int
main ()
{
  namespace shapes = pcl_holefill::shapes;
  const auto cut = shapes::cutHoles (shapes::cube ().sample (9192), {{{1, 1, 1}, 0.2}});
  pcl_holefill::HoleFilling<pcl::PointNormal> filler;
  filler.setInputCloud (cut.kept.makeShared ());
  shapes::Cloud output;
  filler.filter (output);
  const auto q = shapes::evaluateFill (shapes::cube (), cut, {{{1, 1, 1}, 0.2}}, output, shapes::meanSpacing (cut.kept));
  std::printf ("downstream: %zu points filled, max error %.5f, coverage %.3f\n", q.filled, q.max_error, q.coverage);
  return q.kept_unchanged && q.filled > 0 && q.max_error < 0.0046 && q.coverage > 0.99 ? 0 : 1;
}
