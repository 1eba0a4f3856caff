/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <cmath>
#include <initializer_list>
#include <limits>
#include <sstream>
#include <string>

namespace pcl_holefill
{
/** \brief sigma_n meaning "no normal-dissimilarity constraint" (the paper's "Sup"). */
constexpr float kSup = std::numeric_limits<float>::infinity ();

/** \brief One numeric parameter of HoleFilling: its default, range and unit,
  * written here once. The filter's defaults and checkParameters (), the
  * command's options, their checks and its usage text all read them (the
  * meaning of each is documented at its setter and in doc/parameters.md). */
struct ParameterSpec
{
  const char *name;          //!< the paper's name, as messages print it
  const char *meaning;       //!< what it does, in one line
  const char *option;        //!< the command's option ("" if it has none)
  const char *setter;        //!< its setter (HoleFilling's unless a class is named)
  float default_value;
  float low;                 //!< smallest value accepted
  float high;                //!< largest value accepted (or, if high_open, the bound below it)
  bool high_open;            //!< high itself refused
  bool infinity_allowed;     //!< +infinity accepted (sigma_n: kSup)
  const char *unit;          //!< unit, and what 0 means where it means "automatic"
  bool zero_is_automatic = false;  //!< 0 accepted below low, meaning "automatic"

  /** \brief Is \a value in range? NaN never is. */
  bool
  accepts (float value) const
  {
    if (zero_is_automatic && value == 0.f)
      return true;
    if (std::isinf (value))
      return infinity_allowed && value > 0.f;
    return value >= low && (high_open ? value < high : value <= high);
  }
};

/** \brief One on/off parameter of HoleFilling, written here once like
  * ParameterSpec. */
struct SwitchSpec
{
  const char *name;
  const char *meaning;
  const char *option;        //!< the command's option ("" if it has none)
  bool option_sets;          //!< the value the option gives the parameter
  const char *setter;        //!< HoleFilling's setter
  bool default_value;
};

/** \brief The parameters of HoleFilling (and of detection, which it drives). */
namespace parameters
{
constexpr float kUnbounded = std::numeric_limits<float>::max ();

// Each: name, meaning, option, setter; default, low, high, high excluded, infinity
// allowed; unit (and what 0 means).

constexpr ParameterSpec kRadius{
    "radius r", "neighbourhood of eq. (1) and (7)", "-radius", "setRadius",
    0.f, 0.f, kUnbounded, false, false,
    "cloud units; 0 = max(4 h, 3.5 p, 2.5 d_eq) per hole"};
constexpr ParameterSpec kRadiusShrinkFactor{
    "radius shrink factor", "r shrinks by this factor after each pass", "-shrink", "setRadiusShrinkFactor",
    1.f, 1.f, kUnbounded, false, false,
    "no unit; r <- r / factor after each pass (the paper's 1.1)"};
constexpr ParameterSpec kSigmaD{
    "sigma_d", "std of the distance weight g1", "-sigma_d", "setSigmaD",
    0.f, 0.f, kUnbounded, false, false,
    "cloud units; 0 = r / 2"};
constexpr ParameterSpec kSigmaN{
    "sigma_n", "std of the normal weight g2: small keeps edges sharp", "-sigma_n", "setSigmaN",
    0.f, 0.f, kUnbounded, false, true,
    "no unit (over |n_p - n_ref|, 0..2); 0 = per hole; kSup (infinity) = g2 off"};
constexpr ParameterSpec kSigmaR{
    "sigma_r", "width of the elastic force (eq. 6)", "-sigma_r", "setSigmaR",
    0.f, 0.f, kUnbounded, false, false,
    "cloud units; d_eq = sigma_r^2 ln(1e4); 0 = d_eq from the spacing factor"};
constexpr ParameterSpec kSpacingFactor{
    "spacing factor", "spacing of new points d_eq when sigma_r is 0", "-spacing", "setSpacingFactor",
    1.1f, 0.25f, 10.f, false, false,
    "sampling pitches; d_eq = factor x p when sigma_r is 0"};
constexpr ParameterSpec kTerminationRatio{
    "termination ratio", "the termination rule of sec. 4.2", "-ratio", "setTerminationRatio",
    0.3f, 0.f, 1.f, true, false,
    "no unit; stop when kept control points / boundary points < ratio"};
constexpr ParameterSpec kMaxPasses{
    "max passes", "bound on the passes of one hole", "-max_passes", "setMaxPasses",
    0.f, 0.f, 100000.f, false, false,
    "passes per hole; 0 = 4 x rim diameter / d_eq + 20"};
constexpr ParameterSpec kMaxBoundaryGrowth{
    "max boundary growth", "bound on a diverging boundary", "", "setMaxBoundaryGrowth",
    1.5f, 1.f, kUnbounded, false, false,
    "no unit; a boundary longer than this times the first is diverging"};
constexpr ParameterSpec kMaxHoleDiameter{
    "max hole diameter", "holes wider than this are left alone", "-max_hole_size", "setMaxHoleDiameter",
    0.f, 0.f, kUnbounded, false, false,
    "cloud units; 0 = fill every hole"};
constexpr ParameterSpec kMinHoleSize{
    "min hole size", "smallest hole, told from the gaps of the sampling", "-min_hole_size", "setMinHoleSize",
    0.f, 2.f, 100.f, false, false,
    "sampling pitches: the empty disc a hole must hold; 0 = 6 (random samples) to 4 (even ones)",
    true};

// Detection only (HoleBoundaryEstimation; HoleFilling uses the defaults).

constexpr ParameterSpec kKSearch{
    "k", "neighbours of the rim test and of the local sampling pitch", "",
    "HoleBoundaryEstimation::setKSearch", 16.f, 3.f, 64.f, false, false,
    "points (PCL's BoundaryEstimation uses 16 too)"};
constexpr ParameterSpec kAngleThreshold{
    "angle threshold", "widest empty sector a point off the rim may have", "",
    "HoleBoundaryEstimation::setAngleThreshold", static_cast<float> (M_PI / 2.0), static_cast<float> (M_PI / 2.0),
    static_cast<float> (2.0 * M_PI), true, false, "radians (PCL's BoundaryEstimation: pi/2)"};
constexpr ParameterSpec kLinkDistanceFactor{
    "link distance factor", "rim points closer than this are chained into one loop", "",
    "HoleBoundaryEstimation::setLinkDistanceFactor", 4.5f, 1.f, kUnbounded, false, false,
    "sampling pitches: the cloud's mean, or where the cloud is sparser the pitch around the rim point "
    "(a rim of random samples, thinned to the points an empty disc touches, has steps of up to 4)"};
constexpr ParameterSpec kMinLoopPoints{
    "min loop points", "shorter loops are ignored as noise", "",
    "HoleBoundaryEstimation::setMinLoopPoints", 6.f, 3.f, kUnbounded, false, false, "points"};
constexpr ParameterSpec kMinHoleDiameter{
    "min hole diameter", "min hole size in cloud units instead of pitches", "",
    "HoleBoundaryEstimation::setMinHoleDiameter", 0.f, 0.f, kUnbounded, false, false,
    "cloud units; 0 = from min hole size"};

/** \brief Every numeric parameter, in the order the docs list them. */
constexpr const ParameterSpec *kNumeric[] = {&kRadius,           &kRadiusShrinkFactor, &kSigmaD,
                                             &kSigmaN,           &kSigmaR,             &kSpacingFactor,
                                             &kTerminationRatio, &kMaxPasses,          &kMaxBoundaryGrowth,
                                             &kMinHoleSize,      &kMaxHoleDiameter,    &kKSearch,
                                             &kAngleThreshold,   &kLinkDistanceFactor, &kMinLoopPoints,
                                             &kMinHoleDiameter};

// Each: name, meaning, option, what the option sets, setter, default.

constexpr SwitchSpec kFirstOrder{
    "first order", "a linear normal field continues the rim's curvature (beyond the paper)",
    "-zero_order", false, "setFirstOrder", true};
constexpr SwitchSpec kCombinationConstraint{
    "combination constraint", "sec. 4.4: a patch stops at the edges its rim shows", "", false,
    "setCombinationConstraint", true};
constexpr SwitchSpec kDenoise{
    "denoise", "sec. 3.2 bilateral preprocessing first (moves input points)", "-denoise", true, "setDenoise",
    false};

/** \brief Every switch, in the order the docs list them. */
constexpr const SwitchSpec *kSwitches[] = {&kFirstOrder, &kCombinationConstraint, &kDenoise};

/** \brief The range of \a spec as text: ">= 0", "0.25..10", "0..1, 1 excluded". */
inline std::string
rangeText (const ParameterSpec &spec)
{
  std::ostringstream text;
  if (spec.zero_is_automatic)
    text << "0 or ";
  if (spec.high == kUnbounded)
    text << ">= " << spec.low;
  else
    text << spec.low << ".." << spec.high << (spec.high_open ? ", " : "");
  if (spec.high_open)
    text << spec.high << " excluded";
  if (spec.infinity_allowed)
    text << ", or infinity";
  return text.str ();
}
/** \brief A parameter's value, to be checked against its spec. */
struct CheckedValue
{
  const ParameterSpec &spec;
  float value;
};

/** \brief "name = value (range; unit)" for the first value its spec refuses,
  * empty when every one is accepted: what a checkParameters () prints. */
inline std::string
firstRefused (std::initializer_list<CheckedValue> values)
{
  for (const auto &checked : values)
    if (!checked.spec.accepts (checked.value))
    {
      std::ostringstream text;
      text << checked.spec.name << " = " << checked.value << " (" << rangeText (checked.spec) << "; "
           << checked.spec.unit << ")";
      return text.str ();
    }
  return "";
}
}  // namespace parameters

}  // namespace pcl_holefill
