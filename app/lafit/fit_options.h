#pragma once
// The fitting options lafit's `fit` and `batch` share, read from the command line.

#include <set>
#include <string>

#include "app/io/point_file.h"
#include "app/lafit/cli_args.h"
#include "fitting/pipeline.h"

namespace la::cli {

inline const std::set<std::string> kFitValued = {"--tolerance", "--tolerance-abs", "--max-extrema", "--g2",
                                                 "--g2-threshold", "--significance", "--time-budget",
                                                 "--max-points", "--max-polish-segments", "--max-strokes",
                                                 "--max-svg-points", "--max-nesting"};
inline const std::set<std::string> kFitFlags = {"--no-corners", "--no-close", "--closed", "--paper-only", "--stages"};

inline constexpr const char* kFitOptionsHelp = R"(fitting options:
  --tolerance F        max distance from the points, as a fraction of the stroke's
                       bounding-box diagonal (default 0.005)
  --tolerance-abs D    max distance in the input's units (overrides --tolerance)
  --max-extrema N      keep at most N curvature extrema in each smooth part of a stroke
                       (between two corners; simplification; default: all significant)
  --significance S     curvature extrema whose pair differs by less than S times the
                       largest |curvature| are noise (default 0.2)
  --g2 METHOD          newton (default: all joints at once), bisection (the paper's
                       joint-by-joint method), or off (G1 only)
  --g2-threshold T     relative curvature gap allowed at a joint (default 1e-10)
  --no-corners         fair across sharp corners instead of keeping them
  --no-close           never close a stroke whose end meets its start
  --closed             every stroke is a closed contour, whatever the gap between its
                       ends (font outlines, profiles whose closing edge is not sampled)
  --paper-only         stop after the paper's joint deformation (stage 6): no least-
                       squares fit of the whole chain to the points and no choice of
                       its segments (stage 7, on by default: closer to the points,
                       truer alphas, the segments the points need)
  --time-budget MS     wall time one stroke's fit may take (default 0: no limit); when it
                       runs out, stage 7 stops and keeps the best G2 chain found so far,
                       with a warning (the cap of --max-extrema still holds)
  --stages             include every intermediate stage in the JSON

limits (the work one input may cost; over a limit the file or stroke is refused, or
stage 7 left out, with a message naming the flag):
  --max-points N       raw samples in one stroke (default 1000000)
  --max-polish-segments N
                       segments in all (of the stages 1-6 chains) that stage 7 fits in
                       one stroke (default 40; it fits a part's whole chain at once, at
                       a cost growing with their cube); the other parts keep stage 6's,
                       fitted by stage 7 without its choice of segments where it has
                       gaps (again up to N segments), and an open part's in pieces
                       where it still has gaps or bends tighter than the tolerance
  --max-strokes N      strokes in one file (default 100000)
  --max-svg-points N   points one SVG element flattens to (default 200000)
  --max-nesting N      JSON arrays/objects or SVG elements nested (default 256)
)";

FitOptions fitOptionsFrom(const Args& args);
/// The reader limits of the flags above (app/io/point_file.h).
ReadLimits readLimitsFrom(const Args& args);

}  // namespace la::cli
