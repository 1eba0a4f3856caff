/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "fill_options.h"

#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

namespace pcl_holefill_tool
{
namespace
{
bool
toFloat (const std::string &text, float &value)
{
  std::istringstream in (text);
  in >> value;
  return !in.fail () && in.eof () && std::isfinite (value);
}

bool
toInt (const std::string &text, int &value)
{
  std::istringstream in (text);
  in >> value;
  return !in.fail () && in.eof ();
}

/** An option that sets one of the filter's numeric parameters: its name, default and range are the parameter's. */
struct FloatOption
{
  float Options::*field;
  const pcl_holefill::ParameterSpec *spec;
};
}  // namespace

namespace
{
/** Two lines of usage for a numeric parameter: its meaning, then its unit,
  * range and default, all from its ParameterSpec. */
std::string
parameterUsage (const pcl_holefill::ParameterSpec &spec, const char *metavar)
{
  std::ostringstream head, out;
  head << "  " << spec.option << ' ' << metavar;
  out << head.str () << std::string (head.str ().size () < 20 ? 20 - head.str ().size () : 1, ' ') << spec.meaning
      << "\n                    " << spec.unit << "; " << pcl_holefill::parameters::rangeText (spec) << "; default "
      << spec.default_value << "\n";
  return out.str ();
}

/** Two lines of usage for an option that switches a parameter, from its SwitchSpec. */
std::string
switchUsage (const pcl_holefill::SwitchSpec &spec)
{
  std::ostringstream head, out;
  head << "  " << spec.option;
  out << head.str () << std::string (head.str ().size () < 20 ? 20 - head.str ().size () : 1, ' ') << spec.name
      << (spec.option_sets ? " on" : " off") << " (default " << (spec.default_value ? "on" : "off")
      << ")\n                    " << spec.meaning << "\n";
  return out.str ();
}
}  // namespace

std::string
usage (const char *program)
{
  namespace P = pcl_holefill::parameters;
  std::ostringstream out;
  out << "Usage: " << program << " input.{pcd,ply,xyz,pts,txt} output.{pcd,ply,xyz,pts,txt} [options]\n"
      << "       " << program << " -demo DIR\n\n"
      << "Fills the holes of an oriented point cloud (Shape controllable geometry completion).\n"
      << "Input points are written unchanged, then the filled points, which have the field\n"
      << "'filled' = 1 (0 for input points) and the other fields of their nearest input point.\n"
      << "Text clouds (.xyz, .pts, .txt): x y z per line, then normals and other columns if\n"
      << "any (space, tab or comma separated; '#' comments and a point-count line skipped).\n"
      << "A cloud without normals gets them estimated (k = 16, more if noisy) and oriented.\n"
      << "Lengths are in the cloud's units; 0 means derived from the nearest-neighbour spacing\n"
      << "h or the sampling pitch p (sqrt(area per point)) around each hole.\n\n"
      << "Options:\n"
      << parameterUsage (P::kRadius, "R") << parameterUsage (P::kSigmaN, "S|auto|sup")
      << "                    (auto = 0: 2 x the spread of the rim's normals, within 0.1..0.3;\n"
      << "                    sup: g2 off, round patches)\n"
      << parameterUsage (P::kSigmaR, "S") << parameterUsage (P::kSpacingFactor, "F")
      << parameterUsage (P::kSigmaD, "S") << parameterUsage (P::kRadiusShrinkFactor, "F")
      << parameterUsage (P::kTerminationRatio, "T") << parameterUsage (P::kMaxPasses, "N")
      << parameterUsage (P::kMinHoleSize, "P|auto")
      << "                    (under 5, the gaps of uniformly random samples count)\n"
      << parameterUsage (P::kMaxHoleDiameter, "D")
      << switchUsage (P::kFirstOrder) << switchUsage (P::kDenoise)
      << "  -holes FILE       fill these loops (one per line, point indices) instead of\n"
      << "                    the detected holes\n"
      << "  -report FILE      per-hole report as JSON\n"
      << "  -detect_only      find the holes, fill nothing: the output gets a field hole_id (the\n"
      << "                    hole's number on its rim points, -1 elsewhere), -report lists every\n"
      << "                    loop (holes and borders, with their indices), and OUTPUT.holes.txt\n"
      << "                    holds the hole loops in the format -holes reads (to check or edit)\n"
      << "  -png FILE         a picture: the result from two sides, filled points orange, each\n"
      << "                    hole's rim blue (closed) or red (left open); below, a close-up of\n"
      << "                    each hole (the first 8) seen from outside the surface\n"
      << "  -threads N        0 = all cores                                                  (0)\n"
      << "  -q                quiet: no progress or notes on stderr\n"
      << "  -v                verbose: PCL's debug output too, on stdout (each pass's counts\n"
      << "                    of kept, repelled and rejected samples)\n"
      << "  -demo DIR         run the built-in demo (cube corner, sphere cap) into DIR\n"
      << "  -h                this text\n";
  return out.str ();
}

namespace
{
/** Sets the switch \a arg (an option without value); false if it is none. */
bool
setSwitch (const std::string &arg, Options &options)
{
  static const std::map<std::string, bool Options::*> switches{
      {"-h", &Options::help},           {"--help", &Options::help},
      {"-q", &Options::quiet},          {"-v", &Options::verbose},
      {pcl_holefill::parameters::kDenoise.option, &Options::denoise},
      {pcl_holefill::parameters::kFirstOrder.option, &Options::zero_order}, {"-detect_only", &Options::detect_only},
  };
  const auto found = switches.find (arg);
  if (found == switches.end ())
    return false;
  options.*(found->second) = true;
  return true;
}

bool
parseSigmaN (const std::string &text, Options &options, std::string &error)
{
  if (text == "sup" || text == "Sup" || text == "inf")
    options.sigma_n = pcl_holefill::kSup;
  else if (text == "auto")
    options.sigma_n = 0.f;
  else if (!toFloat (text, options.sigma_n) || !pcl_holefill::parameters::kSigmaN.accepts (options.sigma_n))
  {
    error = "-sigma_n takes a number >= 0, 'auto' (= 0) or 'sup', not '" + text + "'";
    return false;
  }
  return true;
}

/** -max_passes and -threads: whole numbers in their ranges. */
bool
parseCount (const std::string &arg, const std::string &text, Options &options, std::string &error)
{
  constexpr int kMaxThreads = 1024;
  int n = 0;
  const bool passes = arg == "-max_passes";
  const auto &spec = pcl_holefill::parameters::kMaxPasses;
  if (!toInt (text, n) || n < 0 || (passes ? !spec.accepts (static_cast<float> (n)) : n > kMaxThreads))
  {
    error = arg + " takes a whole number " +
            (passes ? pcl_holefill::parameters::rangeText (spec) : "0.." + std::to_string (kMaxThreads)) + ", not '" +
            text + "'";
    return false;
  }
  (passes ? options.max_passes : options.threads) = n;
  return true;
}

bool
parseFloat (const std::string &arg, const FloatOption &f, const std::string &text, Options &options,
            std::string &error)
{
  float v = 0.f;
  const bool automatic = f.spec->zero_is_automatic && text == "auto";
  if (!automatic && (!toFloat (text, v) || !f.spec->accepts (v)))
  {
    error = arg + " takes a number " + pcl_holefill::parameters::rangeText (*f.spec) +
            (f.spec->zero_is_automatic ? " or 'auto' (= 0)" : "") + ", not '" + text + "'";
    return false;
  }
  options.*(f.field) = v;
  return true;
}

const std::map<std::string, FloatOption> &
floatOptions ()
{
  namespace P = pcl_holefill::parameters;
  static const std::map<std::string, FloatOption> floats = [] {
    const FloatOption options[] = {
        {&Options::radius, &P::kRadius},         {&Options::sigma_r, &P::kSigmaR},
        {&Options::sigma_d, &P::kSigmaD},        {&Options::shrink, &P::kRadiusShrinkFactor},
        {&Options::ratio, &P::kTerminationRatio}, {&Options::spacing, &P::kSpacingFactor},
        {&Options::max_hole_size, &P::kMaxHoleDiameter}, {&Options::min_hole_size, &P::kMinHoleSize},
    };
    std::map<std::string, FloatOption> by_name;
    for (const auto &o : options)
      by_name[o.spec->option] = o;
    return by_name;
  }();
  return floats;
}

const std::map<std::string, std::string Options::*> &
stringOptions ()
{
  static const std::map<std::string, std::string Options::*> strings{
      {"-holes", &Options::holes_file}, {"-report", &Options::report_file},
      {"-png", &Options::png_file},     {"-demo", &Options::demo_dir},
  };
  return strings;
}

bool
takesValue (const std::string &arg)
{
  return arg == "-sigma_n" || arg == "-max_passes" || arg == "-threads" || floatOptions ().count (arg) ||
         stringOptions ().count (arg);
}

/** Sets option \a arg (one that takes a value) to \a text, checked. */
bool
setValue (const std::string &arg, const std::string &text, Options &options, std::string &error)
{
  if (arg == "-sigma_n")
    return parseSigmaN (text, options, error);
  if (arg == "-max_passes" || arg == "-threads")
    return parseCount (arg, text, options, error);
  if (floatOptions ().count (arg))
    return parseFloat (arg, floatOptions ().at (arg), text, options, error);
  options.*(stringOptions ().at (arg)) = text;
  return true;
}

/** The input and output files, or -demo's none. */
bool
takeFiles (const std::vector<std::string> &positional, Options &options, std::string &error)
{
  if (options.help)
    return true;
  if (!options.demo_dir.empty ())
  {
    if (!positional.empty ())
    {
      error = "-demo takes no input or output file";
      return false;
    }
    return true;
  }
  if (positional.size () != 2)
  {
    error = "expected an input and an output file (see -h)";
    return false;
  }
  options.input = positional[0];
  options.output = positional[1];
  return true;
}
}  // namespace

bool
parseOptions (int argc, char **argv, Options &options, std::string &error)
{
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (setSwitch (arg, options))
      continue;
    if (takesValue (arg))
    {
      if (i + 1 >= argc)
      {
        error = "option " + arg + " needs a value";
        return false;
      }
      if (!setValue (arg, argv[++i], options, error))
        return false;
    }
    else if (!arg.empty () && arg[0] == '-' && arg.size () > 1)
    {
      error = "unknown option " + arg + " (see -h)";
      return false;
    }
    else
      positional.push_back (arg);
  }
  return takeFiles (positional, options, error);
}

void
configure (const Options &options, pcl_holefill::HoleFilling<pcl::PointNormal> &filler)
{
  filler.setRadius (options.radius);
  filler.setSigmaN (options.sigma_n);
  filler.setSigmaR (options.sigma_r);
  filler.setSigmaD (options.sigma_d);
  filler.setSpacingFactor (options.spacing);
  filler.setRadiusShrinkFactor (options.shrink);
  filler.setTerminationRatio (options.ratio);
  filler.setMaxPasses (options.max_passes);
  filler.setFirstOrder (!options.zero_order);
  filler.setDenoise (options.denoise);
  filler.setMaxHoleDiameter (options.max_hole_size);
  filler.setMinHoleSize (options.min_hole_size);
  filler.setNumberOfThreads (static_cast<unsigned int> (options.threads));
}

bool
readHoles (const std::string &path, std::size_t cloud_size, std::vector<pcl_holefill::BoundaryLoop> &holes,
           std::string &error)
{
  std::ifstream in (path);
  if (!in)
  {
    error = "cannot read the holes file '" + path + "'";
    return false;
  }
  std::string line;
  std::size_t line_number = 0;
  while (std::getline (in, line))
  {
    ++line_number;
    if (line.empty () || line[0] == '#')
      continue;
    std::istringstream fields (line);
    pcl_holefill::BoundaryLoop loop;
    loop.closed = true;
    loop.is_hole = true;
    std::string token;
    while (fields >> token)
    {
      int index = -1;
      if (!toInt (token, index) || index < 0 || static_cast<std::size_t> (index) >= cloud_size)
      {
        error = path + ":" + std::to_string (line_number) + ": '" + token + "' is not a point index (0.." +
                std::to_string (cloud_size - 1) + ")";
        return false;
      }
      loop.indices.push_back (index);
    }
    if (loop.indices.size () < 3)
    {
      error = path + ":" + std::to_string (line_number) + ": a loop needs at least 3 points";
      return false;
    }
    holes.push_back (loop);
  }
  if (holes.empty ())
  {
    error = "the holes file '" + path + "' has no loop";
    return false;
  }
  return true;
}

bool
writeHoles (const std::string &path, const std::vector<pcl_holefill::BoundaryLoop> &loops, std::string &error)
{
  std::ofstream out (path);
  out << "# hole loops found by pcl_holefill -detect_only: one per line, input point indices in order\n";
  for (const auto &loop : loops)
  {
    if (!loop.is_hole)
      continue;
    for (std::size_t k = 0; k < loop.indices.size (); ++k)
      out << (k ? " " : "") << loop.indices[k];
    out << '\n';
  }
  if (!out)
  {
    error = "cannot write '" + path + "'";
    return false;
  }
  return true;
}

}  // namespace pcl_holefill_tool
